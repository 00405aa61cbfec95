"""motor_axes: MotorJoint axes 2 and 3: enabledAxes, motor2Axis/motor3Axis, axis2Torque/axis3Torque."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import ROUNDING, ROUNDING_ANGLE, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, convention, spec

# motor_axes.x3d: pair -> (the motor's axis, its torque, the user's axis angles it reports); no gravity
MA_I1, MA_I2 = 0.2, 0.4  # rotor (body1) and stator (body2), isotropic
MA_PAIRS = {"Two": (np.array([0.0, 0.0, 1.0]), 0.4, {2: 0.7}),
            "Three": (np.array([0.6, 0.8, 0.0]), -0.3, {1: 0.2, 3: -0.4})}
RELATIVE = spec("37.4.9 MotorJoint: The MotorJoint node allows control of the relative angular velocities between "
                "the two bodies (specified by the body1 and body2 fields) associated with a joint.")
AXES = spec("37.4.9 MotorJoint: The motorAxis fields define the axis vector of the corresponding axis. If the value "
            "is 0, 0, 0, the corresponding axis is disabled and the motor does not apply a force or torque along "
            "that axis.")
ODE_TORQUE = convention("body1 gets +axisNTorque about motorNAxis and body2 its opposite (ODE's "
                        "dJointAddAMotorTorques, Xj3D, FreeWRL); alternative: the other way round")
RATE = spec("37.4.9 MotorJoint: The motor angle output fields provide the calculated angle for this motor joint "
            "from the last frame. The motor angle rate output fields describe the rate, in radians, that the motor "
            "is turning.")
# autoCalc TRUE, no torque: spinner -> its angular velocity; motor axes 2 and 3 are the defaults (0 1 0), (0 0 1)
MA_SPINS = {"SpinY": np.array([0.0, 1.5, 0.0]), "SpinZ": np.array([0.0, 0.0, -2.0])}
USER_ANGLES = convention("in user-calculated mode (autoCalc FALSE) motorNAngle reports the axisNAngle given (ODE's "
                         "AMotor in user mode: dJointGetAMotorAngle returns the angle set); the clause's axis angles "
                         "are 'for this frame ... when in user-calculated mode', its motor angles 'the calculated "
                         "angle': an implementation may report an angle it computes instead")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each motor turns its rotor against its stator about its one axis with the torque tau, every
    step; the bodies are isotropic, so neither turns off the axis: w1 = (tau t / I1) axis, w2 =
    -(tau t / I2) axis. Velocities under a constant acceleration are exact for every one-step
    scheme: ROUNDING (motor_joint_torque's argument; the axes here turn with no body, as each
    body spins about the axis itself, so whichever body or the world carries an axis, it stays).

    Spec measures (the tolerances half the misreading's error at the end, closed_forms.honoured):
    the pair's torques are equal and opposite (I1 w1 + I2 w2 = 0; the torque on one body only
    leaves |tau| T), and the rotor spins up at |tau|/I1 about the motor's axis in either sense
    (enabledAxes or the torque ignored: the rotor still, |tau| T / I1 off; the axis ignored: the
    default axis, as far again). Conventions: ODE's sense (body1 gets +tau: twice the closed form
    for the other), and motorNAngle echoing axisNAngle in user mode (to rounding; not reported,
    or computed: the value's own size off).

    AutoY and AutoZ (autoCalc TRUE, no torque) join the fixed Base to a spinner turning at a
    constant rate about axis 2 (y) or axis 3 (z): |motor2AngleRate| and |motor3AngleRate| are
    |axis . (w1 - w2)| (the spec's "rate ... that the motor is turning"), to rounding, against not
    being reported (0). With the default axes 1 (x) and 3 (z) ODE's Euler frame
    has the same axis 2 (y), and a spinner about y or z keeps the other rate 0 in either frame."""
    tr, s = traces[0], settings[0]
    rates = {"AutoY": (tr.series("AutoY", "motor2AngleRate")[1], tr.series("AutoY", "motor3AngleRate")[1]),
             "AutoZ": (tr.series("AutoZ", "motor2AngleRate")[1], tr.series("AutoZ", "motor3AngleRate")[1])}
    echoed = {("Two", 2): tr.series("TwoMotor", "motor2Angle")[1],
              ("Three", 1): tr.series("ThreeMotor", "motor1Angle")[1],
              ("Three", 3): tr.series("ThreeMotor", "motor3Angle")[1]}
    out = []
    for (motor, spinner), (rate2, rate3) in zip((("AutoY", "SpinY"), ("AutoZ", "SpinZ")), rates.values()):
        _, w2 = tr.series(spinner, "angularVelocity")
        spin = float(np.linalg.norm(MA_SPINS[spinner]))
        for k, reported, axis in ((2, rate2, np.array([0.0, 1.0, 0.0])), (3, rate3, np.array([0.0, 0.0, 1.0]))):
            out.append(Measure(f"|{motor}.motor{k}AngleRate| - |motor{k}Axis . (w1 - w2)|",
                               max_norm(np.abs(reported[:, 0]) - np.abs(-w2 @ axis)),
                               honoured(ROUNDING * (1 + spin), spin), "rad/s", RATE, ROUNDING * (1 + spin)))
    for name, (axis, tau, angles) in MA_PAIRS.items():
        t, w1 = tr.series(f"{name}Rotor", "angularVelocity")
        _, w2 = tr.series(f"{name}Stator", "angularVelocity")
        tp = physics_time(t, s.dt)
        T = float(tp[-1])
        a1 = tau / MA_I1
        sense = 1.0 if float(w1[-1] @ axis) * a1 >= 0 else -1.0
        bound_l, bound_w = ROUNDING * (1 + abs(tau) * T), ROUNDING * (1 + abs(a1) * T)
        out += [Measure(f"I1 {name}Rotor.angularVelocity + I2 {name}Stator.angularVelocity",
                        max_norm(MA_I1 * w1 + MA_I2 * w2), honoured(bound_l, abs(tau) * T), "kg m^2/s", RELATIVE,
                        bound_l),
                Measure(f"{name}Rotor.angularVelocity, {abs(a1):g} t about the motor's axis, either sense",
                        max_norm(w1 - np.outer(sense * a1 * tp, axis)), honoured(bound_w, abs(a1) * T), "rad/s", AXES,
                        bound_w),
                Measure(f"{name}Rotor.angularVelocity = {a1:g} t about the motor's axis",
                        max_norm(w1 - np.outer(a1 * tp, axis)), honoured(bound_w, 2 * abs(a1) * T), "rad/s",
                        ODE_TORQUE, bound_w)]
        for k, value in angles.items():
            out.append(Measure(f"{name}Motor.motor{k}Angle - axis{k}Angle {value:g}",
                               max_norm(echoed[name, k][:, 0] - value), honoured(ROUNDING_ANGLE, abs(value)), "rad",
                               USER_ANGLES, ROUNDING_ANGLE))
    return out


