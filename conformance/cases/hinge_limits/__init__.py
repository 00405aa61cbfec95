"""hinge_limits: SingleAxisHingeJoint minAngle / maxAngle: the angle stays within the limits."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import G, stop_overshoot
from conformance.results import Measure, Settings


# hinge_limits.x3d
HINGE_MIN, HINGE_MAX, HINGE_ERP = -0.6, 0.4, 0.8  # SingleAxisHingeJoint.stopErrorCorrection default
HINGE_M, HINGE_L, HINGE_I = 1.0, 1.0, 0.001


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The arm falls from horizontal through |minAngle| = 0.6 rad: impact rate
    w = sqrt(2 m g L sin 0.6 / I_p) = 3.33 rad/s, angular acceleration at most m g L / I_p;
    tolerance stop_overshoot with the hinge's default stopErrorCorrection 0.8 (about 0.014 rad
    at dt = 1/240). The arm must rest at minAngle at the end, within the same tolerance."""
    tr, s = traces[0], settings[0]
    _, ang = tr.series("Hinge", "angle")
    ang = ang[:, 0]
    i_p = HINGE_I + HINGE_M * HINGE_L ** 2
    w = math.sqrt(2 * HINGE_M * G * HINGE_L * math.sin(-HINGE_MIN) / i_p)
    tol = stop_overshoot(w, HINGE_M * G * HINGE_L / i_p, s.dt, HINGE_ERP)
    beyond = max(float(np.max(ang)) - HINGE_MAX, HINGE_MIN - float(np.min(ang)), 0.0)
    return [Measure("Hinge.angle beyond limits", beyond, tol, "rad"),
            Measure("Hinge.angle at the end - minAngle", abs(float(ang[-1]) - HINGE_MIN), tol, "rad")]


CASE = Case("hinge_limits", "hinge_limits.x3d",
            "SingleAxisHingeJoint minAngle -0.6 / maxAngle 0.4: angle stays within the limits",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("SingleAxisHingeJoint.limits", "SingleAxisHingeJoint.minAngle",
                       "SingleAxisHingeJoint.maxAngle"),
            mutations=((" minAngle='-0.6'", ""),))
