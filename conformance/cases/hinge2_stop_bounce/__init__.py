"""hinge2_stop_bounce: DoubleAxisHingeJoint stop1Bounce: axis 1's stop sends the turn back part way."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import (HINGE2 as JOINT, HINGE2_LIMITS as LIMITS, ROUNDING, ROUNDING_ANGLE,
                                            honoured, max_norm, stop_rebound)
from conformance.results import Measure, Settings, convention, spec

# hinge2_stop_bounce.x3d: Knuckle (body2) turns at W0 about -axis1 against Carrier (body1), both free
HB_AXIS1 = np.array([0.0, 1.0, 0.0])
HB_W0, HB_BOUNCE, HB_ERP, HB_MIN, HB_MAX, HB_I1, HB_I2 = 2.0, 0.3, 0.2, -0.2, 0.31, 0.2, 0.05
HB_CFM, HB_CFM_DEFAULT = 0.005, 0.001  # stop1ConstantForceMix, and its default
HB_L0 = np.array([0.0, -HB_I2 * HB_W0, 0.0])  # the pair's angular momentum
BOUNCES = spec("37.4.8 DoubleAxisHingeJoint: The stopBounce1 field is used to set how bouncy the minimum and maximum "
               "angle stops are for axis 1. A value of zero means they are not bouncy while a value of 1 means maximum "
               "bounciness (full reflection of force arriving at the stop).")
SOFT_STOP = convention("ODE's soft stop: the stop's row yields by stop1ConstantForceMix times its impulse over h, so "
                       "the rebound falls short of stop1Bounce x the impact rate by c (1 + e) w / (1 + c), c = CFM I / "
                       "h (I the pair's reduced moment); the clause says only that the force mix lets a joint be 'a "
                       "fraction springy'")
LINEAR = convention("ODE's stop bounce: the stop's row targets the rebound rate -stop1Bounce x the impact rate (or "
                    "the error correction's stop1ErrorCorrection x depth / h, if larger: at most 0.2 x 2 rad/s here, "
                    "so never); the clause fixes only the ends, 0 not bouncy and 1 full reflection")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """slider_bounce's argument on axis 1: r = axis1 . (w1 - w2) is W0 until the first stop
    (closed_forms.stop_rebound: part way back, ODE's law a convention); the stop's row yields by
    its CFM (stop1ConstantForceMix, default 0.001) times its force: CFM I (1 + e) W0 / h with the
    pair's reduced moment I = I1 I2 / (I1 + I2). The turn reaches each stop (in 1.2 s, in either
    sense) and goes past it by at most a step's travel W0 h: half the distance to the stop's
    default (+-pi) the tolerance. The pair's angular momentum is kept (the joint is internal), to
    rounding; its tolerance half the error where the stop's impulse goes to the world (body1 off
    the joint: (1 + e) I2 W0). The bounce is 0.3, not 0.5: the first step past maxAngle1 0.31 ends
    0.8 of a step's travel deep, which the default stop1ErrorCorrection 0.8 would correct at
    1.28 rad/s, a rebound ODE's law (0.6) is then off by more than half its 0.6 (0.5's 1.0 would
    hide it). Convention (ODE's soft stop): the rebound falls short of e x the impact rate by the
    stop's yield c (1 + e) w / (1 + c), c = CFM I / h (the yield taken out of the impulse that makes
    it), to 0.1 % of the yield (what ODE's iterative solve leaves of the four rows coupled with the
    stop's); the tolerance half the yield's change at the default CFM 0.001.

    Reaching minAngle1 takes about 1.2 s at the softened rebound: the run is 1.4 s."""
    tr, s = traces[0], settings[0]
    h = s.dt
    _, w1 = tr.series("Carrier", "angularVelocity")
    _, w2 = tr.series("Knuckle", "angularVelocity")
    _, angle = tr.series("Steer", "hinge1Angle")
    angle = angle[:, 0]
    r = (w1 - w2) @ HB_AXIS1
    reduced = HB_I1 * HB_I2 / (HB_I1 + HB_I2)
    c, c_default = HB_CFM * reduced / h, HB_CFM_DEFAULT * reduced / h
    softness = c * (1 + HB_BOUNCE) * HB_W0 / (1 + c)
    unsoftened = c_default * (1 + HB_BOUNCE) * HB_W0 / (1 + c_default)
    turned = np.flatnonzero(r[:-1] * r[1:] < 0)
    k = int(turned[0]) if turned.size else -1
    short = (abs(HB_BOUNCE * abs(float(r[k])) - softness - abs(float(r[k + 1]))) if turned.size else np.inf)
    travel = HB_W0 * h + ROUNDING_ANGLE
    rounding = ROUNDING * (1 + HB_W0)
    return [Measure(f"Steer.hinge1Angle farthest out - maxAngle1 {HB_MAX:g}", abs(float(np.max(angle)) - HB_MAX),
                    honoured(travel, np.pi - HB_MAX), "rad", LIMITS, travel),
            Measure(f"Steer.hinge1Angle farthest in - minAngle1 {HB_MIN:g}", abs(float(np.min(angle)) - HB_MIN),
                    honoured(travel, np.pi + HB_MIN), "rad", LIMITS, travel),
            Measure("I1 Carrier.angularVelocity + I2 Knuckle.angularVelocity - its start",
                    max_norm(HB_I1 * w1 + HB_I2 * w2 - HB_L0), honoured(rounding, (1 + HB_BOUNCE) * HB_I2 * HB_W0),
                    "kg m^2/s", JOINT, rounding),
            *stop_rebound(r, HB_BOUNCE, HB_ERP * HB_W0, softness, "rad/s", "the turn", BOUNCES, LINEAR),
            Measure("rebound rate - (stop bounce x impact rate - the soft stop's yield)", short,
                    honoured(1e-3 * softness, softness - unsoftened), "rad/s", SOFT_STOP, 1e-3 * softness)]


CASE = Case("hinge2_stop_bounce", "hinge2_stop_bounce.x3d",
            "DoubleAxisHingeJoint stop1Bounce 0.3, stop1ErrorCorrection 0.2, stops -0.2 and 0.31, two free bodies: "
            "each stop is reached, and sends the turn back part way (ODE's law: at 0.3 x the impact rate); the "
            "pair's angular momentum kept",
            (Settings(1.4, 1 / 240, None),), expect,
            exercises=("DoubleAxisHingeJoint.stop1Bounce", "DoubleAxisHingeJoint.stop1ErrorCorrection",
                       "DoubleAxisHingeJoint.stop1ConstantForceMix",
                       "DoubleAxisHingeJoint.minAngle1", "DoubleAxisHingeJoint.maxAngle1"),
            mutations=(
                (" stop1Bounce='0.3'", ""),
                # ERP 0.8: a step's depth corrected faster than the bounce (ODE's law then fails)
                Mutation(" stop1ErrorCorrection='0.2'", "", spec=False),
                Mutation(" stop1ConstantForceMix='0.005'", "", spec=False),  # a stiffer stop: a faster rebound
            ))
