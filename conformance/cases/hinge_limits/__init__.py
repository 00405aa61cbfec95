"""hinge_limits: SingleAxisHingeJoint minAngle / maxAngle: the angle stays within the limits."""

from __future__ import annotations

from collections.abc import Sequence

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import hinge_limit
from conformance.results import Measure, Settings


# hinge_limits.x3d: the arm (1 kg, 1 m out, I 0.001 about its centre) starts horizontal at +x and
# falls turning in the negative sense about z: with ODE's sign its angle falls to minAngle
HINGE_MIN, HINGE_MAX = -0.6, 0.4


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """closed_forms.hinge_limit: the fall reaches minAngle (ODE's sign), -0.6 rad."""
    return hinge_limit(traces[0], settings[0], "Hinge", HINGE_MIN, HINGE_MAX, HINGE_MIN)


CASE = Case("hinge_limits", "hinge_limits.x3d",
            "SingleAxisHingeJoint minAngle -0.6 / maxAngle 0.4: the farthest the arm travels is the limit "
            "its fall reaches (ODE's sign: minAngle); accuracy: within a rigid stop's overshoot, resting there",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("SingleAxisHingeJoint.limits", "SingleAxisHingeJoint.minAngle",
                       "SingleAxisHingeJoint.maxAngle"),
            mutations=((" minAngle='-0.6'", ""),))
