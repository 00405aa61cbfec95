"""The frame loop: a fixed physics step kept in step with frames of any length.

The physics step never depends on the frame rate: at the end of a frame at time t the
world has taken floor(t / dt) steps in all, whatever the frames before it were, so
30 Hz and 144 Hz frames see the same physics at the times they share. Outputs are
read at frame ends. What the spec defines and an engine need not know (damping,
joint outputs) is done here, once for every backend.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from x3d_core.model import fields as F
from x3d_core.traces.trace import Column, Trace

from . import rotation as R
from . import engine as _engine
from .collision import CONTACT_DEFAULTS, Collisions, ContactPoints, friction_directions
from .engine import BlewUp, Engine, Simulation, Stopped, Unsupported
from .joint_outputs import JointOutputs, MotorAxes
from .world import STATIC, State, World, parallel, undirected

# A frame end that lands within this fraction of a step of a step boundary counts as
# on it: frame times are sums of decimal fractions and carry rounding of ~1e-16 s.
_STEP_SLACK = 1e-9
# The largest |position| (m) and |velocity| (m/s, rad/s) a body may have before its run counts
# as blown up. An engine that hides a non-finite joint transform (DART uses the identity)
# carries on with finite but absurd states (1e157 rad/s). 1e12 is beyond any scene the
# component models: 1e12 m is 7 AU, where float64 keeps only 0.1 mm (less than contact and
# joint tolerances); 1e12 m/s is 3000 times the speed of light; at 1e12 rad/s a body turns
# 1e6 rad in a microsecond step, so its orientation means nothing.
STATE_BOUND = 1e12
_OUTPUT_TYPES = {"angle": "SFFloat", "angleRate": "SFFloat", "separation": "SFFloat", "separationRate": "SFFloat",
                 "hinge1Angle": "SFFloat", "hinge1AngleRate": "SFFloat", "hinge2Angle": "SFFloat",
                 "hinge2AngleRate": "SFFloat", "body1AnchorPoint": "SFVec3f", "body2AnchorPoint": "SFVec3f",
                 "body1Axis": "SFVec3f", "body2Axis": "SFVec3f",
                 **{f"motor{k}{s}": "SFFloat" for k in (1, 2, 3) for s in ("Angle", "AngleRate")}}


@dataclass
class RunSettings:
    duration: float = 1.0
    dt: float = 1.0 / 240.0
    frame_rate: float = 60.0

    def frame_times(self) -> np.ndarray:
        """Frame end times: every 1/frame_rate, and the duration itself last."""
        n = int(math.floor(self.duration * self.frame_rate + _STEP_SLACK))
        times = np.arange(1, n + 1) / self.frame_rate
        if n == 0 or times[-1] < self.duration - _STEP_SLACK / self.frame_rate:
            times = np.append(times, self.duration)
        return times


# A collection's solver iterations over a run (its steps x its iterations field) at most: an
# iteration of ODE's quick step costs ~50 ns a body (58 ns for one on a hinge, 48 ns each of a
# 50-link chain: docs/limits.md), so the bound is ~1.5 h of CPU a body, what the 10^9 steps a run
# may take (options.MAX_STEPS) cost at ODE's ~6 us a step for one body. iterations 1000000000 for
# the default 240 steps asked for 4 h a body, at --duration 10 for 40 h: without end.
MAX_SOLVER_ITERATIONS = 10**11


def too_much_solving(worlds: list[World], settings: RunSettings) -> tuple[World, float] | None:
    """The first world whose iterations field makes more than MAX_SOLVER_ITERATIONS over the
    run's steps, with how many; None where none does. Asked before any engine is built: every
    backend is refused alike, as for the steps themselves (DART and Drake ignore the field,
    PhysX takes 255 at most; the scene asks for the work all the same)."""
    steps = settings.duration / settings.dt
    for w in worlds:
        if steps * w.iterations > MAX_SOLVER_ITERATIONS:
            return w, steps * w.iterations
    return None


class _Damping:
    """autoDamp as ODE defines it: each step takes a fraction of each velocity away. The spec
    (37.4.10) damps "a multiple of the value calculated in the last frame" each frame; its model
    evaluates the physics once a frame, and damping once a step keeps the motion independent of
    the frame rate (conformance case damping accepts once a frame and once a step)."""

    def __init__(self, world: World):
        b = world.bodies
        on = b.auto_damp & ~b.fixed
        self.active = bool(on.any())
        self.keep_linear = np.where(on, 1.0 - b.linear_damping, 1.0)[:, None]
        self.keep_angular = np.where(on, 1.0 - b.angular_damping, 1.0)[:, None]


class _Motors:
    """MotorJoint torques as ODE's AMotor applies them (dJointAddAMotorTorques): each of the
    enabledAxes first axes, where 37.4.9 anchors it (joint_outputs.MotorAxes: axis 1 fixed in the
    world, axis 2 turning with body1, axis 3 with body2), gets axisNTorque along its current
    direction, body1 the torque and body2 its opposite, at every step. A disabled axis (0 0 0)
    adds nothing."""

    def __init__(self, world: World):
        self.motors = []
        for j in world.joints:
            n = int(j.params.get("enabledAxes", 0)) if j.type == "MotorJoint" else 0
            torques = np.zeros(3)
            torques[:n] = [j.params[f"axis{k + 1}Torque"] for k in range(n)]
            if np.any(torques[:, None] * j.axes):
                self.motors.append((j, MotorAxes(j, world.bodies), torques))
        self.active = bool(self.motors)

    def add_torques(self, torques: np.ndarray, s: State) -> None:
        for j, axes, amounts in self.motors:
            tau = amounts @ axes.current(s.orientation)
            if j.body1 != STATIC:
                torques[j.body1] += tau
            if j.body2 != STATIC:
                torques[j.body2] -= tau


class _SliderForces:
    """SliderJoint.sliderForce as ODE's dJointAddSliderForce: +F along the axis (carried by body1,
    or fixed in the world where body1 is the static environment) on body1 and -F on body2, at
    every step. Between two bodies each also gets the torque c x F, c half the vector from body1's
    centre of mass to body2's: the pair's forces then act along one line, so the joint's force
    turns neither body about the other (ODE's linear torque decoupling)."""

    def __init__(self, world: World):
        b = world.bodies
        self.sliders = []
        for j in world.joints:
            force = j.params.get("sliderForce", 0.0) if j.type == "SliderJoint" and j.body1 != j.body2 else 0.0
            if force:
                q1 = R.IDENTITY if j.body1 == STATIC else b.orientation[j.body1]
                self.sliders.append((j, R.rotate(R.conjugate(q1), j.axes[0]), force))
        self.com = b.com
        self.active = bool(self.sliders)

    def add_loads(self, forces: np.ndarray, torques: np.ndarray, s: State) -> None:
        for j, local_axis, amount in self.sliders:
            q1 = R.IDENTITY if j.body1 == STATIC else s.orientation[j.body1]
            f = amount * R.rotate(q1, local_axis)
            if j.body1 != STATIC:
                forces[j.body1] += f
            if j.body2 != STATIC:
                forces[j.body2] -= f
            if STATIC not in (j.body1, j.body2):
                ends = [s.position[k] + R.rotate(s.orientation[k], self.com[k]) for k in (j.body1, j.body2)]
                tau = np.cross(0.5 * (ends[1] - ends[0]), f)
                torques[j.body1] += tau
                torques[j.body2] += tau


class _AutoDisable:
    """autoDisable as clause 37 words it: "Once any one of these values is achieved, the body
    is considered as being at rest, unless acted upon by an external force (e.g., collision
    or action of connected joint)".

    Disabling, the literal reading: a candidate body whose linear speed is under its
    disableLinearSpeed OR whose angular speed is under its disableAngularSpeed (any one of
    the speed values) at every step for disableTime seconds (ceil(disableTime/dt) steps) is
    disabled. disableTime is read as the interval the condition must hold ("interval when
    body becomes at rest"), not as a third alternative: alone it has no clock to count from
    and would stop every body, however fast, at that time. ODE's reading (both speeds under
    their thresholds for the time) is the documented alternative; it disables later or never.

    A disabled body is held: no loads (its gravity cancelled), velocities zeroed after every
    step. It wakes (idle clock reset, the step's velocities kept) when acted upon:
    - a contact: one the body did not have at the step before (a new collision, with a body
      or the environment), or one with a body that is awake (ODE wakes a disabled body an
      enabled one touches). The contact it rests on does not wake it. Contacts are read only
      while some body is disabled: scenes without autoDisable, or before a body stops, pay
      nothing;
    - a force or torque: RigidBody.forces/torques are constant in a run (x3drbp has no
      events), so a body with a non-zero one is acted upon at every step and never disabled;
      wake() is the hook for loads or velocities set during a run.
    A body's own thresholds apply where its autoDisable is TRUE, else the collection's where
    that is. Only bodies on no joint take part: ODE disables whole islands of jointed bodies
    at once, and a joint's action wakes them, which x3drbp does not model (declared
    approximate)."""

    def __init__(self, world: World, dt: float):
        b = world.bodies
        c = world.node
        on_collection = bool(c.get("autoDisable"))
        collection = np.array([c.get("disableLinearSpeed"), c.get("disableAngularSpeed"), c.get("disableTime")])
        jointed = np.zeros(len(b), dtype=bool)
        for j in world.joints:
            for row in (j.body1, j.body2):
                if row != STATIC:
                    jointed[row] = True
        self.candidates = (b.auto_disable | on_collection) & ~b.fixed & ~jointed
        self.thresholds = np.where(b.auto_disable[:, None], b.disable_thresholds, collection)
        self.active = bool(self.candidates.any())
        # acted upon by an applied force or torque at every step
        self.pushed = np.any(b.forces != 0.0, axis=1) | np.any(b.torques != 0.0, axis=1)
        # idle time counted in whole steps, so that 0.5 s at 1/240 s is 120 steps, not 121
        self.needed = np.ceil(self.thresholds[:, 2] / dt - _STEP_SLACK)
        self.idle = np.zeros(len(b))
        self.disabled = np.zeros(len(b), dtype=bool)
        geometries = world.collisions.geometries if world.collisions is not None else []
        self.geometry_body = np.array([g.body for g in geometries], dtype=int)
        self.touching: set[tuple[int, int]] = set()  # geometry pairs in contact at the last step, if any body is off

    def wake(self, rows: np.ndarray) -> None:
        """Rows acted upon (a load or velocity set on them): awake, their idle clock reset."""
        self.disabled[rows] = False
        self.idle[rows] = 0

    def update(self, s: State, sim: Simulation) -> None:
        """After a step: wake the disabled bodies a contact acts on, then count idle steps and
        disable the bodies whose time has come."""
        pairs = None
        if self.disabled.any() and len(self.geometry_body):
            pairs = self._pairs(sim)
            self.wake(self._struck(pairs))
        slow = (np.linalg.norm(s.linear_velocity, axis=1) < self.thresholds[:, 0]) | \
            (np.linalg.norm(s.angular_velocity, axis=1) < self.thresholds[:, 1])
        self.idle = np.where(slow & self.candidates & ~self.pushed, self.idle + 1, 0)
        self.disabled |= self.candidates & (self.idle >= self.needed)
        if self.disabled.any() and len(self.geometry_body):
            self.touching = self._pairs(sim) if pairs is None else pairs
        else:
            self.touching = set()

    def _pairs(self, sim: Simulation) -> set[tuple[int, int]]:
        pts = sim.contacts()
        return {(min(a, b), max(a, b)) for a, b in zip(pts.geometry1.tolist(), pts.geometry2.tolist())}

    def _struck(self, pairs: set[tuple[int, int]]) -> np.ndarray:
        """The disabled rows a contact acts on: a new contact, or one with an awake body."""
        rows = []
        for pair in pairs:
            bodies = self.geometry_body[list(pair)]
            new = pair not in self.touching
            for me, other in ((bodies[0], bodies[1]), (bodies[1], bodies[0])):
                if me != STATIC and self.disabled[me] and (
                        new or (other != STATIC and not self.disabled[other])):
                    rows.append(me)
        return np.array(rows, dtype=int)


class _StepInputs:
    """What changes at every step and must be done between engine steps: motor torques, slider
    forces, damping, auto-disable. Inactive (and free) for scenes that use none of them."""

    def __init__(self, world: World, dt: float):
        self.world = world
        self.damping = _Damping(world)
        self.motors = _Motors(world)
        self.sliders = _SliderForces(world)
        self.disable = _AutoDisable(world, dt)
        self.pushing = self.motors.active or self.sliders.active  # loads that follow the bodies
        self.active = self.damping.active or self.pushing or self.disable.active
        b = world.bodies
        with np.errstate(over="ignore", invalid="ignore"):  # an overflowing weight blows up as a non-finite state
            self.weight = b.mass[:, None] * world.gravity * b.use_gravity[:, None]
        self.held = False  # loads set with a disabled body's weight cancelled

    def before(self, sim: Simulation) -> None:
        held = bool(self.disable.disabled.any())
        if not (self.pushing or held or self.held):  # self.held: a body woke, its loads come back
            return
        self.held = held
        b = self.world.bodies
        forces, torques = b.forces.copy(), b.torques.copy()
        s = sim.state()
        self.motors.add_torques(torques, s)
        self.sliders.add_loads(forces, torques, s)
        off = self.disable.disabled
        forces[off] = -self.weight[off]  # a disabled body feels nothing: its loads cancel gravity
        torques[off] = 0.0
        sim.set_loads(forces, torques)

    def after(self, sim: Simulation) -> None:
        if not (self.damping.active or self.disable.active):
            return
        s = sim.state()
        lin = s.linear_velocity * self.damping.keep_linear
        ang = s.angular_velocity * self.damping.keep_angular
        if self.disable.active:
            self.disable.update(s, sim)
            lin[self.disable.disabled] = 0.0
            ang[self.disable.disabled] = 0.0
        sim.set_velocities(lin, ang)


def run(worlds: list[World], engine: Engine, settings: RunSettings, frame_times: np.ndarray | None = None) -> Trace:
    """Simulate every world and return the event trace. Unsupported, before any engine sees
    it, where a joint needs an axis that is zero (world.undirected) or a joint's two axes are one
    line (world.parallel): one answer on every backend."""
    zero = [axis for w in worlds for axis in undirected(w)]
    if zero:
        raise Unsupported("; ".join(f"{a}: a joint axis of no direction (the spec gives none in its place)"
                                    for a in zero))
    one_line = [joint for w in worlds for joint in parallel(w)]
    if one_line:
        raise Unsupported("; ".join(f"{j}: one line, not the two independent axes the joint turns about"
                                    for j in one_line))
    dt = settings.dt
    sims = [engine.build(w, dt) for w in worlds]
    inputs = [_StepInputs(w, dt) for w in worlds]
    recorders = [_Recorder(w, sim) for w, sim in zip(worlds, sims)]
    trace = Trace()
    # trace.blocks[:progress.whole] are the frames recorded for every world; an engine that
    # aborts the process from inside a step finds them there too (engine.engine_abort)
    progress = _engine.progress = _engine.Progress(trace)
    try:
        for rec in recorders:
            rec.record(trace, 0.0)
        progress.whole = len(trace.blocks)
        steps = 0
        for t in settings.frame_times() if frame_times is None else frame_times:
            due = int(math.floor(t / dt + _STEP_SLACK))
            progress.t = due * dt
            for sim, step_inputs in zip(sims, inputs):
                try:
                    if step_inputs.active:
                        for _ in range(due - steps):
                            step_inputs.before(sim)
                            sim.step()
                            step_inputs.after(sim)
                    elif due > steps:
                        sim.step(due - steps)
                except BlewUp as e:
                    raise BlewUp(f"blew up by t={due * dt:g}: {e}") from None
            steps = max(steps, due)
            for rec in recorders:
                rec.record(trace, float(t))
            progress.whole = len(trace.blocks)
    except Stopped as e:
        del trace.blocks[progress.whole:]
        e.trace = trace
        raise
    finally:
        if _engine.progress is progress:
            _engine.progress = None
    return trace


class _Sensors:
    """CollisionSensor outputs from the engine's contact points, in the spec's terms: per
    contact a Contact node (position, contactNormal from body1 towards body2, depth, the
    bodies and collidables, the first friction direction, 0 0 0 where the contacts apply no
    friction, and the collection's contact parameters with its appliedParameters, which say
    which of them apply), the collidables in contact as intersections, and isActive. Recorded as
    columns (Trace.add_table): a frame costs a few array operations however many contacts."""

    def __init__(self, world: World, c: Collisions):
        self.names = [n for n, _ in c.sensors]
        self.geometry_names = np.array([g.name for g in c.geometries], dtype=object)
        self.body_names = np.array([world.bodies.names[g.body] if g.body != STATIC else "NULL"
                                    for g in c.geometries], dtype=object)
        p = c.parameters
        # the collection's own values (collision.CONTACT_DEFAULTS), not those applied: which of them
        # apply is what appliedParameters says, written as the set of names x3drbp reads (X3D 4.0 spelling)
        self.constant = [
            Column("appliedParameters", None, F.format_xml(F.FIELD_TYPES["MFString"], sorted(p.applied)), True),
            *(Column(name, c.collider.spec.fields[source].type, c.collider.get(source), True)
              for name, source in CONTACT_DEFAULTS.items())]
        # 37.4.7: "If there is no friction, the direction should be set to 0, 0, 0." (None: there is)
        self.no_direction = (Column("frictionDirection", F.FIELD_TYPES["SFVec3f"], np.zeros(3), True)
                             if p.frictionless else None)

    def __bool__(self) -> bool:
        return bool(self.names)

    def record(self, trace: Trace, t: float, pts: ContactPoints) -> None:
        k = len(pts.depth)
        f = F.FIELD_TYPES
        g1, g2 = pts.geometry1, pts.geometry2
        direction = self.no_direction
        if direction is None:
            direction = Column("frictionDirection", f["SFVec3f"], friction_directions(pts.normal)[0] if k else pts.normal)
        contacts = [Column("position", f["SFVec3f"], pts.position), Column("contactNormal", f["SFVec3f"], pts.normal),
                    Column("depth", f["SFFloat"], pts.depth),
                    Column("body1", None, self.body_names[g1]), Column("body2", None, self.body_names[g2]),
                    Column("geometry1", None, self.geometry_names[g1]),
                    Column("geometry2", None, self.geometry_names[g2]), direction, *self.constant]
        # the collidables in contact, each once, in the order the contacts first name them
        both = np.column_stack([g1, g2]).ravel()
        unique, first = np.unique(both, return_index=True)
        touching = [Column("", None, self.geometry_names[unique[np.argsort(first)]])]
        for name in self.names:
            trace.add(t, name, "isActive", "SFBool", k > 0)
            trace.add_table(t, name, "contacts", k, contacts)
            trace.add_table(t, name, "intersections", len(unique), touching)


class _Recorder:
    """Reads one world's state at a frame end into the trace, and checks it is finite and
    within STATE_BOUND."""

    def __init__(self, world: World, sim: Simulation):
        self.world, self.sim = world, sim
        self.outputs = JointOutputs(world.joints, world.bodies)
        self.rows = np.flatnonzero(world.bodies.enabled)
        self.names = [world.bodies.names[i] for i in self.rows]
        self.all = len(self.rows) == len(world.bodies)
        self.sensors = _Sensors(world, world.collisions) if world.collisions is not None and world.collisions.sensors \
            else None
        self.watched = [_Sensors(world, c) for c in world.watched]  # each a set only its sensors watch

    def record(self, trace: Trace, t: float) -> None:
        try:
            s = self.sim.state()
        except BlewUp as e:  # an engine that found its state unsound (pybullet at its speed clamp)
            raise BlewUp(f"blew up at t={t:g}: {e}") from None
        # the bounded fields in one reduction (a numpy call costs more than a few bodies' numbers); a
        # state read whole brings its unit quaternions into it, each component within the bound
        if s.whole is not None:
            sound = np.abs(s.whole).max(initial=0.0) <= STATE_BOUND  # false for a NaN or an infinity too
        else:
            bounded = np.concatenate((s.position, s.linear_velocity, s.angular_velocity), axis=1)
            sound = np.abs(bounded).max(initial=0.0) <= STATE_BOUND and np.isfinite(s.orientation).all()
        if not sound:
            self._blew_up(s, t)
        position, orientation, linear, angular = s.position, s.orientation, s.linear_velocity, s.angular_velocity
        if not self.all:
            rows = self.rows
            position, orientation, linear, angular = position[rows], orientation[rows], linear[rows], angular[rows]
        trace.add_many(t, self.names, "position", "SFVec3f", position)
        trace.add_many(t, self.names, "orientation", "SFRotation", orientation, convert=R.to_axis_angle)
        trace.add_many(t, self.names, "linearVelocity", "SFVec3f", linear)
        trace.add_many(t, self.names, "angularVelocity", "SFVec3f", angular)
        for joint, field, value in self.outputs.values(s):
            trace.add(t, joint, field, _OUTPUT_TYPES[field], value)
        if self.sensors:
            self.sensors.record(trace, t, self.sim.contacts())
        for k, sensors in enumerate(self.watched):
            sensors.record(trace, t, self.sim.watched_contacts(k))

    def _blew_up(self, s: State, t: float) -> None:
        """BlewUp naming the first body whose state is not finite, else the first beyond STATE_BOUND."""
        for arr in (s.position, s.orientation, s.linear_velocity, s.angular_velocity):
            if not np.isfinite(arr).all():
                row = int(np.flatnonzero(~np.isfinite(arr).reshape(len(arr), -1).all(axis=1))[0])
                raise BlewUp(f"blew up at t={t:g}: {self.world.bodies.names[row]} has a non-finite state")
        for arr, what in ((s.position, "position"), (s.linear_velocity, "linear velocity"),
                          (s.angular_velocity, "angular velocity")):
            if len(arr) and np.abs(arr).max() > STATE_BOUND:
                row = int(np.flatnonzero((np.abs(arr) > STATE_BOUND).any(axis=1))[0])
                raise BlewUp(f"blew up at t={t:g}: {self.world.bodies.names[row]}'s {what} is beyond "
                             f"{STATE_BOUND:g} (SI units)")
