"""hinge_limits: SingleAxisHingeJoint minAngle / maxAngle: the angle stays within the limits."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import G, stop_overshoot
from conformance.results import Measure, Settings, convention, spec


# hinge_limits.x3d
HINGE_MIN, HINGE_MAX, HINGE_ERP = -0.6, 0.4, 0.8  # SingleAxisHingeJoint.stopErrorCorrection default
HINGE_M, HINGE_L, HINGE_I = 1.0, 1.0, 0.001
LIMITS = spec("37.4.12 SingleAxisHingeJoint: The minAngle and maxAngle fields are used to control the maximum "
              "angles through which the hinge is allowed to travel.")
ODE_ANGLE = convention("angle of body1 relative to body2 about the axis, from the initial configuration (ODE's "
                       "dJointGetHingeAngle): the arm falls to negative angles and rests at minAngle; alternative: "
                       "body2 relative to body1, or the axis's other sense: the fall is positive and the arm rests "
                       "at maxAngle")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The arm falls from horizontal: with ODE's sign through |minAngle| = 0.6 rad, impact rate
    w = sqrt(2 m g L sin 0.6 / I_p) = 3.33 rad/s, angular acceleration at most m g L / I_p;
    tolerance stop_overshoot with the hinge's default stopErrorCorrection 0.8 (about 0.014 rad
    at dt = 1/240); with the other sign the fall is positive and meets maxAngle (0.4 rad) sooner,
    at a lower speed: the same tolerance covers it.

    Spec: the reported angle stays within [minAngle, maxAngle], and the arm rests at the limit
    its fall reaches: minAngle where the angle fell, maxAngle where it rose (the sign is not the
    spec's). Convention (ODE's sign): it rests at minAngle."""
    tr, s = traces[0], settings[0]
    _, ang = tr.series("Hinge", "angle")
    ang = ang[:, 0]
    i_p = HINGE_I + HINGE_M * HINGE_L ** 2
    w = math.sqrt(2 * HINGE_M * G * HINGE_L * math.sin(max(-HINGE_MIN, HINGE_MAX)) / i_p)
    tol = stop_overshoot(w, HINGE_M * G * HINGE_L / i_p, s.dt, HINGE_ERP)
    beyond = max(float(np.max(ang)) - HINGE_MAX, HINGE_MIN - float(np.min(ang)), 0.0)
    end = float(ang[-1])
    return [Measure("Hinge.angle beyond limits", beyond, tol, "rad", LIMITS),
            Measure("Hinge.angle at the end - the limit the fall reaches",
                    abs(end - (HINGE_MIN if end <= 0 else HINGE_MAX)), tol, "rad", LIMITS),
            Measure("Hinge.angle at the end - minAngle", abs(end - HINGE_MIN), tol, "rad", ODE_ANGLE)]


CASE = Case("hinge_limits", "hinge_limits.x3d",
            "SingleAxisHingeJoint minAngle -0.6 / maxAngle 0.4: angle stays within the limits, rests at the one "
            "the fall reaches (ODE's sign: minAngle)",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("SingleAxisHingeJoint.limits", "SingleAxisHingeJoint.minAngle",
                       "SingleAxisHingeJoint.maxAngle"),
            mutations=((" minAngle='-0.6'", ""),))
