"""motor_disabled_axis: MotorJoint motorNAxis 0 0 0: a disabled axis, no torque along it, outputs 0."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, ROUNDING_ANGLE, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, convention, spec

# motor_disabled_axis.x3d: every motor axis 0 0 0; the torques given on axes 1 and 3, the angle on 3
MD_I, MD_TORQUE1, MD_TORQUE3, MD_ANGLE3 = 0.2, 0.2, 0.5, 0.3
MD_SPIN = np.array([0.0, 0.0, 0.8])
DISABLED = spec("37.4.9 MotorJoint: The motorAxis fields define the axis vector of the corresponding axis. If the "
                "value is 0, 0, 0, the corresponding axis is disabled and the motor does not apply a force or torque "
                "along that axis.")
DISABLED_OUTPUTS = convention("a disabled axis (motorNAxis 0 0 0) reports motorNAngle 0 and motorNAngleRate 0, in "
                              "either mode: it has no direction to turn about (x3drbp); alternative: axisNAngle "
                              "echoed in user-calculated mode (ODE's AMotor reports the angle set, whatever the axis)")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """No torque acts on the isotropic rotor, so it keeps its angular velocity: exact for every
    scheme (ROUNDING). The spec measure's tolerance (closed_forms.honoured) is half the nearest
    misreading's error at the end: X3D 4.0's default axis 1 0 0 in axis 1's place pushes
    axis1Torque along x (w gains axis1Torque t / I, the nearer), 0 0 1 in axis 3's 2.5 t along z.
    Convention measures: the disabled axis's rate and angle are 0, to rounding, against the rate
    about the default axis 0 0 1 (0.8 rad/s and more) and the echoed axis3Angle (0.3 rad)."""
    tr, s = traces[0], settings[0]
    t, w = tr.series("Rotor", "angularVelocity")
    _, rate = tr.series("Motor", "motor3AngleRate")
    _, angle = tr.series("Motor", "motor3Angle")
    T = float(physics_time(t, s.dt)[-1])
    spin = float(np.linalg.norm(MD_SPIN))
    bound_w = ROUNDING * (1 + spin)
    return [Measure("Rotor.angularVelocity = 0 0 0.8 (no torque along a disabled axis)", max_norm(w - MD_SPIN),
                    honoured(bound_w, MD_TORQUE1 * T / MD_I, MD_TORQUE3 * T / MD_I), "rad/s", DISABLED, bound_w),
            Measure("Motor.motor3AngleRate = 0 (a disabled axis)", max_norm(rate[:, 0]), honoured(bound_w, spin),
                    "rad/s", DISABLED_OUTPUTS, bound_w),
            Measure("Motor.motor3Angle = 0 (a disabled axis)", max_norm(angle[:, 0]),
                    honoured(ROUNDING_ANGLE, MD_ANGLE3), "rad", DISABLED_OUTPUTS, ROUNDING_ANGLE)]


CASE = Case("motor_disabled_axis", "motor_disabled_axis.x3d",
            "MotorJoint motor1Axis = motor2Axis = motor3Axis = 0 0 0 (enabledAxes 3, axis1Torque 0.2, axis3Torque "
            "0.5): disabled, the rotor keeps w = (0, 0, 0.8); motor3Angle and motor3AngleRate 0",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("MotorJoint.motor1Axis", "MotorJoint.motor3Axis", "MotorJoint.axis1Torque",
                       "MotorJoint.axis3Torque", "MotorJoint.enabledAxes", "MotorJoint.axis3Angle"),
            mutations=(
                (" motor1Axis='0 0 0'", ""),  # 4.0's default 1 0 0: axis1Torque turns the rotor about x
                (" motor3Axis='0 0 0'", ""),  # 4.0's default 0 0 1: axis3Torque spins it up
            ))
