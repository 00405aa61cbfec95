"""motor_joint_torque: MotorJoint axis1Torque: equal and opposite torques on two free bodies."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, physics_time, max_norm
from conformance.results import Measure, Settings


# motor_joint_torque.x3d: an AMotor between two free bodies, no gravity
MJ_TORQUE, MJ_I1, MJ_I2 = 0.6, 0.2, 0.4  # the moments about the motor's axis z
MJ_AXIS = np.array([0.0, 0.0, 1.0])


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """body1 gets +tau about the axis, body2 -tau, every step; the axis is a principal axis of
    both, so neither turns off it (no gyroscopic torque) and each has a constant angular
    acceleration: w1 = tau t / I1, w2 = -tau t / I2, and motor1AngleRate = axis . (w1 - w2) =
    (1/I1 + 1/I2) tau t. Velocities under a constant acceleration are exact for every one-step
    scheme: ROUNDING."""
    tr, s = traces[0], settings[0]
    t, w1 = tr.series("Rotor", "angularVelocity")
    _, w2 = tr.series("Stator", "angularVelocity")
    _, rate = tr.series("Motor", "motor1AngleRate")
    tp = physics_time(t, s.dt)
    a1, a2 = MJ_TORQUE / MJ_I1, -MJ_TORQUE / MJ_I2
    T = float(tp[-1])
    return [Measure("Rotor.angularVelocity", max_norm(w1 - np.outer(a1 * tp, MJ_AXIS)),
                    ROUNDING * (1 + abs(a1) * T), "rad/s"),
            Measure("Stator.angularVelocity", max_norm(w2 - np.outer(a2 * tp, MJ_AXIS)),
                    ROUNDING * (1 + abs(a2) * T), "rad/s"),
            Measure("Motor.motor1AngleRate", max_norm(rate[:, 0] - (a1 - a2) * tp),
                    ROUNDING * (1 + (a1 - a2) * T), "rad/s")]


CASE = Case("motor_joint_torque", "motor_joint_torque.x3d",
            "MotorJoint axis1Torque 0.6 about motor1Axis 0 0 1, two free bodies (I_zz 0.2, 0.4): w1 = tau t/I1, "
            "w2 = -tau t/I2, motor1AngleRate = (1/I1 + 1/I2) tau t",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("MotorJoint.axis1Torque", "MotorJoint.motor1Axis", "MotorJoint.autoCalc",
                       "RigidBody.inertia"),
            mutations=(
                (" axis1Torque='0.6'", ""),
                (" autoCalc='true'", ""),  # motor1AngleRate is then the user's (0)
            ))
