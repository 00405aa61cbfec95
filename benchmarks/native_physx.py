"""engine_speed.py's three scenes written in SAPIEN 3's own API (PhysX 5, CPU, no renderer), as
backends/physx.py builds them: the 10-link chain (run_overhead.py's), the car (car.py's) and
the 100-box pile (pile.py's). Imports sapien and numpy and the scene constants beside it, no
x3drbp code.

The model, as the backend sets it: a scene config of gravity, bounce threshold (minBounceSpeed
where something collides, else PhysX's 2 m/s), PCM, PGS (no TGS), no CCD, enhanced
determinism, friction every iteration, no worker threads; one rigid dynamic per moving body,
created in the scene's order, with its mass, principal moments (every inertia here is
diagonal), no damping, no speed clamps, no sleeping, 10 position iterations and 1 velocity
iteration; the static shapes on one static actor created after them; joints as D6 drives
locking linear axes only (a hinge: a ball at the anchor plus a point half a metre along the
axis kept on it; a DoubleAxisHingeJoint: the ball plus the wheel's axle point kept in the
chassis's plane normal to the steering axis), a fixed end being one kinematic actor at the
origin; one material (mu, mu, bounce 0) for every shape, rest offset 0, contact offset 0.02 m.
Each frame reads every body's pose and velocities.
"""

from __future__ import annotations

import warnings

import numpy as np

import car
import pile
import run_overhead

with warnings.catch_warnings():  # SAPIEN warns that it found no libvulkan: no renderer is used
    warnings.simplefilter("ignore")
    import sapien
    import sapien.physx as px

ARM = 0.5  # m: the backend's distance between a joint's point constraints
NO_BOUNCE_THRESHOLD = 2.0  # m/s: PhysX's default, where nothing collides
CONTACT_OFFSET = 0.02  # m
ITERATIONS = 10


def _pose(p, q=(1.0, 0.0, 0.0, 0.0)) -> sapien.Pose:
    return sapien.Pose(np.asarray(p, dtype=np.float32), np.asarray(q, dtype=np.float32))


def _axis_frame(axis: np.ndarray) -> np.ndarray:
    """The quaternion (w x y z) of a frame whose x axis is the unit vector axis (the D6's twist
    axis), its y axis axis x (0 1 0) (x (1 0 0) where axis is near y)."""
    a = axis / np.linalg.norm(axis)
    u = np.cross(a, [0.0, 1.0, 0.0] if abs(a[1]) < 0.9 else [1.0, 0.0, 0.0])
    u /= np.linalg.norm(u)
    m = np.stack([a, u, np.cross(a, u)], axis=1)
    rows = np.array([[1 + m[0, 0] + m[1, 1] + m[2, 2], m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1]],
                     [m[2, 1] - m[1, 2], 1 + m[0, 0] - m[1, 1] - m[2, 2], m[0, 1] + m[1, 0], m[0, 2] + m[2, 0]],
                     [m[0, 2] - m[2, 0], m[0, 1] + m[1, 0], 1 - m[0, 0] + m[1, 1] - m[2, 2], m[1, 2] + m[2, 1]],
                     [m[1, 0] - m[0, 1], m[0, 2] + m[2, 0], m[1, 2] + m[2, 1], 1 - m[0, 0] - m[1, 1] + m[2, 2]]])
    q = rows[np.argmax(np.diag(rows))]
    return q / np.linalg.norm(q)


class Scene:
    """A SAPIEN scene on the CPU PhysX system, its actors and drives made as the backend makes them."""

    def __init__(self, gravity: float, bounce_threshold: float, mu: float | None):
        px.set_scene_config(gravity=np.array([0.0, -gravity, 0.0], dtype=np.float32),
                            bounce_threshold=bounce_threshold, enable_pcm=True, enable_tgs=False, enable_ccd=False,
                            enable_enhanced_determinism=True, enable_friction_every_iteration=True, cpu_workers=0)
        self.scene = sapien.Scene([px.PhysxCpuSystem()])
        self.scene.set_timestep(car.DT)
        self.material = None if mu is None else px.PhysxMaterial(mu, mu, 0.0)
        self.bodies: list[px.PhysxRigidDynamicComponent] = []
        self.shapes: list = []
        self.anchor = None

    def _shaped(self, shape, local: np.ndarray = np.zeros(3)):
        shape.set_local_pose(_pose(local))
        shape.set_rest_offset(0.0)
        shape.set_contact_offset(CONTACT_OFFSET)
        self.shapes.append(shape)
        return shape

    def sphere(self, radius: float):
        return self._shaped(px.PhysxCollisionShapeSphere(radius, self.material))

    def box(self, size, centre=np.zeros(3)):
        return self._shaped(px.PhysxCollisionShapeBox(np.asarray(size, dtype=np.float32) / 2, self.material), centre)

    def body(self, name: str, mass: float, moments, position, orientation=(1.0, 0.0, 0.0, 0.0), shape=None):
        comp = px.PhysxRigidDynamicComponent()
        if shape is not None:
            comp.attach(shape)
        entity = sapien.Entity()
        entity.name = name
        entity.add_component(comp)
        entity.set_pose(_pose(position, orientation))
        self.scene.add_entity(entity)
        comp.set_mass(mass)
        comp.set_inertia(np.asarray(moments, dtype=np.float32))
        comp.set_cmass_local_pose(_pose(np.zeros(3)))
        comp.set_linear_damping(0.0)
        comp.set_angular_damping(0.0)
        comp.set_max_angular_velocity(1e7)
        comp.set_max_linear_velocity(1e7)
        comp.set_sleep_threshold(0.0)
        comp.set_solver_position_iterations(ITERATIONS)
        comp.set_solver_velocity_iterations(1)
        comp.set_disable_gravity(False)
        self.bodies.append(comp)
        return comp

    def static(self, shapes) -> None:
        comp = px.PhysxRigidStaticComponent()
        for s in shapes:
            comp.attach(s)
        entity = sapien.Entity()
        entity.name = "static"
        entity.add_component(comp)
        self.scene.add_entity(entity)

    def world(self):
        """The kinematic actor at the origin that joins a joint to the static world (made once, on first use)."""
        if self.anchor is None:
            comp = px.PhysxRigidDynamicComponent()
            entity = sapien.Entity()
            entity.name = "anchor"
            entity.add_component(comp)
            self.scene.add_entity(entity)
            comp.set_kinematic(True)
            self.anchor = comp
        return self.anchor

    def lock(self, parent, parent_at, child, child_at, point, q, axes: str, child_point=None):
        """A D6 drive at point (world, at the start; child_point in the child where given), turned
        by q, its linear axes `axes` locked; every actor starts unturned, so a frame is its offset."""
        at = point if child_point is None else child_point
        d = self.scene.create_drive(parent, _pose(point - parent_at, q), child, _pose(at - child_at, q))
        for x in axes:
            getattr(d, f"set_limit_{x}")(0.0, 0.0)
        return d

    def collide_all(self) -> None:
        """Every shape in collision group 1 colliding with group 1, no ignore bits (a D6 keeps its own actors apart)."""
        for shape in self.shapes:
            shape.set_collision_groups([1, 1, 0, 1])

    def start(self, velocities) -> None:
        for comp, (v, w) in zip(self.bodies, velocities):
            comp.set_linear_velocity(np.asarray(v, dtype=np.float32))
            comp.set_angular_velocity(np.asarray(w, dtype=np.float32))

    def run(self, frames: int, steps_per_frame: int) -> np.ndarray:
        """Every frame's positions (frames, bodies, 3), every pose and velocity read."""
        out = []
        for _ in range(frames):
            for _ in range(steps_per_frame):
                self.scene.step()
            out.append([(c.entity_pose, c.linear_velocity, c.angular_velocity) for c in self.bodies])
        return np.array([[pose.p for pose, _, _ in frame] for frame in out], dtype=np.float64)


