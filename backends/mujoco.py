"""MuJoCo backend (MjSpec): joints become a kinematic tree; loops become equalities.

Bodies are built in the world's tree order: a body on the static environment hangs
from the world body, a free body gets a free joint, a body whose parent joint is in
the tree gets that joint's degrees of freedom (a ball, a hinge, a slide, two hinges
for a universal joint). MuJoCo measures a child's joint coordinate relative to its
parent; x3d_core's outputs measure body1 relative to body2, so limits are mirrored
where the child is body2. State is read for every body at once from d.xpos, d.xquat
and d.cvel after the position and velocity stages of mj_forward (linear velocity at
each body's centre of mass).

Collisions (world.collisions): a geom per Geometry on its body (static ones on the world
body), massless (bodies keep the scene's inertia): boxes, spheres and cylinders natively
(MuJoCo's cylinder axis z turned onto y), a cone as the hull of a 64-gon and its apex, a
mesh as MuJoCo's convex hull of its points (a flat one as a thin slab behind its faces), an
ElevationGrid on the static environment or a fixed body as a height field. Every pair that
collisions.may_touch allows, with a side able to move, is an explicit `pair` carrying the
collection's parameters: friction [mu2, mu1] (MuJoCo's first tangent is z on a floor,
ODE's x) with condim 3 on an elliptic cone, softened friction rows and no-slip iterations
(FRICTION_BDT), or condim 1 without friction; solref from bounce, softness or the world's
ERP; with a surface layer, a damper pair from touching and a spring pair from the layer's
depth (_layers). Two immovable geoms get no pair (it would exert nothing, so contacts()
never lists such contacts). Explicit pairs are all tested every step: measured with N
spheres in a box (dt 1/240), 20900 pairs stepped in 0.60 ms against 0.52 ms through
contype/conaffinity and the broad phase, and built in 0.17 s against 0.02 s; 81800 pairs
took 2.1 ms and 1.1 s against 1.5 ms and 0.06 s. Past PAIR_CAP pairs, geoms therefore
collide through contype/conaffinity with an `exclude` per joined body pair: the same
parameters per geom combine to the same values (MuJoCo takes the max friction, mixes or
takes the stiffer solref), except that mu2, the softer friction rows, the layer's two pairs
and the pair's reduced mass for softness are lost (mu1 everywhere; friction rows as stiff as
the normal's; margin -thickness; each geom's own body mass). contacts() reads d.contact:
normal frame[0:3] from geom1 to geom2, depth -dist. A set only sensors watch (world.watched)
is geoms on the same bodies with contype and conaffinity 0, which no step collides; at each
frame's end mj_geomDistance tests its pairs where the bodies are (watched_contacts).
"""

from __future__ import annotations

import os
import sys

# No renderer: unless the user chose a GL backend, mujoco's import skips its GL context and
# glfw (about 90 ms of every run's start; this backend never draws)
os.environ.setdefault("MUJOCO_GL", "disable")
import mujoco  # noqa: E402  (after MUJOCO_GL)
import numpy as np  # noqa: E402

from x3d_core.semantics import rotation as R
from x3d_core.semantics.collision import Collisions, ContactPoints, Geometry, friction_directions
from x3d_core.semantics.engine import BlewUp, Unsupported
from x3d_core.semantics.world import STATIC, World, State

from .base import BODIES, JOINTS, RK4, SEMI_IMPLICIT, Backend, Declared, Support, approximate, native, unsupported

def _warning(text: str) -> None:
    """MuJoCo's warnings, out of MUJOCO_LOG.TXT: each is counted in d.warning, and step() turns
    those of a state MuJoCo reset into a blow-up (so they are not printed again); others go
    to stderr as one line."""
    if not text.startswith("Nan, Inf or huge value"):
        print(f"MuJoCo warning: {text.strip()}", file=sys.stderr)


mujoco.set_mju_user_warning(_warning)

_FULL_TURN = np.pi - 1e-9  # an angle range this wide is no limit at all
# ODE's motors reach their target velocity in one step if the torque limit allows. A
# velocity servo with gain k = s * I / dt (I the child's inertia about the axis) closes
# the fraction s of the gap each step; s = 0.5 stays clear of explicit Euler's
# stability bound (s < 2) where the parent's inertia adds to I. Torque is clipped to
# maxTorque like ODE's fMax.
MOTOR_STEPS = 0.5

