"""finite_rotation: RigidBody.useFiniteRotation / finiteRotationAxis: a fast wheel turns by each step's whole rotation.

"Setting the field value to TRUE uses the finite calculation model": the body turns, each
step, by the rotation its angular velocity makes in that step (the exponential map; ODE's
finite rotation mode, about finiteRotationAxis where one is given), not by the first-order
update q += h/2 w q (ODE's infinitesimal mode), which turns it by 2 atan(|w| h/2) a step. A
wheel spinning at 60 rad/s about the axis keeps that rate, so its angle is 60 t exactly."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import (ROUNDING, ROUNDING_ANGLE, honoured, infinitesimal_lag, max_norm,
                                           physics_time)
from conformance.results import Measure, Settings, accuracy, spec


FINITE = spec("37.4.10 RigidBody: The useFiniteRotation field is used to influence the way the body's rotation is "
              "calculated. In very fast rotating objects, such as a wheel of a car, an infinitely small time step "
              "can cause the modelling to explode. The default value is to use the faster infinite mode. Setting the "
              "field value to TRUE uses the finite calculation model. Using the finite model is more costly to "
              "compute but will be more accurate for high rotation speed bodies.")
EXACT = accuracy("a torque-free spin about a principal axis keeps its angular velocity, and the finite model turns "
                 "the body by each step's whole rotation: Rz(w t) and w to rounding, whatever the step")

# finite_rotation.x3d: the wheel's spin about z (its finiteRotationAxis), rad/s
FR_OMEGA = 60.0
FR_AXIS = np.array([0.0, 0.0, 1.0])


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The angle about the axis (the rotation's twist, unwrapped from frame to frame: the wheel
    turns 1 rad a frame at 60 Hz, under pi) against 60 t. Accuracy: the finite model is exact for
    a constant w, so only rounding (ROUNDING_ANGLE). Spec tolerance (closed_forms.honoured): half
    the infinitesimal model's lag, (w h - 2 atan(w h/2)) t/h (0.31 rad at 1 s at h = 1/240): a run
    nearer the finite model's angle than the infinite one's uses the finite model."""
    tr, s = traces[0], settings[0]
    t, rot = tr.series("Wheel", "orientation")
    _, w = tr.series("Wheel", "angularVelocity")
    tp = physics_time(t, s.dt)
    T = float(tp[-1])
    quat = R.from_axis_angle(rot)
    twist = np.unwrap(R.twist_angle(quat, FR_AXIS))
    spin = np.column_stack([np.tile(FR_AXIS, (len(tp), 1)), FR_OMEGA * tp])
    return [Measure("Wheel angle about finiteRotationAxis - w t", float(np.max(np.abs(twist - FR_OMEGA * tp))),
                    honoured(ROUNDING_ANGLE, infinitesimal_lag(FR_OMEGA, s.dt) * T), "rad", FINITE, ROUNDING_ANGLE),
            Measure("Wheel.orientation - Rz(w t)", float(np.max(R.angle_between(quat, R.from_axis_angle(spin)))),
                    ROUNDING_ANGLE, "rad", EXACT),
            Measure("Wheel.angularVelocity - (0, 0, w)", max_norm(w - FR_OMEGA * FR_AXIS), ROUNDING * FR_OMEGA,
                    "rad/s", EXACT)]


CASE = Case("finite_rotation", "finite_rotation.x3d",
            "RigidBody.useFiniteRotation TRUE, finiteRotationAxis 0 0 1: a wheel spinning at 60 rad/s about the axis "
            "turns 60 t (the infinitesimal update lags 0.31 rad a second at h = 1/240)",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.useFiniteRotation", "RigidBody.finiteRotationAxis", "RigidBody.angularVelocity"),
            # an engine that ignores the flag (the infinitesimal update) turns the wheel by 2 atan(w h/2) a step:
            # as the finite model turns a wheel spinning at 2 atan(60 h/2)/h = 59.690 rad/s (h = 1/240)
            mutations=(("angularVelocity='0 0 60'", f"angularVelocity='0 0 {60 - infinitesimal_lag(60, 1 / 240)!r}'"),
                       # the flag dropped: ODE then takes the first-order update (MuJoCo, the reference, would not)
                       Mutation(" useFiniteRotation='true'", "", on="ode")))
