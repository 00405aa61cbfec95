"""torque_free: RigidBody.inertia off-diagonal: a tumbling body keeps its energy and angular momentum."""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, accuracy, spec


INERTIA = spec("37.4.10 RigidBody: The inertia field represents a 3x2 inertia tensor matrix.")


# torque_free.x3d
TF_INERTIA = np.array([[0.2, 0.03, 0.01], [0.03, 0.15, -0.02], [0.01, -0.02, 0.1]])
TF_ORIENTATION = (1.0, 1.0, 0.0, 0.7)
TF_OMEGA = np.array([1.0, 2.0, 0.5])


def torque_free_bounds(inertia: np.ndarray = TF_INERTIA, orientation=TF_ORIENTATION,
                       omega: np.ndarray = TF_OMEGA) -> dict[str, float]:
    """E0, L0 and the per-second, per-dt drift constants of a first-order rotational update.

    Euler's equations I w' = (I w) x w in body axes. A first-order step updates w with the
    gyroscopic torque tau = (I w) x w at one end of the step (explicit: the start; implicit:
    the end) and turns the body with the new w. Writing I = Ibar + D, Ibar = (Imax+Imin)/2,
    |D| = dI/2 with dI = Imax - Imin, tau = (D w) x w, so |tau| <= (dI/2) |w|^2. Then per step
      energy:   dE = dt^2/2 tau . I^-1 tau <= dt^2/2 (dI/2)^2 |w|^4 / Imin
      momentum: L_world changes by dt^2 [(I^-1 tau) x L + w x tau + 1/2 w x (w x L)]
                <= dt^2 |w|^3 (dI/2) (Imax/Imin + 3/2)
    (the exact flow keeps both; expand R exp(dt w') (L + dt L x w) to second order). Summed
    over t/dt steps: c*t*dt, first order. |w| is bounded through the energy: |w|^2 <= 2E/Imin."""
    q0 = R.from_axis_angle(np.asarray(orientation, dtype=np.float64))
    rot = R.matrix(q0)
    i_world = rot @ inertia @ rot.T
    e0 = 0.5 * omega @ i_world @ omega
    l0 = i_world @ omega
    ev = np.linalg.eigvalsh(inertia)
    i_min, i_max = float(ev[0]), float(ev[-1])
    half_spread = 0.5 * (i_max - i_min)
    w_max = math.sqrt(2.0 * e0 / i_min)
    return {"E0": float(e0), "L0": l0,
            "energy_rate": 0.5 * half_spread ** 2 * w_max ** 4 / i_min / e0,  # relative, x t dt
            "momentum_rate": w_max ** 3 * half_spread * (i_max / i_min + 1.5)}  # kg m^2/s, x t dt


# what the inertia becomes where a browser misreads it: its products ignored, or X3D's default (the identity)
MISREAD = (np.diag(np.diag(TF_INERTIA)), np.eye(3))
CONSERVED = accuracy("a torque-free body keeps E = 1/2 w.Iw and world L = R I R^T w; a first-order rotational update "
                     "drifts by at most c t dt (torque_free_bounds)")


