"""universal_free: UniversalJoint between two free bodies: the anchor stays common, the momentum kept."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ERROR_CORRECTION, ROUNDING, anchor_gap, honoured, max_norm, omega
from conformance.results import Measure, Settings, spec

# universal_free.x3d: Yoke (body1) and Fork (body2) 0.3 m either side of the anchor, unturned
UF_ANCHOR, UF_YOKE, UF_FORK = (0.0, 1.0, 0.0), (-0.3, 1.0, 0.0), (0.3, 1.0, 0.0)
UF_M1, UF_M2, UF_I1, UF_I2, UF_ARM = 1.0, 2.0, 0.01, 0.02, 0.3
UF_W0 = 2.0  # Fork's turn about axis2 through the anchor at the start
UF_P0 = np.array([0.0, UF_M2 * UF_W0 * UF_ARM, 0.0])  # the pair's momentum: Fork's at the start
LIKE_BALL = spec("37.4.14 UniversalJoint: A universal joint is like a BallJoint that constrains an extra degree of "
                 "rotational freedom.")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The anchor point as Yoke and as Fork carry it (closed_forms.anchor_gap): ball_chain's drift
    bound, dt^2/(2 ERP) (|w1|^2 + |w2|^2) r with the rates read from the trace (each capped by all
    of the pair's energy in that body's turn), r = 0.3 m; its tolerance half the lever, the gap where
    the joint holds one body to the world instead (body1 or body2 ignored: the other flies off).
    The pair's momentum m1 v1 + m2 v2: kept (the joint is internal) to rounding by an engine that
    steps the bodies (ODE, Chipmunk); one that steps the joint's coordinates (MuJoCo, Bullet's
    multibody, DART) rebuilds the bodies' velocities each step along the turned joint, which can
    miss the centripetal part of each body's motion about the anchor for that step, m |w|^2 r h
    (not compounding: the next step's rebuild starts again from the joint's rates): the bound.
    Its tolerance half the momentum itself (the joint holding a body to the world takes it)."""
    tr, s = traces[0], settings[0]
    _, v1 = tr.series("Yoke", "linearVelocity")
    _, v2 = tr.series("Fork", "linearVelocity")
    energy = 0.5 * float(UF_P0 @ UF_P0) / UF_M2 + 0.5 * UF_I2 * UF_W0 ** 2
    w1 = np.minimum(omega(tr, "Yoke"), np.sqrt(2 * energy / UF_I1))
    w2 = np.minimum(omega(tr, "Fork"), np.sqrt(2 * energy / UF_I2))
    bound = float(np.max(w1 ** 2 + w2 ** 2)) * UF_ARM * s.dt ** 2 / (2 * ERROR_CORRECTION) + ROUNDING
    gap = anchor_gap(tr, "Yoke", "Fork", UF_ANCHOR, UF_YOKE, UF_FORK)
    rounding = ROUNDING * (1 + float(np.linalg.norm(UF_P0)))
    rebuilt = float(np.max(UF_M1 * w1 ** 2 + UF_M2 * w2 ** 2)) * UF_ARM * s.dt + rounding
    return [Measure("Cross anchor point as Yoke and as Fork carry it: gap", float(np.max(gap)),
                    honoured(bound, UF_ARM), "m", LIKE_BALL, bound),
            Measure("m1 Yoke.linearVelocity + m2 Fork.linearVelocity - m2 v0",
                    max_norm(UF_M1 * v1 + UF_M2 * v2 - UF_P0),
                    honoured(rebuilt, float(np.linalg.norm(UF_P0))), "kg m/s", LIKE_BALL, rebuilt)]


CASE = Case("universal_free", "universal_free.x3d",
            "UniversalJoint between free bodies (anchor 0 1 0, axes y and z): Fork, turning about the anchor, drags "
            "Yoke along; the "
            "anchor stays common to both, the pair's momentum kept",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("UniversalJoint.anchorPoint", "UniversalJoint.axis1", "UniversalJoint.axis2"),
            mutations=(
                ("<RigidBody USE='Fork' containerField='body2'/>", ""),  # Yoke held by the world, Fork flies off
                ("<RigidBody USE='Yoke' containerField='body1'/>", ""),  # Fork held by the world
            ))
