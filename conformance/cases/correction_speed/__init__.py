"""correction_speed: RigidBodyCollection maxCorrectionSpeed: a deep contact is undone no faster than the cap."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import CFM_DEFAULT, CORRECTION, ROUNDING, G, honoured
from conformance.results import Measure, Settings, convention

# correction_speed.x3d: the ball starts DEPTH into the floor; the cap
CS_CAP, CS_DEPTH, CS_M, CS_ERP, CS_RADIUS = 0.2, 0.04, 1.0, 0.2, 0.1  # CS_ERP: errorCorrection; the floor's top y = 0
CAPPED = convention("ODE's dWorldSetContactMaxCorrectingVel: a contact's error correction (ERP depth / h) moves the "
                    "bodies apart no faster than maxCorrectionSpeed; no sentence of the clause on the field was "
                    "readable and the UOM's description is only its range (\"or -1, maxCorrectionSpeed.\")")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The ball's fastest rise against the cap: ODE's contact row targets min(ERP depth / h, cap)
    and is solved with the step's gravity, so the ball rises at the cap while it is in the floor,
    up to its row's softness (the row's rate off target by CFM m g: the whole weight on it) and,
    for an engine whose contact acts a step late, one step of gravity g h either way: the bound.
    The tolerance is half the error of the correction uncapped (ERP depth / h, errorCorrection
    0.2: an engine that caps the correction's ERP itself, as MuJoCo does at 0.25, still differs).

    Spec (CORRECTION, errorCorrection 0.2 is some correction): the intersection is resolved by the
    end, the ball resting on the floor's top; a ball let through the floor (X_ITE's, whose floor
    is a collidable on no body) or left in it fails, whatever the cap."""
    tr, s = traces[0], settings[0]
    _, v = tr.series("Ball", "linearVelocity")
    rise = float(np.max(v[:, 1]))
    bound = G * s.dt + CFM_DEFAULT * CS_M * G + ROUNDING
    uncapped = CS_ERP * CS_DEPTH / s.dt
    _, p = tr.series("Ball", "position")
    # capped, the depth is gone after DEPTH / cap = 0.2 s of the run's 0.5: the ball ends resting on the floor,
    # within a step of unresisted fall (g h^2) and the rows' softness (CFM m g h / ERP); not corrected at all,
    # it stays DEPTH deep (the tolerance half that); let through, it falls
    rest = G * s.dt * s.dt + CFM_DEFAULT * CS_M * G * s.dt / CS_ERP + ROUNDING
    end = abs(float(p[-1, 1]) - CS_RADIUS)
    return [Measure(f"Ball's height at the end - resting on the floor ({CS_RADIUS:g}): the intersection resolved",
                    end, honoured(rest, CS_DEPTH), "m", CORRECTION, rest),
            Measure(f"Ball's fastest rise - maxCorrectionSpeed {CS_CAP:g}", abs(rise - CS_CAP),
                    honoured(bound, uncapped - CS_CAP), "m/s", CAPPED, bound)]


CASE = Case("correction_speed", "correction_speed.x3d",
            "RigidBodyCollection maxCorrectionSpeed 0.2: a ball started 4 cm into the floor rises out at 0.2 m/s, "
            "not the error correction's 1.92 (errorCorrection 0.2; ODE's reading, a convention)",
            (Settings(0.5, 1 / 240),), expect,
            exercises=("RigidBodyCollection.maxCorrectionSpeed",),
            mutations=(Mutation(" maxCorrectionSpeed='0.2'", "", spec=False),))
