"""MuJoCo backend (MjSpec): joints become a kinematic tree; loops become equalities.

Bodies are built in the world's tree order: a body on the static environment hangs
from the world body, a free body gets a free joint, a body whose parent joint is in
the tree gets that joint's degrees of freedom (a ball, a hinge, a slide, two hinges
for a universal joint). MuJoCo measures a child's joint coordinate relative to its
parent; x3d_core's outputs measure body1 relative to body2, so limits are mirrored
where the child is body2. State is read for every body at once from d.xpos, d.xquat
and d.cvel after the position and velocity stages of mj_forward (linear velocity at
each body's centre of mass).
"""

from __future__ import annotations

import mujoco
import numpy as np

from x3d_core import rotation as R
from x3d_core.engine import BlewUp, Unsupported
from x3d_core.world import STATIC, World, State

from .base import BODIES, JOINTS, Backend, approximate, native, unsupported

_FULL_TURN = np.pi - 1e-9  # an angle range this wide is no limit at all
# ODE's motors reach their target velocity in one step if the torque limit allows. A
# velocity servo with gain k = s * I / dt (I the child's inertia about the axis) closes
# the fraction s of the gap each step; s = 0.5 stays clear of explicit Euler's
# stability bound (s < 2) where the parent's inertia adds to I. Torque is clipped to
# maxTorque like ODE's fMax.
MOTOR_STEPS = 0.5