def misread_drift(inertia: np.ndarray, duration: float, h: float = 1e-3) -> tuple[float, float]:
    """How far E and world L, computed with the scene's tensor, stray over `duration` when the body
    turns as one with `inertia` would (from the scene's orientation and angular velocity): RK4 on
    the orientation, w = R inertia^-1 R^T L' with L' conserved, at h = 1 ms (its error, h^4, is
    far below the drifts it measures)."""
    q = R.from_axis_angle(np.asarray(TF_ORIENTATION, dtype=np.float64))
    rot = R.matrix(q)
    momentum = rot @ inertia @ rot.T @ TF_OMEGA
    inverse = np.linalg.inv(inertia)

    def rate(q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        m = R.matrix(q / np.linalg.norm(q))
        w = m @ inverse @ m.T @ momentum
        return 0.5 * R.multiply(np.concatenate(([0.0], w)), q), w

    b = torque_free_bounds()
    worst_e = worst_l = 0.0
    for _ in range(int(round(duration / h))):
        k1, w = rate(q)
        m = R.matrix(q)
        i_world = m @ TF_INERTIA @ m.T
        worst_e = max(worst_e, abs(0.5 * w @ i_world @ w - b["E0"]) / b["E0"])
        worst_l = max(worst_l, float(np.linalg.norm(i_world @ w - b["L0"])))
        k2, _ = rate(q + 0.5 * h * k1)
        k3, _ = rate(q + 0.5 * h * k2)
        k4, _ = rate(q + h * k3)
        q = q + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        q = q / np.linalg.norm(q)
    return worst_e, worst_l


@functools.cache
def _drifts(duration: float) -> tuple[tuple[float, float], ...]:
    return tuple(misread_drift(m, duration) for m in MISREAD)


def _held(bound: float, drifts: list[float]) -> float:
    """honoured() over the misreadings this measure can see: the identity turns the body about w
    itself, which keeps E exactly, so it sets no tolerance for the energy."""
    seen = [d for d in drifts if d > bound]
    return honoured(bound, *seen) if seen else bound


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """E and world L against their start. Spec: the inertia field is the body's tensor
    (INERTIA), and the motion its tensor makes keeps both; the tolerance is half the drift the
    nearest misreading shows (closed_forms.honoured: the products ignored, or the identity),
    never less than the first-order bound, which grades the run (CONSERVED): no sentence
    of the clause says an integrator conserves them."""
    tr, s = traces[0], settings[0]
    t, rot = tr.series("Tumbler", "orientation")
    _, w = tr.series("Tumbler", "angularVelocity")
    b = torque_free_bounds()
    mats = R.matrix(R.from_axis_angle(rot))
    i_world = mats @ TF_INERTIA @ np.swapaxes(mats, 1, 2)
    lw = np.einsum("nij,nj->ni", i_world, w)
    energy = 0.5 * np.einsum("ni,ni->n", w, lw)
    T = float(physics_time(t, s.dt)[-1])
    scale_l = float(np.linalg.norm(b["L0"]))
    energy_bound = b["energy_rate"] * T * s.dt + ROUNDING
    momentum_bound = b["momentum_rate"] * T * s.dt + ROUNDING * (1 + scale_l)
    drifts = _drifts(T)
    e_error = float(np.max(np.abs(energy - b["E0"]))) / b["E0"]
    l_error = max_norm(lw - b["L0"])
    return [Measure("Tumbler.energy (relative)", e_error, _held(energy_bound, [d[0] for d in drifts]), "",
                    INERTIA, energy_bound),
            Measure("Tumbler.angularMomentum (world)", l_error, _held(momentum_bound, [d[1] for d in drifts]),
                    "kg m^2/s", INERTIA, momentum_bound),
            Measure("Tumbler.energy (relative), against the first-order bound", e_error, energy_bound, "", CONSERVED),
            Measure("Tumbler.angularMomentum (world), against the first-order bound", l_error, momentum_bound,
                    "kg m^2/s", CONSERVED)]


CASE = Case("torque_free", "torque_free.x3d",
            "RigidBody.inertia off-diagonal, angularVelocity, orientation: E = 1/2 w.Iw and world "
            "L = R I R^T w constant",
            (Settings(1.0, 1 / 240),), expect,
            convergence="Tumbler.energy (relative)", expected_order=1.0,
            exercises=("RigidBody.inertia.offDiagonal", "RigidBody.angularVelocity", "RigidBody.orientation"),
            mutations=(("inertia='0.2 0.03 0.01 0.03 0.15 -0.02 0.01 -0.02 0.1'",
                        "inertia='0.2 0 0 0 0.15 0 0 0 0.1'"),
                       # the body frame unturned: the world angular momentum I_world w is not L0
                       (" orientation='1 1 0 0.7'", "")))
