"""pymunk backend (Chipmunk2D): planar worlds only, a fourth opinion on 2D scenes.

x3d_core.semantics.planar decides whether each body stays in its plane z = c (parallel planes
allowed: shapes that can never meet across them are kept apart) and gives its shapes'
sections; a world that does not is refused (x3d_core.semantics.engine.Unsupported, naming the
body or joint, the field and its value). Each moving body is a pymunk body with the
mass, the moment of inertia about z, and the centre of mass in its frame; fixed bodies
and static collidables are shapes on the space's static body, in world coordinates.
state() turns the 2D state back into 3D terms: z as at the start, the orientation a turn
about z, the angular velocity along z.

pymunk facts this relies on (pymunk 7.3.1, Chipmunk 2.0.1 as pymunk bundles it; measured in
tests/test_backend_pymunk.py): a step first moves every body with its velocity, then
collides, then adds gravity and forces to the velocities and solves, so positions lag
semi-implicit Euler's by one step (x_n = x0 - g dt^2 n(n-1)/2: explicit Euler's bound on the
other side; integration = POSITION_FIRST): in free motion a body trails the other engines'
by dt (v - v0), g dt^2 n after n steps of a fall from rest (1.70e-4 m a step at g 9.81 and
dt 1/240 s, 1 mm by the sixth step; measured to 1e-15 m in
tests/test_compare_integration.py), and its angle by dt (w - w0); body.force and body.torque
are cleared after each step (loads are written before every one, through pymunk.batch, which
reads and writes every dynamic body in the order they were added); body.position is the
frame's origin, body.velocity the centre of gravity's, and setting center_of_gravity moves
the origin (so it is set first); space damping 1 and sleep_time_threshold inf (the defaults)
mean no damping and no sleeping; a constraint's error_bias is the fraction of its error left
after one second and it corrects 1 - error_bias^dt of it per step, so error_bias = (1 -
ERP)^(1/dt) is ODE's ERP exactly, and collision_bias likewise for contacts; collision_slop
is the overlap left uncorrected (ODE's surface layer; measured: a box rests 1e-4 m deep with
slop 1e-4); friction and elasticity are the product of the two shapes' values (every shape
gets sqrt(mu) and sqrt(bounce)); the bounce is e times the approach speed before the step's
gravity; GearJoint(a, b, phase, 1) holds b.angle - a.angle = phase and RotaryLimitJoint(a,
b, lo, hi) keeps b.angle - a.angle in [lo, hi]; an arbiter's normal points from its first
shape to its second, and a surface velocity set in pre_solve makes friction drive v_b - v_a
(at the contact) towards minus its tangential part (measured: a box on a static belt).
"""

from __future__ import annotations

import numpy as np
import pymunk
import pymunk.batch as batch

from x3d_core.model.schema import node_type
from x3d_core.semantics import planar
from x3d_core.semantics import rotation as R
from x3d_core.semantics.collision import Collisions, ContactPoints
from x3d_core.semantics.engine import Unsupported
from x3d_core.semantics.world import STATIC, Joint, State, World

from .base import BODIES, JOINTS, POSITION_FIRST, Backend, approximate, native, unsupported

_FULL_TURN = np.pi - 1e-9  # an angle range this wide is no limit at all
_STATE = batch.BodyFields.POSITION | batch.BodyFields.ANGLE | batch.BodyFields.VELOCITY | \
    batch.BodyFields.ANGULAR_VELOCITY
_VELOCITIES = batch.BodyFields.VELOCITY | batch.BodyFields.ANGULAR_VELOCITY
_LOADS = batch.BodyFields.FORCE | batch.BodyFields.TORQUE
# every feature name a DoubleAxisHingeJoint can need but forceOutput (the evaluator's)
_HINGE2 = ("DoubleAxisHingeJoint", "DoubleAxisHingeJoint.limits",
           *(f"DoubleAxisHingeJoint.{f}" for f, fd in node_type("DoubleAxisHingeJoint").fields.items()
             if fd.access != "outputOnly" and fd.type.kind != "node" and f not in ("forceOutput", "metadata")))


