"""pybullet backend: joints become multibody trees; ball joints closing loops become constraints.

Each tree of the world's joint forest is one multibody, in a DIRECT client of its own
per simulation: a free root is a free base, a root hanging from the static environment
is a link of a massless (so fixed) base at the world origin, and a body whose parent
joint is in the tree is a link with that joint's degrees of freedom (spherical,
revolute, prismatic; a universal joint or a hinge2 is two revolute links through a
massless link). A link's frame sits at the joint's anchor, turned as its body is at the
start, so the body frame is a fixed offset in it. pybullet measures a child's joint
coordinate relative to its parent; x3d_core's outputs measure body1 relative to body2,
so limits and motor targets are mirrored where the child is body2. pybullet reports
each link's centre of mass and principal axes (its link frame poses only in single
precision): state() turns them back into the body frame's origin and orientation, with
the centre of mass's velocity, for every body in one pass.

pybullet facts this relies on (measured with pybullet 3.2.7):
createMultiBody's linkParentIndices count the base as 0; its joints carry velocity
motors that hold them still until given zero force; multibodies are damped and joint
speeds clamped to 100 rad/s by default; a free base or a ball joint turns at most pi/4
per step (faster spins are clamped: 188 rad/s at dt = 1/240), a revolute joint exactly.
"""

from __future__ import annotations

import importlib.metadata
from dataclasses import dataclass, field

import numpy as np
import pybullet as p

from x3d_core import rotation as R
from x3d_core.engine import Unsupported
from x3d_core.world import STATIC, Joint, State, World

from .base import BODIES, JOINTS, Backend, approximate, native, unsupported

_FULL_TURN = np.pi - 1e-9  # an angle range this wide is no limit at all
_MAX_SPEED = 1e6  # pybullet clamps joint speeds to 100 rad/s unless told otherwise
_MAX_FORCE = 1e12  # a loop constraint's impulse bound (pybullet's default is 500 N)
_SUBSTEPS_ACCURATE = 4  # internal steps per step when preferAccuracy asks for more


def _xyzw(q: np.ndarray) -> list[float]:
    return [float(q[1]), float(q[2]), float(q[3]), float(q[0])]


def _wxyz(q: np.ndarray) -> np.ndarray:
    """pybullet's (x, y, z, w) quaternions, in bulk, as x3d_core's (w, x, y, z)."""
    return np.asarray(q, dtype=np.float64)[..., [3, 0, 1, 2]]


