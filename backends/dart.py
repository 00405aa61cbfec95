"""DART backend (dartpy): each tree of the joint forest is one Skeleton; loops become constraints.

A tree's root gets a FreeJoint (a free root) or its tree joint to the world (a root
hanging from the static environment); every other body gets its tree joint to its
parent (BallJoint, RevoluteJoint, PrismaticJoint, UniversalJoint). A joint's frame sits
at the anchor with the child's starting orientation, so the child starts at its X3D
pose with every joint coordinate zero and axes are the child's local axes. DART
measures a child's joint coordinate relative to its parent; x3d_core's outputs
measure body1 relative to body2, so limits are mirrored where the child is body2 (as
in backends/mujoco.py). A fixed body is an immobile skeleton welded to the world.
Joints closing loops become BallJointConstraints (two along a hinge's axis).

DART facts this relies on (measured with dartpy 6.20, see tests/test_backend_dart.py):
deactivation (sleeping) is enabled by default, and X3D bodies sleep only where
autoDisable asks, so it is turned off; external forces are cleared after every step,
so the loads are added before each one; joint limits are predictive (a step ends on
the stop) and ignore the limit ERP;
getCOMLinearVelocity() is the centre of mass's velocity in world coordinates (X3D's
linearVelocity); FreeJoint velocities are world-frame [angular; linear at the origin],
not body-frame, so velocities are set through world Jacobians at the centre of mass,
which needs no convention at all; the loop constraints' ERP, CFM and correction cap are
class-wide (static), so each simulation sets its own before it steps.
"""

from __future__ import annotations

import dartpy as dart
import numpy as np

from x3d_core import rotation as R
from x3d_core.engine import Unsupported
from x3d_core.world import STATIC, Joint, State, World

from .base import BODIES, JOINTS, Backend, approximate, native, unsupported

_FULL_TURN = np.pi - 1e-9  # an angle range this wide is no limit at all
_LOOPS = dart.constraint.DynamicJointConstraint  # holds the loop constraints' class-wide parameters
# the mass of a link between a hinge2's degrees of freedom, relative to its child's (its
# inertia likewise): DART warns that a massless body node may misbehave; this one changes
# the child's effective inertia by as little (measured in tests/test_backend_dart.py)
_LINK_MASS = 1e-9


def _isometry(q: np.ndarray, p: np.ndarray) -> dart.math.Isometry3:
    t = dart.math.Isometry3()
    t.set_rotation(R.matrix(q))
    t.set_translation(np.asarray(p, dtype=np.float64))
    return t


