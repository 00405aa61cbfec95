"""motor_speed: DoubleAxisHingeJoint desiredAngularVelocity2 / maxTorque2: a torque-limited ramp to the target rate."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import HINGE2_OUTPUTS, ROUNDING, STEP_SLACK, honoured, max_norm, steps
from conformance.results import Measure, Settings, convention, spec


# motor_speed.x3d: a wheel (body2) on a fixed chassis (body1), its axle motor on axis2
MOTOR_TARGET, MOTOR_MAX_TORQUE, MOTOR_I = 4.0, 0.2, 0.05
MOTOR_AXIS2 = np.array([0.0, 0.0, 1.0])
MOTOR = spec("37.4.8 DoubleAxisHingeJoint: The maxTorque1 field defines the maximum amount of torque that the "
             "motor can apply on axis 1 in order to achieve the desired desiredAngularVelocity1 value. Similarly, "
             "maxTorque2 controls the maximum amount of torque to achieve desiredAngularVelocity2 on axis 2.")
ODE_RATE = convention("the motor drives hinge2AngleRate = axis2 . (w1 - w2), body1 relative to body2 (ODE's hinge2 "
                      "motor), to desiredAngularVelocity2: the wheel (body2) turns at -4 rad/s about axis2; "
                      "alternative: body2 relative to body1, the wheel turning at +4 rad/s")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """ODE's joint motor is a velocity constraint whose force is bounded by maxTorque: each step
    it reaches the target rate if a torque within the bound can, else it pushes with maxTorque.
    The rate (hinge2AngleRate = axis2 . (w1 - w2), the wheel being body2 on a fixed body1) is
    alpha n h for steps n < n* = t*/h, alpha = maxTorque/I, and w from step n* on; the wheel's
    angular velocity is -rate along axis2 (its centre of mass on the anchor, its axle a principal
    axis: no other torque acts).

    Ramp (steps n < n*): a constant torque, so the rate is exact for every one-step scheme:
    ROUNDING. Hold (steps n >= n*): a velocity constraint is exactly on the target; a motor acting
    through a torque computed at the start of the step (a servo) can be off it, but by no more
    than one step at the torque limit can change the rate: alpha h.

    Spec measures: the ramp and the hold in the sense the wheel turns (which body's rate the motor
    drives to the target is not the spec's). Convention measure: ODE's sense, -rate along axis2.
    Those figures are accuracy bounds; the tolerances (closed_forms.honoured) are half the
    misreading's error: maxTorque2 ignored (the wheel at the target at once: the ramp's error is
    then the target less one step's rise), the target ignored (the wheel held still: 4 rad/s
    off), and for the convention the other sense (twice the rate). The output hinge2AngleRate
    reports the rate in either sense (|hinge2AngleRate| = |axis2 . w|, the chassis still): rounding,
    against its not being reported (0 at the target)."""
    tr, s = traces[0], settings[0]
    t, w = tr.series("Wheel", "angularVelocity")
    _, reported = tr.series("Axle", "hinge2AngleRate")
    n = steps(t, s.dt)
    alpha = MOTOR_MAX_TORQUE / MOTOR_I
    n_star = math.ceil(MOTOR_TARGET / (alpha * s.dt) - STEP_SLACK)
    rate = np.minimum(alpha * n * s.dt, MOTOR_TARGET)
    sense = -1.0 if float(np.sum(w @ MOTOR_AXIS2)) <= 0 else 1.0  # ODE's: -1
    error = np.linalg.norm(w - np.outer(sense * rate, MOTOR_AXIS2), axis=1)
    ramp, hold = n < n_star, n >= n_star
    rounding = ROUNDING * (1 + MOTOR_TARGET)
    held = alpha * s.dt + rounding
    return [Measure("Wheel.angularVelocity, torque-limited ramp (t < t*)",
                    float(np.max(error[ramp])) if ramp.any() else math.inf,
                    honoured(rounding, MOTOR_TARGET - alpha * s.dt), "rad/s", MOTOR, rounding),
            Measure("Wheel.angularVelocity, at the target (t >= t*)",
                    float(np.max(error[hold])) if hold.any() else math.inf, honoured(held, MOTOR_TARGET), "rad/s",
                    MOTOR, held),
            Measure("Wheel.angularVelocity along -axis2", max_norm(w - np.outer(-rate, MOTOR_AXIS2)),
                    honoured(held, 2 * MOTOR_TARGET), "rad/s", ODE_RATE, held),
            Measure("|Axle.hinge2AngleRate| - |axis2 . Wheel.angularVelocity|",
                    max_norm(np.abs(reported[:, 0]) - np.abs(w @ MOTOR_AXIS2)), honoured(rounding, MOTOR_TARGET),
                    "rad/s", HINGE2_OUTPUTS, rounding)]


T_STAR = MOTOR_I * MOTOR_TARGET / MOTOR_MAX_TORQUE  # s: the end of the ramp
CASE = Case("motor_speed", "motor_speed.x3d",
            "DoubleAxisHingeJoint desiredAngularVelocity2 4 / maxTorque2 0.2, I 0.05: rate = (maxTorque/I) t "
            f"until t* = I w / maxTorque = {T_STAR:g} s, then w",
            (Settings(1.5, 1 / 240, None),), expect,
            exercises=("DoubleAxisHingeJoint.desiredAngularVelocity2", "DoubleAxisHingeJoint.maxTorque2",
                       "DoubleAxisHingeJoint.axis2", "RigidBody.inertia"),
            mutations=(
                (" maxTorque2='0.2'", ""),
                (" desiredAngularVelocity2='4'", ""),
                # the pivot at the chassis' origin, 0.5 m under the wheel: the motor tips it over
                (" anchorPoint='0 0.5 0'", ""),
                # both axes at their defaults, 1 0 0 and 0 1 0 (axis2's alone would lie along axis1: a
                # degenerate joint ODE refuses): the motor turns the wheel about y, not its axle
                (" axis1='0 1 0' axis2='0 0 1'", ""),
                # the wheel not on the joint: nothing drives it
                ("<RigidBody USE='Wheel' containerField='body2'/>", ""),
            ))
