"""motor_joint_torque: MotorJoint axis1Torque: equal and opposite torques on two free bodies.

Two motors: UserMotor in user-calculated mode (autoCalc FALSE), where the UOM and the clause both
apply axis1Torque, and AutoMotor with autoCalc TRUE, whose motor1AngleRate is computed. The UOM
says the torque acts "when in user-calculated mode"; the clause, as H3D copies it, ties that
phrase to the axis angles only. A browser may read either, so that AutoMotor's torque acts is a
convention (x3drbp's and ODE's, whose AMotor takes torques in both modes); what the spec asks of
AutoMotor is that its rate output is the rate its bodies turn at about the axis, whatever the
torque did, and that its angle output is the angle they turned through. The rate is the bodies'
in user-calculated mode too (UserMotor); only the angle is the user's there."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, ROUNDING_ANGLE, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, convention, spec


# motor_joint_torque.x3d: an AMotor between two free bodies, no gravity, one axis
MJ_TORQUE, MJ_I1, MJ_I2 = 0.6, 0.2, 0.4  # the moments about the motor's axis z
MJ_AXIS = np.array([0.0, 0.0, 1.0])
RELATIVE = spec("37.4.9 MotorJoint: The MotorJoint node allows control of the relative angular velocities between "
                "the two bodies (specified by the body1 and body2 fields) associated with a joint.")
RATE = spec("37.4.9 MotorJoint: The motor angle output fields provide the calculated angle for this motor joint "
            "from the last frame. The motor angle rate output fields describe the rate, in radians, that the motor "
            "is turning.")
AUTO_ANGLE = spec("37.4.9 MotorJoint: The autoCalc field is used to control whether the user shall manually provide "
                  "the individual angle rotations each frame or if they are to be automatically calculated from the "
                  "motor’s implementation.")
ODE_TORQUE = convention("body1 gets +axis1Torque about motor1Axis and body2 its opposite (ODE's "
                        "dJointAddAMotorTorques, Xj3D, FreeWRL); alternative: the other way round")
TORQUE_ANY_MODE = convention("axis1Torque acts whatever autoCalc is (x3drbp; ODE's AMotor takes torques in user and "
                             "Euler mode); alternative: only in user-calculated mode, autoCalc FALSE (the UOM's "
                             "\"applied by corresponding motor axis when in user-calculated mode\")")
ODE_RATE = convention("motor1AngleRate = motor1Axis . (w1 - w2), body1 relative to body2 (ODE's AMotor); "
                      "alternative: body2 relative to body1, the opposite sign")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each motor turns its bodies against each other about its axis with axis1Torque tau, every
    step; the axis is a principal axis of both, so neither turns off it (no gyroscopic torque)
    and each has a constant angular acceleration: |w1| = tau t / I1, |w2| = tau t / I2, opposite,
    and |motor1AngleRate| = (1/I1 + 1/I2) tau t. Velocities under a constant acceleration are
    exact for every one-step scheme: ROUNDING.

    Spec measures: each pair's torques are equal and opposite (I1 w1 + I2 w2 = 0, nothing else
    acts, and so also where no torque acts); UserRotor spins up at tau/I1 about the axis in either
    sense; |motor1AngleRate| is |axis . (w1 - w2)| of each motor's bodies, UserMotor's (autoCalc
    FALSE) too; |AutoMotor.motor1Angle| is the angle AutoRotor turned through about the axis
    relative to AutoStator since the start, read from their orientations (ROUNDING_ANGLE), so that
    whether the torque acts does not enter; its misreading, the echoed axis1Angle (0), is off by
    the turn, (1/I1 + 1/I2) tau T^2 / 2 = 2.25 rad at the end. Conventions: that
    AutoMotor's torque acts too, which body gets +tau, and the rate's sign (ODE's). One axis only:
    motor1AngleRate does not depend on how several axes' angles are split (the per-axis twist
    x3drbp computes against ODE's Euler angles, backends/base.py).

    Those ROUNDING figures are the accuracy bounds. The clause asks for control of the relative
    velocities, not for that exactness: each measure's tolerance (closed_forms.honoured) is half
    its misreading's error at the end: the torque on one body only (I1 w1 + I2 w2 = tau T), the
    torque ignored (the rotor still: tau T / I1), the rate of one body alone or none (tau T / I2
    off), and for a convention the other reading (the opposite sense: twice the closed form)."""
    tr, s = traces[0], settings[0]
    w = {name: tr.series(name, "angularVelocity")[1] for name in ("UserRotor", "UserStator", "AutoRotor", "AutoStator")}
    t, rate = tr.series("AutoMotor", "motor1AngleRate")
    rate = rate[:, 0]
    user_rate = tr.series("UserMotor", "motor1AngleRate")[1][:, 0]
    angle = tr.series("AutoMotor", "motor1Angle")[1][:, 0]
    q1, q2 = (R.from_axis_angle(tr.series(name, "orientation")[1]) for name in ("AutoRotor", "AutoStator"))
    turned = R.twist_angle(R.multiply(R.conjugate(q2), q1), MJ_AXIS)
    tp = physics_time(t, s.dt)
    a1, a2 = MJ_TORQUE / MJ_I1, -MJ_TORQUE / MJ_I2
    T = float(tp[-1])

    def spun(name: str) -> float:
        """How far a rotor is from spinning up at tau/I1 about the axis, in the sense it took."""
        sense = 1.0 if float(w[name][-1] @ MJ_AXIS) >= 0 else -1.0
        return max_norm(w[name] - np.outer(sense * a1 * tp, MJ_AXIS))
    turning = (w["AutoRotor"] - w["AutoStator"]) @ MJ_AXIS
    user_turning = (w["UserRotor"] - w["UserStator"]) @ MJ_AXIS
    bound_l, bound_w = ROUNDING * (1 + MJ_TORQUE * T), ROUNDING * (1 + abs(a1) * T)
    bound_rate = ROUNDING * (1 + (a1 - a2) * T)
    tol_l, tol_w = honoured(bound_l, MJ_TORQUE * T), honoured(bound_w, a1 * T)
    tol_rate = honoured(bound_rate, -a2 * T)
    return [Measure(f"I1 {p}Rotor.angularVelocity + I2 {p}Stator.angularVelocity",
                    max_norm(MJ_I1 * w[f"{p}Rotor"] + MJ_I2 * w[f"{p}Stator"]), tol_l, "kg m^2/s", RELATIVE, bound_l)
            for p in ("User", "Auto")] + [
            Measure("UserRotor.angularVelocity, either sense", spun("UserRotor"), tol_w, "rad/s", RELATIVE, bound_w),
            Measure("|AutoMotor.motor1AngleRate| = |motor1Axis . (w1 - w2)|", max_norm(np.abs(rate) - np.abs(turning)),
                    tol_rate, "rad/s", RATE, bound_rate),
            Measure("|UserMotor.motor1AngleRate| = |motor1Axis . (w1 - w2)| (autoCalc FALSE)",
                    max_norm(np.abs(user_rate) - np.abs(user_turning)), tol_rate, "rad/s", RATE, bound_rate),
            Measure("|AutoMotor.motor1Angle| = |AutoRotor's turn about motor1Axis relative to AutoStator|",
                    max_norm(np.abs(angle) - np.abs(turned)), honoured(ROUNDING_ANGLE, (a1 - a2) * T * T / 2), "rad",
                    AUTO_ANGLE, ROUNDING_ANGLE),
            Measure("UserRotor.angularVelocity", max_norm(w["UserRotor"] - np.outer(a1 * tp, MJ_AXIS)),
                    honoured(bound_w, 2 * a1 * T), "rad/s", ODE_TORQUE, bound_w),
            Measure("AutoRotor.angularVelocity, either sense (the torque acts with autoCalc TRUE)", spun("AutoRotor"),
                    tol_w, "rad/s", TORQUE_ANY_MODE, bound_w),
            Measure("AutoMotor.motor1AngleRate", max_norm(rate - (a1 - a2) * tp),
                    honoured(bound_rate, 2 * (a1 - a2) * T), "rad/s", ODE_RATE, bound_rate)]


