"""double_pendulum_energy: Two SingleAxisHingeJoints: a double pendulum's energy, and its first step."""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, ROUNDING_ANGLE, G, honoured, max_norm, steps
from conformance.results import Measure, Settings, accuracy, spec


# double_pendulum_energy.x3d: absolute angles phi from the downward vertical, about +z
DP_M1, DP_D1, DP_L1, DP_I1 = 2.0, 0.5, 1.0, 0.16  # mass, shoulder-centre, shoulder-elbow, I_zz
DP_M2, DP_D2, DP_I2 = 1.5, 0.4, 0.08  # mass, elbow-centre, I_zz
DP_PHI = (math.radians(30.0), math.radians(45.0))
DP_INERTIA = {"Upper": np.diag([0.1, 0.1, DP_I1]), "Lower": np.diag([0.05, 0.05, DP_I2])}
DP_MASS = {"Upper": DP_M1, "Lower": DP_M2}
HINGES = spec("37.4.12 SingleAxisHingeJoint: This node represents a joint with a single axis about which to "
              "rotate.")
# the clause says what the hinges, masses and inertias mean, not that an integrator keeps energy
ENERGY_BOUND = accuracy("a conservative chain keeps E = E0; over n steps a first-order scheme of the Euler family "
                        "drifts by at most (E0 - E_min)((1 + (w2 h)^2)^n - 1), w2 the chain's faster mode at rest")
FIRST_STEP = accuracy("from rest, every one-step scheme of the Euler family gives w(h) = h q''(0) with rigid joints; a "
                      "joint softened by the default constantForceMix, or an iterative solve, starts otherwise and "
                      "converges as h shrinks")


@dataclass(frozen=True)
class Chain:
    """The chain's inertial parameters: the scene's, or a misreading of them."""
    m1: float = DP_M1
    i1: float = DP_I1
    m2: float = DP_M2
    i2: float = DP_I2


# what the links' fields become where a browser ignores them: X3D's defaults, mass 1 kg and the
# identity inertia (I_zz 1 kg m^2)
MISREAD = (Chain(m1=1.0), Chain(m2=1.0), Chain(i1=1.0), Chain(i2=1.0))
WINDOW = 0.5  # s: the motion compared with the closed form's integration, before it turns chaotic


def _dp_matrices(phi1: float, phi2: float, c: Chain = Chain()) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mass matrix M(q), potential Hessian K(q) and generalized gravity force f(q) = -dV/dq of
    the chain in the absolute angles q = (phi1, phi2):
    T = 1/2 [A phi1'^2 + 2 B cos(phi1 - phi2) phi1' phi2' + C phi2'^2],
    V = -P1 g cos phi1 - P2 g cos phi2."""
    a = c.i1 + c.m1 * DP_D1 ** 2 + c.m2 * DP_L1 ** 2
    b = c.m2 * DP_L1 * DP_D2 * math.cos(phi1 - phi2)
    cc = c.i2 + c.m2 * DP_D2 ** 2
    p1, p2 = (c.m1 * DP_D1 + c.m2 * DP_L1) * G, c.m2 * DP_D2 * G
    return (np.array([[a, b], [b, cc]]), np.diag([p1 * math.cos(phi1), p2 * math.cos(phi2)]),
            np.array([-p1 * math.sin(phi1), -p2 * math.sin(phi2)]))


def _accel(c: Chain, p1: float, p2: float, w1: float, w2: float) -> tuple[float, float]:
    """q'' from Lagrange's equations, M q'' = f - (B sin(p1 - p2) w2^2, -B sin(p1 - p2) w1^2),
    B = m2 L1 D2 (plain floats: this runs thousands of times per expectation)."""
    a = c.i1 + c.m1 * DP_D1 ** 2 + c.m2 * DP_L1 ** 2
    bb = c.m2 * DP_L1 * DP_D2
    cc = c.i2 + c.m2 * DP_D2 ** 2
    b, s = bb * math.cos(p1 - p2), bb * math.sin(p1 - p2)
    f1 = -(c.m1 * DP_D1 + c.m2 * DP_L1) * G * math.sin(p1) - s * w2 * w2
    f2 = -c.m2 * DP_D2 * G * math.sin(p2) + s * w1 * w1
    det = a * cc - b * b
    return (cc * f1 - b * f2) / det, (a * f2 - b * f1) / det


@functools.cache
def _motion(c: Chain, h: float, n: int, exact: bool) -> np.ndarray:
    """(phi1, phi2) after each of n steps of h from rest at DP_PHI: RK4 in `exact` steps of h/20
    each (the closed form's integration), else semi-implicit Euler at h (the scheme the bound
    is argued from). Cached: every backend's run of the case asks the same (read only)."""
    p1, p2 = DP_PHI
    w1 = w2 = 0.0
    out = np.empty((n, 2))
    sub = 20 if exact else 1
    k = h / sub
    for i in range(n):
        for _ in range(sub):
            if exact:
                def f(y: tuple[float, ...]) -> tuple[float, ...]:
                    return (y[2], y[3], *_accel(c, *y))
                y0 = (p1, p2, w1, w2)
                k1 = f(y0)
                k2 = f(tuple(y + 0.5 * k * d for y, d in zip(y0, k1)))
                k3 = f(tuple(y + 0.5 * k * d for y, d in zip(y0, k2)))
                k4 = f(tuple(y + k * d for y, d in zip(y0, k3)))
                p1, p2, w1, w2 = (y + k / 6 * (d1 + 2 * d2 + 2 * d3 + d4)
                                  for y, d1, d2, d3, d4 in zip(y0, k1, k2, k3, k4))
            else:
                a1, a2 = _accel(c, p1, p2, w1, w2)
                w1, w2 = w1 + k * a1, w2 + k * a2
                p1, p2 = p1 + k * w1, p2 + k * w2
        out[i] = p1, p2
    return out


