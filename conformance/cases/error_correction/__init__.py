"""error_correction: RigidBodyCollection errorCorrection 0 corrects no intersection, 1 corrects it in a single step."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import CFM_DEFAULT, CORRECTION, ROUNDING, honoured, max_norm
from conformance.results import Measure, Settings, convention

# error_correction.x3d: ball -> (errorCorrection, start); each ball (1 kg, radius 0.1 m) starts EC_DEPTH into its floor
EC_BALLS = {"ZeroBall": (0.0, np.array([-2.0, 0.095, 0.0])), "HalfBall": (0.5, np.array([0.0, 0.095, 0.0])),
            "OneBall": (1.0, np.array([2.0, 0.095, 0.0]))}
EC_DEPTH, EC_RADIUS, EC_M = 0.005, 0.1, 1.0
X3D_DEFAULT, ENGINE_DEFAULT = 0.8, 0.2  # errorCorrection's default; ODE's own world ERP
PER_STEP = convention("the first step that corrects an intersection removes the fraction errorCorrection of its depth "
                      "(ODE's ERP on a contact row, pybullet's erp, pymunk's collision bias): the correction linear "
                      "in the field between the clause's 0 (none) and 1 (all in a single step); alternatives: a "
                      "stiffness or time constant that corrects a share not linear in it (MuJoCo's solref, capped "
                      "at 0.25 a step), an engine's own depenetration whatever the field (PhysX's, DART's, Drake's "
                      "compliant contact)")


def _depths(tr: TraceView, name: str) -> np.ndarray:
    """The ball's depth in its floor at every frame (one a step): radius - height."""
    return EC_RADIUS - tr.series(name, "position")[1][:, 1]


def first_fraction(depth: np.ndarray, still: float) -> float:
    """The fraction of the depth the first step that corrects removes: (d_k - d_k+1) / d_k at the
    first k where the depth falls by more than `still` (a contact that acts a step late corrects in
    the second); 0 where none does."""
    fell = np.flatnonzero(depth[:-1] - depth[1:] > still)
    if not fell.size:
        return 0.0
    k = int(fell[0])
    return float((depth[k] - depth[k + 1]) / depth[k])


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """A frame after every step (the run's frame rate is None). No gravity and nothing else acts:
    only the contact's error correction moves a ball.

    ZeroBall (CORRECTION, 'no correction at all'): max |p - p0| over the run, 0 to ROUNDING (the
    bound: ODE's row targets no velocity, and no load presses it); the misreading, an engine's own
    correction in the field's place (ODE's own default ERP 0.2, the nearest; X3D's
    default 0.8), moves it 1 mm in the first step, so the tolerance is 0.5 mm (closed_forms.honoured).

    OneBall (CORRECTION, 'all errors corrected in a single step') and HalfBall (PER_STEP, ODE's
    reading between the two): the fraction of the depth the first correcting step removes
    (first_fraction), against errorCorrection. ODE's row is softened by constantForceMix: a row
    pushing from rest reaches only 1 / (1 + s) of its target velocity, s = m CFM / h (0.024 at
    1 kg, the default 1e-4 and h = 1/240): ERP s / (1 + s) short, to 0.1 % (what an iterative solve
    leaves of the rows coupled with it: ODE's quick step at the scene's 10 iterations leaves 1.4e-4
    of that more), the bound, with ROUNDING on the depths. The tolerance is half the nearest
    misreading's error: the field ignored, X3D's default 0.8 in its place (0.2 off at 1, 0.3 at 0.5)
    or the engine's own 0.2 (0.8 off at 1, 0.3 at 0.5), or the fraction taken per frame of four
    steps (1 - 0.5^(1/4) a step at 0.5: 0.34 off): 0.1 at 1, 0.15 at 0.5."""
    tr, s = traces[0], settings[0]
    soft = EC_M * CFM_DEFAULT / s.dt
    out = []
    for name, (erp, start) in EC_BALLS.items():
        rounding = ROUNDING * (1 + float(np.linalg.norm(start)))
        if erp == 0.0:
            _, p = tr.series(name, "position")
            out.append(Measure(f"{name} moved (errorCorrection 0: no correction)", max_norm(p - start),
                               honoured(rounding, ENGINE_DEFAULT * EC_DEPTH), "m", CORRECTION, rounding))
            continue
        got = first_fraction(_depths(tr, name), rounding)
        bound = erp * soft / (1 + soft) * 1.001 + 2 * rounding / EC_DEPTH
        misread = [X3D_DEFAULT - erp, ENGINE_DEFAULT - erp, 1 - (1 - erp) ** 0.25 - erp]
        out.append(Measure(f"{name} share of the depth its first correcting step removes - errorCorrection {erp:g}",
                           abs(got - erp), honoured(bound, *(m for m in misread if m)), "",
                           CORRECTION if erp == 1.0 else PER_STEP, bound))
    return out


CASE = Case("error_correction", "error_correction.x3d",
            "RigidBodyCollection errorCorrection 0, 0.5 and 1, no gravity: a ball started 5 mm into its floor stays "
            "there at 0; its first correcting step removes the whole 5 mm at 1 and half at 0.5 (ODE's per-step "
            "fraction, a convention)",
            (Settings(0.25, 1 / 240, None),), expect,
            exercises=("RigidBodyCollection.errorCorrection",),
            mutations=(
                (" errorCorrection='0'", ""),  # the default 0.8: ZeroBall is pushed out
                (" errorCorrection='1'", ""),  # 0.8 of the depth in the first step
                Mutation(" errorCorrection='0.5'", "", spec=False),
            ))