class MujocoSimulation:
    def __init__(self, world: World, dt: float):
        self.world = world
        b = world.bodies
        spec = mujoco.MjSpec()
        spec.compiler.degree = False
        spec.option.timestep = dt
        spec.option.gravity = world.gravity
        spec.option.iterations = max(1, world.iterations)
        if world.prefer_accuracy:
            spec.option.integrator = mujoco.mjtIntegrator.mjINT_RK4
        spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT  # collisions: the collision issue
        self.free = np.zeros(len(b), dtype=bool)
        self.dt = dt
        # (joint name, target velocity, torque limit, servo gain)
        self.motors: list[tuple[str, float, float, float]] = []
        handles = {}
        for i in world.order:
            p = world.parent[i]
            parent_body = spec.worldbody if p < 0 else handles[p]
            ppos, pq = (np.zeros(3), R.IDENTITY) if p < 0 else (b.position[p], b.orientation[p])
            cq = R.conjugate(pq)
            body = parent_body.add_body(name=f"b{i}", pos=R.rotate(cq, b.position[i] - ppos),
                                        quat=R.multiply(cq, b.orientation[i]))
            handles[i] = body
            body.explicitinertial = True
            body.mass = b.mass[i]
            body.ipos = b.com[i]
            m = b.inertia[i]
            body.fullinertia = [m[0, 0], m[1, 1], m[2, 2], m[0, 1], m[0, 2], m[1, 2]]
            if not b.use_gravity[i]:
                body.gravcomp = 1.0
            if b.fixed[i]:
                continue
            if p == World.FREE:
                body.add_freejoint()
                self.free[i] = True
            elif world.parent_joint[i] >= 0:
                self._tree_joint(body, i, world.joints[world.parent_joint[i]])
        for k in world.loop_joints:
            self._loop(spec, world.joints[k], dt)
        for name, _, limit, gain in self.motors:
            a = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            a.set_to_velocity(kv=gain)
            a.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
            a.forcerange = [-limit, limit]
            a.ctrllimited = mujoco.mjtLimited.mjLIMITED_FALSE
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        self.ids = np.array([self.model.body(f"b{i}").id for i in range(len(b))], dtype=int)
        self.roots = self.model.body_rootid[self.ids]
        # bodies are usually numbered in row order: read them as one slice (a view, no gather)
        n = len(self.ids)
        contiguous = n and np.array_equal(self.ids, np.arange(self.ids[0], self.ids[0] + n))
        self.rows = slice(int(self.ids[0]), int(self.ids[0]) + n) if contiguous else self.ids
        self.bad_acceleration = self.data.warning[mujoco.mjtWarning.mjWARN_BADQACC]
        # free bodies with nothing hanging from them take velocities directly (the usual
        # case for big scenes); anything jointed goes through a least-squares fit
        moving = ~b.fixed
        lone = self.free & ~np.isin(np.arange(len(b)), world.parent[world.parent >= 0])
        self.direct = np.flatnonzero(lone) if np.array_equal(lone, moving) else None
        if self.direct is not None:
            adr = self.model.jnt_dofadr[self.model.body_jntadr[self.ids[self.direct]]]
            self.dof_lin = adr[:, None] + np.arange(3)
            self.dof_ang = adr[:, None] + np.arange(3, 6)
        mujoco.mj_forward(self.model, self.data)
        self._set_body_velocities(b.linear_velocity, b.angular_velocity)
        self.set_loads(b.forces, b.torques)
        self.data.ctrl[:] = [target for _, target, _, _ in self.motors]

    # -- building -----------------------------------------------------------
    def _tree_joint(self, body, child: int, j) -> None:
        b = self.world.bodies
        cq = R.conjugate(b.orientation[child])
        pos = R.rotate(cq, j.anchor - b.position[child])
        axes = R.rotate(cq, j.axes)
        sign = -1.0 if child == j.body2 else 1.0  # MuJoCo: child relative to parent
        if j.type == "BallJoint":
            body.add_joint(type=mujoco.mjtJoint.mjJNT_BALL, pos=pos)
        elif j.type == "SingleAxisHingeJoint":
            jt = body.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, pos=pos, axis=axes[0])
            self._limit(jt, j.params["minAngle"], j.params["maxAngle"], sign, j.params["stopErrorCorrection"])
        elif j.type == "SliderJoint":
            jt = body.add_joint(type=mujoco.mjtJoint.mjJNT_SLIDE, pos=pos, axis=axes[0])
            self._limit(jt, j.params["minSeparation"], j.params["maxSeparation"], sign,
                        j.params["stopErrorCorrection"], angular=False)
        elif j.type == "UniversalJoint":
            first, second = (axes[0], axes[1]) if child == j.body2 else (axes[1], axes[0])
            body.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, pos=pos, axis=first)
            body.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, pos=pos, axis=second)
        elif j.type == "DoubleAxisHingeJoint":
            self._hinge2(body, child, j, pos, axes, sign)
        else:
            raise Unsupported(f"{j.type} {j.name}: not built by the mujoco backend yet")

    def _hinge2(self, body, child: int, j, pos: np.ndarray, axes: np.ndarray, sign: float) -> None:
        """ODE's hinge2: a hinge about axis 1 (carried by body1, with its limits and motor),
        a suspension spring along axis 1 (ODE's k = ERP/(h*CFM), c = (1-ERP)/CFM) and a hinge
        about axis 2 (carried by body2, with its motor)."""
        p = j.params

        def hinge(k: int) -> None:
            jt = body.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, pos=pos, axis=axes[k - 1], name=f"{j.name}:{k}")
            if k == 1:
                self._limit(jt, p["minAngle1"], p["maxAngle1"], sign, p["stop1ErrorCorrection"])

        def suspension() -> None:
            if p["suspensionForce"] > 0:
                dt, cfm, erp = self.dt, p["suspensionForce"], p["suspensionErrorCorrection"]
                # MuJoCo's Euler step takes damping implicitly and stiffness explicitly: ODE's
                # implicit spring-damper (k = ERP/(h CFM), c = (1-ERP)/CFM) is then exactly
                # stiffness k with damping c + h k = 1/CFM
                body.add_joint(type=mujoco.mjtJoint.mjJNT_SLIDE, pos=pos, axis=axes[0],
                               stiffness=erp / (dt * cfm), damping=1.0 / cfm)

        # MuJoCo chains a body's joints from its parent outwards: the parent's axis first
        if child == j.body2:
            hinge(1), suspension(), hinge(2)
        else:
            hinge(2), hinge(1), suspension()
        b = self.world.bodies
        com = b.com[child]
        for k in (1, 2):
            if p[f"maxTorque{k}"] > 0:
                a = axes[k - 1]  # the child's inertia about the motor's axis line sets the servo gain
                r = (com - pos) - a * (a @ (com - pos))
                inertia = a @ b.inertia[child] @ a + b.mass[child] * (r @ r)
                self.motors.append((f"{j.name}:{k}", sign * p[f"desiredAngularVelocity{k}"], p[f"maxTorque{k}"],
                                    MOTOR_STEPS * inertia / self.dt))

    def _limit(self, jt, lo: float, hi: float, sign: float, erp: float, angular: bool = True) -> None:
        """A stop whose error a step corrects by the fraction ERP: MuJoCo's limit time constant
        dt/ERP, critically damped, no shorter than the 2 dt MuJoCo needs to stay stable."""
        if angular and lo <= -_FULL_TURN and hi >= _FULL_TURN:
            return
        a, b = sorted((sign * lo, sign * hi))
        jt.limited = mujoco.mjtLimited.mjLIMITED_TRUE
        jt.range = [a, b]
        jt.solref_limit = [max(2 * self.dt, self.dt / max(erp, 1e-9)), 1.0]

    def _loop(self, spec, j, dt: float) -> None:
        """A joint closing a loop, as equality constraints between body frames."""
        if j.body1 == j.body2 or (j.body1 == STATIC and j.body2 == STATIC):
            return  # both ends in the static environment: nothing to hold together
        if j.type not in ("BallJoint", "SingleAxisHingeJoint"):
            raise Unsupported(f"{j.type} {j.name} closes a loop of joints; the mujoco backend closes loops "
                              "with BallJoint and SingleAxisHingeJoint only")
        b = self.world.bodies
        points = [j.anchor] if j.type == "BallJoint" else [j.anchor, j.anchor + j.axes[0]]
        for point in points:  # a hinge is two points held together along its axis
            names, local = [], None
            for row in (j.body1, j.body2):
                names.append("world" if row == STATIC else f"b{row}")
            if j.body1 == STATIC:
                local = point
            else:
                local = R.rotate(R.conjugate(b.orientation[j.body1]), point - b.position[j.body1])
            eq = spec.add_equality(type=mujoco.mjtEq.mjEQ_CONNECT, objtype=mujoco.mjtObj.mjOBJ_BODY,
                                   name1=names[0], name2=names[1], solref=[2 * dt, 1.0])
            data = np.array(eq.data)
            data[:3] = local  # the anchor in body1's frame; the rest keeps MuJoCo's defaults
            eq.data = data

    # -- running ------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        mujoco.mj_step(self.model, self.data, nstep=n)
        if self.bad_acceleration.number:  # MuJoCo resets the state and goes on: a blow-up it would hide
            raise BlewUp("MuJoCo found a non-finite or huge acceleration at degree of freedom "
                         f"{self.bad_acceleration.lastinfo}")

    def _forward_kinematics(self) -> None:
        m, d = self.model, self.data
        mujoco.mj_kinematics(m, d)
        mujoco.mj_comPos(m, d)
        mujoco.mj_comVel(m, d)

    def state(self) -> State:
        self._forward_kinematics()
        d = self.data
        rows = self.rows
        cvel = d.cvel[rows]  # [angular, linear at the subtree centre of the body's root]
        ang = cvel[:, :3].copy()
        lin = cvel[:, 3:] + R.cross(ang, d.xipos[rows] - d.subtree_com[self.roots])
        return State(d.xpos[rows].copy(), d.xquat[rows].copy(), lin, ang)

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        self._set_body_velocities(linear, angular)

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        self.data.xfrc_applied[self.ids, :3] = forces  # MuJoCo keeps these until changed
        self.data.xfrc_applied[self.ids, 3:] = torques

    def _set_body_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        """The joint velocities whose body velocities come closest to those asked for
        (exact for free bodies: a least-squares fit through the body Jacobians)."""
        m, d = self.model, self.data
        if m.nv == 0:
            return
        self._forward_kinematics()
        if self.direct is not None:  # a free joint moves its origin: v_origin = v_com - w x (com - origin)
            rows, ids = self.direct, self.ids[self.direct]
            d.qvel[self.dof_lin] = linear[rows] - R.cross(angular[rows], d.xipos[ids] - d.xpos[ids])
            d.qvel[self.dof_ang] = R.rotate(R.conjugate(d.xquat[ids]), angular[rows])  # body frame
            return
        moving = [i for i in range(len(self.ids)) if not self.world.bodies.fixed[i]]
        jac = np.zeros((6 * len(moving), m.nv))
        target = np.zeros(6 * len(moving))
        for r, i in enumerate(moving):
            jacp, jacr = np.zeros((3, m.nv)), np.zeros((3, m.nv))
            mujoco.mj_jacBodyCom(m, d, jacp, jacr, self.ids[i])
            jac[6 * r:6 * r + 3], jac[6 * r + 3:6 * r + 6] = jacp, jacr
            target[6 * r:6 * r + 3], target[6 * r + 3:6 * r + 6] = linear[i], angular[i]
        d.qvel[:] = np.linalg.lstsq(jac, target, rcond=None)[0]


