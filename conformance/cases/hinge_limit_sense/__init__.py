"""hinge_limit_sense: SingleAxisHingeJoint limits far from symmetric: each limits the side of the angle it names.

What the clause fixes and what it leaves. "The minAngle and maxAngle fields are used to control the maximum angles
through which the hinge is allowed to travel": minAngle bounds the angle the hinge reports from below, maxAngle from
above, on one angle. Which way about the axis that angle grows it does not say: the axis is "along the unit vector
described in the axis field", the angle "the current relative angle between the two bodies", with no rule of the
hand and no order of the bodies (either flipped alone turns the sign; both together restore it). So the sign is a
convention (ODE's here, as in hinge_limits), and an implementation that flips it for its outputs and its stops alike
conforms. Stops that act in the other sense from the angle reported do not: the arm falling to minAngle's side is
held at -maxAngle, the other let on to -minAngle, past maxAngle, which only unequal limits show (hinge_limits' -0.6
and 0.4 are 0.2 apart, within what ODE's own stop yields there)."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import G, HINGE_LIMITS, HINGE_TRAVEL, honoured, stop_overshoot
from conformance.results import Measure, Settings, convention

# hinge_limit_sense.x3d: per hinge, the limit its fall reaches with ODE's sign; both hinges share the limits
HLS_MIN, HLS_MAX = -0.8, 0.2
HLS_M, HLS_L, HLS_I, HLS_ERP = 1.0, 1.0, 0.1, 0.8  # arm mass, pivot to centre, inertia about the centre, stop ERP
HLS_FALLS = {"RightHinge": HLS_MIN, "LeftHinge": HLS_MAX}
ODE_SIGN = convention("angle of body1 relative to body2 about the axis by the right-hand rule, from the initial "
                      "configuration (ODE's dJointGetHingeAngle): Right's fall reaches minAngle, Left's maxAngle; "
                      "alternative: body2 relative to body1, or the axis's other sense: Right reaches maxAngle and "
                      "Left minAngle, outputs and stops alike")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Per hinge, from its reported angle: the side its fall takes (the sign of its farthest
    angle) names the limit that holds it, minAngle below 0, maxAngle above.

    Accuracy (closed_forms.stop_overshoot, HINGE_TRAVEL): a rigid stop acting on the step after
    the one that crosses it lets the arm past by one step at the impact rate, at most
    w = sqrt(2 m g L sin 0.8 / I_p) = 3.6 rad/s (I_p = I + m L^2), and the error correction's
    steady state under gravity's m g L / I_p: 0.015 rad at dt = 1/240. The bound of the angle
    beyond the limits and of each rest at the end. The arms are rods (I 0.1 kg m^2), not
    hinge_limits' near point masses (0.001), on which ODE's quick-step stop yields 0.25 rad at
    -0.8 and throws the arm back past 0; on a rod it holds within the bound (0.011 rad).

    Spec (HINGE_LIMITS), the tolerances half the nearest misreading's error (closed_forms.honoured):
    the farthest angle against the limit on its side, the misreadings the limits in degrees (the
    arm held within |limit| degrees of the start), ignored (it swings to the vertical at least:
    pi/2 - |limit| past) and enforced in the other sense from the angle reported (held at the
    other limit's size: 0.6 rad off); the angle beyond the limits (either hinge), against the
    limits ignored (pi/2 - 0.8 beyond) and the other sense (Left let on to 0.8, 0.6 beyond).
    Convention (ODE_SIGN): Right reaches minAngle and Left maxAngle, against the other sign
    (each at the other limit: 1 rad off)."""
    tr, s = traces[0], settings[0]
    i_p = HLS_I + HLS_M * HLS_L ** 2
    w = math.sqrt(2 * HLS_M * G * HLS_L * math.sin(max(-HLS_MIN, HLS_MAX)) / i_p)
    bound = stop_overshoot(w, HLS_M * G * HLS_L / i_p, s.dt, HLS_ERP)
    other_sense = abs(-HLS_MIN - HLS_MAX)
    out, beyond = [], 0.0
    for joint, ode_limit in HLS_FALLS.items():
        ang = tr.series(joint, "angle")[1][:, 0]
        beyond = max(beyond, float(np.max(ang)) - HLS_MAX, HLS_MIN - float(np.min(ang)))
        extreme = float(ang[np.argmax(np.abs(ang))])
        limit = HLS_MIN if extreme <= 0 else HLS_MAX
        end = float(ang[-1])
        named = "minAngle" if ode_limit == HLS_MIN else "maxAngle"
        out += [Measure(f"{joint}.angle farthest - the limit on its side", abs(extreme - limit),
                        honoured(bound, abs(limit) - math.radians(abs(limit)), math.pi / 2 - abs(limit), other_sense),
                        "rad", HINGE_LIMITS, bound),
                Measure(f"{joint}.angle at the end - the limit on its side", abs(end - (HLS_MIN if end <= 0 else HLS_MAX)),
                        bound, "rad", HINGE_TRAVEL),
                Measure(f"{joint}.angle farthest - {named}", abs(extreme - ode_limit),
                        honoured(bound, HLS_MAX - HLS_MIN), "rad", ODE_SIGN)]
    out.append(Measure("RightHinge, LeftHinge angle beyond limits", max(beyond, 0.0),
                       honoured(bound, math.pi / 2 - max(-HLS_MIN, HLS_MAX), other_sense), "rad", HINGE_LIMITS, bound))
    return out


CASE = Case("hinge_limit_sense", "hinge_limit_sense.x3d",
            "SingleAxisHingeJoint minAngle -0.8 / maxAngle 0.2, two arms falling opposite ways: each is held at the "
            "limit on its side of the angle it reports (spec), Right at minAngle and Left at maxAngle (ODE's sign)",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("SingleAxisHingeJoint.limits", "SingleAxisHingeJoint.minAngle",
                       "SingleAxisHingeJoint.maxAngle"),
            # on one hinge the limits exchanged and negated: its stops in the other sense from the angle it reports
            mutations=(("minAngle='-0.8' maxAngle='0.2'", "minAngle='-0.2' maxAngle='0.8'"),
                       ("maxAngle='0.2' minAngle='-0.8'", "maxAngle='0.8' minAngle='-0.2'")))