# -- collisions ---------------------------------------------------------------
# Every allowed geometry pair becomes an explicit MuJoCo `pair` (exact friction, solref and
# filtering per pair) up to this many pairs; beyond, geoms collide through contype/conaffinity
# bits with `exclude`s for joined bodies (MuJoCo's broad phase: explicit pairs are all tested
# every step, see the module notes for the cost measured).
PAIR_CAP = 20000
# Friction: Coulomb's elliptic cone per pair. MuJoCo's convex contact model (Anitescu's
# relaxation) lets a sliding contact push its bodies apart: a 1 kg box put down sliding at 3 m/s
# (mu 0.6) hopped at 1.3 m/s with friction rows as stiff as the normal's (b = 1/dt), and its
# speed strayed 0.8 m/s from v0 - mu g t. Softer friction rows (damping FRICTION_BDT/dt) ask
# less of the cone: measured at dt 1/240 (b dt = 0.1 / 0.15 / 0.2), the hop fell to 0.12 /
# 0.19 / 0.28 m/s and the speed error to 0.08 / 0.11 / 0.17 m/s, a box sliding down a 35 deg
# incline kept a = g (sin - mu cos) within 0.03 %, while sticking got softer: a stack of five
# boxes under a 1 m/s^2 sideways load crept 1.6 / 1.2 / 1.0 mm in 10 s (16 mm at dt 1/60 with
# 0.15), a box on a 20 deg incline 0.56 / 0.37 / 0.28 mm in 2 s. MuJoCo's no-slip pass (PGS on
# the friction rows with the normal forces held) stops the rest of the creep: without it the
# stack slid 131 mm. (Friction 1e4 times softer than the normal, impratio 1e-4, with the
# no-slip pass solving friction alone removes the hop but not the creep: with the normal forces
# fixed, friction's torque cannot shift them and the stack slid 220 mm.) Those figures were
# taken with MuJoCo's default impedance; with the hard contacts' (HARD_SOLIMP) the stack crept
# 0.6 mm (11 mm at dt 1/60, 0.06 mm at 1/1000).
FRICTION_BDT = 0.15
NOSLIP_ITERATIONS = 30
CONE_EDGES = 64  # a cone collides as the hull of its apex and a 64-gon: radius error 1 - cos(pi/64) = 0.12 %
_Z_TO_Y = np.array([np.sqrt(0.5), -np.sqrt(0.5), 0.0, 0.0])  # MuJoCo's cylinder and hfield axis z onto X3D's y
# MuJoCo has no restitution coefficient: a bouncing contact is a spring-damper (direct solref
# -k, -b, acceleration units) with natural frequency w/dt and damping ratio zeta. A soft
# contact lets go when its force reaches zero, so e(zeta) is the unilateral Kelvin-Voigt law
# as MuJoCo's step discretises it. The table is e measured in MuJoCo 4.0 without gravity,
# averaged over where in a step the contact begins (dt, mass and speed drop out: the law is in
# accelerations and w is per step). That phase moves e by up to +-0.055 about the table, and
# gravity during the contact lowers e by about 2 g dt / (w v) at impact speed v. w = 0.35
# trades those against the penetration of the bounce (about 1.3 v dt / w deep: 3.5 cm at
# 4.4 m/s, dt = 1/240); damping is capped at b dt = 0.75 (w = 0.375/zeta past zeta = 1.07),
# where MuJoCo's step stays stable.
_BOUNCE_ZETA = np.array([0, 0.025, 0.05, 0.075, 0.1, 0.125, 0.15, 0.175, 0.2, 0.225, 0.25, 0.275, 0.3, 0.325, 0.35,
                         0.375, 0.4, 0.425, 0.45, 0.475, 0.5, 0.525, 0.55, 0.575, 0.6, 0.625, 0.65, 0.675, 0.7, 0.725,
                         0.75, 0.775, 0.8, 0.825, 0.85, 0.875, 0.9, 0.925, 0.95, 0.975, 1, 1.1, 1.25, 1.5, 1.75, 2,
                         2.5, 3, 4])
_BOUNCE_E = np.array([1.0000, 0.9257, 0.8585, 0.7975, 0.7420, 0.6913, 0.6449, 0.6025, 0.5638, 0.5283, 0.4956, 0.4654,
                      0.4374, 0.4113, 0.3873, 0.3652, 0.3448, 0.3259, 0.3082, 0.2916, 0.2760, 0.2612, 0.2475, 0.2349,
                      0.2232, 0.2122, 0.2019, 0.1922, 0.1830, 0.1741, 0.1657, 0.1577, 0.1504, 0.1437, 0.1374, 0.1314,
                      0.1257, 0.1203, 0.1150, 0.1099, 0.1050, 0.0889, 0.0729, 0.0541, 0.0415, 0.0329, 0.0220, 0.0158,
                      0.0092])
