"""DART backend (dartpy): each tree of the joint forest is one Skeleton; loops become constraints.

A tree's root gets a FreeJoint (a free root) or its tree joint to the world (a root
hanging from the static environment); every other body gets its tree joint to its
parent (BallJoint, RevoluteJoint, PrismaticJoint, UniversalJoint; a DoubleAxisHingeJoint is
a UniversalJoint, or with its suspension a chain of revolute, prismatic and revolute
joints through links of negligible mass). A joint's frame sits
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
class-wide (static), so each simulation sets its own before it steps; a joint's spring
and damper are integrated implicitly (f = -k (q + h v') - c v', v' the velocity after the
step), but constraint impulses (stops, servos, loops) move its joint without them; a
stop's row takes priority over a SERVO actuator on the same degree of freedom (so hinge2
motors are joint forces computed here, see _Drives); per-degree-of-freedom actuator types
are refused except MIMIC.
"""

from __future__ import annotations

from dataclasses import dataclass

import dartpy as dart
import numpy as np

from x3d_core import rotation as R
from x3d_core.engine import Unsupported
from x3d_core.world import STATIC, Joint, State, World

from .base import BODIES, JOINTS, Backend, approximate, native, unsupported

_FULL_TURN = np.pi - 1e-9  # an angle range this wide is no limit at all
_LOOPS = dart.constraint.DynamicJointConstraint  # holds the loop constraints' class-wide parameters
# the mass of a link between a hinge2's degrees of freedom, relative to its child's (its
# inertia likewise): DART warns that a massless body node may misbehave. Measured against
# MuJoCo's massless stack of joints, outputs move by about 10 * _LINK_MASS (rad/s over
# 1 s; 3e-14 with massless links): linear in it, so no rounding trouble down to here
_LINK_MASS = 1e-12


def _isometry(q: np.ndarray, p: np.ndarray) -> dart.math.Isometry3:
    t = dart.math.Isometry3()
    t.set_rotation(R.matrix(q))
    t.set_translation(np.asarray(p, dtype=np.float64))
    return t


@dataclass
class _Motor:
    """ODE's hinge2 motor: the rate sum(weight * joint velocity) driven to target, |torque| <= limit."""
    skeleton: dart.dynamics.Skeleton
    row: list[tuple[dart.dynamics.Joint, int, float]]  # (joint, degree of freedom, weight)
    target: float
    limit: float


class _Drives:
    """The motors of one skeleton, as ODE solves them: each motor's torque is the one that
    brings its rate to the target in this step if no more than its limit does, else the
    limit (all of the skeleton's motors at once, a box-bounded linear problem).

    DART's own SERVO actuator is not used, though its ramp and hold are ODE's: its row goes
    through DART's constraint solver, where a stop's row on the same degree of freedom
    takes priority, so a joint that a load presses on a stop stays there however much
    stronger the motor pulling it off (measured: 0.2 N m against 0.1), and its impulse
    moves the joint without a suspension's implicit spring-damper (measured: 20% more
    speed in a step under c h / m = 0.4). Here the torques are joint forces (FORCE
    actuators, the default) found from DART's own next-step velocity, which these
    quantities reproduce to rounding (measured): v' = v + h A^-1 f, with A = M + h D + h^2 K
    and f = Fext - (Coriolis and gravity) - K (q + h v - q0) - D v. DART's stops and loops
    then act on the result in its constraint solve, after the motors, so a motor answers
    their impulses at the next step (ODE solves them together)."""

    def __init__(self, skeleton: dart.dynamics.Skeleton, motors: list[_Motor], dt: float):
        self.skeleton, self.dt = skeleton, dt
        n = skeleton.getNumDofs()
        dofs = [skeleton.getDof(i) for i in range(n)]
        self.stiffness = np.array([d.getSpringStiffness() for d in dofs])
        self.damping = np.array([d.getDampingCoefficient() for d in dofs])
        self.rest = np.array([d.getRestPosition() for d in dofs])
        self.implicit = np.diag(dt * self.damping + dt * dt * self.stiffness)
        self.rows = np.zeros((len(motors), n))
        self.actuated: dict[int, tuple[dart.dynamics.Joint, int]] = {}
        for k, m in enumerate(motors):
            for joint, i, weight in m.row:
                column = joint.getIndexInSkeleton(i)
                self.rows[k, column] += weight
                self.actuated[column] = (joint, i)
        self.target = np.array([m.target for m in motors])
        self.limit = np.array([m.limit for m in motors])
        self.rhs = np.column_stack([np.zeros(n), self.rows.T])  # the forces, then each motor's unit torque

    def command(self) -> None:
        s, h = self.skeleton, self.dt
        q, v = s.getPositions(), s.getVelocities()
        f = (s.getExternalForces() - s.getCoriolisAndGravityForces()
             - self.stiffness * (q + h * v - self.rest) - self.damping * v)
        self.rhs[:, 0] = f
        x = np.linalg.solve(s.getMassMatrix() + self.implicit, self.rhs)
        free = self.rows @ (v + h * x[:, 0])  # each motor's rate next step without it
        torque = _box(h * self.rows @ x[:, 1:], self.target - free, self.limit)
        force = self.rows.T @ torque
        for column, (joint, i) in self.actuated.items():
            joint.setCommand(i, float(force[column]))  # a FORCE actuator's command is its force; reset every step