class MujocoBackend(Backend):
    name = "mujoco"
    declared = {
        **native(*BODIES, *JOINTS, "RigidBody.useGlobalGravity", "RigidBodyCollection.iterations",
                 "DoubleAxisHingeJoint", "DoubleAxisHingeJoint.anchorPoint", "DoubleAxisHingeJoint.axis1",
                 "DoubleAxisHingeJoint.axis2", "DoubleAxisHingeJoint.limits", "DoubleAxisHingeJoint.minAngle1",
                 "DoubleAxisHingeJoint.maxAngle1", "DoubleAxisHingeJoint.suspensionForce",
                 "DoubleAxisHingeJoint.suspensionErrorCorrection"),
        **approximate(f"a velocity servo closing {MOTOR_STEPS:g} of the speed gap per step, torque clipped "
                      "to maxTorque, for ODE's velocity constraint",
                      "DoubleAxisHingeJoint.desiredAngularVelocity1", "DoubleAxisHingeJoint.desiredAngularVelocity2",
                      "DoubleAxisHingeJoint.maxTorque1", "DoubleAxisHingeJoint.maxTorque2"),
        **unsupported("MuJoCo limits are soft constraints without a restitution coefficient",
                      "DoubleAxisHingeJoint.stop1Bounce"),
        **unsupported("limit softness is MuJoCo's solimp, not mapped from a CFM",
                      "DoubleAxisHingeJoint.stop1ConstantForceMix"),
        **approximate("MuJoCo has no ERP/CFM: tree joints are exact (generalized coordinates) and loop "
                      "constraints use solref=(2*dt, 1)",
                      "RigidBodyCollection.errorCorrection", "RigidBodyCollection.constantForceMix"),
        **approximate("selects MuJoCo's RK4 integrator (the iterative solver is used either way)",
                      "RigidBodyCollection.preferAccuracy"),
        **unsupported("MuJoCo limits are soft constraints without a restitution coefficient",
                      "SingleAxisHingeJoint.stopBounce", "SliderJoint.stopBounce"),
        **approximate("a soft limit with time constant max(2 dt, dt/ERP), critically damped: MuJoCo cannot "
                      "correct more than half the error in one step",
                      "SingleAxisHingeJoint.stopErrorCorrection", "SliderJoint.stopErrorCorrection",
                      "DoubleAxisHingeJoint.stop1ErrorCorrection"),
    }

    def version(self) -> str:
        return mujoco.__version__

    def build(self, world: World, dt: float) -> MujocoSimulation:
        return MujocoSimulation(world, dt)


BACKEND = MujocoBackend()