BOUNCE_W, BOUNCE_BDT = 0.35, 0.75
# A contact without bounce is ODE's hard one as MuJoCo's step takes it: a damper that stops
# the approach in one step (b dt = 1; past 1 it overshoots into a rebound of b dt - 1) and a
# spring that undoes ERP of the depth a step (k dt^2 = ERP, up to 0.25: at X3D's default ERP
# 0.8 the stiffer springs let a box on a 20 degree incline, mu 0.5, slide 0.16 m in 2 s,
# against 0.4 mm at 0.25). Like ODE's, that correction leaves the body moving out at ERP
# depth/dt: measured over landing phases at ERP 0.2, a rebound of 0.11 of the impact speed on
# average (0.02 to 0.20; ODE's ERP times the fraction of a step's travel the body had sunk
# when found). The same caps bound softness springs and dampers.
HARD_W, HARD_BDT = 0.5, 1.0
# MuJoCo's default impedance (0.9 to 0.95 over the first millimetre) leaves (1-d)/d of a resting
# load on the spring: 0.1 mm for a body at rest at ERP 0.2, dt 1/240. A hard contact takes
# 0.99: a tenth of that.
HARD_SOLIMP = [0.99, 0.99, 0.001, 0.5, 2.0]


def bounce_spring(e: float, dt: float, w_max: float = BOUNCE_W) -> tuple[float, float]:
    """(stiffness, damping) per unit mass of a contact that rebounds with restitution e."""
    zeta = float(np.interp(min(max(e, 0.0), 1.0), _BOUNCE_E[::-1], _BOUNCE_ZETA[::-1]))
    w = min(w_max, BOUNCE_BDT / (2 * zeta)) if zeta > 0 else w_max
    return (w / dt) ** 2, 2 * zeta * w / dt


def _too_light(world: World) -> str | None:
    """Why MuJoCo refuses a moving body's mass or inertia, or None: its compiler stops on a mass
    or a principal moment under mjMINVAL (1e-15), as other engines on what they cannot invert."""
    b = world.bodies
    for i in np.flatnonzero(~b.fixed):
        least = float(np.linalg.eigvalsh(b.inertia[i])[0])
        if not (b.mass[i] >= mujoco.mjMINVAL and least >= mujoco.mjMINVAL):
            return (f"RigidBody {b.names[i]}: mass {b.mass[i]:g} kg, least principal moment {least:g} kg m^2: "
                    f"MuJoCo refuses a moving body's mass or inertia under mjMINVAL ({mujoco.mjMINVAL:g})")
    return None