class DartSimulation:
    def __init__(self, world: World, dt: float):
        self.world = world
        b = world.bodies
        self.dart_world = dart.simulation.World(world.name)
        self.dart_world.setTimeStep(dt)
        self.dart_world.setGravity(np.asarray(world.gravity, dtype=np.float64))
        self.dt = dt
        self.motors: list[tuple[dart.dynamics.Joint, int, float]] = []  # (joint, degree of freedom, target velocity)
        sleep = self.dart_world.getDeactivationOptions()
        sleep.mEnabled = False  # on by default (under 1 cm/s and 0.05 rad/s for 0.5 s)
        self.dart_world.setDeactivationOptions(sleep)
        self.nodes: list[dart.dynamics.BodyNode] = [None] * len(b)  # filled in tree order below
        self.skeletons: list[dart.dynamics.Skeleton] = []  # one per tree and one per fixed body
        self.members: list[list[int]] = []  # the body rows of each skeleton
        tree: dict[int, int] = {}  # body row -> index in self.skeletons
        for i in world.order:
            p = world.parent[i]
            if b.fixed[i]:
                self._fixed(i)
                continue
            if p < 0:  # a tree's root: free, or hanging from the static environment
                tree[i] = len(self.skeletons)
                skeleton = dart.dynamics.Skeleton(f"tree{i}")
                self.skeletons.append(skeleton)
                self.members.append([i])
            else:
                tree[i] = tree[p]
                skeleton = self.skeletons[tree[i]]
                self.members[tree[i]].append(i)
            if p == World.FREE:
                joint, node = skeleton.createFreeJointAndBodyNodePair(None)
                joint.setPositions(dart.dynamics.FreeJoint.convertToPositions(
                    _isometry(b.orientation[i], b.position[i])))
            else:
                node = self._tree_joint(skeleton, i, world.joints[world.parent_joint[i]])
            self._body(node, i)
        for skeleton in self.skeletons:
            self.dart_world.addSkeleton(skeleton)
        self.loops = [c for k in world.loop_joints for c in self._loop(world.joints[k])]
        for c in self.loops:
            self.dart_world.getConstraintSolver().addConstraint(c)
        # ODE's CFM adds CFM/dt to each row's diagonal; DART's is relative (measured: a row's
        # diagonal A becomes A*(1 + cfm) + cfm), so they agree for a unit effective mass
        self.cfm = max(world.constant_force_mix / (2.0 * dt), 1e-9)  # DART warns and clamps below 1e-9
        self.moving = [k for k, s in enumerate(self.skeletons) if s.getNumDofs() > 0]
        self.set_loads(b.forces, b.torques)
        self.set_velocities(b.linear_velocity, b.angular_velocity)

    # -- building -----------------------------------------------------------
    def _body(self, node: dart.dynamics.BodyNode, i: int) -> None:
        b = self.world.bodies
        node.setName(f"b{i}")
        node.setInertia(dart.dynamics.Inertia(float(b.mass[i]), b.com[i], b.inertia[i]))
        node.setGravityMode(bool(b.use_gravity[i]))
        self.nodes[i] = node

    def _fixed(self, i: int) -> None:
        """A fixed body: its own skeleton, welded to the world at its pose, immobile."""
        b = self.world.bodies
        skeleton = dart.dynamics.Skeleton(f"fixed{i}")
        joint, node = skeleton.createWeldJointAndBodyNodePair(None)
        joint.setTransformFromParentBodyNode(_isometry(b.orientation[i], b.position[i]))
        self._body(node, i)
        skeleton.setMobile(False)
        self.skeletons.append(skeleton)
        self.members.append([i])

    def _tree_joint(self, skeleton: dart.dynamics.Skeleton, child: int, j: Joint) -> dart.dynamics.BodyNode:
        """The child's body node, joined to its parent (or the world) at the joint's anchor."""
        b = self.world.bodies
        p = self.world.parent[child]
        pp, pq = (np.zeros(3), R.IDENTITY) if p < 0 else (b.position[p], b.orientation[p])
        cq = R.conjugate(b.orientation[child])
        parent = None if p < 0 else self.nodes[p]
        axes = R.rotate(cq, j.axes)  # joint frame = the child's starting orientation
        sign = -1.0 if child == j.body2 else 1.0  # DART: child relative to parent
        to_parent = _isometry(R.multiply(R.conjugate(pq), b.orientation[child]),
                              R.rotate(R.conjugate(pq), j.anchor - pp))
        to_child = _isometry(R.IDENTITY, R.rotate(cq, j.anchor - b.position[child]))
        if j.type == "DoubleAxisHingeJoint":
            return self._hinge2(skeleton, parent, child, j, axes, sign, to_parent, to_child)
        if j.type == "BallJoint":
            joint, node = skeleton.createBallJointAndBodyNodePair(parent)
        elif j.type == "SingleAxisHingeJoint":
            joint, node = skeleton.createRevoluteJointAndBodyNodePair(parent)
            joint.setAxis(axes[0])
            self._limit(joint, 0, j.params["minAngle"], j.params["maxAngle"], sign, angular=True)
        elif j.type == "SliderJoint":
            joint, node = skeleton.createPrismaticJointAndBodyNodePair(parent)
            joint.setAxis(axes[0])
            self._limit(joint, 0, j.params["minSeparation"], j.params["maxSeparation"], sign, angular=False)
        elif j.type == "UniversalJoint":
            joint, node = skeleton.createUniversalJointAndBodyNodePair(parent)
            first, second = (axes[0], axes[1]) if child == j.body2 else (axes[1], axes[0])
            joint.setAxis1(first)  # fixed in the parent
            joint.setAxis2(second)  # carried by the child
        else:
            raise Unsupported(f"{j.type} {j.name}: not built by the dart backend yet")
        joint.setTransformFromParentBodyNode(to_parent)
        joint.setTransformFromChildBodyNode(to_child)
        return node

    def _hinge2(self, skeleton: dart.dynamics.Skeleton, parent: dart.dynamics.BodyNode | None, child: int, j: Joint,
                axes: np.ndarray, sign: float, to_parent: dart.math.Isometry3,
                to_child: dart.math.Isometry3) -> dart.dynamics.BodyNode:
        """ODE's hinge2: a hinge about axis 1 (carried by body1, with its limits and motor), a
        suspension spring along axis 1 (k = ERP/(h*CFM), c = (1-ERP)/CFM; none when
        suspensionForce is 0) and a hinge about axis 2 (carried by body2, with its motor).

        Degrees of freedom from the parent outwards, as in backends/mujoco.py: hinge 1,
        slide, hinge 2 when the child is body2; hinge 2, hinge 1, slide when it is body1.
        Without suspension the two hinges are one UniversalJoint; with it they are a chain of
        single-dof joints through bodies of _LINK_MASS times the child's mass (and inertia),
        without gravity. DART's joint spring is implicit, f = -k (q + h v') - c v' with v' the
        velocity after the step: ODE's soft constraint row, term for term."""
        p = j.params
        b = self.world.bodies
        spring = p["suspensionForce"] > 0
        order = [1, 0, 2] if child == j.body2 else [2, 1, 0]  # hinge number; 0: the suspension slide
        if not spring:
            order.remove(0)
            joint, node = skeleton.createUniversalJointAndBodyNodePair(parent)
            joint.setAxis1(axes[order[0] - 1])  # fixed in the parent
            joint.setAxis2(axes[order[1] - 1])  # carried by the child
            joint.setTransformFromParentBodyNode(to_parent)
            joint.setTransformFromChildBodyNode(to_child)
            dof = {k: (joint, n) for n, k in enumerate(order)}
        else:
            dof = {}
            link_inertia = _LINK_MASS * np.trace(b.inertia[child]) / 3 * np.eye(3)
            for n, k in enumerate(order):
                if k == 0:
                    joint, node = skeleton.createPrismaticJointAndBodyNodePair(parent)
                    joint.setAxis(axes[0])
                    cfm, erp = p["suspensionForce"], p["suspensionErrorCorrection"]
                    joint.setSpringStiffness(0, erp / (self.dt * cfm))
                    joint.setDampingCoefficient(0, (1 - erp) / cfm)
                    joint.setRestPosition(0, 0.0)
                else:
                    joint, node = skeleton.createRevoluteJointAndBodyNodePair(parent)
                    joint.setAxis(axes[k - 1])
                joint.setName(f"{j.name}:{k}")
                if n == 0:
                    joint.setTransformFromParentBodyNode(to_parent)
                if n < len(order) - 1:  # a link between two degrees of freedom, at the anchor
                    node.setName(f"{j.name}:link{n}")
                    node.setInertia(dart.dynamics.Inertia(_LINK_MASS * float(b.mass[child]), np.zeros(3),
                                                          link_inertia))
                    node.setGravityMode(False)
                    parent = node
                else:
                    joint.setTransformFromChildBodyNode(to_child)
                dof[k] = (joint, 0)
        limited, index = dof[1]
        self._limit(limited, index, p["minAngle1"], p["maxAngle1"], sign, angular=True)
        for k in (1, 2):
            if p[f"maxTorque{k}"] > 0:
                joint, index = dof[k]
                self._servo(joint, index, sign * p[f"desiredAngularVelocity{k}"], p[f"maxTorque{k}"])
        return node

    def _servo(self, joint: dart.dynamics.Joint, index: int, target: float, limit: float) -> None:
        """ODE's motor: a velocity constraint whose torque is bounded by maxTorque. DART's SERVO
        actuator is that row in its constraint solver (the command is the target velocity,
        the force limits bound its impulse over the step). DART sets actuator types per
        joint only, so a joint's other degrees of freedom get zero force limits: no motor."""
        if joint.getActuatorType() != dart.dynamics.ActuatorType.SERVO:
            joint.setActuatorType(dart.dynamics.ActuatorType.SERVO)
            for i in range(joint.getNumDofs()):
                joint.setForceLowerLimit(i, 0.0)
                joint.setForceUpperLimit(i, 0.0)
        joint.setForceLowerLimit(index, -limit)
        joint.setForceUpperLimit(index, limit)
        self.motors.append((joint, index, target))

    @staticmethod
    def _limit(joint: dart.dynamics.Joint, index: int, lo: float, hi: float, sign: float, angular: bool) -> None:
        if angular and lo <= -_FULL_TURN and hi >= _FULL_TURN:
            return
        a, b = sorted((sign * lo, sign * hi))
        joint.setPositionLowerLimit(index, a)
        joint.setPositionUpperLimit(index, b)
        joint.setLimitEnforcement(True)

    def _loop(self, j: Joint) -> list[dart.constraint.BallJointConstraint]:
        """A joint closing a loop, as ball-joint constraints between body nodes (anchors in
        world coordinates): one at the anchor and, for a hinge, one more a metre along its
        axis, as backends/mujoco.py does. DART's RevoluteJointConstraint is not used: it blew
        up a four-bar linkage and misplaced the axis of a turned body (measured)."""
        if j.body1 == j.body2:
            return []  # a body joined to itself, or the static environment to itself: nothing moves
        if j.type not in ("BallJoint", "SingleAxisHingeJoint"):
            raise Unsupported(f"{j.type} {j.name} closes a loop of joints; the dart backend closes loops "
                              "with BallJoint and SingleAxisHingeJoint only")
        ends = [self.nodes[r] for r in (j.body1, j.body2) if r != STATIC]
        points = [j.anchor] if j.type == "BallJoint" else [j.anchor, j.anchor + j.axes[0]]
        return [dart.constraint.BallJointConstraint(*ends, np.asarray(p, dtype=np.float64)) for p in points]

    # -- running ------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        if self.loops:  # class-wide: another world may have set its own
            _LOOPS.setErrorReductionParameter(self.world.error_correction)
            _LOOPS.setConstraintForceMixing(self.cfm)
            _LOOPS.setMaxErrorReductionVelocity(np.inf)  # ODE does not cap joint error correction
        for _ in range(n):
            for node, force, com, torque in self.pushed:  # DART clears them after every step
                node.addExtForce(force, com, False, True)
                node.addExtTorque(torque, False)
            for joint, index, target in self.motors:  # and the commands too
                joint.setCommand(index, target)
            self.dart_world.step()

    def state(self) -> State:
        n = len(self.nodes)
        m = np.empty((n, 4, 4))
        lin, ang = np.empty((n, 3)), np.empty((n, 3))
        for i, node in enumerate(self.nodes):
            m[i] = node.getWorldTransform().matrix()
            lin[i] = node.getCOMLinearVelocity()  # world coordinates
            ang[i] = node.getAngularVelocity()
        return State(m[:, :3, 3].copy(), R.from_matrix(m[:, :3, :3]), lin, ang)

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        """Per skeleton, the joint velocities whose body velocities come closest to those asked
        for: a least-squares fit through the world Jacobians at the centres of mass, exact
        for a free body."""
        com = self.world.bodies.com
        for k in self.moving:
            skeleton, rows = self.skeletons[k], self.members[k]
            jac = np.concatenate([skeleton.getWorldJacobian(self.nodes[i], com[i]) for i in rows])  # [ang; lin]
            target = np.concatenate([np.concatenate([angular[i], linear[i]]) for i in rows])
            skeleton.setVelocities(np.linalg.lstsq(jac, target, rcond=None)[0])

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        """Kept and added before every step (DART clears external forces after each), to the
        bodies that get any: a force at the centre of mass, world frame."""
        b = self.world.bodies
        pushed = (np.abs(forces).sum(axis=1) + np.abs(torques).sum(axis=1) > 0) & ~b.fixed
        self.pushed = [(self.nodes[i], forces[i].copy(), b.com[i].copy(), torques[i].copy())
                       for i in np.flatnonzero(pushed)]


