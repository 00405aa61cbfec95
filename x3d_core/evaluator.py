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

from . import rotation as R
from .engine import BlewUp, Engine, Simulation
from .joint_outputs import JointOutputs
from .trace import Trace
from .world import STATIC, World

# A frame end that lands within this fraction of a step of a step boundary counts as
# on it: frame times are sums of decimal fractions and carry rounding of ~1e-16 s.
_STEP_SLACK = 1e-9
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


class _Damping:
    """autoDamp as ODE defines it: each step takes a fraction of each velocity away."""

    def __init__(self, world: World):
        b = world.bodies
        on = b.auto_damp & ~b.fixed
        self.active = bool(on.any())
        self.keep_linear = np.where(on, 1.0 - b.linear_damping, 1.0)[:, None]
        self.keep_angular = np.where(on, 1.0 - b.angular_damping, 1.0)[:, None]

    def apply(self, sim: Simulation) -> None:
        s = sim.state()
        sim.set_velocities(s.linear_velocity * self.keep_linear, s.angular_velocity * self.keep_angular)


class _Motors:
    """MotorJoint as ODE's AMotor: each enabled axis (carried by body1, or fixed in the
    world where body1 is the static environment) gets axisNTorque, body1 the torque and
    body2 its opposite, at every step."""

    def __init__(self, world: World):
        self.world = world
        self.motors = []
        for j in world.joints:
            n = int(j.params.get("enabledAxes", 0)) if j.type == "MotorJoint" else 0
            torques = np.array([j.params[f"axis{k + 1}Torque"] for k in range(n)])
            if n and np.any(torques):
                q1 = R.IDENTITY if j.body1 == STATIC else world.bodies.orientation[j.body1]
                self.motors.append((j, R.rotate(R.conjugate(q1), j.axes[:n]), torques))
        self.active = bool(self.motors)

    def apply(self, sim: Simulation) -> None:
        s = sim.state()
        torques = self.world.bodies.torques.copy()
        for j, local_axes, amounts in self.motors:
            q1 = R.IDENTITY if j.body1 == STATIC else s.orientation[j.body1]
            tau = amounts @ R.rotate(q1, local_axes)
            if j.body1 != STATIC:
                torques[j.body1] += tau
            if j.body2 != STATIC:
                torques[j.body2] -= tau
        sim.set_loads(self.world.bodies.forces, torques)


def run(worlds: list[World], engine: Engine, settings: RunSettings, frame_times: np.ndarray | None = None) -> Trace:
    """Simulate every world and return the event trace."""
    dt = settings.dt
    sims = [engine.build(w, dt) for w in worlds]
    damping = [_Damping(w) for w in worlds]
    motors = [_Motors(w) for w in worlds]
    recorders = [_Recorder(w, sim) for w, sim in zip(worlds, sims)]
    trace = Trace()
    for rec in recorders:
        rec.record(trace, 0.0)
    steps = 0
    for t in settings.frame_times() if frame_times is None else frame_times:
        due = int(math.floor(t / dt + _STEP_SLACK))
        for sim, damp, motor in zip(sims, damping, motors):
            try:
                if damp.active or motor.active:  # inputs that change at every step
                    for _ in range(due - steps):
                        if motor.active:
                            motor.apply(sim)
                        sim.step()
                        if damp.active:
                            damp.apply(sim)
                elif due > steps:
                    sim.step(due - steps)
            except BlewUp as e:
                raise BlewUp(f"blew up by t={due * dt:g}: {e}") from None
        steps = max(steps, due)
        for rec in recorders:
            rec.record(trace, float(t))
    return trace


class _Recorder:
    """Reads one world's state at a frame end into the trace, and checks it is finite."""

    def __init__(self, world: World, sim: Simulation):
        self.world, self.sim = world, sim
        self.outputs = JointOutputs(world.joints, world.bodies)
        self.rows = np.flatnonzero(world.bodies.enabled)
        self.names = [world.bodies.names[i] for i in self.rows]
        self.all = len(self.rows) == len(world.bodies)

    def record(self, trace: Trace, t: float) -> None:
        s = self.sim.state()
        for arr in (s.position, s.orientation, s.linear_velocity, s.angular_velocity):
            if not np.isfinite(arr).all():
                row = int(np.flatnonzero(~np.isfinite(arr).reshape(len(arr), -1).all(axis=1))[0])
                raise BlewUp(f"blew up at t={t:g}: {self.world.bodies.names[row]} has a non-finite state")
        pick = (lambda a: a) if self.all else (lambda a: a[self.rows])
        trace.add_many(t, self.names, "position", "SFVec3f", pick(s.position))
        trace.add_many(t, self.names, "orientation", "SFRotation", pick(s.orientation), convert=R.to_axis_angle)
        trace.add_many(t, self.names, "linearVelocity", "SFVec3f", pick(s.linear_velocity))
        trace.add_many(t, self.names, "angularVelocity", "SFVec3f", pick(s.angular_velocity))
        for joint, field, value in self.outputs.values(s):
            trace.add(t, joint, field, _OUTPUT_TYPES[field], value)
