"""hinge2_steering: DoubleAxisHingeJoint axis 1: its motor drives the bodies' relative turn to its stop."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import (HINGE2 as JOINT, HINGE2_LIMITS as LIMITS, HINGE2_OUTPUTS as OUTPUTS,
                                            ROUNDING, ROUNDING_ANGLE, STEP_SLACK, anchor_outputs, honoured, max_norm,
                                            steps, stop_overshoot)
from conformance.results import Measure, Settings, accuracy, convention, spec

# hinge2_steering.x3d: two pairs of free bodies on their joint's anchor, no gravity
H2_TARGET, H2_MAX_TORQUE, H2_I1, H2_I2 = 1.5, 0.2, 0.2, 0.05  # |desiredAngularVelocity1|, Carrier's, Knuckle's
H2_ERP = 0.8  # stop1ErrorCorrection default
# pair -> (axis1, the sign of desiredAngularVelocity1, the stop it heads for, the other stop)
H2_PAIRS = {"Up": (np.array([0.0, 0.6, 0.8]), 1.0, 0.5, -0.6),
            "Down": (np.array([0.0, 1.0, 0.0]), -1.0, -0.7, 0.4)}
H2_AXIS2 = {"Up": np.array([0.0, 0.8, -0.6]), "Down": np.array([0.0, 0.0, 1.0])}
H2_ANCHOR = {"Up": (-1.0, 0.0, 0.0), "Down": (1.0, 0.0, 0.0)}  # both bodies of a pair start on it, unturned
MOTOR = spec("37.4.8 DoubleAxisHingeJoint: The maxTorque1 field defines the maximum amount of torque that the motor "
             "can apply on axis 1 in order to achieve the desired desiredAngularVelocity1 value.")
TRAVEL = accuracy("a rigid stop acting on the step after the one that crosses it, the motor still pushing: the turn "
                  "past the stop by one step's travel and the error correction's steady state "
                  "(closed_forms.stop_overshoot), and resting there")
ODE_SENSE = convention("the motor drives r = axis1 . (w1 - w2), body1 relative to body2 (ODE's hinge2, as "
                       "hinge1AngleRate reports it), to desiredAngularVelocity1; alternative: body2 relative to body1, "
                       "the bodies turning the other way")


def _pair(tr: TraceView, s: Settings, name: str) -> list[Measure]:
    """One pair's measures (expect's docstring)."""
    axis, sign, stop, other = H2_PAIRS[name]
    h, T = s.dt, s.duration
    t, w1 = tr.series(f"{name}Carrier", "angularVelocity")
    _, w2 = tr.series(f"{name}Knuckle", "angularVelocity")
    _, o1 = tr.series(f"{name}Carrier", "orientation")
    _, o2 = tr.series(f"{name}Knuckle", "orientation")
    _, angle = tr.series(f"{name}Hinge", "hinge1Angle")
    _, rate = tr.series(f"{name}Hinge", "hinge1AngleRate")
    _, angle2 = tr.series(f"{name}Hinge", "hinge2Angle")
    _, axis1_out = tr.series(f"{name}Hinge", "body1Axis")
    _, axis2_out = tr.series(f"{name}Hinge", "body2Axis")
    n = steps(t, h)
    alpha = H2_MAX_TORQUE * (1 / H2_I1 + 1 / H2_I2)
    t_star = H2_TARGET / alpha
    n_star = math.ceil(t_star / h - STEP_SLACK)
    t_stop = t_star + (abs(stop) - 0.5 * H2_TARGET * t_star) / H2_TARGET
    r = (w1 - w2) @ axis  # ODE's sense
    turn = R.twist_angle(R.multiply(R.conjugate(R.from_axis_angle(o2)), R.from_axis_angle(o1)), axis)
    sense = 1.0 if float(np.sum(r)) * sign >= 0 else -1.0  # the implementation's: ODE's +1
    toward = sense * sign  # r and the turn, signed so that the drive makes them grow
    ramp, hold = n < n_star, (n >= n_star) & (n * h < t_stop - 2 * h)
    closed = np.minimum(alpha * n * h, H2_TARGET)
    rounding = ROUNDING * (1 + H2_TARGET)
    held = alpha * h + rounding
    bound = stop_overshoot(H2_TARGET, alpha, h, H2_ERP) + ROUNDING_ANGLE
    # the stops ignored: the turn by the end; read in degrees: the hinge stops at once
    free = H2_TARGET * (T - t_star) + 0.5 * H2_TARGET * t_star
    travel = honoured(bound, abs(stop) - math.radians(abs(stop)), free - abs(stop))
    grown = toward * turn
    momentum = H2_I1 * w1 + H2_I2 * w2
    axis2 = H2_AXIS2[name]
    bound_l = ROUNDING * (1 + H2_MAX_TORQUE * T)
    return [
        Measure(f"{name}: axis1 . (w1 - w2), torque-limited ramp (t < t*), either sense",
                max_norm(toward * r[ramp] - closed[ramp]) if ramp.any() else math.inf,
                honoured(rounding, H2_TARGET - alpha * h), "rad/s", MOTOR, rounding),
        Measure(f"{name}: axis1 . (w1 - w2) at the target (t* <= t < the stop), either sense",
                max_norm(toward * r[hold] - H2_TARGET) if hold.any() else math.inf,
                honoured(held, H2_TARGET), "rad/s", MOTOR, held),
        Measure(f"{name}: farthest relative turn about axis1 - the stop the target heads for ({stop:g})",
                abs(float(np.max(grown)) - abs(stop)), travel, "rad", LIMITS, bound),
        Measure(f"{name}: relative turn at the end - that stop", abs(float(grown[-1]) - abs(stop)), bound, "rad",
                TRAVEL),
        Measure(f"{name}: I1 w1 + I2 w2 (the motor's torques equal and opposite)", max_norm(momentum),
                honoured(bound_l, H2_I2 * H2_TARGET), "kg m^2/s", JOINT, bound_l),
        Measure(f"{name}Hinge |hinge1Angle| - |relative turn|", max_norm(np.abs(angle[:, 0]) - np.abs(turn)),
                honoured(ROUNDING_ANGLE, abs(stop)), "rad", OUTPUTS, ROUNDING_ANGLE),
        Measure(f"{name}Hinge |hinge1AngleRate| - |axis1 . (w1 - w2)|", max_norm(np.abs(rate[:, 0]) - np.abs(r)),
                honoured(rounding, H2_TARGET), "rad/s", OUTPUTS, rounding),
        Measure(f"{name}: axis1 . (w1 - w2) at the target = {sign * H2_TARGET:g}",
                max_norm(r[hold] - sign * H2_TARGET) if hold.any() else math.inf,
                honoured(held, 2 * H2_TARGET), "rad/s", ODE_SENSE, held),
        Measure(f"{name}Hinge |hinge2Angle| (nothing turns about axis 2)", max_norm(angle2[:, 0]),
                honoured(ROUNDING_ANGLE, abs(stop)), "rad", OUTPUTS, ROUNDING_ANGLE),
        Measure(f"{name}Hinge.body1Axis - axis1 as {name}Carrier carries it",
                max_norm(axis1_out - R.rotate(R.from_axis_angle(o1), axis)), honoured(ROUNDING, 1.0), "", JOINT,
                ROUNDING),
        # in the world as Knuckle carries it, or in Knuckle's own frame (axis2: it starts unturned), either
        # (docs/spec-loose-ends.md 22.1)
        Measure(f"{name}Hinge.body2Axis - axis2 as {name}Knuckle carries it (world or its frame)",
                min(max_norm(axis2_out - R.rotate(R.from_axis_angle(o2), axis2)), max_norm(axis2_out - axis2)),
                honoured(ROUNDING, 1.0), "", JOINT, ROUNDING),
        anchor_outputs(tr, f"{name}Hinge", f"{name}Carrier", f"{name}Knuckle", H2_ANCHOR[name], H2_ANCHOR[name],
                       H2_ANCHOR[name])]


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each pair: the motor is a velocity constraint on r = axis1 . (w1 - w2) whose torque is at
    most maxTorque1 (tau), acting on body1 and body2 equal and opposite; the bodies sit on the
    anchor with isotropic inertias, so nothing else acts and r ramps at alpha = tau (1/I1 + 1/I2)
    = 5 rad/s^2: r = alpha n h for steps n < n* = t*/h, then the target w = 1.5 rad/s, until the
    relative turn (int r dt) reaches the stop the target heads for (Up: maxAngle1 0.5 rad at
    0.483 s; Down: minAngle1 -0.7 at 0.617 s), where it stays.

    Accuracy bounds (motor_speed's argument): the ramp is a constant torque, exact for every
    one-step scheme: ROUNDING; the hold is exact for a velocity constraint, and within alpha h
    for a servo whose torque is computed at the step's start. The stop: stop_overshoot at the
    target rate with the motor pushing at alpha, stop1ErrorCorrection 0.8. The pair's angular
    momentum stays 0 up to rounding: the joint's torques are internal.

    Spec tolerances (closed_forms.honoured): half the nearest misreading's error: maxTorque1
    ignored (the target at once: w - alpha h into the ramp), desiredAngularVelocity1 ignored (no
    drive: w off at the hold), the stops ignored (the turn goes on to 1.275 rad by 1 s) or read
    in degrees (stopped within 0.01 rad of the start), the motor acting on body2 only (the pair
    keeps Knuckle's I2 w); an output not reported (0 where the turn is the stop's, the rate w;
    hinge2Angle, 0 throughout, as hinge1Angle's stop); body1Axis and body2Axis are axis1 and axis2
    as body1 and body2 carry them (the clause's "relative to"), to rounding, against an axis not
    reported (0): body2Axis in the world or in Knuckle's own frame, where it stays axis2 (the clause
    gives both, docs/spec-loose-ends.md 22.1; body1Axis is the same in either, Carrier turning about
    axis1 alone); the anchor points (closed_forms.anchor_outputs) a convention.
    Which way the bodies turn is the sense the implementation measures the angle in: the spec
    measures take either (the drive's), the convention holds it to ODE's (body1 relative to
    body2), with twice the target for the other sense."""
    tr, s = traces[0], settings[0]
    return [m for name in H2_PAIRS for m in _pair(tr, s, name)]


