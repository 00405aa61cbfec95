"""auto_disable: RigidBody autoDisable: a body at rest is disabled after disableTime and held
still; a collision wakes it; a body an applied force acts on is never disabled.

Clause 37 (RigidBody, and RigidBodyCollection, the same paragraph): "The disable fields define
conditions for when the body ceases to considered as part of the rigid body calculations and
should be considered as at rest. ... Once any one of these values is achieved, the body is
considered as being at rest, unless acted upon by an external force (e.g., collision or action of
connected joint)." What "any one of these values" means for two speeds and a time, and so the
moment a body stops, is a convention (x3drbp: any one speed under its threshold, for disableTime;
ODE: both speeds); that a body at rest is still, and that a collision or a force acts on it, is
the spec's sentence.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import (AT_REST, CFM_DEFAULT, ERP_DEFAULT, ROUNDING, ROUNDING_ANGLE, G,
                                            ballistic, honoured, max_norm, steps, stops_at)
from conformance.results import Measure, Settings, convention


# auto_disable.x3d: thresholds 0.1 m/s, 0.1 rad/s, 0.25 s on every autoDisable body; 1 kg bodies
AD_TIME, AD_M = 0.25, 1.0
AD_HIT = 0.5  # Striker (2 m/s, 1.0 m away) meets Resting
AD_HELD = (AD_TIME, 0.45)  # Resting disabled, Striker still 0.1 m away
AD_AWAKE_UNTIL = AD_HIT + AD_TIME - 0.05  # before Resting, sliding without spin, may be disabled again
AD_STRIKER_U = np.array([2.0, 0.0, 0.0])
AD_PUSH = np.array([0.02, 0.0, 0.0])  # Pushed's force / mass
AD_DRIFT_P0, AD_DRIFT_V0, AD_DRIFT_W0 = np.array([0.0, 2.0, 0.0]), np.array([0.05, 0.0, 0.0]), np.array([0.0, 0.0, 0.5])

ANY_ONE = ("any one speed under its threshold, held for disableTime, stops a body (x3drbp, the literal reading of "
           "'Once any one of these values is achieved'); ODE, Xj3D: both speeds under their thresholds for the "
           "time (never here: it spins at 0.5 rad/s); X_ITE: Bullet's sleeping thresholds and its own 2 s")


def _angle(q: np.ndarray, q0: np.ndarray) -> np.ndarray:
    """The angle (rad) of each rotation q (axis-angle rows) relative to q0."""
    a = R.from_axis_angle(q)
    b = R.from_axis_angle(q0[None, :])
    dot = np.clip(np.abs(np.sum(a * b, axis=1)), 0.0, 1.0)
    return 2.0 * np.arccos(dot)


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Resting, held (frames from disableTime, when it is disabled under either reading since
    both its speeds are under the thresholds from the first step, to 0.45 s): velocities exactly
    0 (the evaluator zeroes them: ROUNDING); its pose kept up to the depth its weight had pressed
    it into the floor, which the contact's error correction may take back once its weight is
    cancelled (x3drbp holds a body by its velocities and loads; the engine's contact still
    corrects penetration): at most g h^2 + CFM m g h / ERP (resting_penetration's bound), and
    the turn of a 0.2 m box lifted that much at one edge, twice it over 0.1 m.

    Woken by the collision: the floor is frictionless (frictionCoefficients 0) and flat, so the
    only horizontal forces on Resting and Striker are their contact's, equal and opposite:
    m (vR + vS) . x = m u at every frame until Resting, sliding without spin, may be disabled
    again (0.7 s < 0.5 + disableTime). A Resting held through the impact keeps none of it (its
    velocity is zeroed every step) and the sum drops towards 0: the tolerance is half that, m u / 2
    (closed_forms.honoured), and the bound that grades it up to ROUNDING per step on the 2 kg m/s
    exchanged, and a box tilted by the held pose's bound above tips its floor force by that angle:
    m g angle over the run.

    Pushed: acted upon by an applied force at every step, never disabled: the constant-force
    closed form (closed_forms.ballistic, a = 0.02 m/s^2) throughout; disabled at disableTime it
    would stop at 0.6 mm of the 1 cm it travels.

    Drifting (convention: ANY_ONE): free flight until disableTime, then still: after n steps
    p = p0 + v0 dt min(n, N), v = v0 and w = w0 while n < N, 0 after, N = ceil(disableTime/dt).
    Exact but for ROUNDING."""
    tr, s = traces[0], settings[0]
    h = s.dt
    out = []
    # Resting held
    t, p = tr.series("Resting", "position")
    _, q = tr.series("Resting", "orientation")
    _, v = tr.series("Resting", "linearVelocity")
    _, w = tr.series("Resting", "angularVelocity")
    n = steps(t, h)
    held = (n >= np.ceil(AD_TIME / h - 1e-9)) & (t <= AD_HELD[1])
    depth = G * h * h + CFM_DEFAULT * AD_M * G * h / ERP_DEFAULT
    first = int(np.flatnonzero(held)[0])
    rest = AT_REST
    out += [Measure("Resting held: |linearVelocity|", max_norm(v[held]), ROUNDING, "m/s", rest),
            Measure("Resting held: |angularVelocity|", max_norm(w[held]), ROUNDING, "rad/s", rest),
            Measure("Resting held: position moved", max_norm(p[held] - p[first]), depth + ROUNDING, "m", rest),
            Measure("Resting held: orientation turned", float(np.max(_angle(q[held], q[first]))),
                    2.0 * depth / 0.1 + ROUNDING_ANGLE, "rad", rest)]
    # woken by the collision: horizontal momentum
    _, vs = tr.series("Striker", "linearVelocity")
    early = t <= AD_AWAKE_UNTIL + 1e-9
    momentum = AD_M * (v[early, 0] + vs[early, 0]) - AD_M * AD_STRIKER_U[0]
    tilt = 2.0 * depth / 0.1
    momentum_bound = AD_M * G * tilt * AD_AWAKE_UNTIL + ROUNDING * AD_M * np.linalg.norm(AD_STRIKER_U) * \
        AD_AWAKE_UNTIL / h
    out.append(Measure("Resting woken: m (vResting + vStriker).x - m u", max_norm(momentum),
                       honoured(momentum_bound, AD_M * float(np.linalg.norm(AD_STRIKER_U))), "kg m/s", rest,
                       momentum_bound))
    # Pushed: never disabled while a force acts on it
    pushed = ballistic("Pushed", (0.0, 1.0, 0.0), (0.0, 0.0, 0.0), AD_PUSH, rest)(traces, settings)
    out += [dataclasses.replace(m, quantity=f"{m.quantity} (pushed, never disabled)") for m in pushed]
    # Drifting: the moment it stops (convention)
    return out + stops_at(tr, s, "Drifting", AD_DRIFT_P0, AD_DRIFT_V0, AD_DRIFT_W0, AD_TIME, convention(ANY_ONE))


