"""damping: RigidBody.autoDamp: damping takes a fraction of each velocity away, every frame or every step.

The spec (37.4.10 RigidBody) says the damping factor "is used to take a multiple of the value
calculated in the last frame and apply it in opposition to the current motion for this frame".
Read against the spec's own model, in which the physics is evaluated once a frame, a frame is one
evaluation: a browser whose step is its frame (Xj3D, X_ITE) damps once a step and once a frame at
once. A browser that steps several times a frame may do either: once a frame by the letter, or
once a step (ODE's dBodySetLinearDamping, and x3drbp, whose motion must not depend on the frame
rate: frame_rate checks that with a damped body). The spec measures accept both and everything
between: from one frame to the next each velocity keeps its direction and is multiplied by a
ratio between (1-d)^k (once at each of the frame's k steps) and (1-d) (once a frame). x3drbp's
per-step reading is the convention measure. At the case's settings (d = 0.01 linear, 0.02
angular, 60 frames/s, step 1/240 s), v(1 s)/v0 is 0.99^240 = 0.0896 and 0.98^240 = 0.0078 once a
step, 0.99^60 = 0.547 and 0.98^60 = 0.298 once a frame. The default factor (0.001, what a browser
that ignores linearDampingFactor uses) keeps 0.996 a frame at most: beyond (1-d), a spec failure.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, steps, max_norm
from conformance.results import Measure, Settings, convention, spec


# damping.x3d
DAMP_V0, DAMP_W0 = np.array([2.0, 0.0, -1.0]), np.array([0.0, 0.0, 3.0])
DAMP_LINEAR, DAMP_ANGULAR = 0.01, 0.02
DAMPED = spec("37.4.10 RigidBody: The value of the field is used to take a multiple of the value calculated in "
              "the last frame and apply it in opposition to the current motion for this frame.")
PER_STEP = convention("each velocity is multiplied by (1 - factor) at every physics step, v_n = v0 (1-d)^n after "
                      "n steps (ODE's body damping, x3drbp); alternative: once a frame, v = v0 (1-d)^frames (the "
                      "spec's words where a frame holds several steps; Xj3D and X_ITE, stepping once a frame, do "
                      "both at once)")


def per_frame_error(t: np.ndarray, v: np.ndarray, d: float, dt: float) -> float:
    """How far each frame's velocity is from the nearest r x the previous frame's, r between
    (1-d)^k (damped at each of the k steps between the frames) and (1-d) (once a frame)."""
    k = np.diff(steps(t, dt))
    prev, cur = v[:-1], v[1:]
    den = np.einsum("ij,ij->i", prev, prev)
    r = np.einsum("ij,ij->i", cur, prev) / np.where(den > 0, den, 1.0)
    r = np.clip(r, (1.0 - d) ** k, (1.0 - d) ** np.minimum(k, 1))
    return max_norm(cur - r[:, None] * prev)


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """No gravity, no force, isotropic inertia: nothing but the damping changes the velocities,
    under any integrator. Spec: per_frame_error, within ROUNDING (a ratio and a product per frame).
    Convention (x3drbp's, ODE's): after n = floor(t/dt) steps v_n = v0 (1-d)^n, exact up to
    ROUNDING (n multiplications, each within an ulp). There is no continuous limit to converge
    to: at a fixed d the decay per second depends on dt (or on the frame rate) by definition."""
    tr, s = traces[0], settings[0]
    t, v = tr.series("Damped", "linearVelocity")
    _, w = tr.series("Damped", "angularVelocity")
    n = steps(t, s.dt)[:, None]
    tol_v, tol_w = ROUNDING * np.linalg.norm(DAMP_V0), ROUNDING * np.linalg.norm(DAMP_W0)
    return [Measure("Damped.linearVelocity, each frame r x the last, (1-d)^steps <= r <= 1-d",
                    per_frame_error(t, v, DAMP_LINEAR, s.dt), tol_v, "m/s", DAMPED),
            Measure("Damped.angularVelocity, each frame r x the last, (1-d)^steps <= r <= 1-d",
                    per_frame_error(t, w, DAMP_ANGULAR, s.dt), tol_w, "rad/s", DAMPED),
            Measure("Damped.linearVelocity = v0 (1-d)^steps", max_norm(v - DAMP_V0 * (1.0 - DAMP_LINEAR) ** n),
                    tol_v, "m/s", PER_STEP),
            Measure("Damped.angularVelocity = w0 (1-d)^steps", max_norm(w - DAMP_W0 * (1.0 - DAMP_ANGULAR) ** n),
                    tol_w, "rad/s", PER_STEP)]


CASE = Case("damping", "damping.x3d",
            "RigidBody.autoDamp, linearDampingFactor 0.01, angularDampingFactor 0.02: each frame v = r v_last, "
            "(1-d)^steps <= r <= 1-d (x3drbp: v_n = v0 (1-d)^n)",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.autoDamp", "RigidBody.linearDampingFactor", "RigidBody.angularDampingFactor"),
            mutations=((" linearDampingFactor='0.01'", ""),))
