"""motor_enabled_axes: MotorJoint enabledAxes 0, 1 and 2 with a torque on every axis: only the enabled axes turn."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, spec

# motor_enabled_axes.x3d: no gravity; each motor turns a free rotor (body1) against a free stator (body2), both
# isotropic, its three axes one direction, so that whichever body carries an axis, it stays put
EA_I1, EA_I2 = 0.2, 0.4
EA_TORQUES = np.array([0.3, 0.2, 0.1])  # axis1Torque, axis2Torque, axis3Torque on every motor
# motor -> (enabledAxes, the motor's axis)
EA_MOTORS = {"Off": (0, np.array([0.0, 0.6, 0.8])), "One": (1, np.array([0.6, 0.8, 0.0])),
             "Two": (2, np.array([0.0, 0.0, 1.0]))}
DISABLED = spec("37.4.9 MotorJoint: When the autoCalc field is set to FALSE, the enabledAxes field indicates how many "
                "axes can currently be controlled and modified. If the value is zero, the motor is effectively "
                "disabled.")
ENABLED = spec("37.4.9 MotorJoint: If the value is 1, only axis1 is enabled, a value of 2 has axis 1 and axis 2 enabled "
               "and a value of 3 has all axes enabled.")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each motor's enabled axes (the first enabledAxes of them) turn its rotor with the sum of their
    torques tau about the one axis, every step, and its stator the other way: w1 = (tau t / I1) axis,
    w2 = -(tau t / I2) axis; the bodies are isotropic, so nothing turns them off the axis. Velocities
    under a constant torque are exact for every one-step scheme: ROUNDING (motor_axes' argument).

    Spec (DISABLED): Off (enabledAxes 0, torques on all three axes) turns neither body, to ROUNDING;
    the tolerance half the nearest misreading's error at the end: the field ignored (its default 1:
    axis 1's 0.3 N m acts, 1.5 rad/s by 1 s) or every torque given applied. Spec (ENABLED): One's
    rotor (enabledAxes 1) spins up at axis1Torque / I1 = 1.5 rad/s^2 and Two's (enabledAxes 2) at
    (axis1Torque + axis2Torque) / I1 = 2.5, about the axis in either sense (which body gets +tau is
    motor_axes' convention); the tolerances half the nearest misreading's error at the end: One with
    the disabled axes acting (3 rad/s^2), Two with axis 3 acting too (3) or axis 2 not (1.5)."""
    tr, s = traces[0], settings[0]
    out = []
    for motor, (enabled, axis) in EA_MOTORS.items():
        t, w1 = tr.series(f"{motor}Rotor", "angularVelocity")
        _, w2 = tr.series(f"{motor}Stator", "angularVelocity")
        T = float(physics_time(t, s.dt)[-1])
        tau = float(np.sum(EA_TORQUES[:enabled]))
        a1 = tau / EA_I1
        bound = ROUNDING * (1 + float(np.sum(EA_TORQUES)) / EA_I1 * T)
        if enabled == 0:
            out.append(Measure("Off: |angularVelocity| of rotor and stator (enabledAxes 0: disabled)",
                               max(max_norm(w1), max_norm(w2)), honoured(bound, EA_TORQUES[0] / EA_I1 * T), "rad/s",
                               DISABLED, bound))
            continue
        sense = 1.0 if float(w1[-1] @ axis) >= 0 else -1.0
        closed = np.outer(sense * a1 * physics_time(t, s.dt), axis)
        misread = [EA_TORQUES[k] / EA_I1 * T for k in range(enabled, 3)]  # a disabled axis acting
        misread += [EA_TORQUES[k] / EA_I1 * T for k in range(1, enabled)]  # an enabled one (past the first) not
        out += [Measure(f"{motor}Rotor.angularVelocity, {a1:g} t about the motor's axis, either sense",
                        max_norm(w1 - closed), honoured(bound, *misread), "rad/s", ENABLED, bound),
                Measure(f"{motor}Stator.angularVelocity, {tau / EA_I2:g} t the other way",
                        max_norm(w2 + closed * EA_I1 / EA_I2), honoured(bound, *(m * EA_I1 / EA_I2 for m in misread)),
                        "rad/s", ENABLED, bound)]
    return out


CASE = Case("motor_enabled_axes", "motor_enabled_axes.x3d",
            "MotorJoint enabledAxes 0 / 1 / 2, axis1Torque 0.3, axis2Torque 0.2, axis3Torque 0.1 on every motor, its "
            "axes one direction: Off turns nothing, One's rotor w = 1.5 t, Two's 2.5 t about the axis",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("MotorJoint.enabledAxes", "MotorJoint.motor1Axis", "MotorJoint.motor2Axis",
                       "MotorJoint.motor3Axis", "MotorJoint.axis1Torque", "MotorJoint.axis2Torque",
                       "MotorJoint.axis3Torque"),
            mutations=(
                ("DEF='Off' enabledAxes='0'", "DEF='Off'"),  # the default 1: axis 1 turns the pair
                ("DEF='One' enabledAxes='1'", "DEF='One' enabledAxes='3'"),  # every torque given applied
                ("DEF='Two' enabledAxes='2'", "DEF='Two' enabledAxes='3'"),  # axis 3 acting too
                ("DEF='Two' enabledAxes='2'", "DEF='Two' enabledAxes='1'"),  # axis 2 left out
            ))