class DartBackend(Backend):
    name = "dart"
    declared = {
        **native(*BODIES, *JOINTS, "RigidBody.useGlobalGravity", "RigidBodyCollection.errorCorrection"),
        **approximate("DART's CFM is relative to each constraint row (its diagonal A becomes A*(1+cfm)+cfm), "
                      "ODE's adds CFM/dt: converted as cfm = CFM/(2*dt), exact for a unit effective mass; "
                      "it acts on loop constraints only (tree joints are exact)",
                      "RigidBodyCollection.constantForceMix"),
        **approximate("DART solves the joint constraints (loops, limits) with a direct Dantzig LCP solver, "
                      "as if iterations were unlimited; tree joints need none",
                      "RigidBodyCollection.iterations"),
        **approximate("DART has one integrator (semi-implicit Euler) and its constraint solver is already "
                      "the accurate direct one: nothing to switch",
                      "RigidBodyCollection.preferAccuracy"),
        **unsupported("DART's joint limits are hard constraints without a restitution coefficient",
                      "SingleAxisHingeJoint.stopBounce", "SliderJoint.stopBounce"),
        **unsupported("DART's joint limits are predictive and exact (a step ends on the stop, measured); the "
                      "limit ERP has no effect, so a stop's error correction cannot be set",
                      "SingleAxisHingeJoint.stopErrorCorrection", "SliderJoint.stopErrorCorrection"),
    }

    def version(self) -> str:
        return dart.__version__

    def build(self, world: World, dt: float) -> DartSimulation:
        return DartSimulation(world, dt)


BACKEND = DartBackend()
