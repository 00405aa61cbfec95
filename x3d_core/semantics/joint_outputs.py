"""Joint output fields, computed from body states the same way for every backend.

Angles and separations are relative to the initial configuration (clause 37.2.5.1).
Signs follow ODE, the engine the component's parameters come from: an angle or a
separation measures body1 relative to body2 (a hinge's angleRate is axis . (w1 - w2),
a slider's separationRate is axis . (v1 - v2)); the static environment is at rest.
A MotorJoint's axes are anchored as 37.4.9 says (MotorAxes), for its torques and outputs alike.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from . import rotation as R
from .world import STATIC, Bodies, Joint, State


class MotorAxes:
    """A MotorJoint's axes where 37.4.9 anchors them: "The motorAxis1 field is anchored to the
    global frame. The motorAxis2 field is anchored to body1's frame of reference, and the
    motorAxis3 field is anchored to body2's frame of reference." Each is given in world
    coordinates at the start (as ODE's dJointSetAMotorAxis takes an axis and its anchor) and then
    turns with its carrier; where that is the static environment (NULL, a fixed body), it stays
    put. A zero axis stays 0 0 0: the clause's disabled axis, along which nothing acts."""

    def __init__(self, joint: Joint, bodies: Bodies):
        self.carriers = np.array([STATIC, joint.body1, joint.body2])
        self.moving = self.carriers != STATIC
        q0 = np.tile(R.IDENTITY, (3, 1))
        q0[self.moving] = bodies.orientation[self.carriers[self.moving]]
        self.local = R.rotate(R.conjugate(q0), joint.axes)  # each axis in its carrier's frame
        self.directed = np.any(joint.axes != 0.0, axis=1)  # the axes not disabled

    def current(self, orientation: np.ndarray) -> np.ndarray:
        """(3, 3) the axes in world coordinates for the bodies' orientations (n, 4)."""
        q = np.tile(R.IDENTITY, (3, 1))
        q[self.moving] = orientation[self.carriers[self.moving]]
        return R.rotate(q, self.local)


@dataclass
class _Frames:
    """A joint's anchor and axes fixed in each body at the start (local coordinates)."""
    anchor1: np.ndarray
    anchor2: np.ndarray
    axes1: np.ndarray  # (3, 3) the joint's axes in body1's frame
    axes2: np.ndarray  # in body2's frame
    q_rel0_conjugate: np.ndarray  # the conjugate of body1's orientation in body2's frame at the start
    offset0: np.ndarray  # body1's origin minus body2's, in body1's frame, at the start
    motor: MotorAxes | None = None  # a MotorJoint's axes as anchored


def _pose(state: State, row: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    if row == STATIC:
        return np.zeros(3), R.IDENTITY, np.zeros(3), np.zeros(3)
    return state.position[row], state.orientation[row], state.linear_velocity[row], state.angular_velocity[row]


class JointOutputs:
    """Computes, per frame, the output fields each joint's forceOutput selects."""

    def __init__(self, joints: list[Joint], bodies: Bodies):
        self.joints = [j for j in joints if j.outputs]
        start = State.initial(bodies)
        self.frames = []
        for j in self.joints:
            p1, q1, _, _ = _pose(start, j.body1)
            p2, q2, _, _ = _pose(start, j.body2)
            c1, c2 = R.conjugate(q1), R.conjugate(q2)
            self.frames.append(_Frames(
                anchor1=R.rotate(c1, j.anchor - p1), anchor2=R.rotate(c2, j.anchor - p2),
                axes1=R.rotate(c1, j.axes), axes2=R.rotate(c2, j.axes),
                q_rel0_conjugate=R.conjugate(R.multiply(c2, q1)), offset0=R.rotate(c1, p1 - p2),
                motor=MotorAxes(j, bodies) if j.type == "MotorJoint" else None))

    def values(self, state: State) -> list[tuple[str, str, Any]]:
        """(joint name, field, value) for every selected output."""
        out = []
        for j, f in zip(self.joints, self.frames):
            computed = _compute(j, f, state)
            out.extend((j.name, name, computed[name]) for name in j.outputs)
        return out


_ON_AXES1 = frozenset({"body1Axis", "angleRate", "hinge1AngleRate", "separation", "separationRate"})
_MOTOR_ANGLES = ("motor1Angle", "motor2Angle", "motor3Angle")
_MOTOR_RATES = ("motor1AngleRate", "motor2AngleRate", "motor3AngleRate")
_ANGLES = frozenset({"angle", "hinge1Angle", "hinge2Angle", *_MOTOR_ANGLES})


def _compute(j: Joint, f: _Frames, state: State) -> dict[str, Any]:
    """The outputs the joint selects, and only those: a sweep's fine steps record a frame per
    step, and every output of every frame was most of such a run's time."""
    want = j.outputs
    p1, q1, v1, w1 = _pose(state, j.body1)
    p2, q2, v2, w2 = _pose(state, j.body2)
    out: dict[str, Any] = {}
    if "body1AnchorPoint" in want:
        out["body1AnchorPoint"] = p1 + R.rotate(q1, f.anchor1)
    if "body2AnchorPoint" in want:
        out["body2AnchorPoint"] = p2 + R.rotate(q2, f.anchor2)
    axes1 = R.rotate(q1, f.axes1) if not _ON_AXES1.isdisjoint(want) else None  # the joint's axes as body1 carries them
    axis2 = R.rotate(q2, f.axes2[1]) if "body2Axis" in want or "hinge2AngleRate" in want else None
    if axes1 is not None and "body1Axis" in want:
        out["body1Axis"] = axes1[0]
    if axis2 is not None and "body2Axis" in want:
        out["body2Axis"] = axis2
    # body1's turn since the start, in body2's frame
    delta = R.multiply(R.multiply(R.conjugate(q2), q1), f.q_rel0_conjugate) if not _ANGLES.isdisjoint(want) else None
    dw = w1 - w2
    t = j.type
    if t == "SingleAxisHingeJoint":
        if "angle" in want:
            out["angle"] = float(R.twist_angle(delta, f.axes2[0]))
        if "angleRate" in want:
            out["angleRate"] = float(axes1[0] @ dw)
    elif t == "DoubleAxisHingeJoint":
        if "hinge1Angle" in want:
            out["hinge1Angle"] = float(R.twist_angle(delta, f.axes2[0]))
        if "hinge1AngleRate" in want:
            out["hinge1AngleRate"] = float(axes1[0] @ dw)
        if "hinge2Angle" in want:
            out["hinge2Angle"] = float(R.twist_angle(delta, f.axes2[1]))
        if "hinge2AngleRate" in want:
            out["hinge2AngleRate"] = float(axis2 @ dw)
    elif t == "SliderJoint":
        if "separation" in want:
            out["separation"] = float(axes1[0] @ (p1 - p2 - R.rotate(q1, f.offset0)))
        if "separationRate" in want:
            out["separationRate"] = float(axes1[0] @ (v1 - v2))
    elif t == "MotorJoint":
        out.update(_motor(j, f.motor, state, q2, delta, dw))
    return out


def _motor(j: Joint, m: MotorAxes, state: State, q2: np.ndarray, delta: np.ndarray | None,
           dw: np.ndarray) -> dict[str, float]:
    """A MotorJoint's outputs about its axes as anchored now: motorNAngleRate is the rate the motor
    is turning, axis . (w1 - w2) (ODE's dJointGetAMotorAngleRate), in either mode; motorNAngle is
    the user's axisNAngle in user-calculated mode (autoCalc FALSE, ODE's user mode), else the twist
    of body1's turn since the start relative to body2 about the axis. A disabled axis (0 0 0)
    reports 0 for both, in either mode: the motor does not act along it, and it has no direction
    to turn about."""
    axes, on = m.current(state.orientation), m.directed
    out = dict(zip(_MOTOR_RATES, np.where(on, axes @ dw, 0.0).tolist()))
    if delta is not None:  # an angle is wanted
        angles = (R.twist_angle(delta, R.rotate(R.conjugate(q2), axes)) if j.params["autoCalc"]
                  else np.array([j.params[f"axis{k}Angle"] for k in (1, 2, 3)]))
        out.update(zip(_MOTOR_ANGLES, np.where(on, angles, 0.0).tolist()))
    return out