def _angles(tr: TraceView) -> tuple[np.ndarray, np.ndarray]:
    """Frame times and (phi1, phi2) from the links' centres: Upper's about the shoulder (the
    origin), Lower's about the elbow at L1 along the upper link."""
    t, up = tr.series("Upper", "position")
    _, low = tr.series("Lower", "position")
    phi1 = np.arctan2(up[:, 0], -up[:, 1])
    elbow = DP_L1 * np.column_stack([np.sin(phi1), -np.cos(phi1)])
    phi2 = np.arctan2(low[:, 0] - elbow[:, 0], -(low[:, 1] - elbow[:, 1]))
    return t, np.column_stack([phi1, phi2])


def double_pendulum() -> dict[str, float | np.ndarray]:
    """E0 and E_min (both links hanging down), the larger normal-mode frequency at rest, and
    the initial angular accelerations (at rest the Coriolis terms vanish: M q'' = f)."""
    p1, p2 = DP_PHI
    y1 = -DP_D1 * math.cos(p1)
    y2 = -DP_L1 * math.cos(p1) - DP_D2 * math.cos(p2)
    e0 = G * (DP_M1 * y1 + DP_M2 * y2)
    e_min = -G * (DP_M1 * DP_D1 + DP_M2 * (DP_L1 + DP_D2))
    m0, k0, _ = _dp_matrices(0.0, 0.0)
    mq, kq, f = _dp_matrices(p1, p2)
    omega_max = math.sqrt(float(np.max(np.linalg.eigvals(np.linalg.solve(m0, k0)).real)))
    return {"E0": e0, "Emin": e_min, "omega_max": omega_max, "accel0": np.linalg.solve(mq, f),
            "stiffness0": float(np.linalg.norm(np.linalg.solve(mq, kq), 2))}