class MujocoSimulation:
    def __init__(self, world: World, dt: float):
        self.world = world
        b = world.bodies
        too_light = _too_light(world)
        if too_light:
            raise Unsupported(too_light)
        spec = mujoco.MjSpec()
        spec.compiler.degree = False
        spec.option.timestep = dt
        spec.option.gravity = world.gravity
        spec.option.iterations = max(1, world.iterations)
        if world.prefer_accuracy:
            spec.option.integrator = mujoco.mjtIntegrator.mjINT_RK4
        if world.collisions is None:
            spec.option.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT
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
        self.geometry_of = None  # MuJoCo geom id -> index into collisions.geometries (-1: none)
        self.pair_mode = None
        self.layered = False  # two pairs per geometry pair (the surface layer)
        if world.collisions is not None:
            self._collisions(spec, handles, world.collisions)
        for n, c in enumerate(world.watched):  # geoms no contact is made for: contype and conaffinity 0
            for k, g in enumerate(c.geometries):
                geom = self._geom(spec, spec.worldbody if g.body == STATIC else handles[g.body], g, f"w{n}_{k}",
                                  g.body == STATIC or bool(b.fixed[g.body]))
                if geom is not None:
                    geom.name, geom.contype, geom.conaffinity = f"w{n}_{k}", 0, 0
        for name, _, limit, gain in self.motors:
            a = spec.add_actuator(name=name, target=name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            a.set_to_velocity(kv=gain)
            a.forcelimited = mujoco.mjtLimited.mjLIMITED_TRUE
            a.forcerange = [-limit, limit]
            a.ctrllimited = mujoco.mjtLimited.mjLIMITED_FALSE
        self.model = spec.compile()
        self.data = mujoco.MjData(self.model)
        if world.collisions is not None:
            self.geometry_of = np.full(self.model.ngeom, -1, dtype=int)
            for k, name in self.geom_names.items():
                self.geometry_of[self.model.geom(name).id] = k
            if self.conveyors:  # MuJoCo's surface velocity is in the geom's frame (meshes are re-posed)
                mujoco.mj_kinematics(self.model, self.data)
                for name in self.conveyors:
                    gid = self.model.geom(name).id
                    frame = self.data.geom_xmat[gid].reshape(3, 3)
                    self.model.geom_surfacevel[gid, :3] = frame.T @ self.surface_velocity
        self.watched = [self._watched_pairs(n, c) for n, c in enumerate(world.watched)]
        self.ids = np.array([self.model.body(f"b{i}").id for i in range(len(b))], dtype=int)
        self.roots = self.model.body_rootid[self.ids]
        # bodies are usually numbered in row order: read them as one slice (a view, no gather)
        n = len(self.ids)
        contiguous = n and np.array_equal(self.ids, np.arange(self.ids[0], self.ids[0] + n))
        self.rows = slice(int(self.ids[0]), int(self.ids[0]) + n) if contiguous else self.ids
        # MuJoCo resets the state when one is non-finite or beyond mjMAXVAL (1e10) and goes on: the
        # three counters it raises then, read after every batch of steps (three integers)
        self.bad = [(self.data.warning[k], what) for k, what in (
            (mujoco.mjtWarning.mjWARN_BADQPOS, "position"), (mujoco.mjtWarning.mjWARN_BADQVEL, "velocity"),
            (mujoco.mjtWarning.mjWARN_BADQACC, "acceleration"))]
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
            if j.stops is not None:
                self._limit(jt, *j.stops, sign, j.params["stopErrorCorrection"], angular=False)
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
        if b - a < 1e-9:  # equal stops lock the joint; MuJoCo wants an open range
            a, b = (a + b) / 2 - 5e-10, (a + b) / 2 + 5e-10
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

    # -- collisions ---------------------------------------------------------
    def _collisions(self, spec, handles, col: Collisions) -> None:
        """A geom per Geometry (no mass: bodies keep the scene's inertia), and the pairs that
        may touch: explicit pairs carrying the collection's contact parameters, or, past
        PAIR_CAP pairs, contype/conaffinity bits with excludes for joined bodies."""
        b, p = self.world.bodies, col.parameters
        immovable = [g.body == STATIC or bool(b.fixed[g.body]) for g in col.geometries]
        layers = 2 if p.surface_thickness > 0 and p.bounce <= 0 else 1  # see _layers
        self.pair_mode = layers * _pair_count(col, immovable) <= PAIR_CAP
        mu1, mu2 = (float(x) for x in p.friction)
        self.frictional = max(mu1, mu2) > 0
        if self.frictional:
            spec.option.cone = mujoco.mjtCone.mjCONE_ELLIPTIC
            spec.option.noslip_iterations = NOSLIP_ITERATIONS
        # the surface moves along ODE's friction directions of the upward normal
        g = np.asarray(self.world.gravity, dtype=np.float64)
        up = -g / np.linalg.norm(g) if np.linalg.norm(g) > 0 else np.array([0.0, 1.0, 0.0])
        t1, t2 = friction_directions(up)
        self.surface_velocity = p.surface_speed[0] * t1[0] + p.surface_speed[1] * t2[0]
        moving_surface = bool(np.any(self.surface_velocity))
        self.geom_names: dict[int, str] = {}
        self.conveyors: list[str] = []
        for k, geometry in enumerate(col.geometries):
            parent = spec.worldbody if geometry.body == STATIC else handles[geometry.body]
            geom = self._geom(spec, parent, geometry, k, immovable[k])
            if geom is None:
                continue
            name = f"c{k}"
            geom.name = name
            geom.contype = geom.conaffinity = 0 if self.pair_mode else 1
            # MuJoCo adds the two geoms' margins and gaps (a pair's are its own)
            geom.margin, geom.gap = -p.surface_thickness / 2, p.surface_thickness / 2
            geom.condim = 3 if self.frictional else 1
            geom.friction = [mu1, 0.0, 0.0]
            geom.solref = self._solref(0.0 if immovable[k] else 1.0 / b.mass[geometry.body], immovable[k])
            if self._solimp() is not None:
                geom.solimp = self._solimp()
            self.geom_names[k] = name
            if moving_surface and immovable[k]:
                geom.surfacevel = [*self.surface_velocity, 0.0, 0.0, 0.0]  # made geom-local after compiling
                self.conveyors.append(name)
        if self.pair_mode:
            self._pairs(spec, col, immovable, mu1, mu2)
        else:
            for lo, hi in sorted(col.excluded):
                spec.add_exclude(bodyname1="world" if lo == STATIC else f"b{lo}", bodyname2=f"b{hi}")

    def _solref(self, inverse_mass: float, static: bool = False) -> list[float]:
        """The contact's solref for these contact parameters. inverse_mass: 1/m1 + 1/m2 of the
        pair (ODE's softness spring is in newtons; MuJoCo's in accelerations)."""
        p, dt, w = self.world.collisions.parameters, self.dt, self.world
        soft = p.softness_erp is not None or p.softness_cfm is not None
        bounce = p.bounce > 0
        if not (soft or bounce):  # ODE's hard contact: approach stopped in a step, ERP of the depth undone a step
            k = min(max(w.error_correction, 1e-6), HARD_W ** 2) / dt ** 2
            return [-k, -HARD_BDT / dt]
        if static and soft:  # bits mode: a static geom defers to the moving one (MuJoCo takes the stiffer)
            return [-1e-12, -1e-12]
        w_max = BOUNCE_W
        if soft:
            erp = p.softness_erp if p.softness_erp is not None else w.error_correction
            cfm = p.softness_cfm if p.softness_cfm is not None else w.constant_force_mix
            big = np.inf if cfm <= 0 else 1.0
            k = big * max(erp, 0.0) / (dt * max(cfm, 1e-300)) * inverse_mass
            c = big * max(1.0 - erp, 0.0) / max(cfm, 1e-300) * inverse_mass
            if not bounce:
                return [-max(min(k, (HARD_W / dt) ** 2), 1e-9), -max(min(c, HARD_BDT / dt), 1e-9)]
            w_max = max(min(BOUNCE_W, np.sqrt(k) * dt), 1e-6)
        k, c = bounce_spring(p.bounce, dt, w_max)
        return [-k, -c]

    def _pairs(self, spec, col: Collisions, immovable: list[bool], mu1: float, mu2: float) -> None:
        b = self.world.bodies
        groups: dict[int, list[int]] = {}
        for k in self.geom_names:
            groups.setdefault(col.geometries[k].body, []).append(k)
        rows = sorted(groups)
        # MuJoCo's first tangent is the normal's closest to world y, else z: along z for a
        # horizontal floor, where ODE's first friction direction is along x
        friction = [mu2, mu1, 0.0, 0.0, 0.0]
        for i, r in enumerate(rows):
            for s in rows[i + 1:]:
                a, c = groups[r][0], groups[s][0]
                if immovable[a] and immovable[c]:
                    continue  # neither side can move: nothing to solve
                if (min(r, s), max(r, s)) in col.excluded:
                    continue
                inverse = sum(0.0 if immovable[groups[x][0]] else 1.0 / b.mass[x] for x in (r, s))
                layers = self._layers(self._solref(inverse), self._solimp())
                for g1 in groups[r]:
                    for g2 in groups[s]:
                        for solref, solimp, margin, gap in layers:
                            pair = spec.add_pair(geomname1=self.geom_names[g1], geomname2=self.geom_names[g2])
                            pair.condim = 3 if self.frictional else 1
                            pair.friction = friction
                            pair.solref = solref
                            pair.solreffriction = [-1e-9, -FRICTION_BDT / self.dt]
                            pair.margin, pair.gap = margin, gap
                            if solimp is not None:
                                pair.solimp = solimp

    def _solimp(self) -> list[float] | None:
        """HARD_SOLIMP for a contact without bounce or softness (None: MuJoCo's default)."""
        p = self.world.collisions.parameters
        hard = p.bounce <= 0 and p.softness_erp is None and p.softness_cfm is None
        return HARD_SOLIMP if hard else None

    def _layers(self, solref: list[float], solimp: list[float] | None) -> list[tuple]:
        """The pairs (solref, solimp, margin, gap) one geometry pair becomes. ODE's surface layer
        L stops the approach at first touch but corrects depth only past L: with L > 0 a
        contact without bounce is two pairs, a damper from touching (impedance 0.9999: a
        resting load leaks through it at 1e-4 g / b, 4 micrometres a second at dt 1/240) and
        the spring from depth L. A bouncing contact keeps one pair from touching: the layer
        is not applied to it."""
        thickness = self.world.collisions.parameters.surface_thickness
        if thickness <= 0 or self.world.collisions.parameters.bounce > 0:
            return [(solref, solimp, 0.0, 0.0)]
        self.layered = True
        k, c = -solref[0], -solref[1]
        if solref[0] > 0:  # not reached: without bounce the solref is direct
            raise AssertionError(solref)
        return [([-1e-9, -c], [0.9999, 0.9999, 0.001, 0.5, 2.0], 0.0, 0.0),
                ([-k, -1e-9], solimp, -thickness, 0.0)]

    def _watched_pairs(self, n: int, c: Collisions) -> list[tuple[int, int, int, int]]:
        """Watched set n's pairs may_touch allows, as (geometry, geometry, MuJoCo geom, MuJoCo geom)."""
        names = {self.model.geom(i).name: i for i in range(self.model.ngeom)}
        i, j = np.triu_indices(len(c.geometries), 1)
        kept = c.may_touch(i, j)
        return [(a, b, names[f"w{n}_{a}"], names[f"w{n}_{b}"]) for a, b in zip(i[kept].tolist(), j[kept].tolist())
                if f"w{n}_{a}" in names and f"w{n}_{b}" in names]

    def _geom(self, spec, parent, g: Geometry, k: int | str, immovable: bool):
        """A MuJoCo geom for one Geometry, or None where it has no volume to collide with."""
        tiny = 1e-9
        geom_type, size, quat, mesh = None, [tiny, 0.0, 0.0], np.asarray(g.orientation, dtype=np.float64), None
        if g.kind == "box":
            geom_type, size = mujoco.mjtGeom.mjGEOM_BOX, np.maximum(np.asarray(g.size) / 2, tiny)
        elif g.kind == "sphere":
            geom_type, size = mujoco.mjtGeom.mjGEOM_SPHERE, [max(g.size[0], tiny), 0.0, 0.0]
        elif g.kind == "cylinder":
            geom_type, size = mujoco.mjtGeom.mjGEOM_CYLINDER, [max(g.size[0], tiny), max(g.size[1] / 2, tiny), 0.0]
            quat = R.multiply(quat, _Z_TO_Y)
        elif g.kind == "cone":
            r, h = g.size
            angle = 2 * np.pi * np.arange(CONE_EDGES) / CONE_EDGES
            base = np.stack([r * np.cos(angle), np.full(CONE_EDGES, -h / 2), r * np.sin(angle)], axis=1)
            mesh = np.vstack([[0.0, h / 2, 0.0], base])
        elif g.kind == "heightfield" and immovable:
            return self._hfield(spec, parent, g, k)
        else:  # a mesh, or a grid of points on a moving body: MuJoCo collides the convex hull
            mesh = _hull_points(g)
            if mesh is None:
                return None
        if mesh is not None:
            asset = spec.add_mesh(name=f"mesh{k}")
            asset.uservert = np.asarray(mesh, dtype=np.float64).ravel()
            asset.inertia = mujoco.mjtMeshInertia.mjMESH_INERTIA_CONVEX
            geom = parent.add_geom(type=mujoco.mjtGeom.mjGEOM_MESH, meshname=f"mesh{k}", pos=g.position, quat=quat)
        else:
            geom = parent.add_geom(type=geom_type, size=size, pos=g.position, quat=quat)
        geom.density = 0.0
        return geom

    def _hfield(self, spec, parent, g: Geometry, k: int):
        """An ElevationGrid as a MuJoCo height field: grid x along the field's x, grid z
        along its -y (rows from the far z end), heights up its z."""
        nx, nz = g.grid
        points = np.asarray(g.vertices, dtype=np.float64)
        heights = points[:, 1].reshape(nz, nx)
        lo, hi = float(heights.min()), float(heights.max())
        rx = (points[:, 0].max() - points[:, 0].min()) / 2
        rz = (points[:, 2].max() - points[:, 2].min()) / 2
        if rx <= 0 or rz <= 0:
            return None
        span = max(hi - lo, 1e-9)
        field = spec.add_hfield(name=f"hfield{k}")
        field.nrow, field.ncol = nz, nx
        field.size = [rx, rz, span, max(0.1 * max(rx, rz), span)]  # a base below the lowest point
        field.userdata = ((heights[::-1] - lo) / span).ravel().tolist()
        centre = np.array([points[:, 0].min() + rx, lo, points[:, 2].min() + rz])
        return parent.add_geom(type=mujoco.mjtGeom.mjGEOM_HFIELD, hfieldname=f"hfield{k}",
                               pos=g.position + R.rotate(g.orientation, centre),
                               quat=R.multiply(g.orientation, _Z_TO_Y))

    def contacts(self) -> ContactPoints:
        """The last step's contacts, as MuJoCo found them (normal from geom1 to geom2)."""
        d = self.data
        n = d.ncon
        if self.geometry_of is None or n == 0:
            return ContactPoints.none()
        c = d.contact
        keep = slice(0, n)
        if self.layered:  # the layer's spring pairs repeat their dampers' contacts
            keep = np.flatnonzero(c.includemargin[:n] > -1e-12)
        return ContactPoints(c.pos[keep].copy(), c.frame[keep, :3].copy(), -c.dist[keep],
                             self.geometry_of[c.geom1[keep]], self.geometry_of[c.geom2[keep]])

    def watched_contacts(self, k: int) -> ContactPoints:
        """mj_geomDistance over watched set k's pairs where the bodies are now (mj_kinematics, which
        the next step redoes): one point per overlapping pair, midway between the two surface points
        it gives, the normal from geom1 towards geom2, depth minus the signed distance."""
        m, d = self.model, self.data
        mujoco.mj_kinematics(m, d)
        fromto = np.zeros(6)
        rows = []
        for a, b, ga, gb in self.watched[k]:
            dist = mujoco.mj_geomDistance(m, d, ga, gb, 0.0, fromto)
            if dist < 0:  # overlapping: geom1's surface point lies in geom2, past geom2's
                rows.append((a, b, *fromto, -dist))
        if not rows:
            return ContactPoints.none()
        r = np.array(rows, dtype=np.float64)
        along = r[:, 2:5] - r[:, 5:8]
        return ContactPoints((r[:, 2:5] + r[:, 5:8]) / 2, along / np.linalg.norm(along, axis=1, keepdims=True),
                             r[:, 8], r[:, 0].astype(int), r[:, 1].astype(int))

    # -- running ------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        mujoco.mj_step(self.model, self.data, nstep=n)
        for stat, what in self.bad:  # MuJoCo reset the state and went on: a blow-up it would hide
            if stat.number:
                raise BlewUp(f"MuJoCo found a non-finite or huge {what} (beyond 1e10) at degree of freedom "
                             f"{stat.lastinfo} and reset the simulation")

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
        if not (linear.any() or angular.any()):  # at rest: every joint is still, and no fit (cubic in bodies) is needed
            d.qvel[:] = 0.0
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


def _pair_count(col: Collisions, immovable: list[bool]) -> int:
    """How many geometry pairs may touch with at least one side able to move."""
    counts: dict[int, list] = {}
    for g, fixed in zip(col.geometries, immovable):
        counts.setdefault(g.body, [0, fixed])[0] += 1
    moving = [c for c, fixed in counts.values() if not fixed]
    m, i = sum(moving), sum(c for c, fixed in counts.values() if fixed)
    total = (m * m - sum(c * c for c in moving)) // 2 + m * i
    for lo, hi in col.excluded:
        if lo in counts and hi in counts and not (counts[lo][1] and counts[hi][1]):
            total -= counts[lo][0] * counts[hi][0]
    return total


def _hull_points(g: Geometry) -> np.ndarray | None:
    """The points whose convex hull MuJoCo collides for a mesh (or a grid on a moving body):
    a flat set gets a slab 1 % of its size thick behind its faces (MuJoCo cannot hull a
    plane); a set without area gets nothing, as ODE's trimesh touches nothing then."""
    vertices = np.asarray(g.vertices, dtype=np.float64)
    points = vertices[np.unique(g.triangles)] if g.triangles is not None else vertices
    if len(points) < 3:
        return None
    centre = points.mean(axis=0)
    _, s, vt = np.linalg.svd(points - centre, full_matrices=False)
    if s[0] <= 0 or len(s) < 2 or s[1] <= 1e-9 * s[0]:
        return None
    if len(s) == 3 and s[2] > 1e-6 * s[0]:
        return points
    normal = vt[-1] if len(s) == 3 else np.cross(vt[0], vt[1])
    facing = np.array([0.0, 1.0, 0.0])
    if g.triangles is not None:  # the faces' side by their winding (ccw unless the geometry says not)
        tri = vertices[g.triangles]
        facing = R.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]).sum(axis=0)
        try:
            if not g.node.get("shape").get("geometry").get("ccw"):
                facing = -facing
        except (AttributeError, KeyError):
            pass
        if abs(facing @ normal) < 1e-12 * max(np.linalg.norm(facing), 1e-300):
            facing = np.array([0.0, 1.0, 0.0])
    if normal @ facing < 0:
        normal = -normal
    thickness = max(0.01 * float(np.linalg.norm(np.ptp(points, axis=0))), 1e-6)
    return np.vstack([points, points - thickness * normal])


