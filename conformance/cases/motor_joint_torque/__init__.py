"""motor_joint_torque: MotorJoint axis1Torque: equal and opposite torques on two free bodies."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, physics_time, max_norm
from conformance.results import Measure, Settings, convention, spec


# motor_joint_torque.x3d: an AMotor between two free bodies, no gravity, one axis
MJ_TORQUE, MJ_I1, MJ_I2 = 0.6, 0.2, 0.4  # the moments about the motor's axis z
MJ_AXIS = np.array([0.0, 0.0, 1.0])
RELATIVE = spec("37.4.9 MotorJoint: The MotorJoint node allows control of the relative angular velocities between "
                "the two bodies (specified by the body1 and body2 fields) associated with a joint.")
RATE = spec("37.4.9 MotorJoint: The motor angle rate output fields describe the rate, in radians, that the motor is "
            "turning.")
ODE_TORQUE = convention("body1 gets +axis1Torque about motor1Axis and body2 its opposite (ODE's "
                        "dJointAddAMotorTorques, Xj3D, FreeWRL); alternative: the other way round")
ODE_RATE = convention("motor1AngleRate = motor1Axis . (w1 - w2), body1 relative to body2 (ODE's AMotor); "
                      "alternative: body2 relative to body1, the opposite sign")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The motor turns the bodies against each other about its axis with axis1Torque tau, every
    step; the axis is a principal axis of both, so neither turns off it (no gyroscopic torque)
    and each has a constant angular acceleration: |w1| = tau t / I1, |w2| = tau t / I2, opposite,
    and |motor1AngleRate| = (1/I1 + 1/I2) tau t. Velocities under a constant acceleration are
    exact for every one-step scheme: ROUNDING.

    Spec measures: the torques are equal and opposite (I1 w1 + I2 w2 = 0, nothing else acts),
    body1 spins up at tau/I1 about the axis in either sense, and |motor1AngleRate| grows at
    (1/I1 + 1/I2) tau. Which body gets +tau, and the rate's sign, are ODE's (convention measures).
    One axis only: motor1AngleRate does not depend on how several axes' angles are split (the
    per-axis twist x3drbp computes against ODE's Euler angles, backends/base.py)."""
    tr, s = traces[0], settings[0]
    t, w1 = tr.series("Rotor", "angularVelocity")
    _, w2 = tr.series("Stator", "angularVelocity")
    _, rate = tr.series("Motor", "motor1AngleRate")
    rate = rate[:, 0]
    tp = physics_time(t, s.dt)
    a1, a2 = MJ_TORQUE / MJ_I1, -MJ_TORQUE / MJ_I2
    T = float(tp[-1])
    sense = 1.0 if float(w1[-1] @ MJ_AXIS) >= 0 else -1.0
    return [Measure("I1 Rotor.angularVelocity + I2 Stator.angularVelocity", max_norm(MJ_I1 * w1 + MJ_I2 * w2),
                    ROUNDING * (1 + MJ_TORQUE * T), "kg m^2/s", RELATIVE),
            Measure("Rotor.angularVelocity, either sense", max_norm(w1 - np.outer(sense * a1 * tp, MJ_AXIS)),
                    ROUNDING * (1 + abs(a1) * T), "rad/s", RELATIVE),
            Measure("|Motor.motor1AngleRate|", max_norm(np.abs(rate) - (a1 - a2) * tp),
                    ROUNDING * (1 + (a1 - a2) * T), "rad/s", RATE),
            Measure("Rotor.angularVelocity", max_norm(w1 - np.outer(a1 * tp, MJ_AXIS)),
                    ROUNDING * (1 + abs(a1) * T), "rad/s", ODE_TORQUE),
            Measure("Motor.motor1AngleRate", max_norm(rate - (a1 - a2) * tp),
                    ROUNDING * (1 + (a1 - a2) * T), "rad/s", ODE_RATE)]


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