CASE = Case("motor_joint_torque", "motor_joint_torque.x3d",
            "MotorJoint axis1Torque 0.6 about motor1Axis 0 0 1, two free bodies (I_zz 0.2, 0.4), autoCalc FALSE "
            "and TRUE: w1 = tau t/I1, w2 = -tau t/I2, motor1AngleRate = (1/I1 + 1/I2) tau t in both modes, "
            "AutoMotor's motor1Angle the bodies' relative turn",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("MotorJoint.axis1Torque", "MotorJoint.motor1Axis", "MotorJoint.autoCalc",
                       "RigidBody.inertia"),
            mutations=(
                ("DEF='UserMotor' enabledAxes='1' motor1Axis='0 0 1' axis1Torque='0.6'",
                 "DEF='UserMotor' enabledAxes='1' motor1Axis='0 0 1'"),
                (" autoCalc='true'", ""),  # motor1Angle is then the user's axis1Angle (0) while the bodies turn
                # the torque on one body of the pair only: I1 w1 + I2 w2 = -/+ tau t
                ("<RigidBody USE='UserRotor' containerField='body1'/>", ""),
                ("<RigidBody USE='UserStator' containerField='body2'/>", ""),
                # the default axis 1 0 0: UserRotor spins about x, not z
                ("DEF='UserMotor' enabledAxes='1' motor1Axis='0 0 1'", "DEF='UserMotor' enabledAxes='1'"),
            ))