def chain(duration: float) -> np.ndarray:
    """The chain: each link a rigid dynamic, then each hinge (the link as the D6's first actor,
    its parent, or the world's anchor, second). The links' positions at the end (LINKS, 3)."""
    s = Scene(car.GRAVITY, NO_BOUNCE_THRESHOLD, None)
    links = run_overhead.LINKS
    centres = [run_overhead.DIRECTION * (0.35 * k + 0.175) for k in range(links)]
    for k, c in enumerate(centres):
        s.body(f"L{k}", run_overhead.MASS, run_overhead.MOMENTS, c)
    q = _axis_frame(np.array([0.0, 0.0, 1.0]))
    for k in range(links):
        anchor = run_overhead.DIRECTION * 0.35 * k
        parent, parent_at = (s.world(), np.zeros(3)) if k == 0 else (s.bodies[k - 1], centres[k - 1])
        s.lock(s.bodies[k], centres[k], parent, parent_at, anchor, q, "xyz")
        s.lock(s.bodies[k], centres[k], parent, parent_at, anchor + ARM * np.array([0.0, 0.0, 1.0]), q, "yz")
    s.start([(np.zeros(3), np.zeros(3))] * links)
    return s.run(round(duration * car.FRAME_RATE), round(1 / (car.FRAME_RATE * car.DT)))[-1]


def car_run(duration: float) -> np.ndarray:
    """The car: the chassis and wheels (a sphere each), the floor, then per wheel a ball at its
    centre (wheel first, chassis second) and the chassis's plane normal to the steering axis
    holding the wheel's point half a metre along its axle. Every frame's positions (frames, 5, 3)."""
    s = Scene(car.GRAVITY, car.MIN_BOUNCE_SPEED, car.MU)
    chassis = s.body("Chassis", car.CHASSIS_MASS, car.CHASSIS_MOMENTS, car.START)
    for k, centre in enumerate(car.WHEELS):
        s.body(f"W{k}", car.WHEEL_MASS, [car.WHEEL_MOMENT] * 3, centre, shape=s.sphere(car.RADIUS))
    s.static([s.box(car.FLOOR_SIZE, np.array(car.FLOOR_CENTRE))])
    steer, axle = np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])
    q = _axis_frame(steer)
    for centre, wheel in zip(car.WHEELS, s.bodies[1:]):
        s.lock(wheel, centre, chassis, car.START, centre, q, "xyz")
        s.lock(chassis, car.START, wheel, centre, centre, q, "x", child_point=centre + ARM * axle)
    s.collide_all()
    s.start([((car.SPEED, 0.0, 0.0), np.zeros(3))] + [((car.SPEED, 0.0, 0.0), car.SPIN)] * len(car.WHEELS))
    return s.run(*car._frames(duration))


def pile_run(duration: float) -> np.ndarray:
    """The pile: a box per body, turned as drawn, then the floor and walls on the static actor.
    Every frame's positions (frames, 100, 3)."""
    s = Scene(pile.GRAVITY, pile.MIN_BOUNCE_SPEED, pile.MU)
    for k, (_, position, axis, angle) in enumerate(pile.draws()):
        s.body(f"B{k}", pile.MASS, [pile.BOX_MOMENT] * 3, position, pile._quaternion(axis, angle),
               shape=s.box([pile.EDGE] * 3))
    s.static([s.box(size, np.array(centre)) for _, size, centre in pile.STATIC])
    s.collide_all()
    s.start([(np.zeros(3), np.zeros(3))] * len(s.bodies))
    return s.run(*pile._frames(duration))


NATIVE = {"chain": chain, "car": car_run, "pile": pile_run}
