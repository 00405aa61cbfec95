"""PhysX backend (NVIDIA PhysX 5 through SAPIEN 3's Python bindings, CPU only, no renderer).

Every moving RigidBody is a PhysX rigid dynamic and every joint a set of PhysX D6 joints
between two of them: maximal coordinates, as X3D (and ODE, whose parameters the component
takes) describes its bodies. Joints versus articulations: a PhysX articulation is a
reduced-coordinate tree (exact joints, as pybullet's multibodies here), but X3D's joints
form any graph (loops close through the same joint types, a body hangs from several), an
articulation joint cannot join two roots or close a loop, and SAPIEN 3 exposes no spherical
or universal articulation joint; a D6 joint takes any pair, in any graph, with the bodies'
own state as X3D keeps it (position, orientation, velocities all read and written per body),
at the cost of the constraint drifting by what the iterative solver leaves each step. So
joints are D6s. SAPIEN 3.0.3's D6 (PhysxDriveComponent) locks a linear axis (low = high = 0)
but can neither lock nor limit its swing axes (set_limit_cone leaves their motion free), so
every joint is built from point constraints (each D6 locking linear axes only), as in
_joint: a ball is one D6 with x, y and z locked; a hinge that ball plus a point on the axis
kept on it; a slider three points of one body (at its centre of mass) each kept on a line of the
other along the axis (the lines on the end that turns least: _slider); a universal joint
(and a DoubleAxisHingeJoint) the ball plus a point of body2's axis kept in the plane normal
to body1's axis. A hinge's stops are the ball's twist limit about the axis (PhysX measures
the twist of the child, body1, relative to the parent, body2: X3D's angle); a slider's stops
the first point's x limit; DoubleAxisHingeJoint motors D6 velocity drives about each axis
with maxTorque as the force limit. A static end (the world, or a fixed RigidBody) is one
kinematic actor at the origin, so every D6 joins two actors.

PhysX facts this relies on (SAPIEN 3.0.3, PhysX 5, measured in tests/test_backend_physx.py):
PhysX holds poses and velocities in single precision (float32: positions round to ~1e-7
relative); a rigid dynamic's pose is its actor frame (the X3D body frame) and its
centre-of-mass frame is set apart (set_cmass_local_pose: the centre of mass and the
principal axes, since PhysX takes principal moments only: the tensor is diagonalised here);
linear velocity is the centre of mass's; SAPIEN's defaults are angular damping 0.05, a
100 rad/s angular speed clamp and a sleep threshold: all are turned off (x3d_core damps and
disables bodies itself); forces added with add_force_torque act for one step; a D6 joint
never lets its two actors collide (PhysX's constraint flag), and collision groups
(word 2, the ignore bits, under one id in word 3) keep the other joined pairs apart.
Collisions: one PhysxMaterial for every shape (PhysX averages two shapes' friction and
restitution: equal values give the collection's), restitution applies above the scene's
bounce threshold (minBounceSpeed); contacts come from the CPU system's contact list.
"""

from __future__ import annotations

import functools
import math
import warnings

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.semantics.collision import ContactPoints
from x3d_core.semantics.engine import BlewUp, Unsupported
from x3d_core.semantics.world import STATIC, Joint, State, World

from .base import BODIES, JOINTS, SEMI_IMPLICIT, Backend, approximate, below, native, unsupported

with warnings.catch_warnings():  # SAPIEN warns that it found no system libvulkan: no renderer is used
    warnings.simplefilter("ignore")
    import sapien
    import sapien.physx as px

_FLOAT32_MAX = float(np.finfo(np.float32).max)
_FLOAT32_TINY = float(np.finfo(np.float32).tiny)
_FULL_TURN = np.pi - 1e-6  # a hinge range this wide is no limit at all
_ARM = 0.5  # m: how far apart the point constraints that make a hinge, slider or universal joint sit
_CONE_SIDES = 64
_MAX_SPEED = 1e7  # rad/s and m/s: PhysX's speed clamps, set far beyond any scene's
_DRIVE = 1e9  # a motor's velocity drive damping (N m s): stiff, bounded by maxTorque
_BOUNCE_THRESHOLD = 2.0  # PhysX's default bounce threshold, m/s (where nothing collides)
_SMALL = 1e-9
_PACKED = 13  # float32 a rigid dynamic in PhysxCpuSystem.pack()


def _pose(p, q) -> sapien.Pose:
    return sapien.Pose(np.asarray(p, dtype=np.float32), np.asarray(q, dtype=np.float32))