def _box(s: np.ndarray, r: np.ndarray, limit: np.ndarray) -> np.ndarray:
    """The x with s x = r where |x| < limit allows, x = +-limit elsewhere (s symmetric positive
    definite: the minimum of x.s.x/2 - x.r over the box, found by moving torques onto and
    off their limits until its optimality conditions hold)."""
    x = np.linalg.solve(s, r)
    at = np.abs(x) > limit  # the torques held at a limit
    if not at.any():
        return x  # the usual case once the motors have reached their targets
    x = np.minimum(np.maximum(x, -limit), limit)  # np.clip costs more on a few numbers
    for _ in range(4 * len(r) + 4):
        free = ~at
        if free.any():
            rows = s[free]
            x[free] = np.linalg.solve(rows[:, free], r[free] - rows[:, at] @ x[at])
            over = free & (np.abs(x) > limit)
            if over.any():
                x[over] = np.copysign(limit[over], x[over])
                at |= over
                continue
        back = at & ((r - s @ x) * x < 0)  # r - s x: where more torque lowers the objective
        if not back.any():
            break
        at &= ~back
    return x


class DartSimulation:
    def __init__(self, world: World, dt: float):
        self.world = world
        b = world.bodies
        self.dart_world = dart.simulation.World(world.name)
        self.dart_world.setTimeStep(dt)
        self.dart_world.setGravity(np.asarray(world.gravity, dtype=np.float64))
        self.dt = dt
        self.motors: list[_Motor] = []  # hinge2 motors, as they are built
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
        self.drives = [_Drives(s, [m for m in self.motors if m.skeleton is s], dt) for s in self.skeletons
                       if any(m.skeleton is s for m in self.motors)]
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
        joint, index = dof[1]
        self._limit(joint, index, p["minAngle1"], p["maxAngle1"], sign, angular=True)
        for k in (1, 2):
            if p[f"maxTorque{k}"] > 0:
                # its rate in joint space: the motor's axis against each hinge's (constant: each
                # hinge turns about its own axis, and the other hinge's axis is carried across it)
                row = [(dof[h][0], dof[h][1], float(axes[h - 1] @ axes[k - 1])) for h in (1, 2)]
                self.motors.append(_Motor(skeleton, row, sign * p[f"desiredAngularVelocity{k}"], p[f"maxTorque{k}"]))
        return node

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
            for drives in self.drives:  # after the loads: the motors answer them
                drives.command()
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
        **native("DoubleAxisHingeJoint", "DoubleAxisHingeJoint.anchorPoint", "DoubleAxisHingeJoint.axis1",
                 "DoubleAxisHingeJoint.axis2", "DoubleAxisHingeJoint.limits", "DoubleAxisHingeJoint.minAngle1",
                 "DoubleAxisHingeJoint.maxAngle1"),
        **approximate("ODE's motor rows solved here before each step from DART's own next-step dynamics, "
                      "applied as joint forces: a motor reaches its target in one step when maxTorque allows "
                      "and ramps at maxTorque otherwise (measured exact), and leaves a stop a load presses it "
                      "on when it is the stronger; DART solves stops and loop constraints after, so in a step "
                      "where one acts on the same tree the motors answer its impulse a step late (ODE solves "
                      "them together)",
                      "DoubleAxisHingeJoint.desiredAngularVelocity1", "DoubleAxisHingeJoint.desiredAngularVelocity2",
                      "DoubleAxisHingeJoint.maxTorque1", "DoubleAxisHingeJoint.maxTorque2"),
        **approximate("a prismatic joint along axis 1 between the two hinges, with DART's implicit spring-damper "
                      "k = ERP/(h*CFM), c = (1-ERP)/CFM: ODE's soft row term for term (measured against its "
                      "recurrence to 1e-12 m), through links of 1e-12 the child's mass; DART's stop and loop "
                      "impulses move it without the spring-damper's implicit terms in their step",
                      "DoubleAxisHingeJoint.suspensionForce", "DoubleAxisHingeJoint.suspensionErrorCorrection"),
        **unsupported("DART's joint limits are hard constraints without a restitution coefficient",
                      "SingleAxisHingeJoint.stopBounce", "SliderJoint.stopBounce", "DoubleAxisHingeJoint.stop1Bounce"),
        **unsupported("DART's joint limits are predictive and exact (a step ends on the stop, measured); the "
                      "limit ERP has no effect, so a stop's error correction cannot be set",
                      "SingleAxisHingeJoint.stopErrorCorrection", "SliderJoint.stopErrorCorrection",
                      "DoubleAxisHingeJoint.stop1ErrorCorrection"),
        **unsupported("DART's joint limits are hard: their rows' CFM is one class-wide relative value (1e-9), "
                      "not a per-stop softness", "DoubleAxisHingeJoint.stop1ConstantForceMix"),
    }

    def version(self) -> str:
        return dart.__version__

    def build(self, world: World, dt: float) -> DartSimulation:
        return DartSimulation(world, dt)


BACKEND = DartBackend()