# the scene's text just before Drifting's disable fields (the other bodies' read alike)
DRIFTING = "angularVelocity='0 0 0.5' inertia='0.004 0 0 0 0.004 0 0 0 0.004'\n         "


CASE = Case("auto_disable", "auto_disable.x3d",
            "RigidBody autoDisable (0.1 m/s, 0.1 rad/s, 0.25 s): a box at rest on the floor is held still, "
            "a collision wakes it (horizontal momentum m u kept); a pushed body is never disabled; a drifting, "
            "spinning one stops at disableTime (any one speed under its threshold)",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.autoDisable", "RigidBody.disableLinearSpeed", "RigidBody.disableAngularSpeed",
                       "RigidBody.disableTime", "RigidBody.forces"),
            mutations=((" forces='0.02 0 0'", ""), (" linearVelocity='2 0 0'", ""),
                       # Drifting never stops (no test, or no linear speed under 0), or stops at once
                       *(Mutation(DRIFTING + old, DRIFTING + new, spec=False) for old, new in (
                           (" autoDisable='true'", ""),
                           (" autoDisable='true' disableLinearSpeed='0.1'", " autoDisable='true'"),
                           (" autoDisable='true' disableLinearSpeed='0.1' disableAngularSpeed='0.1' "
                            "disableTime='0.25'", " autoDisable='true' disableLinearSpeed='0.1' "
                                                  "disableAngularSpeed='0.1'")))))