CASE = Case("hinge2_steering", "hinge2_steering.x3d",
            "DoubleAxisHingeJoint axis 1 between free bodies: its motor (desiredAngularVelocity1 +-1.5, maxTorque1 "
            "0.2) ramps the relative rate at 5 rad/s^2 to the target, its stops (maxAngle1 0.5, minAngle1 -0.7) "
            "end the turn; the pair's angular momentum stays 0; hinge1Angle/Rate report the turn",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("DoubleAxisHingeJoint.axis1", "DoubleAxisHingeJoint.anchorPoint",
                       "DoubleAxisHingeJoint.desiredAngularVelocity1", "DoubleAxisHingeJoint.maxTorque1",
                       "DoubleAxisHingeJoint.minAngle1", "DoubleAxisHingeJoint.maxAngle1",
                       "DoubleAxisHingeJoint.limits", "DoubleAxisHingeJoint.forceOutput"),
            mutations=(
                (" maxAngle1='0.5'", ""),  # Up turns on past 0.5
                (" minAngle1='-0.7'", ""),  # Down turns on past -0.7
                (" desiredAngularVelocity1='1.5'", ""),  # Up undriven
                (" maxTorque1='0.2' minAngle1='-0.6'", " minAngle1='-0.6'"),  # Up's motor without its torque
                (" axis1='0 0.6 0.8'", ""),  # Up turns about x, not axis1
                (" anchorPoint='-1 0 0'", ""),  # Up's pivot 1 m from both bodies: a slower ramp
                ("<RigidBody USE='UpCarrier' containerField='body1'/>", ""),  # the torque on Knuckle alone
            ))
