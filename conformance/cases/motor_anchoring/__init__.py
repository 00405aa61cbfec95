"""motor_anchoring: MotorJoint motor1Axis fixed in the world, motor2Axis turning with body1, motor3Axis with body2."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, ROUNDING_ANGLE, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, spec

# motor_anchoring.x3d: three isotropic rotors spinning about y, each pushed along x by one motor axis
# (axis 1 given as -1 0 0 with torque -0.2, off its default)
MA_I, MA_OMEGA, MA_TORQUE = 0.2, 2.0, 0.2
MA_ALPHA = MA_TORQUE / MA_I
ANCHORED = spec("37.4.9 MotorJoint: The motorAxis1 field is anchored to the global frame. The motorAxis2 field is "
                "anchored to body1’s frame of reference, and the motorAxis3 field is anchored to body2’s frame of "
                "reference.")
# rotor -> whether its closed form holds in its own frame (else the world's)
MA_ROTORS = {"WorldRotor": False, "Body1Rotor": True, "Body2Rotor": True}


def _turned(spin: np.ndarray, h: float, in_body: bool) -> np.ndarray:
    """The orientation after steps of h, each an exact turn about its angular velocity spin[k] (its
    value at the step's middle), given in the body's frame (in_body) or the world's."""
    steps = R.from_axis_angle(np.column_stack([spin, np.linalg.norm(spin, axis=1) * h]))
    q = R.IDENTITY
    for step in steps:
        q = R.multiply(q, step) if in_body else R.multiply(step, q)
    return q


def misread(T: float, n: int = 300) -> float:
    """The end error of the measure on the other anchoring's exact motion, the nearest over both
    senses: a body-carried torque read in the world (the rotor's frame holds (s alpha t, Omega, 0),
    its orientation turning with it) and a world-fixed torque read in the rotor's frame. The
    orientation is the midpoint rule's, second order: ~1e-5 relative at n = 300 for these rates,
    nothing beside a tolerance of half the figure."""
    h = T / n
    mid = (np.arange(n) + 0.5) * h
    errors = []
    for s in (1.0, -1.0):
        spin = np.column_stack([s * MA_ALPHA * mid, np.full(n, MA_OMEGA), np.zeros(n)])
        end = np.array([s * MA_ALPHA * T, MA_OMEGA, 0.0])
        seen = (R.rotate(_turned(spin, h, True), end), R.rotate(R.conjugate(_turned(spin, h, False)), end))
        errors += [float(np.linalg.norm(w - [s2 * MA_ALPHA * T, MA_OMEGA, 0.0])) for w in seen for s2 in (1.0, -1.0)]
    return min(errors)


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each rotor is isotropic, so no gyroscopic torque acts and its angular momentum changes only
    by the motor's torque. Fixed in the world (WorldRotor) it adds alpha t along x to w in the
    world; turning with the rotor (Body1Rotor, body1 of axis 2; Body2Rotor, body2 of axis 3) it is
    constant in the rotor's frame, so there w = (+-alpha t, Omega, 0). The world's closed form is
    exact for every one-step scheme (a constant acceleration: ROUNDING). The rotor's is exact for
    every scheme that turns a body about its new angular velocity w' in a step (semi-implicit Euler;
    ODE's quaternion step, the exponential map): the torque is taken at the step's start R,
    w' = w + h alpha R x, and the turn leaves w' fixed, so R'^T w' = R^T w + h alpha x. Read from
    the trace, the rotor's frame carries its orientation's rounding too: ROUNDING_ANGLE |w|. An
    engine that integrates through the step with the torque held where the step's start put it
    (the evaluator sets loads once a step; Drake's continuous plant) lets the rotor turn under it:
    the torque lags by up to |w| h in the rotor's frame, alpha |w| h t / 2 in all, graded only.

    Spec measures, in either sense (which body gets +torque is motor_axes's convention): each
    rotor's w against its closed form in its frame. The tolerance (closed_forms.honoured) is half
    the misreading's error, the axis anchored elsewhere (misread(): the world's axis carried by
    body1, as ODE's Euler mode anchors axis 1; body1's or body2's axis fixed in the world, as
    where the static environment carries it)."""
    tr, s = traces[0], settings[0]
    t = tr.series("WorldRotor", "orientation")[0]
    tp = physics_time(t, s.dt)
    T = float(tp[-1])
    speed = float(np.hypot(MA_OMEGA, MA_ALPHA * T))
    other = misread(T)
    out = []
    for name, own in MA_ROTORS.items():
        _, rot = tr.series(name, "orientation")
        _, w = tr.series(name, "angularVelocity")
        seen = R.rotate(R.conjugate(R.from_axis_angle(rot)), w) if own else w
        sense = 1.0 if float(seen[-1, 0]) >= 0 else -1.0
        exact = np.column_stack([sense * MA_ALPHA * tp, np.full(len(tp), MA_OMEGA), np.zeros(len(tp))])
        bound = ROUNDING * (1 + speed) + (ROUNDING_ANGLE * speed if own else 0.0)
        frame = f"in {name}'s frame" if own else "in the world"
        out.append(Measure(f"{name}.angularVelocity {frame} = ({MA_ALPHA:g} t, {MA_OMEGA:g}, 0), either sense",
                           max_norm(seen - exact), honoured(bound, other), "rad/s", ANCHORED, bound))
    return out


CASE = Case("motor_anchoring", "motor_anchoring.x3d",
            "MotorJoint torque 0.2 along x on isotropic rotors (I 0.2) spinning at 2 rad/s about y: motor1Axis "
            "fixed in the world (w = (t, 2, 0) there), motor2Axis and motor3Axis turning with body1 and body2 "
            "(w = (+-t, 2, 0) in the rotor's frame)",
            (Settings(1.5, 1 / 240),), expect,
            exercises=("MotorJoint.motor1Axis", "MotorJoint.motor2Axis", "MotorJoint.motor3Axis",
                       "MotorJoint.axis1Torque", "MotorJoint.axis2Torque", "MotorJoint.axis3Torque",
                       "MotorJoint.enabledAxes", "RigidBody.angularVelocity"),
            mutations=(
                # the world's axis carried by body1 (ODE's Euler mode; x3drbp once carried every axis so)
                ("DEF='WorldMotor' enabledAxes='1' motor1Axis='-1 0 0' axis1Torque='-0.2'",
                 "DEF='WorldMotor' enabledAxes='2' motor2Axis='-1 0 0' axis2Torque='-0.2'"),
                # body1's axis fixed in the world
                ("DEF='Body1Motor' enabledAxes='2' motor2Axis='1 0 0' axis2Torque='0.2'",
                 "DEF='Body1Motor' enabledAxes='1' motor1Axis='1 0 0' axis1Torque='0.2'"),
                # body2's axis fixed in the world (x3drbp once carried it with body1, here the environment)
                ("DEF='Body2Motor' enabledAxes='3' motor3Axis='1 0 0' axis3Torque='0.2'",
                 "DEF='Body2Motor' enabledAxes='1' motor1Axis='1 0 0' axis1Torque='0.2'"),
            ))
