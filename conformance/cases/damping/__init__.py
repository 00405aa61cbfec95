"""damping: RigidBody.autoDamp: damping takes a fraction of each velocity away, every frame or every step.

The spec (37.4.10 RigidBody) says the damping factor "is used to take a multiple of the value
calculated in the last frame and apply it in opposition to the current motion for this frame".
It says neither how often within a frame, nor whether the multiple is taken off the velocity or
applied as a force, nor whether the factor is per evaluation or per second. Real implementations
take each of these readings, and the spec measures accept every one of them. From one frame to
the next (k steps of dt, h = k dt of physics time) each velocity keeps its direction and is
multiplied by a ratio r:
- the factor taken off the velocity, (1-d)^k <= r <= 1-d: once at each step (ODE's
  dBodySetLinearDamping, x3drbp, whose motion must not depend on the frame rate: frame_rate
  checks that with a damped body) or once a frame (the clause's words where a frame holds
  several steps); a browser whose step is its frame does both at once;
- the factor as a force -d v (a torque -d w), once a frame or at each step,
  1 - d h/m <= r <= (1 - d dt/m)^k (Xj3D's dBodyAddForce, H3D's field comments): mass-dependent;
- the factor as a rate per second, r = (1-d)^h (Bullet's btRigidBody damping, X_ITE).
x3drbp's per-step reading is the convention measure. At the case's settings (d = 0.01 linear,
0.02 angular, m = 1 kg, I = 0.1 kg m^2, 60 frames/s, step 1/240 s) v(1 s)/v0 is 0.99^240 = 0.0896
once a step, 0.99^60 = 0.547 once a frame, 0.990 as a force or per second. A browser that ignores
linearDampingFactor and uses the default 0.001 under any of these readings keeps a ratio outside
every band (0.996 to 0.999 a frame multiplied, 0.99998 as a force or per second, against 0.9998
for the scene's factor): a spec failure, by 1.5e-4 of the velocity a frame at least, against
rounding of 1e-9.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, honoured, max_norm, physics_time, single, steps
from conformance.results import Measure, Settings, also, convention, spec


# damping.x3d
DAMP_V0, DAMP_W0 = np.array([2.0, 0.0, -1.0]), np.array([0.0, 0.0, 3.0])
DAMP_LINEAR, DAMP_ANGULAR = 0.01, 0.02
DAMPED = spec("37.4.10 RigidBody: The damping factor fields allow the user to instruct the implementation to "
              "automatically damp the motion of the body over time. The value of the field is used to take a "
              "multiple of the value calculated in the last frame and apply it in opposition to the current motion "
              "for this frame.")
# the per-frame measures: each frame's velocity r x the last, r of a band that does not depend on the speed, so a
# damping not proportional to the velocity (a constant or a quadratic drag) leaves the bands as the body slows,
# and autoDamp TRUE applying the linear damping alone (or none) leaves a ratio of 1, off every band by 3.7e-4 m/s
# (1e-3 rad/s) at least, against rounding; that autoDamp FALSE applies none (sentence 34): UNDAMPED
DAMPED_WHEN_TRUE = also(DAMPED, "37.4.10 RigidBody: Damping is proportional to the current velocity and/or rotation "
                        "of the object.",
                        "37.4.10 RigidBody: When the value is TRUE, rotational and translational damping is "
                        "calculated and applied.")
# Undamped (autoDamp FALSE, the same factors): its velocities kept, to rounding
UNDAMPED = spec("37.4.10 RigidBody: The application of damping is controlled through the use of the autoDamp field. "
                "When the value is FALSE, no damping is applied.")
PER_STEP = convention("each velocity is multiplied by (1 - factor) at every physics step, v_n = v0 (1-d)^n after "
                      "n steps (ODE's body damping, x3drbp); alternatives: once a frame, v = v0 (1-d)^frames (the "
                      "spec's words where a frame holds several steps); a force -d v once a frame (Xj3D, H3D); "
                      "(1-d) per second of physics time (X_ITE's Bullet)")
DAMP_MASS, DAMP_MOMENT = 1.0, 0.1  # damping.x3d: the body's mass and (isotropic) moment of inertia


def per_frame_error(t: np.ndarray, v: np.ndarray, d: float, dt: float, inertia: float) -> float:
    """How far each frame's velocity is from the nearest r x the previous frame's, r in the band
    of any one reading of the factor (the module's docstring): taken off the velocity once a step
    to once a frame, a force (torque) -d v over the frame's h = k dt against `inertia` (the mass
    or the moment), or (1-d) per second. A velocity off the bands by e is e from the nearest."""
    k = np.diff(steps(t, dt))
    h = k * dt
    prev, cur = v[:-1], v[1:]
    den = np.einsum("ij,ij->i", prev, prev)
    r = np.einsum("ij,ij->i", cur, prev) / np.where(den > 0, den, 1.0)
    bands = (((1.0 - d) ** k, (1.0 - d) ** np.minimum(k, 1)),
             (1.0 - d * h / inertia, (1.0 - d * dt / inertia) ** k),
             ((1.0 - d) ** h, (1.0 - d) ** h))
    off = [np.linalg.norm(cur - np.clip(r, lo, hi)[:, None] * prev, axis=1) for lo, hi in bands]
    return max_norm(np.min(off, axis=0))


def least_loss(d: float, inertia: float, t: float, dt: float) -> float:
    """The least share of a velocity that damping at factor d takes off by physics time t under any
    reading of the factor (the module's docstring), at 60 frames/s: the least of (1-d) once a frame,
    a force -d v once a frame or at each step, and (1-d) per second."""
    frames, n = round(t * 60), round(t / dt)
    kept = max((1.0 - d) ** frames, (1.0 - d / 60 / inertia) ** frames, (1.0 - d * dt / inertia) ** n, (1.0 - d) ** t)
    return 1.0 - kept


def _undamped(tr: TraceView, s: Settings) -> list[Measure]:
    """Undamped (autoDamp FALSE, Damped's factors, velocities and inertia): nothing changes its
    velocities, so max |v - v0| and |w - w0| over the run are rounding (ROUNDING of the size, the
    bound). The misreading, the factors applied whatever autoDamp says, takes off at least
    least_loss of each by the last frame (1.0e-2 of |v0|, 2.0e-2 of |w0| at 1 s, the per-second and
    force readings): the tolerance is half that (closed_forms.honoured)."""
    t, v = tr.series("Undamped", "linearVelocity")
    _, w = tr.series("Undamped", "angularVelocity")
    end = float(physics_time(t, s.dt)[-1])
    out = []
    for field, got, start, d, inertia, unit in (("linearVelocity", v, DAMP_V0, DAMP_LINEAR, DAMP_MASS, "m/s"),
                                                ("angularVelocity", w, DAMP_W0, DAMP_ANGULAR, DAMP_MOMENT, "rad/s")):
        size = float(np.linalg.norm(start))
        bound = ROUNDING * size
        out.append(Measure(f"Undamped |{field} - its start| (autoDamp FALSE: no damping)", max_norm(got - start),
                           honoured(bound, least_loss(d, inertia, end, s.dt) * size), unit, UNDAMPED, bound))
    return out


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """No gravity, no force, isotropic inertia: nothing but the damping changes the velocities,
    under any integrator. Spec: per_frame_error, within ROUNDING (a ratio and a product per frame,
    each reading's r exact up to rounding: a product of k factors or one).
    Convention (x3drbp's, ODE's): after n = floor(t/dt) steps v_n = v0 (1-d)^n, exact up to
    ROUNDING (n multiplications, each within an ulp): the bound; the tolerance allows single
    precision (closed_forms.single). There is no continuous limit to converge
    to: at a fixed d the decay per second depends on dt (or on the frame rate) by definition."""
    tr, s = traces[0], settings[0]
    t, v = tr.series("Damped", "linearVelocity")
    _, w = tr.series("Damped", "angularVelocity")
    n = steps(t, s.dt)[:, None]
    bound_v, bound_w = ROUNDING * np.linalg.norm(DAMP_V0), ROUNDING * np.linalg.norm(DAMP_W0)
    ops = float(n[-1, 0]) + 1
    tol_v = single(bound_v, float(np.linalg.norm(DAMP_V0)), ops)
    tol_w = single(bound_w, float(np.linalg.norm(DAMP_W0)), ops)
    return [Measure("Damped.linearVelocity, each frame r x the last, r of one reading (per step or frame, force, "
                    "per second)", per_frame_error(t, v, DAMP_LINEAR, s.dt, DAMP_MASS), tol_v, "m/s", DAMPED_WHEN_TRUE,
                    bound_v),
            Measure("Damped.angularVelocity, each frame r x the last, r of one reading (per step or frame, torque, "
                    "per second)", per_frame_error(t, w, DAMP_ANGULAR, s.dt, DAMP_MOMENT), tol_w, "rad/s",
                    DAMPED_WHEN_TRUE, bound_w),
            Measure("Damped.linearVelocity = v0 (1-d)^steps", max_norm(v - DAMP_V0 * (1.0 - DAMP_LINEAR) ** n),
                    tol_v, "m/s", PER_STEP, bound_v),
            Measure("Damped.angularVelocity = w0 (1-d)^steps", max_norm(w - DAMP_W0 * (1.0 - DAMP_ANGULAR) ** n),
                    tol_w, "rad/s", PER_STEP, bound_w)] + _undamped(tr, s)


CASE = Case("damping", "damping.x3d",
            "RigidBody.autoDamp, linearDampingFactor 0.01, angularDampingFactor 0.02: each frame v = r v_last, "
            "r = (1-d) once a step or a frame, 1 - d h/m, or (1-d)^h (x3drbp: v_n = v0 (1-d)^n); the same factors with "
            "autoDamp FALSE: velocities kept",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.autoDamp", "RigidBody.linearDampingFactor", "RigidBody.angularDampingFactor"),
            mutations=(("autoDamp='true' linearDampingFactor='0.01'", "autoDamp='true'"),
                       (" autoDamp='true'", ""),  # no damping: a ratio of 1, no reading's
                       ("linearDampingFactor='0.01' angularDampingFactor='0.02'",
                        "linearDampingFactor='0.01'"),  # the default 0.001
                       ("autoDamp='false'", "autoDamp='true'")))  # Undamped damped: it slows
