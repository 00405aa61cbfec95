"""hinge_max_limit: SingleAxisHingeJoint maxAngle: hinge_limits mirrored, the fall reaching maxAngle."""

from __future__ import annotations

from collections.abc import Sequence

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import hinge_limit
from conformance.results import Measure, Settings

# hinge_max_limit.x3d: the arm starts horizontal at -x and falls turning in the positive sense about z
MAX_MIN, MAX_MAX = -0.6, 0.8


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """closed_forms.hinge_limit: the fall reaches maxAngle (ODE's sign), 0.8 rad: far enough that
    the limits read in degrees or ignored miss it by more than twice the 0.27 rad ODE's stop
    yields at X3D's defaults (quick-step, 10 iterations; at maxAngle 0.4 it yields 0.21 rad, past
    half the degrees misreading's 0.39)."""
    return hinge_limit(traces[0], settings[0], "Hinge", MAX_MIN, MAX_MAX, MAX_MAX)


CASE = Case("hinge_max_limit", "hinge_max_limit.x3d",
            "SingleAxisHingeJoint minAngle -0.6 / maxAngle 0.8, the arm falling the other way: the farthest it "
            "travels is the limit its fall reaches (ODE's sign: maxAngle); accuracy: within a rigid stop's "
            "overshoot, resting there",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("SingleAxisHingeJoint.limits", "SingleAxisHingeJoint.minAngle",
                       "SingleAxisHingeJoint.maxAngle"),
            mutations=((" maxAngle='0.8'", ""),))
