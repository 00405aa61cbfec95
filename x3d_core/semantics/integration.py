"""How an engine advances a body over one step, and what that alone does to free motion.

The spec names no integrator, but the order of a step's updates decides where free motion
under a constant load lands after t seconds at step h: semi-implicit Euler (v += h a, then
x += h v) lands h (v - v0) / 2 ahead of the exact path, explicit Euler in position (x += h v
with the old v, then v += h a) as far behind, and fourth-order Runge-Kutta on it (a
polynomial of degree two) exactly. Orientations under a constant torque alike, with w for v.
Two engines of different orders part by the difference, from the first step: `x3drbp
compare` says so, so that the lag is not read as a fault of either.
"""

from __future__ import annotations

SEMI_IMPLICIT = "semi-implicit Euler"
POSITION_FIRST = "explicit Euler in position"
RK4 = "fourth-order Runge-Kutta"

# where each scheme lands free motion under a constant load, in units of h |v - v0| ahead of the exact path
LEAD = {SEMI_IMPLICIT: 0.5, POSITION_FIRST: -0.5, RK4: 0.0}


def in_substeps(scheme: str, n: int) -> str:
    """A scheme run n times per step at a step of h / n (Bullet's preferAccuracy)."""
    return f"{scheme} in {n} substeps"


def lead(scheme: str) -> float | None:
    """LEAD of a scheme, substeps included (a lead of h / n per substep); None for one not known here."""
    name, _, substeps = scheme.partition(" in ")
    if substeps.endswith(" substeps") and substeps[:-len(" substeps")].isdigit() and name in LEAD:
        return LEAD[name] / int(substeps[:-len(" substeps")])
    return LEAD.get(scheme)
