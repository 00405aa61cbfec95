"""anisotropic_friction: frictionCoefficients with FRICTION_COEFFICIENT-2, a friction per friction direction.

The spec applies frictionCoefficients (table 37.2) but leaves which tangent is friction direction 1
to the system: that the two boxes slow at mu1 g and mu2 g, in one assignment or the other, is the
spec's (FRICTION); that the box pushed along -x gets mu1 is ODE's first friction direction
(FRICTION_DIRECTIONS, a convention)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import FRICTION, FRICTION_DIRECTIONS, friction_fit
from conformance.results import Measure, Settings


# anisotropic_friction.x3d: boxes pushed at 3 m/s along ODE's two friction directions of an
# upward normal (-x, +z)
AF_MU, AF_V0 = (0.2, 0.6), 3.0
AF_BOXES = {"Along1": (0, np.array([-1.0, 0.0, 0.0])), "Along2": (1, np.array([0.0, 0.0, 1.0]))}


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each box against friction_fit() twice: with ODE's assignment (Along1 mu1, Along2 mu2: the
    convention) and with whichever of the two assignments fits better (the spec)."""
    tr, s = traces[0], settings[0]
    fits = {swap: {name: friction_fit(tr, s, name, AF_MU[k ^ swap], AF_V0, 0.0, d) for name, (k, d) in AF_BOXES.items()}
            for swap in (0, 1)}
    best = min((0, 1), key=lambda swap: max(e / tol for e, tol in fits[swap].values()))
    out = [Measure(f"{name}.linearVelocity slows at mu1 g or mu2 g, the two boxes one each (the better "
                   "assignment)", *fits[best][name], "m/s", FRICTION)
           for name, (k, d) in AF_BOXES.items()]
    out += [Measure(f"{name}.linearVelocity (mu{k + 1} = {AF_MU[k]:g} along ODE's friction direction {k + 1}, "
                    f"{d.tolist()})", *fits[0][name], "m/s", FRICTION_DIRECTIONS)
            for name, (k, d) in AF_BOXES.items()]
    return out


CASE = Case("anisotropic_friction", "anisotropic_friction.x3d",
            "frictionCoefficients 0.2 0.6 with FRICTION_COEFFICIENT-2: one box slows at mu1 g, the other at mu2 g; "
            "ODE's directions give mu1 to the one pushed along -x, mu2 to the one along +z",
            (Settings(2.0, 1 / 240),), expect,
            exercises=("CollisionCollection.frictionCoefficients",
                       "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2", "RigidBody.linearVelocity"),
            mutations=(
                ("appliedParameters='\"BOUNCE\" \"FRICTION_COEFFICIENT-2\"'", "appliedParameters='\"BOUNCE\"'"),
                (" frictionCoefficients='0.2 0.6'", ""),
            ))