def _bias(erp: float, dt: float) -> float:
    """Chipmunk's error bias (the error left after a second) for ODE's ERP at step dt."""
    return float(np.clip(1.0 - erp, 0.0, 1.0) ** (1.0 / dt))


def _buffer(values: np.ndarray) -> batch.Buffer:
    buf = batch.Buffer()
    buf.set_float_buf(np.ascontiguousarray(values, dtype=np.float64).tobytes())
    return buf


class _Track:
    """An unstopped slider's line (world.slider_stops: none where minSeparation > maxSeparation): a
    groove of body2 along the axis through body1's point, recentred on that point before every
    step. Chipmunk's groove has ends that stop the slider, and no fixed length serves every run:
    it reads the line's offset from the ends' world positions, so their rounding is the line's
    (2e-4 m for ends at STATE_BOUND's 1e12 m, from the first step), and any shorter groove stops a
    run that slides farther. Recentred, it reaches 1 m plus twice the step's travel each way (a
    step moves a body with its velocity at the step's start, module notes): no end is reached, and
    the rounding stays that of the bodies' own coordinates."""

    def __init__(self, body1: pymunk.Body, body2: pymunk.Body, point: pymunk.Vec2d, axis: pymunk.Vec2d):
        self.body1, self.body2 = body1, body2
        self.origin = body2.world_to_local(point)  # separation 0, in body2's frame
        self.along = axis.rotated(-body2.angle)
        self.groove = pymunk.GrooveJoint(body2, body1, tuple(self.origin - self.along), tuple(self.origin + self.along),
                                         (0.0, 0.0))

    def recentre(self, dt: float) -> None:
        here = self.body1.position  # body1's point: its origin (the static body's is the world's)
        travel = (self.body1.velocity_at_world_point(here) - self.body2.velocity_at_world_point(here)).length * dt
        centre = self.origin + self.along * self.along.dot(self.body2.world_to_local(here) - self.origin)
        reach = self.along * (1.0 + 2.0 * travel)
        self.groove.groove_a, self.groove.groove_b = centre - reach, centre + reach


