"""Joint output fields, computed from body states the same way for every backend.

Angles and separations are relative to the initial configuration (clause 37.2.5.1).
Signs follow ODE, the engine the component's parameters come from: an angle or a
separation measures body1 relative to body2 (a hinge's angleRate is axis . (w1 - w2),
a slider's separationRate is axis . (v1 - v2)); the static environment is at rest.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from . import rotation as R
from .world import STATIC, Bodies, Joint, State


@dataclass
class _Frames:
    """A joint's anchor and axes fixed in each body at the start (local coordinates)."""
    anchor1: np.ndarray
    anchor2: np.ndarray
    axes1: np.ndarray  # (3, 3) the joint's axes in body1's frame
    axes2: np.ndarray  # in body2's frame
    q_rel0_conjugate: np.ndarray  # the conjugate of body1's orientation in body2's frame at the start
    offset0: np.ndarray  # body1's origin minus body2's, in body1's frame, at the start


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
                q_rel0_conjugate=R.conjugate(R.multiply(c2, q1)), offset0=R.rotate(c1, p1 - p2)))

    def values(self, state: State) -> list[tuple[str, str, Any]]:
        """(joint name, field, value) for every selected output."""
        out = []
        for j, f in zip(self.joints, self.frames):
            computed = _compute(j, f, state)
            out.extend((j.name, name, computed[name]) for name in j.outputs)
        return out


_ON_AXES1 = frozenset({"body1Axis", "angleRate", "hinge1AngleRate", "separation", "separationRate",
                       "motor1AngleRate", "motor2AngleRate", "motor3AngleRate"})
_ANGLES = frozenset({"angle", "hinge1Angle", "hinge2Angle", "motor1Angle", "motor2Angle", "motor3Angle"})


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
    elif t == "MotorJoint" and not j.params["autoCalc"]:  # ODE's user mode: the angles the user gives
        for k in range(3):
            out[f"motor{k + 1}Angle"] = j.params[f"axis{k + 1}Angle"]
            out[f"motor{k + 1}AngleRate"] = 0.0
    elif t == "MotorJoint":
        for k in range(3):
            if f"motor{k + 1}Angle" in want:
                out[f"motor{k + 1}Angle"] = float(R.twist_angle(delta, f.axes2[k]))
            if f"motor{k + 1}AngleRate" in want:
                out[f"motor{k + 1}AngleRate"] = float(axes1[k] @ dw)
    return out
