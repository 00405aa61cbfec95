"""hinge_limits: SingleAxisHingeJoint minAngle / maxAngle: the angle stays within the limits."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import G, honoured, stop_overshoot
from conformance.results import Measure, Settings, accuracy, convention, spec


# hinge_limits.x3d
HINGE_MIN, HINGE_MAX, HINGE_ERP = -0.6, 0.4, 0.8  # SingleAxisHingeJoint.stopErrorCorrection default
HINGE_M, HINGE_L, HINGE_I = 1.0, 1.0, 0.001
LIMITS = spec("37.4.12 SingleAxisHingeJoint: The minAngle and maxAngle fields are used to control the maximum "
              "angles through which the hinge is allowed to travel. A hinge may not travel more than π radians (or "
              "the equivalent angle base units) in either direction from its initial position.", "V3.3")
TRAVEL = accuracy("a rigid stop acting on the step after the one that crosses it: the arm past the limit by at most "
                  "one step's travel and the error correction's steady state (closed_forms.stop_overshoot), and "
                  "resting at the limit by the end")
ODE_ANGLE = convention("angle of body1 relative to body2 about the axis, from the initial configuration (ODE's "
                       "dJointGetHingeAngle): the arm falls to negative angles and reaches minAngle; alternative: "
                       "body2 relative to body1, or the axis's other sense: the fall is positive and the arm reaches "
                       "maxAngle")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The arm falls from horizontal: with ODE's sign through |minAngle| = 0.6 rad, impact rate
    w = sqrt(2 m g L sin 0.6 / I_p) = 3.33 rad/s, angular acceleration at most m g L / I_p.

    Accuracy: a rigid stop acting on the step after the one that crosses it lets the arm past by
    stop_overshoot with the hinge's default stopErrorCorrection 0.8 (about 0.014 rad at
    dt = 1/240), and holds it there: the bound on the angle beyond the limits and on the rest
    angle at the end. With the other sign the fall is positive and meets maxAngle (0.4 rad)
    sooner, at a lower speed: the same bound covers it.

    Spec: the limits bound the hinge's travel, so the farthest the arm goes is the limit its
    fall reaches. The tolerance (closed_forms.honoured) is half the nearest misreading's error:
    the limits read in degrees (the arm stops within 0.6 degrees of the start: 0.59 rad short of
    minAngle, 0.39 of maxAngle) or ignored (the arm swings to the vertical at least: pi/2 - 0.6
    past minAngle). A stop that yields (the joints' default constantForceMix, ODE's quick-step
    at the scene's 10 iterations: 0.23 rad past, then thrown back) is graded, not accused; so is
    where the arm is at the end (the clause fixes the limits of travel, not a rest).

    Convention (ODE's sign): the fall reaches minAngle, not maxAngle (1 rad apart)."""
    tr, s = traces[0], settings[0]
    _, ang = tr.series("Hinge", "angle")
    ang = ang[:, 0]
    i_p = HINGE_I + HINGE_M * HINGE_L ** 2
    w = math.sqrt(2 * HINGE_M * G * HINGE_L * math.sin(max(-HINGE_MIN, HINGE_MAX)) / i_p)
    bound = stop_overshoot(w, HINGE_M * G * HINGE_L / i_p, s.dt, HINGE_ERP)
    beyond = max(float(np.max(ang)) - HINGE_MAX, HINGE_MIN - float(np.min(ang)), 0.0)
    extreme = float(ang[np.argmax(np.abs(ang))])
    limit = HINGE_MIN if extreme <= 0 else HINGE_MAX
    travel = honoured(bound, abs(limit) - math.radians(abs(limit)), math.pi / 2 - abs(limit))
    end = float(ang[-1])
    return [Measure("Hinge.angle farthest - the limit the fall reaches", abs(extreme - limit), travel, "rad",
                    LIMITS, bound),
            Measure("Hinge.angle beyond limits", beyond, bound, "rad", TRAVEL),
            Measure("Hinge.angle at the end - the limit the fall reaches", abs(end - (HINGE_MIN if end <= 0 else
                                                                                     HINGE_MAX)), bound, "rad",
                    TRAVEL),
            Measure("Hinge.angle farthest - minAngle", abs(extreme - HINGE_MIN),
                    honoured(bound, HINGE_MAX - HINGE_MIN), "rad", ODE_ANGLE)]


CASE = Case("hinge_limits", "hinge_limits.x3d",
            "SingleAxisHingeJoint minAngle -0.6 / maxAngle 0.4: the farthest the arm travels is the limit "
            "its fall reaches (ODE's sign: minAngle); accuracy: within a rigid stop's overshoot, resting there",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("SingleAxisHingeJoint.limits", "SingleAxisHingeJoint.minAngle",
                       "SingleAxisHingeJoint.maxAngle"),
            mutations=((" minAngle='-0.6'", ""),))