def _principal(inertia: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Principal moments and the principal frame's orientation in the body frame (PhysX takes a
    diagonal inertia in a turned centre-of-mass frame)."""
    if not np.any(inertia - np.diag(np.diag(inertia))):
        return np.diag(inertia).copy(), R.IDENTITY.copy()
    moments, axes = np.linalg.eigh(inertia)
    if np.linalg.det(axes) < 0:
        axes[:, 2] = -axes[:, 2]
    return moments, R.from_matrix(axes[None])[0]


_Y, _X = np.array([0.0, 1.0, 0.0]), np.array([1.0, 0.0, 0.0])


def _frame(axis: np.ndarray) -> np.ndarray:
    """An orientation whose x axis is the unit vector axis, worked out once an axis (a chain's
    hinges share theirs; R.cross: np.cross's axis handling was two thirds of a hinge's build)."""
    return _axis_frame(np.asarray(axis, dtype=np.float64).tobytes())  # bytes: -0.0 apart from 0.0


@functools.lru_cache(maxsize=256)
def _axis_frame(axis: bytes) -> np.ndarray:
    v = np.frombuffer(axis)
    a = v / np.linalg.norm(v)
    u = R.cross(a, _Y if abs(a[1]) < 0.9 else _X)
    u /= np.linalg.norm(u)
    q = R.from_matrix(np.stack([a, u, R.cross(a, u)], axis=1)[None])[0]
    q.setflags(write=False)  # shared by every joint on this axis
    return q


def _cone(radius: float, height: float) -> np.ndarray:
    a = 2 * np.pi * np.arange(_CONE_SIDES) / _CONE_SIDES
    rim = np.stack([radius * np.cos(a), np.full(_CONE_SIDES, -height / 2), radius * np.sin(a)], axis=1)
    return np.vstack([rim, [[0.0, height / 2, 0.0]]])


def _grid_mesh(g) -> tuple[np.ndarray, np.ndarray]:
    nx, nz = g.grid
    idx = np.arange(nx * nz).reshape(nz, nx)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[:-1, 1:].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel()
    tris = np.concatenate([np.stack([a, c, b], axis=1), np.stack([b, c, d], axis=1)])
    return np.asarray(g.vertices, dtype=np.float64), tris


_Z_TO_X = R.from_axis_angle(np.array([0.0, 0.0, 1.0, np.pi / 2]))  # SAPIEN's cylinder axis x, turned to X3D's y


class PhysxSimulation:
    def __init__(self, world: World, dt: float):
        self.world, self.dt = world, dt
        b = world.bodies
        c = world.collisions
        threshold = _BOUNCE_THRESHOLD
        if c is not None and "BOUNCE" in c.parameters.applied:
            threshold = max(float(c.parameters.min_bounce_speed), 1e-6)
        px.set_scene_config(gravity=np.asarray(world.gravity, dtype=np.float32), bounce_threshold=threshold,
                            enable_pcm=True, enable_tgs=False, enable_ccd=False, enable_enhanced_determinism=True,
                            enable_friction_every_iteration=True, cpu_workers=0)
        self.system = px.PhysxCpuSystem()
        self.scene = sapien.Scene([self.system])
        self.scene.set_timestep(dt)
        self.material = None
        if c is not None:
            p = c.parameters
            self.material = px.PhysxMaterial(float(p.friction[0]), float(p.friction[0]), float(p.bounce))
        self.rows = np.flatnonzero(~b.fixed)
        self.every = len(self.rows) == len(b)  # no fixed body: state() is the read as it is
        self.actors: dict[int, px.PhysxRigidDynamicComponent] = {}
        self.shape_geometry: dict[int, int] = {}  # id(shape wrapper) -> geometry index
        self.shapes: list = []
        geoms: dict[int, list[int]] = {}
        if c is not None:
            for k, g in enumerate(c.geometries):
                geoms.setdefault(g.body if g.body == STATIC or not b.fixed[g.body] else STATIC, []).append(k)
        for i in self.rows:
            self.actors[int(i)] = self._body(int(i), geoms.get(int(i), []))
        if geoms.get(STATIC):
            self._static(geoms[STATIC])
        self.anchor = None
        self.built_pairs: set[tuple[int, int]] = set()
        self.drives = []
        for j in world.joints:
            self._joint(j)
        if c is not None:
            self._groups()
        start = State.initial(b)
        start.linear_velocity[b.fixed] = 0.0
        start.angular_velocity[b.fixed] = 0.0
        # every body's start in _read's columns: the fixed bodies' state, whatever the steps
        self.start_read = np.hstack([start.orientation, start.position, start.linear_velocity, start.angular_velocity])
        self.list = [self.actors[int(i)] for i in self.rows]
        self.set_velocities(b.linear_velocity, b.angular_velocity)
        self.set_loads(b.forces, b.torques)
        self.packed = self._packed_rows()

    # -- building -----------------------------------------------------------
    def _shape(self, k: int, moving: bool, frame: tuple[np.ndarray, np.ndarray]):
        g = self.world.collisions.geometries[k]
        m = self.material
        turn = R.IDENTITY
        if g.kind == "box":
            s = px.PhysxCollisionShapeBox(np.maximum(np.asarray(g.size, dtype=np.float32) / 2, 1e-6), m)
        elif g.kind == "sphere":
            s = px.PhysxCollisionShapeSphere(float(g.size[0]), m)
        elif g.kind == "cylinder":
            s = px.PhysxCollisionShapeCylinder(float(g.size[0]), float(g.size[1]) / 2, m)
            turn = _Z_TO_X
        elif g.kind == "cone":
            s = px.PhysxCollisionShapeConvexMesh(_cone(float(g.size[0]), float(g.size[1])).astype(np.float32),
                                                 np.ones(3, dtype=np.float32), m)
        else:
            if g.kind == "mesh":
                v, t = np.asarray(g.vertices, dtype=np.float64), np.asarray(g.triangles)
            else:
                v, t = _grid_mesh(g)
            if moving:
                s = px.PhysxCollisionShapeConvexMesh(v.astype(np.float32), np.ones(3, dtype=np.float32), m)
            else:
                s = px.PhysxCollisionShapeTriangleMesh(v.astype(np.float32), t.astype(np.uint32),
                                                       np.ones(3, dtype=np.float32), m)
        fp, fq = frame
        s.set_local_pose(_pose(fp + R.rotate(fq, g.position), R.multiply(R.multiply(fq, g.orientation), turn)))
        thickness = self.world.contact_surface_thickness
        s.set_rest_offset(-float(thickness) / 2 if thickness > 0 else 0.0)  # PhysX sums the two shapes' offsets
        s.set_contact_offset(max(0.02, 2 * float(thickness)))
        self.shapes.append((s, k))
        return s

    def _body(self, i: int, geoms: list[int]) -> px.PhysxRigidDynamicComponent:
        b, w = self.world.bodies, self.world
        m, inertia = float(b.mass[i]), b.inertia[i]
        moments, principal = _principal(inertia)
        if not (m >= _FLOAT32_TINY and np.all(moments >= _FLOAT32_TINY)):
            raise Unsupported(f"RigidBody {b.names[i]}: PhysX needs a positive mass and a positive definite inertia "
                              f"in single precision (mass {m:g}, principal moments {moments.tolist()}): it takes 0, "
                              f"or a value under {_FLOAT32_TINY:.4g} that rounds to 0, as infinite")
        comp = px.PhysxRigidDynamicComponent()
        for k in geoms:
            comp.attach(self._shape(k, True, (np.zeros(3), R.IDENTITY)))
        e = sapien.Entity()
        e.name = b.names[i]
        e.add_component(comp)
        e.set_pose(_pose(b.position[i], b.orientation[i]))
        self.scene.add_entity(e)
        comp.set_mass(m)
        comp.set_inertia(moments.astype(np.float32))
        comp.set_cmass_local_pose(_pose(b.com[i], principal))
        comp.set_linear_damping(0.0)
        comp.set_angular_damping(0.0)
        comp.set_max_angular_velocity(_MAX_SPEED)
        comp.set_max_linear_velocity(_MAX_SPEED)
        comp.set_sleep_threshold(0.0)
        comp.set_solver_position_iterations(max(1, min(255, w.iterations)))
        comp.set_solver_velocity_iterations(1)
        comp.set_disable_gravity(not bool(b.use_gravity[i]))
        if w.max_correction_speed >= 0:
            comp.set_max_depenetration_velocity(float(w.max_correction_speed))
        return comp

    def _static(self, geoms: list[int]) -> None:
        """The static geometries, and those of fixed bodies (placed where the body is), on one static actor."""
        b = self.world.bodies
        comp = px.PhysxRigidStaticComponent()
        for k in geoms:
            g = self.world.collisions.geometries[k]
            frame = (np.zeros(3), R.IDENTITY) if g.body == STATIC else (b.position[g.body], b.orientation[g.body])
            comp.attach(self._shape(k, False, frame))
        e = sapien.Entity()
        e.name = "static"
        e.add_component(comp)
        self.scene.add_entity(e)
        self.static_actor = comp

    def _end(self, row: int):
        """The actor a joint end is, and its pose at the start (a kinematic anchor for the static world)."""
        if row == STATIC or row not in self.actors:
            if self.anchor is None:
                comp = px.PhysxRigidDynamicComponent()
                e = sapien.Entity()
                e.name = "anchor"
                e.add_component(comp)
                self.scene.add_entity(e)
                comp.set_kinematic(True)
                self.anchor = comp
            return self.anchor, np.zeros(3), R.IDENTITY
        b = self.world.bodies
        return self.actors[row], b.position[row], b.orientation[row]

    def _d6(self, parent: int, child: int, point: np.ndarray, q: np.ndarray,
            child_point: np.ndarray | None = None) -> px.PhysxDriveComponent:
        """A D6 joint whose frame is at point, turned by q (world, at the start), in both actors
        (the child's frame at child_point where given); every axis free."""
        pa, pp, pq = self._end(parent)
        ca, cp, cq = self._end(child)
        cpt = point if child_point is None else child_point
        pose0 = _pose(R.rotate(R.conjugate(pq), point - pp), R.multiply(R.conjugate(pq), q))
        pose1 = _pose(R.rotate(R.conjugate(cq), cpt - cp), R.multiply(R.conjugate(cq), q))
        d = self.scene.create_drive(pa, pose0, ca, pose1)
        self.drives.append(d)
        return d

    def _joint(self, j: Joint) -> None:
        if j.type == "MotorJoint" or j.body1 == j.body2:
            return  # a motor is loads (the evaluator's); a body joined to itself moves freely
        p = j.params
        b1, b2 = j.body1, j.body2
        a = j.anchor
        if j.type == "BallJoint":
            self._lock(self._d6(b2, b1, a, R.IDENTITY), "xyz")
        elif j.type == "SingleAxisHingeJoint":
            q = _frame(j.axes[0])
            ball = self._d6(b2, b1, a, q)
            self._lock(ball, "xyz")
            lo, hi = p["minAngle"], p["maxAngle"]
            if not (lo <= -_FULL_TURN and hi >= _FULL_TURN) and lo <= hi:
                ball.set_limit_twist(max(lo, -np.pi), min(hi, np.pi))
            self._lock(self._d6(b2, b1, a + _ARM * j.axes[0], q), "yz")
        elif j.type == "SliderJoint":
            self._slider(j)
        elif j.type in ("UniversalJoint", "DoubleAxisHingeJoint"):
            a1, a2 = j.axes[0], j.axes[1]
            q1 = _frame(a1)
            ball = self._d6(b2, b1, a, q1)
            self._lock(ball, "xyz")
            # body2's point on axis2 stays in body1's plane through the anchor normal to axis1 (at its start offset)
            plane = self._d6(b1, b2, a, q1, child_point=a + _ARM * a2)
            c = float(_ARM * (a1 @ a2))
            if abs(c) < _SMALL:
                plane.set_limit_x(0.0, 0.0)
            else:
                plane.set_limit_x(c, c)
            if j.type == "DoubleAxisHingeJoint":
                lo, hi = p["minAngle1"], p["maxAngle1"]
                if not (lo <= -_FULL_TURN and hi >= _FULL_TURN) and lo <= hi:
                    ball.set_limit_twist(max(lo, -np.pi), min(hi, np.pi))
                for k, axis in ((1, a1), (2, a2)):
                    torque = p[f"maxTorque{k}"]
                    if torque > 0:
                        motor = self._d6(b2, b1, a, _frame(axis))
                        # SAPIEN leaves PhysX's drive limits as impulses (eDRIVE_LIMITS_ARE_FORCES unset): the
                        # torque bound is maxTorque dt a step; PhysX drives the parent (body2) relative to the
                        # child, so the target is X3D's body1-relative rate turned round (measured: both motors)
                        motor.set_drive_property_twist(0.0, _DRIVE, float(min(torque * self.dt, _FLOAT32_MAX)))
                        motor.set_drive_velocity_target(np.zeros(3, dtype=np.float32),
                                                        np.array([-p[f"desiredAngularVelocity{k}"], 0, 0],
                                                                 dtype=np.float32))
        else:
            raise Unsupported(f"{j.type} {j.name}: not built by the physx backend")
        self.built_pairs.add((min(b1, b2), max(b1, b2)))

    def _slider(self, j: Joint) -> None:
        """Three points of the rider kept on lines of the carrier along the axis, at the rider's
        centre of mass (and _ARM off it along the axis and across): a slider has no anchor (x3d_core's
        is the world origin), and each row turns the carrier with the distance between the bodies as
        lever arm, so the carrier is the end that turns least under it (a static end never turns).
        A shared anchor far from both (a body 10 m from the origin) made every row a lever on both,
        and PhysX's iterative solver let the rider swing round it (measured: 10 m off the axis)."""
        axis, q = j.axes[0], _frame(j.axes[0])
        u = R.rotate(q, np.array([0.0, 1.0, 0.0]))
        c1, c2 = self._centre(j.body1), self._centre(j.body2)
        r2 = float(np.sum((c1 - c2) ** 2)) if c1 is not None and c2 is not None else 0.0
        if self._turn(j.body1, r2) < self._turn(j.body2, r2):  # body1 carries: the D6 measures body2 from it
            carrier, rider, point, sign = j.body1, j.body2, c2, -1.0
        else:  # PhysX's x is then X3D's separation: body1 relative to body2
            carrier, rider, point, sign = j.body2, j.body1, c1, 1.0
        if point is None:  # both ends static: the rider is static only then
            point = j.anchor
        first = self._d6(carrier, rider, point, q)
        self._lock(first, "yz")
        if j.stops is not None:
            lo, hi = sorted(sign * s for s in j.stops)
            first.set_limit_x(float(lo), float(hi))
        self._lock(self._d6(carrier, rider, point + _ARM * axis, q), "yz")
        self._lock(self._d6(carrier, rider, point + _ARM * u, q), "yz")

    def _centre(self, row: int) -> np.ndarray | None:
        """A moving body's centre of mass in the world at the start; None for a static end."""
        if row not in self.actors:
            return None
        b = self.world.bodies
        return b.position[row] + R.rotate(b.orientation[row], b.com[row])

    def _turn(self, row: int, r2: float) -> float:
        """How far an end gives to a unit impulse across the axis r2 ** 0.5 from its centre of mass,
        turning about its weakest principal axis (1/m + r^2/I_min); 0 for a static end."""
        if row not in self.actors:
            return 0.0
        b = self.world.bodies
        return 1.0 / float(b.mass[row]) + r2 / float(_principal(b.inertia[row])[0].min())

    @staticmethod
    def _lock(d: px.PhysxDriveComponent, axes: str) -> None:
        for x in axes:
            getattr(d, f"set_limit_{x}")(0.0, 0.0)

    def _groups(self) -> None:
        """Collision groups: every shape collides with every other (words 0 and 1), except pairs of
        bodies joined by a joint PhysX has no constraint for (a MotorJoint's): those share an ignore
        bit (word 2) under one id (word 3). A D6 keeps its own two actors apart."""
        pairs = sorted(p for p in self.world.collisions.excluded if p not in self.built_pairs)
        if len(pairs) > 32:
            raise Unsupported(f"{len(pairs)} pairs of bodies joined only by MotorJoints: PhysX's collision filter "
                              "has 32 ignore bits to keep them apart")
        bits: dict[int, int] = {}
        for k, (lo, hi) in enumerate(pairs):
            for r in (lo, hi):
                bits[r] = bits.get(r, 0) | (1 << k)
        for s, k in self.shapes:
            row = self.world.collisions.geometries[k].body
            s.set_collision_groups([1, 1, bits.get(row, 0), 1])

    # -- running ------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        step = self.system.step  # what sapien.Scene.step calls, without its Python frame each step
        for _ in range(n):
            if self.loaded:
                for comp, f, t in self.loads:
                    comp.add_force_torque(f, t)
            step()

    def state(self) -> State:
        """The bodies' state as views of one fresh (bodies, 13) array (a numpy call costs more than a few
        bodies' numbers): the moving bodies' read, the fixed ones' start where some body is fixed."""
        if not len(self.rows):
            a = self.start_read.copy()
        else:
            a = self._read()
            if not math.isfinite(np.add.reduce(a, axis=None)):  # a float64 sum of float32s overflows never
                raise BlewUp("PhysX's state turned non-finite")
            q = a[:, 0:4]
            q /= np.sqrt(np.add.reduce(q * q, axis=1, keepdims=True))  # np.linalg.norm's sums, without its checks
            if not self.every:
                full = self.start_read.copy()
                full[self.rows] = a
                a = full
        return State(a[:, 4:7], a[:, 0:4], a[:, 7:10], a[:, 10:13], whole=a)

    def _read(self) -> np.ndarray:
        """Every moving body's orientation, position, linear and angular velocity (n, 13) as PhysX
        holds them: from the CPU system's state packed at once where _packed_rows found its layout
        (measured, the 100-box pile: 10 against 370 us a frame read body by body)."""
        return self._each() if self.packed is None else self._unpacked(self.packed)

    def _each(self) -> np.ndarray:
        return np.array([np.concatenate((p.q, p.p, c.linear_velocity, c.angular_velocity))
                         for c in self.list for p in (c.entity_pose,)], dtype=np.float64)

    def _unpacked(self, rows: np.ndarray | slice) -> np.ndarray:
        return np.frombuffer(self.system.pack(), dtype=np.float32).reshape(-1, _PACKED)[rows].astype(np.float64)

    def _packed_rows(self) -> np.ndarray | slice | None:
        """Where each moving body lies in PhysxCpuSystem.pack(): _PACKED float32 a rigid dynamic, in
        the system's order (SAPIEN 3.0.3: orientation w x y z, position, linear and angular velocity);
        None where the packed state is not that layout, as checked against the bodies' own reads."""
        system = self.system.rigid_dynamic_components
        where = {id(c): k for k, c in enumerate(system)}
        if len(self.system.pack()) != 4 * _PACKED * len(system) or any(id(c) not in where for c in self.list):
            return None
        rows = np.array([where[id(c)] for c in self.list], dtype=np.intp)
        if len(rows) and np.array_equal(rows, np.arange(rows[0], rows[0] + len(rows))):  # one block: a slice
            rows = slice(int(rows[0]), int(rows[0]) + len(rows))
        return rows if np.array_equal(self._unpacked(rows), self._each()) else None

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        for i, c in zip(self.rows, self.list):
            c.set_linear_velocity(np.asarray(linear[i], dtype=np.float32))
            c.set_angular_velocity(np.asarray(angular[i], dtype=np.float32))

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        f = np.asarray(forces, dtype=np.float64)[self.rows]
        t = np.asarray(torques, dtype=np.float64)[self.rows]
        on = np.flatnonzero(np.any(f != 0, axis=1) | np.any(t != 0, axis=1))
        self.loads = [(self.list[k] if hasattr(self, "list") else self.actors[int(self.rows[k])],
                       f[k].astype(np.float32), t[k].astype(np.float32)) for k in on]
        self.loaded = bool(len(on))

    def contacts(self) -> ContactPoints:
        if self.world.collisions is None:
            return ContactPoints.none()
        where = {id(s): k for s, k in self.shapes}
        pos, nrm, depth, g1, g2 = [], [], [], [], []
        for c in self.system.get_contacts():
            s0, s1 = c.shapes
            k0, k1 = where.get(id(s0)), where.get(id(s1))
            if k0 is None or k1 is None:
                continue
            for pt in c.points:
                pos.append(pt.position)
                # PhysX's normal points from the second shape into the first
                nrm.append(-np.asarray(pt.normal, dtype=np.float64))
                depth.append(-float(pt.separation))
                g1.append(k0)
                g2.append(k1)
        if not pos:
            return ContactPoints.none()
        return ContactPoints(np.array(pos, dtype=np.float64).reshape(-1, 3), np.array(nrm).reshape(-1, 3),
                             np.array(depth), np.array(g1, dtype=int), np.array(g2, dtype=int))


_FLOAT32 = ("PhysX holds state in single precision: positions and velocities carry ~1e-7 relative rounding "
            "a step")
_JOINTS = ("D6 joints built from point constraints (module docstring), solved iteratively in maximal "
           "coordinates, in float32: measured, a 1 m hinge pendulum's arm stays within 8e-6 m of its length and "
           "4e-6 m of its plane, its period within 0.09% (pendulum_period); universal_joint keeps |body1Axis . "
           "body2Axis| under 3.1e-4; a double pendulum's first step is 5e-4 rad/s off h q''(0), the solver not "
           "converging coupled joints in one step; a slider's body 10 m from a fixed or 1e6 kg base stays within "
           "4.3e-6 m of its line and its stops (tests/test_backend_physx.py), two 1 kg bodies (I 0.01) 8 to 10 m "
           "apart within 0.02 m of it, passing a stop by up to 0.04 m")


class PhysxBackend(Backend):
    name = "physx"
    integration = SEMI_IMPLICIT  # PhysX: v += h a, then x += h v (measured: free fall to float32)
    limits = {"RigidBody.mass": below(_FLOAT32_TINY, "PhysX holds masses in single precision: a value under "
                                      f"{_FLOAT32_TINY:.4g} rounds to 0, which PhysX takes as infinite"),
              "RigidBody.inertia": below(_FLOAT32_TINY, "PhysX holds inertias in single precision: a value under "
                                         f"{_FLOAT32_TINY:.4g} rounds to 0, which PhysX takes as infinite")}
    declared = {
        **native(*BODIES, "RigidBody.useGlobalGravity", "RigidBodyCollection.iterations"),
        **approximate(_JOINTS, *JOINTS, "DoubleAxisHingeJoint", "DoubleAxisHingeJoint.anchorPoint",
                      "DoubleAxisHingeJoint.axis1", "DoubleAxisHingeJoint.axis2"),
        **approximate("PhysX D6 velocity drives about each axis (damping 1e9, bounded by maxTorque dt a step: "
                      "SAPIEN leaves PhysX's drive limits as impulses), twist measured in the D6's own frame: "
                      "measured, motor_speed's torque-limited ramp within 4.9e-6 rad/s, hinge2_steering's within "
                      "1.4e-6", "DoubleAxisHingeJoint.desiredAngularVelocity1",
                      "DoubleAxisHingeJoint.desiredAngularVelocity2", "DoubleAxisHingeJoint.maxTorque1",
                      "DoubleAxisHingeJoint.maxTorque2"),
        **approximate("the D6 twist limit about axis1, the twist of body1's whole turn relative to body2 (with "
                      "the wheel's turn about axis2 in it): exact while the wheel does not turn (hinge2_steering "
                      "ends at its stops)", "DoubleAxisHingeJoint.limits",
                      "DoubleAxisHingeJoint.minAngle1", "DoubleAxisHingeJoint.maxAngle1"),
        **unsupported("PhysX joint limits are hard (or a spring) with its own restitution model, and no ERP/CFM: "
                      "ODE's stop bounce and error correction have no counterpart",
                      "SingleAxisHingeJoint.stopBounce", "SliderJoint.stopBounce",
                      "SingleAxisHingeJoint.stopErrorCorrection", "SliderJoint.stopErrorCorrection",
                      "DoubleAxisHingeJoint.stop1Bounce", "DoubleAxisHingeJoint.stop1ErrorCorrection",
                      "DoubleAxisHingeJoint.stop1ConstantForceMix"),
        **unsupported("a D6 linear axis is locked, limited or free: ODE's suspension spring along axis1 is not "
                      "built", "DoubleAxisHingeJoint.suspensionForce",
                      "DoubleAxisHingeJoint.suspensionErrorCorrection"),
        **approximate("no effect: PhysX's solver has no ERP; its position iterations correct joint and contact "
                      "errors fully each step (contacts at most maxDepenetrationVelocity: measured, correction_speed "
                      "at errorCorrection 0.2 rises at maxCorrectionSpeed 0.2 m/s, not ERP's 1.92)",
                      "RigidBodyCollection.errorCorrection"),
        **unsupported("PhysX's constraint rows carry no CFM: 0, rigid, is PhysX's own",
                      "RigidBodyCollection.constantForceMix", native_at=0.0),
        **unsupported("PhysX has one integrator: preferAccuracy changes nothing", "RigidBodyCollection.preferAccuracy",
                      native_at=False),
        **approximate("PhysX's maxDepenetrationVelocity per body: measured, a ball 4 cm in the floor rises at "
                      "0.2 m/s, but by moving it: its linearVelocity reads 0 meanwhile",
                      "RigidBodyCollection.maxCorrectionSpeed"),
        **approximate("PhysX's rest offset, -thickness/2 a shape (a pair sums them): every resting body settles "
                      "at the full thickness (measured: a box placed touching the floor sinks 0.0100 m at 0.01), "
                      "where ODE's layer leaves it where it lands",
                      "RigidBodyCollection.contactSurfaceThickness"),
        # collisions
        **native("CollisionCollection", "CollisionCollection.appliedParameters", "CollidableShape.geometry.Box",
                 "CollidableShape.geometry.Sphere", "CollisionSensor"),
        **unsupported("SAPIEN binds no PhysX query between two shapes (PxGeometryQuery) and no pair filter that "
                      "detects without responding: its contacts come from a step, in which the shapes of a collection "
                      "only a sensor watches would push the bodies", "CollisionSensor.collider.watchedOnly"),
        **approximate("SAPIEN's cylinder, a PhysX custom geometry: measured, one standing on its end rests at h/2 "
                      "within 3e-6 m (cylinder_cone_rest)", "CollidableShape.geometry.Cylinder"),
        **approximate("PhysX restitution on one material for all shapes (averaged: equal values give e), applied "
                      "above the scene's bounceThreshold (minBounceSpeed); measured (bounce_apex, 1 m drop, dt 1/240):"
                      " e = 0.5 apex after bounce 2 13 mm off e^4 h0; Newton's cradle passes on it", "CollisionCollection.bounce",
                      "CollisionCollection.appliedParameters.BOUNCE", "CollisionCollection.minBounceSpeed"),
        **approximate("PhysX's patch friction, static and dynamic coefficient both mu, on one material: measured, "
                      "an incline slides within 1e-6 of g (sin - mu cos), a five-box stack holds (box_stack)",
                      "CollisionCollection.frictionCoefficients"),
        **approximate(f"the convex hull of a {_CONE_SIDES}-gon and the apex (radius 0.12% short between corners; "
                      "cylinder_cone_rest rests it at h/2 within 3e-6 m)", "CollidableShape.geometry.Cone"),
        **approximate("static: a PhysX triangle mesh (a ball on a sloped mesh meets it along its face normal to "
                      "1e-5); on a moving body: its convex hull (PhysX simulates no triangle mesh on a dynamic actor)", "CollidableShape.geometry.IndexedFaceSet",
                      "CollidableShape.geometry.IndexedTriangleSet", "CollidableShape.geometry.TriangleSet"),
        **approximate("static: a triangle mesh of the grid, each quad split along one diagonal (a ball on a sloped "
                      "grid meets it along its normal to 1e-5); on a moving body: its convex hull", "CollidableShape.geometry.ElevationGrid"),
        **unsupported("PhysX has one friction coefficient per material (no second direction)",
                      "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2",
                      "CollisionCollection.appliedParameters.USER_FRICTION"),
        **unsupported("PhysX contacts have no ERP/CFM softness (a material's compliance is a spring of its own)",
                      "CollisionCollection.appliedParameters.ERROR_REDUCTION",
                      "CollisionCollection.appliedParameters.CONSTANT_FORCE",
                      "CollisionCollection.softnessErrorCorrection", "CollisionCollection.softnessConstantForceMix"),
        **unsupported("PhysX contacts have no surface velocity through SAPIEN (contact modification is not bound)",
                      "CollisionCollection.appliedParameters.SPEED-1", "CollisionCollection.appliedParameters.SPEED-2"),
        **unsupported("PhysX's friction has no force-dependent slip",
                      "CollisionCollection.appliedParameters.SLIP-1", "CollisionCollection.appliedParameters.SLIP-2"),
        **approximate("no effect unless appliedParameters holds SPEED-1 or SPEED-2 (unsupported here)",
                      "CollisionCollection.surfaceSpeed"),
        **approximate("no effect unless appliedParameters holds SLIP-1 or SLIP-2 (unsupported here)",
                      "CollisionCollection.slipFactors"),
    }

    def version(self) -> str:
        import importlib.metadata
        return f"sapien {importlib.metadata.version('sapien')} (PhysX 5)"

    def build(self, world: World, dt: float) -> PhysxSimulation:
        b = world.bodies
        for name, arr in (("position", b.position), ("linearVelocity", b.linear_velocity),
                          ("angularVelocity", b.angular_velocity), ("forces", b.forces), ("torques", b.torques),
                          ("mass", b.mass), ("inertia", b.inertia)):
            with np.errstate(over="ignore", invalid="ignore"):
                ok = (np.isfinite(arr) & (np.abs(arr) <= _FLOAT32_MAX)).reshape(len(arr), math.prod(arr.shape[1:]))
                bad = ~ok.all(axis=1)  # per body (a collection of none has none)
            if bad.any():
                raise Unsupported(f"RigidBody {b.names[int(np.flatnonzero(bad)[0])]}: a {name} beyond single "
                                  "precision (PhysX holds float32)")
        return PhysxSimulation(world, dt)


BACKEND = PhysxBackend()