class _Contacts:
    """The shapes of world.collisions and the callbacks that give each contact x3d_core's
    parameters and filtering."""

    def __init__(self, sim: PymunkSimulation, c: Collisions, found: planar.Planar):
        self.sim, self.collisions = sim, c
        p = c.parameters
        self.index: dict[pymunk.Shape, int] = {}
        self.contact_z = found.contact_z
        mu, e = float(np.sqrt(p.friction[0])), float(np.sqrt(p.bounce))
        for k, (g, s) in enumerate(zip(c.geometries, found.sections)):
            if s is None:  # a static shape clear of every plane: it touches nothing
                continue
            body = sim.body_of(g.body)
            if s.vertices is None:
                shape = pymunk.Circle(body, s.radius, tuple(body.world_to_local(tuple(s.centre))))
            else:
                shape = pymunk.Poly(body, [tuple(body.world_to_local(tuple(v))) for v in s.vertices])
            shape.friction, shape.elasticity = mu, e
            if body is not sim.space.static_body:  # one body's shapes never touch each other
                shape.filter = pymunk.ShapeFilter(group=g.body + 1)
            sim.space.add(shape)
            self.index[shape] = k
        n = len(c.geometries)
        first, second = np.indices((n, n)).reshape(2, -1)
        self.allowed = c.may_touch(first, second).reshape(n, n)
        for i, j in found.apart:  # shapes in parallel planes that never meet in 3D
            self.allowed[i, j] = self.allowed[j, i] = False
        self.speed = float(p.surface_speed[0])
        self.min_bounce = p.min_bounce_speed if p.bounce > 0 else 0.0
        moving = np.array([sim.body_of(g.body) is not sim.space.static_body for g in c.geometries], dtype=bool)
        body = np.array([g.body for g in c.geometries])
        filtered = (~self.allowed & (moving[:, None] | moving) & (body[:, None] != body)).any()
        begin = self._begin if filtered else None
        pre_solve = self._pre_solve if self.speed or self.min_bounce > 0 else None
        if begin or pre_solve:
            sim.space.on_collision(begin=begin, pre_solve=pre_solve)

    def _begin(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        a, b = arbiter.shapes
        if not self.allowed[self.index[a], self.index[b]]:
            arbiter.process_collision = False

    def _pre_solve(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data) -> None:
        n = arbiter.normal  # from the first shape to the second
        if self.speed:  # X3D: (v2 - v1) . t1 = surfaceSpeed[0] with t1 = (-n_y, n_x) (friction_directions)
            arbiter.surface_velocity = (self.speed * n.y, -self.speed * n.x)
        if self.min_bounce > 0:  # ODE bounces only above minBounceSpeed
            a, b = arbiter.bodies
            points = arbiter.contact_point_set.points
            approach = -np.mean([(b.velocity_at_world_point(q.point_b) - a.velocity_at_world_point(q.point_a)).dot(n)
                                 for q in points]) if points else 0.0
            if approach <= self.min_bounce:
                arbiter.restitution = 0.0

    def points(self) -> ContactPoints:
        """The last step's contacts, each pair once, geometry1 the lower index (as ODE's)."""
        found: dict[tuple[int, int], pymunk.Arbiter] = {}

        def keep(arbiter: pymunk.Arbiter) -> None:
            i, j = (self.index[s] for s in arbiter.shapes)
            if self.allowed[i, j]:
                found.setdefault((i, j) if i < j else (j, i), arbiter)

        for body in self.sim.bodies:
            body.each_arbiter(keep)
        rows = []
        for (i, j), arbiter in sorted(found.items()):
            sign = 1.0 if self.index[arbiter.shapes[0]] == i else -1.0
            cps = arbiter.contact_point_set
            for q in cps.points:
                rows.append((*((q.point_a + q.point_b) / 2), *(cps.normal * sign), -q.distance, i, j))
        if not rows:
            return ContactPoints.none()
        a = np.array(rows)
        k = len(a)
        i, j = a[:, 5].astype(int), a[:, 6].astype(int)
        z = np.where(np.isnan(self.contact_z[i]), self.contact_z[j], self.contact_z[i])  # the moving shape's plane
        return ContactPoints(np.column_stack([a[:, 0], a[:, 1], z]), np.column_stack([a[:, 2:4], np.zeros(k)]),
                             a[:, 4].copy(), i, j)


class PymunkSimulation:
    def __init__(self, world: World, dt: float):
        found = planar.analyse(world)  # NotPlanar (an Unsupported) names what leaves the plane
        self.world, self.dt = world, dt
        b = world.bodies
        space = self.space = pymunk.Space()
        space.gravity = tuple(world.gravity[:2])
        space.iterations = max(1, world.iterations)
        space.damping = 1.0  # X3D's damping is the evaluator's
        space.sleep_time_threshold = float("inf")  # X3D's autoDisable is the evaluator's
        self.rows = np.flatnonzero(~b.fixed)
        self.bodies: list[pymunk.Body] = []
        for i in self.rows:
            self.bodies.append(self._body(int(i)))
        space.add(*self.bodies)
        self.start = State.initial(b)
        self.start.linear_velocity[b.fixed] = 0.0
        self.start.angular_velocity[b.fixed] = 0.0
        self.z = self.start.position[self.rows, 2]
        self.constraints: list[pymunk.Constraint] = []
        self.tracks: list[_Track] = []
        for j in world.joints:
            self._joint(j)
        space.add(*self.constraints)
        self.contacts_: _Contacts | None = None
        if world.collisions is not None:
            p = world.collisions.parameters
            space.collision_slop = world.contact_surface_thickness
            space.collision_bias = _bias(p.softness_erp if p.softness_erp is not None else world.error_correction, dt)
            self.contacts_ = _Contacts(self, world.collisions, found)
        self._listing()
        self.weightless = (~b.use_gravity[self.rows])[:, None] * b.mass[self.rows, None] * world.gravity[:2]
        self.set_loads(b.forces, b.torques)

    def _listing(self) -> None:
        """Where each moving body comes in pymunk.batch's listing of the space's bodies (which
        takes in the static body once shapes or joints use it): fixed once built, as nothing
        sleeps and nothing is removed."""
        probe = batch.Buffer()
        batch.get_space_bodies(self.space, batch.BodyFields.BODY_ID, probe)
        listed = list(np.frombuffer(probe.int_buf(), dtype=np.int64))
        self.listed = len(listed)
        self.pick = np.array([listed.index(body.id) for body in self.bodies], dtype=int)

    def _full(self, values: np.ndarray) -> batch.Buffer:
        """A batch buffer for every listed body: these rows for ours, zeros for the static body."""
        out = np.zeros((self.listed, values.shape[1]))
        out[self.pick] = values
        return _buffer(out)

    def body_of(self, row: int) -> pymunk.Body:
        """The pymunk body of a body row: the space's static body for fixed ones and STATIC."""
        if row == STATIC or self.world.bodies.fixed[row]:
            return self.space.static_body
        return self.bodies[int(np.searchsorted(self.rows, row))]

    def _body(self, i: int) -> pymunk.Body:
        b = self.world.bodies
        m, moment = float(b.mass[i]), float(b.inertia[i, 2, 2])
        if not (m > 0 and moment > 0):
            raise Unsupported(f"RigidBody {b.names[i]}: pymunk needs a positive mass and moment of inertia about z "
                              f"(mass {m:g}, moment {moment:g})")
        body = pymunk.Body(m, moment)
        body.center_of_gravity = tuple(b.com[i, :2])  # before the position: setting it moves the origin
        body.position = tuple(b.position[i, :2])
        body.angle = float(R.twist_angle(b.orientation[i], planar.Z))
        body.velocity = tuple(b.linear_velocity[i, :2])
        body.angular_velocity = float(b.angular_velocity[i, 2])
        return body

    def _joint(self, j: Joint) -> None:
        if j.type == "MotorJoint" or j.body1 == j.body2 or j.body1 == j.body2 == STATIC:
            return  # a motor is loads (the evaluator's); the others join nothing that moves
        p = j.params
        body1, body2 = self.body_of(j.body1), self.body_of(j.body2)
        anchor = tuple(j.anchor[:2])
        joint_bias = _bias(self.world.error_correction, self.dt)
        made: list[tuple[pymunk.Constraint, float]] = []
        if j.type in ("BallJoint", "UniversalJoint", "SingleAxisHingeJoint"):  # in the plane, each a pivot
            made.append((pymunk.PivotJoint(body2, body1, anchor), joint_bias))
        if j.type == "SingleAxisHingeJoint" and not (p["minAngle"] <= -_FULL_TURN and p["maxAngle"] >= _FULL_TURN):
            lo, hi = max(p["minAngle"], -np.pi), min(p["maxAngle"], np.pi)
            if j.axes[0, 2] < 0:  # X3D's angle turns about the axis: about -z it is minus pymunk's
                lo, hi = -hi, -lo
            offset = body1.angle - body2.angle
            made.append((pymunk.RotaryLimitJoint(body2, body1, offset + lo, offset + hi),
                         _bias(p["stopErrorCorrection"], self.dt)))
        elif j.type == "SliderJoint":
            made.extend(self._slider(j, body1, body2))
        elif j.type not in ("BallJoint", "UniversalJoint", "SingleAxisHingeJoint"):
            raise Unsupported(f"{j.type} {j.name}: not built by the pymunk backend")
        for constraint, bias in made:
            constraint.error_bias = bias
            self.constraints.append(constraint)

    def _slider(self, j: Joint, body1: pymunk.Body, body2: pymunk.Body) -> list[tuple[pymunk.Constraint, float]]:
        """body1's origin on a groove of body2 along the axis, from minSeparation to maxSeparation
        (its ends are the stops, corrected at stopErrorCorrection), or a _Track where the slider
        has no stops (its line corrected at errorCorrection, as ODE's); the two turning together."""
        start = body1.position  # a static body1 is at the origin: its point is too
        axis = pymunk.Vec2d(*j.axes[0, :2])
        joint_bias = _bias(self.world.error_correction, self.dt)
        lock = (pymunk.GearJoint(body2, body1, body1.angle - body2.angle, 1.0), joint_bias)
        if j.stops is None:
            self.tracks.append(_Track(body1, body2, start, axis))
            return [(self.tracks[-1].groove, joint_bias), lock]
        lo, hi = j.stops
        if hi == lo:  # no groove to slide in: a pivot at the one separation allowed
            held = pymunk.PivotJoint(body2, body1, tuple(start + axis * lo))
        else:
            ends = [body2.world_to_local(tuple(start + axis * s)) for s in (lo, hi)]
            held = pymunk.GrooveJoint(body2, body1, tuple(ends[0]), tuple(ends[1]), (0.0, 0.0))
        return [(held, _bias(j.params["stopErrorCorrection"], self.dt)), lock]

    # -- running ------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        space, dt = self.space, self.dt
        for _ in range(n):
            for track in self.tracks:
                track.recentre(dt)
            if self.loaded:  # Chipmunk clears forces and torques after every step
                batch.set_space_bodies(space, _LOADS, self.loads)
            space.step(dt)

    def state(self) -> State:
        s = self.start
        out = State(s.position.copy(), s.orientation.copy(), s.linear_velocity.copy(), s.angular_velocity.copy())
        if not self.bodies:
            return out
        buf = batch.Buffer()
        batch.get_space_bodies(self.space, _STATE, buf)
        v = np.frombuffer(buf.float_buf(), dtype=np.float64).reshape(-1, 6)[self.pick]  # x, y, angle, vx, vy, w
        rows, k = self.rows, len(self.rows)
        out.position[rows] = np.column_stack([v[:, :2], self.z])
        out.orientation[rows] = R.from_axis_angle(np.column_stack([np.zeros((k, 2)), np.ones(k), v[:, 2]]))
        out.linear_velocity[rows] = np.column_stack([v[:, 3:5], np.zeros(k)])
        out.angular_velocity[rows] = np.column_stack([np.zeros((k, 2)), v[:, 5]])
        return out

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        """The in-plane parts (x3d_core.semantics.planar keeps the rest zero)."""
        if self.bodies:
            rows = self.rows
            batch.set_space_bodies(self.space, _VELOCITIES,
                                   self._full(np.column_stack([linear[rows, :2], angular[rows, 2]])))

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        """Kept and written before every step; a body without gravity gets -m g with it."""
        rows = self.rows
        loads = np.column_stack([forces[rows, :2] - self.weightless, torques[rows, 2]])
        self.loaded = bool(loads.any())
        self.loads = self._full(loads)

    def contacts(self) -> ContactPoints:
        return self.contacts_.points() if self.contacts_ is not None else ContactPoints.none()


class PymunkBackend(Backend):
    name = "pymunk"
    integration = POSITION_FIRST  # Chipmunk moves a body, then adds the step's loads (module notes)
    scope = "planar scenes only"  # x3d_core.semantics.planar: a world whose bodies leave their plane is refused
    declared = {
        **unsupported("not built: x3d_core.semantics.planar cuts 2D sections for a world's collider alone, so a collection "
                      "only a sensor watches has no Chipmunk shapes (shapes_collide could test them without a response)",
                      "CollisionSensor.collider.watchedOnly"),
        # planar worlds only (x3d_core.semantics.planar): out-of-plane values are refused, in-plane ones native
        **native(*(f for f in BODIES if f != "RigidBodyCollection.gravity"), *JOINTS,
                 "RigidBodyCollection.gravity", "RigidBodyCollection.errorCorrection",
                 "SingleAxisHingeJoint.stopErrorCorrection",
                 "CollisionCollection", "CollisionCollection.appliedParameters", "CollisionSensor",
                 "CollidableShape.geometry.Box", "CollidableShape.geometry.Sphere",
                 "CollidableShape.geometry.Cylinder", "CollidableShape.geometry.Cone",
                 "CollisionCollection.frictionCoefficients", "CollisionCollection.bounce",
                 "CollisionCollection.appliedParameters.BOUNCE", "CollisionCollection.surfaceSpeed",
                 "CollisionCollection.appliedParameters.SPEED-1",
                 # for a normal in the plane ODE's second friction direction is z, where nothing moves
                 "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2",
                 "CollisionCollection.appliedParameters.SPEED-2",
                 "CollisionCollection.softnessErrorCorrection",
                 "CollisionCollection.appliedParameters.ERROR_REDUCTION",
                 # the overlap Chipmunk leaves uncorrected: ODE's surface layer
                 "RigidBodyCollection.contactSurfaceThickness"),
        **approximate("a body without gravity gets -m g among its loads at every step (Chipmunk has one "
                      "gravity): exact to rounding", "RigidBody.useGlobalGravity"),
        **approximate("Chipmunk's sequential-impulse solver runs this many sweeps over joints and contacts "
                      "together, as ODE's quick-step does (at least 1)", "RigidBodyCollection.iterations"),
        **approximate("a pivot in the plane: the joint's other freedoms turn out of the plane, where "
                      "x3d_core.semantics.planar has shown nothing drives them", "UniversalJoint"),
        **approximate("pymunk bounces per contact pair, not per point: the bounce is dropped where the pair's "
                      "mean approach speed is at most minBounceSpeed (ODE decides point by point; the same "
                      "wherever a pair's points approach alike, as a face landing flat)",
                      "CollisionCollection.minBounceSpeed"),
        **approximate("a groove on body2 from minSeparation to maxSeparation whose ends are the stops, body1 "
                      "turning with body2 (a gear of ratio 1): the groove corrects its line and its ends together "
                      "at stopErrorCorrection (ODE: the line at errorCorrection)",
                      "SliderJoint.stopErrorCorrection"),
        **unsupported("Chipmunk's joint limits (RotaryLimitJoint, a groove's ends) have no restitution",
                      "SingleAxisHingeJoint.stopBounce", "SliderJoint.stopBounce"),
        **unsupported("Chipmunk's joints are rigid: no constraint force mixing (0, rigid, is Chipmunk's own)",
                      "RigidBodyCollection.constantForceMix", native_at=0.0),
        **unsupported("Chipmunk's contacts are rigid: no constraint force mixing",
                      "CollisionCollection.softnessConstantForceMix",
                      "CollisionCollection.appliedParameters.CONSTANT_FORCE"),
        **unsupported("Chipmunk corrects penetration at collision_bias with no cap on its speed",
                      "RigidBodyCollection.maxCorrectionSpeed"),
        **unsupported("Chipmunk has one integrator and one solver: nothing to switch",
                      "RigidBodyCollection.preferAccuracy"),
        **unsupported("Chipmunk's friction is Coulomb's, without ODE's force-dependent slip",
                      "CollisionCollection.slipFactors", "CollisionCollection.appliedParameters.SLIP-1",
                      "CollisionCollection.appliedParameters.SLIP-2"),
        **unsupported("a CollisionCollection has no friction direction to give",
                      "CollisionCollection.appliedParameters.USER_FRICTION"),
        **unsupported("ODE's hinge2: its suspension and second hinge act out of the plane", *_HINGE2),
        **unsupported("a triangle mesh or an elevation grid has no exact section by the plane",
                      "CollidableShape.geometry.IndexedFaceSet", "CollidableShape.geometry.IndexedTriangleSet",
                      "CollidableShape.geometry.TriangleSet", "CollidableShape.geometry.ElevationGrid"),
    }

    def version(self) -> str:
        return pymunk.version

    def build(self, world: World, dt: float) -> PymunkSimulation:
        return PymunkSimulation(world, dt)


BACKEND = PymunkBackend()