def _principal(inertia: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Principal moments and the principal frame's orientation in the body frame: pybullet
    takes a diagonal inertia in a turned inertial frame, not a full tensor."""
    if not np.any(inertia - np.diag(np.diag(inertia))):  # already principal: keep the body's axes
        return np.maximum(np.diag(inertia), 0.0), R.IDENTITY.copy()
    moments, axes = np.linalg.eigh(inertia)
    if np.linalg.det(axes) < 0:
        axes[:, 2] = -axes[:, 2]
    return np.maximum(moments, 0.0), R.from_matrix(axes[None])[0]


def _angle_limits(lo: float, hi: float, sign: float) -> tuple[float, float] | None:
    """A hinge's stops as pybullet's joint range (None: no stops), mirrored when sign is -1."""
    if lo <= -_FULL_TURN and hi >= _FULL_TURN:
        return None
    return tuple(sorted((sign * lo, sign * hi)))


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


@dataclass
class _Part:
    """A free base or one link of a multibody: what createMultiBody takes, and what reading it back needs."""
    row: int  # body row, or -1 for the massless link between two hinges
    parent: int  # the parent part, -1 for none (a free base, or a link on a fixed base)
    joint_type: int  # p.JOINT_FIXED for a free base
    axis: np.ndarray  # in the link frame
    position: np.ndarray  # link frame in the parent's link frame (for a base: in the world)
    orientation: np.ndarray  # w x y z
    offset: np.ndarray  # the body frame's origin in the link frame (the link frame is turned as the body)
    inertial: np.ndarray  # the centre of mass in the link frame
    principal: np.ndarray  # the principal axes in the link frame (the inertial frame's orientation)
    mass: float
    moments: np.ndarray  # principal moments of inertia
    limits: tuple[float, float] | None = None
    motor: tuple[float, float] | None = None  # target joint velocity, torque limit


@dataclass
class _Tree:
    """One multibody: a free body as its base (parts[0]), or a fixed base at the world origin."""
    free: bool
    parts: list[_Part] = field(default_factory=list)
    uid: int = -1
    dofs: int = 0  # generalized velocities, the free base's six included
    columns: list[int] = field(default_factory=list)  # each part's first velocity column

    @property
    def links(self) -> list[_Part]:
        return self.parts[1:] if self.free else self.parts

    def link(self, part: int) -> int:
        """pybullet's link index of a part (-1: the base)."""
        return part - 1 if self.free else part

    def joints(self, part: int) -> list[int]:
        """The parts whose joints move this one: itself and its ancestors, base excluded."""
        out = []
        while part >= 0 and self.parts[part].joint_type != p.JOINT_FIXED:
            out.append(part)
            part = self.parts[part].parent
        return out


class BulletSimulation:
    def __init__(self, world: World, dt: float):
        self.world = world
        b = world.bodies
        self.client = p.connect(p.DIRECT)
        c = self.client
        p.setGravity(*world.gravity, physicsClientId=c)
        p.setPhysicsEngineParameter(
            fixedTimeStep=dt, numSubSteps=_SUBSTEPS_ACCURATE if world.prefer_accuracy else 0,
            numSolverIterations=max(1, world.iterations), erp=world.error_correction, useSplitImpulse=0,
            physicsClientId=c)
        self.trees: list[_Tree] = []
        self.where: dict[int, tuple[int, int]] = {}  # body row -> (tree, part)
        self.frames: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # body row -> its link frame at the start
        for i in world.order:
            if not b.fixed[i]:
                self._place(i)
        for tree in self.trees:
            self._create(tree)
        # every part of every tree, flat, in the order _read returns them
        parts = [pt for tree in self.trees for pt in tree.parts]
        self.first = np.cumsum([0] + [len(tree.parts) for tree in self.trees])  # each tree's first part
        self.rows = np.array([pt.row for pt in parts], dtype=int)
        self.bodies = self.rows >= 0
        self.unturn = R.conjugate(np.array([pt.principal for pt in parts]).reshape(-1, 4))
        self.inertial = np.array([pt.inertial for pt in parts]).reshape(-1, 3)
        self.offset = np.array([pt.offset for pt in parts]).reshape(-1, 3)
        # per frame: the body origin is the centre of mass less the turned local offset between
        # them; most scenes have neither a turned principal frame nor an offset, and skip the maths
        self.turned = bool(np.any(self.unturn != R.IDENTITY))
        self.com_local = self.inertial - self.offset
        self.shifted = bool(np.any(self.com_local))
        self.static_anchor: int | None = None
        for k in world.loop_joints:
            self._loop(world.joints[k])
        self.moving = np.flatnonzero(~b.fixed)
        self.weight = -b.mass[:, None] * world.gravity * ~b.use_gravity[:, None]  # cancels gravity where it is off
        self.set_loads(b.forces, b.torques)
        self.set_velocities(b.linear_velocity, b.angular_velocity)

    # -- building -----------------------------------------------------------
    def _place(self, i: int) -> None:
        """Body i as the base or a link of a tree, after its parent."""
        w, b = self.world, self.world.bodies
        parent = int(w.parent[i])
        moments, principal = _principal(b.inertia[i])
        q = b.orientation[i]
        if parent == World.FREE:
            self.trees.append(_Tree(free=True, parts=[_Part(
                row=i, parent=-1, joint_type=p.JOINT_FIXED, axis=np.zeros(3), position=b.position[i], orientation=q,
                offset=np.zeros(3), inertial=b.com[i], principal=principal, mass=b.mass[i], moments=moments)]))
            self.where[i] = (len(self.trees) - 1, 0)
            self.frames[i] = (b.position[i], q)
            return
        j = w.joints[w.parent_joint[i]]
        if parent == STATIC:
            self.trees.append(_Tree(free=False))
            t, parent_part = len(self.trees) - 1, -1
            ppos, pq = np.zeros(3), R.IDENTITY
        else:
            t, parent_part = self.where[parent]
            ppos, pq = self.frames[parent]
        tree = self.trees[t]
        cq = R.conjugate(q)
        offset = R.rotate(cq, b.position[i] - j.anchor)
        axes = R.rotate(cq, j.axes)
        sign = -1.0 if i == j.body2 else 1.0  # pybullet: child relative to parent
        link = dict(row=i, parent=parent_part, position=R.rotate(R.conjugate(pq), j.anchor - ppos),
                    orientation=R.multiply(R.conjugate(pq), q), offset=offset, inertial=offset + b.com[i],
                    principal=principal, mass=b.mass[i], moments=moments)
        par = j.params
        if j.type == "BallJoint":
            tree.parts.append(_Part(joint_type=p.JOINT_SPHERICAL, axis=np.array([0.0, 0.0, 1.0]), **link))
        elif j.type == "SingleAxisHingeJoint":
            tree.parts.append(_Part(joint_type=p.JOINT_REVOLUTE, axis=axes[0],
                                    limits=_angle_limits(par["minAngle"], par["maxAngle"], sign), **link))
        elif j.type == "SliderJoint":
            limits = tuple(sorted((sign * par["minSeparation"], sign * par["maxSeparation"])))
            tree.parts.append(_Part(joint_type=p.JOINT_PRISMATIC, axis=axes[0], limits=limits, **link))
        elif j.type in ("UniversalJoint", "DoubleAxisHingeJoint"):
            if par.get("suspensionForce", 0.0) > 0:
                raise Unsupported(f"{j.type} {j.name}: suspensionForce (a soft joint) is not built by the bullet "
                                  "backend: pybullet's multibody joints have no compliance")
            hinges = [{"axis": axes[0]}, {"axis": axes[1]}]  # axis1 is carried by body1, axis2 by body2
            if j.type == "DoubleAxisHingeJoint":
                hinges[0]["limits"] = _angle_limits(par["minAngle1"], par["maxAngle1"], sign)
                for k, h in enumerate(hinges, 1):
                    if par[f"maxTorque{k}"] > 0:  # ODE's motor: a velocity constraint of bounded torque
                        h["motor"] = (sign * par[f"desiredAngularVelocity{k}"], par[f"maxTorque{k}"])
            first, second = hinges if i == j.body2 else hinges[::-1]  # the parent's hinge first
            # the link between the hinges is massless: two hinges in series, as in MuJoCo's body with two joints
            tree.parts.append(_Part(**{**link, "row": -1, "offset": np.zeros(3), "inertial": np.zeros(3),
                                       "principal": R.IDENTITY, "mass": 0.0, "moments": np.zeros(3)},
                                    joint_type=p.JOINT_REVOLUTE, **first))
            link.update(parent=len(tree.parts) - 1, position=np.zeros(3), orientation=R.IDENTITY)
            tree.parts.append(_Part(joint_type=p.JOINT_REVOLUTE, **link, **second))
        else:
            raise Unsupported(f"{j.type} {j.name}: not built by the bullet backend yet")
        self.where[i] = (t, len(tree.parts) - 1)
        self.frames[i] = (j.anchor, q)

    def _create(self, tree: _Tree) -> None:
        c = self.client
        base = tree.parts[0] if tree.free else None
        links = tree.links
        tree.uid = p.createMultiBody(
            baseMass=base.mass if base else 0.0, baseCollisionShapeIndex=-1, baseVisualShapeIndex=-1,
            basePosition=base.position if base else [0, 0, 0],
            baseOrientation=_xyzw(base.orientation if base else R.IDENTITY),
            baseInertialFramePosition=base.inertial if base else [0, 0, 0],
            baseInertialFrameOrientation=_xyzw(base.principal if base else R.IDENTITY),
            linkMasses=[lk.mass for lk in links], linkCollisionShapeIndices=[-1] * len(links),
            linkVisualShapeIndices=[-1] * len(links), linkPositions=[lk.position for lk in links],
            linkOrientations=[_xyzw(lk.orientation) for lk in links],
            linkInertialFramePositions=[lk.inertial for lk in links],
            linkInertialFrameOrientations=[_xyzw(lk.principal) for lk in links],
            linkParentIndices=[tree.link(lk.parent) + 1 for lk in links],  # pybullet counts the base as 0 here
            linkJointTypes=[lk.joint_type for lk in links], linkJointAxis=[lk.axis for lk in links],
            physicsClientId=c)
        if tree.uid < 0:
            raise Unsupported("pybullet refused to build a multibody")
        # pybullet damps multibodies and clamps their joint speeds by default
        p.changeDynamics(tree.uid, -1, linearDamping=0.0, angularDamping=0.0, maxJointVelocity=_MAX_SPEED,
                         physicsClientId=c)
        for k, part in enumerate(tree.parts):
            link = tree.link(k)
            tree.columns.append(tree.dofs)
            # without a collision shape a body has no inertia until given one, with its mass alongside
            p.changeDynamics(tree.uid, link, mass=part.mass, localInertiaDiagonal=part.moments, physicsClientId=c)
            if link < 0:
                tree.dofs += 6
                continue
            p.changeDynamics(tree.uid, link, jointDamping=0.0, physicsClientId=c)
            if part.limits is not None:
                p.changeDynamics(tree.uid, link, jointLowerLimit=part.limits[0], jointUpperLimit=part.limits[1],
                                 physicsClientId=c)
            if part.joint_type == p.JOINT_SPHERICAL:  # createMultiBody's joint motors hold every joint still
                p.setJointMotorControlMultiDof(tree.uid, link, p.POSITION_CONTROL, targetPosition=[0, 0, 0, 1],
                                               force=[0, 0, 0], physicsClientId=c)
                tree.dofs += 3
            else:
                target, limit = part.motor or (0.0, 0.0)
                p.setJointMotorControl2(tree.uid, link, p.VELOCITY_CONTROL, targetVelocity=target, force=limit,
                                        physicsClientId=c)
                tree.dofs += 1

    def _loop(self, j: Joint) -> None:
        """A ball joint closing a loop, as a point-to-point constraint (pybullet's createConstraint
        refuses revolute and spherical joints). Its pivots are in the centre-of-mass frames."""
        if j.body1 == j.body2 == STATIC:
            return  # it joins the static environment to itself: nothing moves
        if j.type != "BallJoint":
            raise Unsupported(f"{j.type} {j.name} closes a loop of joints; the bullet backend closes loops "
                              "with BallJoint only (pybullet's createConstraint refuses revolute joints)")
        ends, pivots = [], []
        com, q_com, _, _ = self._read(velocities=False)
        for row in (j.body1, j.body2):
            if row == STATIC:  # pybullet refuses a constraint from a free body to the world itself
                if self.static_anchor is None:
                    self.static_anchor = p.createMultiBody(baseMass=0.0, baseCollisionShapeIndex=-1,
                                                           physicsClientId=self.client)
                ends.append((self.static_anchor, -1))
                pivots.append(j.anchor)
                continue
            t, k = self.where[row]
            n = self.first[t] + k
            ends.append((self.trees[t].uid, self.trees[t].link(k)))
            pivots.append(R.rotate(R.conjugate(q_com[n]), j.anchor - com[n]))
        cid = p.createConstraint(*ends[0], *ends[1], p.JOINT_POINT2POINT, [0, 0, 0], pivots[0], pivots[1],
                                 physicsClientId=self.client)
        p.changeConstraint(cid, maxForce=_MAX_FORCE, physicsClientId=self.client)

    # -- running ------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        """n steps; pybullet forgets applied forces after each, so loads are applied before every one."""
        c = self.client
        forces, torques = self.forces, self.torques
        for _ in range(n):
            if self.loaded:
                com = np.zeros((len(forces), 3))
                com[self.rows[self.bodies]] = self._read(velocities=False)[0][self.bodies]
                for i in self.moving:
                    t, k = self.where[i]
                    uid, link = self.trees[t].uid, self.trees[t].link(k)
                    if forces[i].any():
                        p.applyExternalForce(uid, link, forces[i], com[i], p.WORLD_FRAME, physicsClientId=c)
                    if torques[i].any():
                        p.applyExternalTorque(uid, link, torques[i], p.WORLD_FRAME, physicsClientId=c)
            p.stepSimulation(physicsClientId=c)

    def _read(self, velocities: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Every part's centre of mass, principal frame orientation (w x y z), and with
        velocities, centre-of-mass velocity and angular velocity, in bulk, parts in order.
        (pybullet's link frame poses come rounded to single precision; these do not.)"""
        c = self.client
        rows = []
        zero = (0.0, 0.0, 0.0)
        for tree in self.trees:
            if tree.free:
                pos, q = p.getBasePositionAndOrientation(tree.uid, physicsClientId=c)
                lin, ang = p.getBaseVelocity(tree.uid, physicsClientId=c) if velocities else (zero, zero)
                rows.append((*pos, *q, *lin, *ang))
            if tree.links:
                for s in p.getLinkStates(tree.uid, list(range(len(tree.links))), computeLinkVelocity=int(velocities),
                                         computeForwardKinematics=1, physicsClientId=c):
                    lin, ang = (s[6], s[7]) if velocities else (zero, zero)
                    rows.append((*s[0], *s[1], *lin, *ang))
        a = np.array(rows, dtype=np.float64).reshape(-1, 13)
        return a[:, :3], _wxyz(a[:, 3:7]), a[:, 7:10], a[:, 10:13]

    def _frames(self, com: np.ndarray, q_com: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Every part's link frame (position, orientation) from its centre-of-mass frame."""
        q = R.multiply(q_com, self.unturn) if self.turned else q_com
        return com - R.rotate(q, self.inertial), q

    def state(self) -> State:
        b = self.world.bodies
        s = State.initial(b)
        s.linear_velocity[b.fixed] = 0.0
        s.angular_velocity[b.fixed] = 0.0
        com, q, v, w = self._read(velocities=True)
        if self.turned:
            q = R.multiply(q, self.unturn)
        rows, on = self.rows[self.bodies], self.bodies
        s.position[rows] = (com - R.rotate(q, self.com_local) if self.shifted else com)[on]
        s.orientation[rows], s.linear_velocity[rows], s.angular_velocity[rows] = q[on], v[on], w[on]
        return s

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        self.forces = forces + self.weight
        self.torques = np.array(torques, dtype=np.float64)
        self.loaded = bool(self.forces[self.moving].any() or self.torques[self.moving].any())

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        """The joint velocities whose body velocities come closest to those asked for (exact
        for free bodies): a least-squares fit through each tree's Jacobian at the centres of
        mass, built from the joints' current axes and pivots."""
        c = self.client
        all_com, q_com, _, _ = self._read(velocities=False)
        all_pos, q = self._frames(all_com, q_com)
        all_turn = R.matrix(q)
        for tree, first in zip(self.trees, self.first):
            if tree.free and not tree.links:
                row = tree.parts[0].row
                p.resetBaseVelocity(tree.uid, linear[row], angular[row], physicsClientId=c)
                continue
            mine = slice(first, first + len(tree.parts))
            com, frame_pos, turn = all_com[mine], all_pos[mine], all_turn[mine]
            bodies = [k for k, pt in enumerate(tree.parts) if pt.row >= 0]
            jac = np.zeros((6 * len(bodies), tree.dofs))
            target = np.zeros(6 * len(bodies))
            for n, k in enumerate(bodies):
                v, wv = slice(6 * n, 6 * n + 3), slice(6 * n + 3, 6 * n + 6)
                target[v], target[wv] = linear[tree.parts[k].row], angular[tree.parts[k].row]
                if tree.free:  # the base's centre-of-mass velocity and its angular velocity
                    jac[v, 0:3] = np.eye(3)
                    jac[v, 3:6] = -_skew(com[k] - com[0])
                    jac[wv, 3:6] = np.eye(3)
                for a in tree.joints(k):
                    part, col = tree.parts[a], tree.columns[a]
                    arm = com[k] - frame_pos[a]
                    if part.joint_type == p.JOINT_SPHERICAL:  # pybullet: angular velocity in the link frame
                        jac[wv, col:col + 3] = turn[a]
                        jac[v, col:col + 3] = -_skew(arm) @ turn[a]
                    elif part.joint_type == p.JOINT_REVOLUTE:
                        axis = turn[a] @ part.axis
                        jac[wv, col] = axis
                        jac[v, col] = np.cross(axis, arm)
                    else:
                        jac[v, col] = turn[a] @ part.axis
            qd = np.linalg.lstsq(jac, target, rcond=None)[0]
            for k, part in enumerate(tree.parts):
                link, col = tree.link(k), tree.columns[k]
                if link < 0:
                    p.resetBaseVelocity(tree.uid, qd[0:3], qd[3:6], physicsClientId=c)
                elif part.joint_type == p.JOINT_SPHERICAL:
                    position = p.getJointStateMultiDof(tree.uid, link, physicsClientId=c)[0]
                    p.resetJointStateMultiDof(tree.uid, link, position, qd[col:col + 3], physicsClientId=c)
                else:
                    position = p.getJointState(tree.uid, link, physicsClientId=c)[0]
                    p.resetJointState(tree.uid, link, position, qd[col], physicsClientId=c)

    def close(self) -> None:
        """Free the pybullet client (each simulation holds one)."""
        if self.client >= 0 and p.isConnected(self.client):
            p.disconnect(self.client)
        self.client = -1

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:  # at interpreter exit pybullet may be gone already
            pass


class BulletBackend(Backend):
    name = "bullet"
    declared = {
        **native(*BODIES, *JOINTS, "RigidBodyCollection.iterations", "DoubleAxisHingeJoint",
                 "DoubleAxisHingeJoint.anchorPoint", "DoubleAxisHingeJoint.axis1", "DoubleAxisHingeJoint.axis2",
                 "DoubleAxisHingeJoint.limits", "DoubleAxisHingeJoint.minAngle1",
                 "DoubleAxisHingeJoint.maxAngle1", "DoubleAxisHingeJoint.desiredAngularVelocity1",
                 "DoubleAxisHingeJoint.desiredAngularVelocity2", "DoubleAxisHingeJoint.maxTorque1",
                 "DoubleAxisHingeJoint.maxTorque2"),
        **approximate("pybullet has no per-body gravity switch: -m*g is applied at the centre of mass each step "
                      "(it cancels gravity to rounding)", "RigidBody.useGlobalGravity"),
        **approximate("tree joints are exact (reduced coordinates); errorCorrection sets pybullet's erp, which "
                      "acts on joint limits and loop constraints", "RigidBodyCollection.errorCorrection"),
        **unsupported("pybullet's multibody constraint rows (limits, loop joints) carry no CFM: the value cannot "
                      "reach them (tree joints are exact either way)", "RigidBodyCollection.constantForceMix"),
        **approximate(f"pybullet has one first-order integrator: {_SUBSTEPS_ACCURATE} internal substeps per step",
                      "RigidBodyCollection.preferAccuracy"),
        **unsupported("pybullet's multibody joints have no compliance and its constraint rows no CFM: ODE's "
                      "suspension spring cannot be expressed", "DoubleAxisHingeJoint.suspensionForce",
                      "DoubleAxisHingeJoint.suspensionErrorCorrection"),
        **unsupported("pybullet's joint limits are inelastic, with one global ERP and no CFM",
                      "SingleAxisHingeJoint.stopBounce", "SliderJoint.stopBounce",
                      "SingleAxisHingeJoint.stopErrorCorrection", "SliderJoint.stopErrorCorrection",
                      "DoubleAxisHingeJoint.stop1Bounce",
                      "DoubleAxisHingeJoint.stop1ErrorCorrection", "DoubleAxisHingeJoint.stop1ConstantForceMix"),
    }

    def version(self) -> str:
        return importlib.metadata.version("pybullet")

    def build(self, world: World, dt: float) -> BulletSimulation:
        return BulletSimulation(world, dt)


BACKEND = BulletBackend()
