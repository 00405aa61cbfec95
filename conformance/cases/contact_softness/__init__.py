"""contact_softness: CollisionCollection softnessErrorCorrection and softnessConstantForceMix act on the contacts.

37.4.4: "The softnessErrorCorrection determines how much of the collision error should be fixed in a set of
evaluations. ... A value of 0 specifies no error correction while a value of 1 specifies that all errors should be
corrected in a single step." Two balls start 1 cm into a floor with nothing else acting (zero gravity): with 0
(Stays) none of the depth is corrected, with 1 (Separates) all of it in one step. "The softnessConstantForceMix value
applies a constant force value to make the colliding surfaces appear to be somewhat soft": two balls rest on
floors whose collections give 0.1 (Soft) and 0.001 (Firm); only the order is the clause's (the larger force mix, the
softer the surface, the deeper the ball), not how deep (ODE's m g h CFM / ERP is contact_defaults' convention). The
world's constantForceMix (X3D's default 0.0001) makes every contact somewhat soft already: ignored, the collections'
values leave the two balls alike, which the order tells from the values applied."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import CFM_DEFAULT, ROUNDING, honoured, steps
from conformance.results import Measure, Settings, spec

# contact_softness.x3d: balls of radius 0.1 m, 1 kg, on floors whose top is y = 0
CSO_R, CSO_M, CSO_DEPTH = 0.1, 1.0, 0.01  # Stays and Separates start CSO_DEPTH into their floors
CSO_WORLD_ERP, CSO_DEFAULT_ERP = 0.2, 0.8  # their worlds' errorCorrection; the collection's default
CORRECTION = spec("37.4.4 CollisionCollection: The softnessErrorCorrection determines how much of the collision error "
                  "should be fixed in a set of evaluations.",
                  also=("37.4.4 CollisionCollection: A value of 0 specifies no error correction while a value of 1 "
                        "specifies that all errors should be corrected in a single step.",))
FORCE_MIX = spec("37.4.4 CollisionCollection: The softnessConstantForceMix value applies a constant force value to "
                 "make the colliding surfaces appear to be somewhat soft.")


def _depth(tr: TraceView, name: str) -> tuple[np.ndarray, np.ndarray]:
    """Frame times and the ball's depth in its floor, r - y."""
    t, p = tr.series(name, "position")
    return t, CSO_R - p[:, 1]


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Depths from the balls' heights, in shares of the starting depth d0 = 0.01 m (a frame after
    every step).

    Stays (softnessErrorCorrection 0): the largest share of d0 corrected by any frame. Nothing acts
    but the contact, which corrects nothing: 0 but for rounding (ROUNDING of the position, in d0).
    Separates (1): the largest share of d0 corrected in one step (the depth clipped at 0: out of the
    floor is all of it), against 1. An engine may act on the contact a step late (found after the
    step): the share is still one step's. ODE's contact row yields by CFM times its force (the
    world's constantForceMix, CONSTANT_FORCE not applied), so its one step corrects 1/(1 + gamma),
    gamma = CFM m / h = 0.024: short by gamma / (1 + gamma), the bound (a rigid row, Bullet's:
    none short). The tolerances (closed_forms.honoured) are half the nearest misreading's error: the
    field ignored (the world's errorCorrection 0.2, which pushes Stays out in five steps and corrects
    0.2 of Separates' depth in its step) or reset to the collection's default 0.8: 0.5 for Stays, 0.1
    for Separates. The bound
    takes 0.1 % more for an iterative solve's residual (as closed_forms.stop_rebound: ODE's
    quick-step leaves 2.5e-4 of the row's share).

    Soft and Firm (softnessConstantForceMix 0.1 and 0.001, CONSTANT_FORCE applied): the mean depth over
    the run's second half (a soft contact may still ring there: ODE's does, MuJoCo's spring barely
    damps), Firm's over Soft's. The clause orders them (the larger force mix, the softer surface),
    so the ratio is below 1; the misreading, both values ignored for the world's, gives both balls
    one contact and the ratio 1 (and a rigid contact no depth to divide by: no finite ratio). The
    tolerance is half the misreading's: Soft must sink at least twice as deep as Firm (ODE, with a
    depth linear in CFM, sinks it 100 times deeper)."""
    tr, s = traces[0], settings[0]
    h = s.dt
    out = []
    t, d = _depth(tr, "Stays")
    rounding = ROUNDING * (1.0 + CSO_R) / CSO_DEPTH
    lost = float(np.max(np.maximum(CSO_DEPTH - d, 0.0))) / CSO_DEPTH
    out.append(Measure("Stays share of the starting depth corrected (softnessErrorCorrection 0)", lost,
                       honoured(rounding, 1.0), "", CORRECTION, rounding))
    t, d = _depth(tr, "Separates")
    n = steps(t, h)
    one = np.flatnonzero(np.diff(n) == 1)  # frames a step apart
    inside = np.maximum(d, 0.0)
    share = float(np.max(inside[one] - inside[one + 1])) / CSO_DEPTH if one.size else -math.inf
    gamma = CFM_DEFAULT * CSO_M / h
    bound = gamma / (1.0 + gamma) * 1.001 + rounding
    out.append(Measure("Separates largest share of the starting depth corrected in one step - 1 "
                       "(softnessErrorCorrection 1)", 1.0 - share,
                       honoured(bound, 1.0 - CSO_DEFAULT_ERP, 1.0 - CSO_WORLD_ERP), "", CORRECTION, bound))
    sunk = {}
    for name in ("Soft", "Firm"):
        t, d = _depth(tr, name)
        sunk[name] = float(np.mean(d[t >= 0.5 * t[-1]]))
    ratio = max(sunk["Firm"], 0.0) / sunk["Soft"] if sunk["Soft"] > 0 else math.inf
    out.append(Measure("Firm mean depth / Soft mean depth (softnessConstantForceMix 0.001 and 0.1: below 1)", ratio,
                       honoured(0.0, 1.0), "", FORCE_MIX))
    return out


CASE = Case("contact_softness", "contact_softness.x3d",
            "CollisionCollection softnessErrorCorrection with ERROR_REDUCTION: 0 leaves a ball 1 cm into a floor "
            "there, 1 takes it out in one step; softnessConstantForceMix with CONSTANT_FORCE: a ball rests deeper "
            "on a floor at 0.1 than at 0.001",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("CollisionCollection.softnessErrorCorrection", "CollisionCollection.softnessConstantForceMix",
                       "CollisionCollection.appliedParameters.ERROR_REDUCTION",
                       "CollisionCollection.appliedParameters.CONSTANT_FORCE"),
            mutations=(
                (" softnessErrorCorrection='0'", ""),
                (" softnessErrorCorrection='1'", ""),
                ("DEF='StaysContacts' containerField='collider' appliedParameters='\"ERROR_REDUCTION\"'",
                 "DEF='StaysContacts' containerField='collider' appliedParameters='\"BOUNCE\"'"),
                (" softnessConstantForceMix='0.1'", ""),
                ("DEF='SoftContacts' containerField='collider' appliedParameters='\"CONSTANT_FORCE\"'",
                 "DEF='SoftContacts' containerField='collider' appliedParameters='\"BOUNCE\"'"),
            ))