def _dp_energy(tr: TraceView) -> tuple[np.ndarray, np.ndarray]:
    """Times and E = sum m g y + 1/2 m |v|^2 + 1/2 w.(R I R^T) w, with the scene's masses and inertias."""
    total, t = 0.0, None
    for name, m in DP_MASS.items():
        t, p = tr.series(name, "position")
        _, v = tr.series(name, "linearVelocity")
        _, w = tr.series(name, "angularVelocity")
        _, rot = tr.series(name, "orientation")
        mats = R.matrix(R.from_axis_angle(rot))
        i_world = mats @ DP_INERTIA[name] @ np.swapaxes(mats, 1, 2)
        total = total + m * (G * p[:, 1] + 0.5 * np.einsum("ni,ni->n", v, v)) + \
            0.5 * np.einsum("ni,nij,nj->n", w, i_world, w)
    return t, total


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Energy: max |E(t) - E0| over 2 s.

    Tolerance for a first-order integrator, argued on the linearised chain (two normal modes,
    frequencies w1 < w2): explicit Euler, the worst of the Euler family, multiplies each mode's
    energy by |eigenvalue|^2 = 1 + (w h)^2 per step; semi-implicit Euler (symplectic) keeps it
    within an O(w h) oscillation with no drift; implicit Euler loses it. So over n steps
    |E - E0| <= (E0 - E_min) ((1 + (w2 h)^2)^n - 1) ~ (E0 - E_min) w2^2 h t: first order.
    Away from rest the local frequencies are lower (the potential's Hessian falls as cos phi, and
    the largest eigenvalue of M(q)^-1 K(q) over |phi1| <= 90, |phi2| <= 120 degrees is at rest),
    so w2 at rest bounds them along the motion. The step is 1 ms: at 1/240 s this bound is 57%
    of the oscillation's energy, too loose to see an inertia ignored; at 1 ms it is 11%.

    The energy is blind to a motion that never starts (a hinge axis ignored, along gravity), so
    the first step is checked too: from rest every one-step scheme of the Euler family gives
    w(h) = h q''(0), q''(0) = M(q0)^-1 f(q0) (Coriolis terms vanish at rest), exact up to
    ROUNDING; a scheme evaluating the acceleration elsewhere in the step differs by at most
    h |M^-1 K| h^2 |q''(0)| (the configuration moves by h^2 |q''| in a step). That exactness
    holds for rigid joints only: X3D's joints carry the default constantForceMix 1e-4, which
    lets the bodies start part free (ODE at X3D's defaults: 9% and 45% off), so the first step
    is graded accuracy, not the spec. The energy bound holds any consistent first-order scheme,
    but no sentence of the clause says a chain keeps its energy: it is graded too, and the
    motion against the equations of motion is the spec's measure."""
    tr, s = traces[0], settings[0]
    d = double_pendulum()
    t, energy = _dp_energy(tr)
    n = steps(t, s.dt)
    drift = (d["E0"] - d["Emin"]) * ((1.0 + (d["omega_max"] * s.dt) ** 2) ** float(n[-1]) - 1.0)
    out = [_motion_measure(tr, s.dt)]
    energy_tol = drift + ROUNDING * (1 + abs(d["E0"]))
    out.append(Measure("double pendulum |E - E0|", float(np.max(np.abs(energy - d["E0"]))), energy_tol, "J",
                       ENERGY_BOUND))
    first = np.flatnonzero(n == 1)
    for k, name in enumerate(DP_MASS):
        a0 = float(d["accel0"][k])
        tol = ROUNDING * (1 + abs(a0) * s.dt) + s.dt ** 3 * d["stiffness0"] * abs(a0)
        if not first.size:
            out.append(Measure(f"{name}.angularVelocity after one step (no frame there)", math.inf, tol, "rad/s",
                               FIRST_STEP))
            continue
        _, w = tr.series(name, "angularVelocity")
        out.append(Measure(f"{name}.angularVelocity after one step - h q''(0)",
                           max_norm(w[first[:1]] - np.array([0.0, 0.0, a0 * s.dt])), tol, "rad/s", FIRST_STEP))
    return out


def _motion_measure(tr: TraceView, h: float) -> Measure:
    """The links' angles over the first WINDOW s against the equations of motion integrated
    finely (RK4 at h/20: its error is far below the rest). Accuracy bound: twice semi-implicit
    Euler's own departure from it at the scene's step (first order; explicit Euler errs as much
    the other way), plus angle rounding. Spec tolerance (closed_forms.honoured): half the
    departure of the nearest misreading of the links' fields (a mass or I_zz at X3D's default):
    the hinges, masses and inertias the clause gives make this motion, and a soft joint or an
    iterative solve that starts otherwise (X3D's default constantForceMix) is graded, not accused."""
    t, phi = _angles(tr)
    n = int(steps(np.array([min(float(t[-1]), WINDOW)]), h)[0])
    k = steps(t, h).astype(int)
    mine = (k >= 1) & (k <= n)
    if n < 1 or not mine.any():
        return Measure("Upper, Lower angles over the first 0.5 s - the equations of motion", math.inf, 0.0, "rad",
                       HINGES)
    exact = _motion(Chain(), h, n, True)
    bound = 2 * float(np.max(np.abs(_motion(Chain(), h, n, False) - exact))) + ROUNDING_ANGLE
    misread = [float(np.max(np.abs(_motion(c, h, n, True) - exact))) for c in MISREAD]
    error = float(np.max(np.abs(phi[mine] - exact[k[mine] - 1])))
    return Measure("Upper, Lower angles over the first 0.5 s - the equations of motion", error,
                   honoured(bound, *misread), "rad", HINGES, bound)


CASE = Case("double_pendulum_energy", "double_pendulum_energy.x3d",
            "two SingleAxisHingeJoints, masses 2 / 1.5 kg, I_zz 0.16 / 0.08, released at 30 / 45 degrees: "
            f"E = {double_pendulum()['E0']:.4f} J constant within the first-order bound; first step w = h q''(0)",
            (Settings(2.0, 1 / 1000, None),), expect,
            convergence="double pendulum |E - E0|", expected_order=1.0,
            exercises=("SingleAxisHingeJoint.axis", "SingleAxisHingeJoint.anchorPoint", "RigidBody.mass",
                       "RigidBody.inertia"),
            mutations=(
                (" inertia='0.05 0 0 0 0.05 0 0 0 0.08'", ""),
                ("DEF='Lower' mass='1.5'", "DEF='Lower'"),
                (" anchorPoint='0.5 -0.8660254037844386 0'", ""),
            ))
