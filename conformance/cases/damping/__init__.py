"""damping: RigidBody.autoDamp: each step takes a fraction of each velocity away."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, steps, max_norm
from conformance.results import Measure, Settings


# damping.x3d
DAMP_V0, DAMP_W0 = np.array([2.0, 0.0, -1.0]), np.array([0.0, 0.0, 3.0])
DAMP_LINEAR, DAMP_ANGULAR = 0.01, 0.02


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """x3drbp's definition (ODE's): each step multiplies each velocity by (1 - d), so after
    n = floor(t/dt) steps v_n = v0 (1-d)^n. No gravity, no force, isotropic inertia: nothing
    else changes the velocities, under any integrator. The check is exact up to ROUNDING
    (n multiplications, each within an ulp). There is no continuous limit to converge to:
    at a fixed d the decay per second depends on dt by definition."""
    tr, s = traces[0], settings[0]
    t, v = tr.series("Damped", "linearVelocity")
    _, w = tr.series("Damped", "angularVelocity")
    n = steps(t, s.dt)[:, None]
    v_exact = DAMP_V0 * (1.0 - DAMP_LINEAR) ** n
    w_exact = DAMP_W0 * (1.0 - DAMP_ANGULAR) ** n
    return [Measure("Damped.linearVelocity", max_norm(v - v_exact), ROUNDING * np.linalg.norm(DAMP_V0), "m/s"),
            Measure("Damped.angularVelocity", max_norm(w - w_exact), ROUNDING * np.linalg.norm(DAMP_W0), "rad/s")]


CASE = Case("damping", "damping.x3d",
            "RigidBody.autoDamp, linearDampingFactor 0.01, angularDampingFactor 0.02: v_n = v0 (1-d)^n",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.autoDamp", "RigidBody.linearDampingFactor", "RigidBody.angularDampingFactor"),
            mutations=((" linearDampingFactor='0.01'", ""),))