CASE = Case("motor_axes", "motor_axes.x3d",
            "MotorJoint axes 2 and 3 (enabledAxes 2 and 3, motor2Axis 0 0 1 / motor3Axis 0.6 0.8 0, axis2Torque 0.4 / "
            "axis3Torque -0.3), free isotropic bodies: w1 = tau t / I1 about the axis, I1 w1 + I2 w2 = 0; "
            "motorNAngle echoes axisNAngle in user mode (ODE's)",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("MotorJoint.enabledAxes", "MotorJoint.motor2Axis", "MotorJoint.motor3Axis",
                       "MotorJoint.axis2Torque", "MotorJoint.axis3Torque", "MotorJoint.axis1Angle",
                       "MotorJoint.axis2Angle", "MotorJoint.axis3Angle"),
            mutations=(
                (" enabledAxes='2'", ""),  # axis 2 not used: TwoRotor still
                (" motor2Axis='0 0 1'", ""),  # TwoRotor spins about y
                (" axis2Torque='0.4'", ""),
                ("DEF='ThreeMotor' enabledAxes='3'", "DEF='ThreeMotor'"),
                (" motor3Axis='0.6 0.8 0'", ""),  # ThreeRotor spins about z
                (" axis3Torque='-0.3'", ""),
                *(Mutation(old, "", spec=False) for old in (" axis2Angle='0.7'", " axis1Angle='0.2'",
                                                              " axis3Angle='-0.4'")),
            ))