class MujocoBackend(Backend):
    name = "mujoco"
    integration = SEMI_IMPLICIT
    accurate_integration = RK4  # preferAccuracy selects mjINT_RK4
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
        **approximate("MuJoCo has no ERP/CFM: tree joints are exact (generalized coordinates), loop "
                      "constraints use solref=(2*dt, 1), and contacts without softness or bounce a direct solref: "
                      "damping 1/dt (the approach stops in a step) and stiffness ERP/dt^2 (ERP of the depth undone "
                      "a step, ERP capped at 0.25, X3D's default 0.8 included: stiffer, MuJoCo's friction lets "
                      "sticking bodies slide; like ODE's correction it leaves the body moving out at ERP depth/dt: "
                      "a rebound of 0.02-0.20 of the impact speed at ERP 0.2), impedance 0.99; CFM is not mapped",
                      "RigidBodyCollection.errorCorrection", "RigidBodyCollection.constantForceMix"),
        # collisions
        **native("CollisionCollection", "CollidableShape.geometry.Box", "CollidableShape.geometry.Sphere",
                 "CollidableShape.geometry.Cylinder", "CollisionCollection.appliedParameters", "CollisionSensor",
                 # a set only sensors watch: geoms with contype and conaffinity 0, mj_geomDistance'd
                 "CollisionSensor.collider.watchedOnly"),
        **approximate("Coulomb's elliptic cone with the scene's mu on every pair, but MuJoCo's convex contact model "
                      "pushes sliding contacts apart and lets sticking ones creep. Measured at dt 1/240: a box put "
                      "down sliding at 3 m/s (mu 0.6) hops at up to 0.19 m/s and strays up to 0.11 m/s from v0 - "
                      "mu g t; a box sliding down an incline keeps g (sin - mu cos) within 0.03 %; one sticking on a "
                      "20 degree incline creeps 0.4 mm in 2 s, five stacked boxes under a 1 m/s^2 sideways load 0.6 "
                      "mm in 10 s (11 mm at dt 1/60)",
                      "CollisionCollection.frictionCoefficients"),
        "CollisionCollection.slipFactors": Declared(
            Support.NATIVE, "read only where appliedParameters has SLIP-1 or SLIP-2 (declared there)"),
        **approximate(f"the convex hull of the apex and a {CONE_EDGES}-gon: radius 0.12 % short between its corners",
                      "CollidableShape.geometry.Cone"),
        **approximate("MuJoCo collides a mesh as its convex hull (exact for convex meshes; a concave one, static "
                      "or moving, fills in); a flat mesh becomes a slab 1 % of its size thick behind its faces",
                      "CollidableShape.geometry.IndexedFaceSet", "CollidableShape.geometry.IndexedTriangleSet",
                      "CollidableShape.geometry.TriangleSet"),
        **approximate("a grid on the static environment or a fixed body is a MuJoCo height field (each cell two "
                      "triangles on MuJoCo's diagonal, which X3D leaves open); a grid on a moving body collides as "
                      "the convex hull of its points",
                      "CollidableShape.geometry.ElevationGrid"),
        **approximate("MuJoCo has no restitution: a spring-damper contact whose damping ratio gives e from a table "
                      "measured in MuJoCo (natural frequency 0.35/dt). Measured at dt 1/240, drops of 1.4-8.9 m/s, "
                      "e from rebound heights: e 0.8 within -0.03..+0.035, e 0.5 within -0.08..+0.05, e 0.2 within "
                      "-0.18..+0.04 (gravity during the soft contact costs low speeds most); the ball sinks about "
                      "0.6-1.1 cm per m/s of impact while it bounces",
                      "CollisionCollection.bounce", "CollisionCollection.appliedParameters.BOUNCE"),
        **approximate("no threshold: impacts slower than minBounceSpeed rebound too (ODE stops them), rising at "
                      "most e^2 minBounceSpeed^2 / 2g", "CollisionCollection.minBounceSpeed"),
        **approximate("per-pair friction [mu2, mu1] in MuJoCo's contact frame, whose first tangent is world z for a "
                      "horizontal contact (exact there: ODE's first direction is x); for other normals MuJoCo's "
                      "tangents (world y or z projected) differ from ODE's",
                      "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2"),
        **approximate("MuJoCo's geom surface velocity on static and fixed geoms: one world velocity along ODE's "
                      "friction directions of the upward (against gravity) normal, projected on each contact's "
                      "tangent plane (exact for horizontal conveyors; contacts between two moving bodies get none)",
                      "CollisionCollection.surfaceSpeed", "CollisionCollection.appliedParameters.SPEED-1",
                      "CollisionCollection.appliedParameters.SPEED-2"),
        **approximate("ODE's spring k = ERP/(dt CFM) and damper (1-ERP)/CFM divided by the pair's reduced mass "
                      "(translation only) as a direct solref, capped at MuJoCo's stable 0.5/dt natural frequency "
                      "and 1/dt damping. MuJoCo's impedance (0.9-0.95) puts only the rest of a resting load on the "
                      "spring: a body rests some 1/10 to 1/19 as deep as on ODE's spring (0.2 mm for ODE's 2 mm at "
                      "ERP 0.2, CFM 0.01, 1 kg); with BOUNCE the spring only softens the bounce's",
                      "CollisionCollection.softnessErrorCorrection", "CollisionCollection.softnessConstantForceMix",
                      "CollisionCollection.appliedParameters.ERROR_REDUCTION",
                      "CollisionCollection.appliedParameters.CONSTANT_FORCE"),
        **approximate("as ODE's layer, two pairs per geometry pair: a damper from touching (the approach stops; "
                      "MuJoCo's impedance lets a resting load sink through it at 1e-4 g dt, 4 micrometres a second "
                      "at dt 1/240, where ODE's CFM sinks it at CFM m g) and the ERP spring from that depth. Not "
                      "applied to bouncing contacts; past PAIR_CAP pairs a geom margin -thickness instead (bodies "
                      "settle that deep)", "RigidBodyCollection.contactSurfaceThickness"),
        **unsupported("ODE's force-dependent slip has no MuJoCo counterpart (solreffriction softens friction "
                      "but keeps Coulomb's cone)", "CollisionCollection.appliedParameters.SLIP-1",
                      "CollisionCollection.appliedParameters.SLIP-2"),
        **unsupported("MuJoCo chooses each contact's tangent frame; no direction can be given",
                      "CollisionCollection.appliedParameters.USER_FRICTION"),
        **approximate("not applied: contacts undo depth at up to ERP depth/dt (ERP capped at 0.25) with no cap on "
                      "that speed, so they differ from ODE's where it passes maxCorrectionSpeed (deep overlaps); no "
                      "effect without a collider", "RigidBodyCollection.maxCorrectionSpeed"),
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
