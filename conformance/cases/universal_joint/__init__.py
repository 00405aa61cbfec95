"""universal_joint: UniversalJoint axis1 / axis2: the axes stay perpendicular."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, G, ERROR_CORRECTION, anchor_gap, anchor_outputs, honoured, omega
from conformance.results import Measure, Settings, spec


UJ_INERTIA = {"Upper": 0.02, "Lower": 0.01}
# |cosine|: the same whichever sense either axis output has
PERPENDICULAR = spec("37.4.14 UniversalJoint: Given the axis specified by the axis1 field on the body specified by "
                     "the body1 field, and the axis specified by the axis2 field on body2 that is perpendicular "
                     "to axis1, the UniversalJoint node keeps the axes perpendicular to each other.")
LIKE_BALL = spec("37.4.14 UniversalJoint: A universal joint is like a BallJoint that constrains an extra degree of "
                 "rotational freedom.")
# universal_joint.x3d: the anchor, and the arms' starts (unturned)
UJ_ANCHOR, UJ_UPPER, UJ_LOWER = (0.6, -0.8, 0.0), (0.3, -0.4, 0.0), (0.6, -0.8, 0.5)
UJ_ARM = 0.5  # each arm's centre from the anchor
# the most energy gravity can give the arms: Upper's centre (0.5 m from the fixed shoulder, at
# y = -0.4) can fall 0.1 m; Lower's (at most 1.0 + 0.5 m from the shoulder, at y = -0.8) 0.7 m
UJ_ENERGY = 1.0 * G * 0.1 + 0.5 * G * 0.7


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """|body1Axis . body2Axis| (the cosine; the joint keeps it 0), and the gap between the anchor
    point as Upper and as Lower carry it (from their poses: the joint's pivot is shared).

    Tree-built joints: rounding only. Velocity-level constraints keep d/dt (a1 . a2) = 0; one
    step's second-order term is at most dt^2/2 |d^2/dt^2 (a1 . a2)| <= dt^2/2 (|w1| + |w2|)^2,
    and error correction settles the drift below dt^2/(2 ERP) (|w1| + |w2|)^2, with the rates
    read from the trace at every step (each capped by the energy the arms can release): the bound
    that grades the run; the spec's tolerance (closed_forms.honoured) is half the cosine of axes
    not kept apart at all, held one line (1): a sentence says the joint keeps them perpendicular,
    none how closely an integrator must. The
    anchor gap, as ball_chain argues it: dt^2/(2 ERP) (|w1|^2 + |w2|^2) r, r = 0.5 m each arm's
    lever; its tolerance (closed_forms.honoured) half the lever, the gap where the joint pivots
    about a body's origin or another point (the anchorPoint ignored), or holds one arm only
    (body1 ignored: Upper swings away). The joint's anchor outputs: closed_forms.anchor_outputs
    (a convention)."""
    tr, s = traces[0], settings[0]
    _, a1 = tr.series("Cross", "body1Axis")
    _, a2 = tr.series("Cross", "body2Axis")
    w1 = np.minimum(omega(tr, "Upper"), math.sqrt(2 * UJ_ENERGY / UJ_INERTIA["Upper"]))
    w2 = np.minimum(omega(tr, "Lower"), math.sqrt(2 * UJ_ENERGY / UJ_INERTIA["Lower"]))
    with np.errstate(invalid="ignore", divide="ignore"):  # an axis of length 0 is NaN: a failure
        cos = np.abs(np.einsum("ni,ni->n", a1, a2)) / (np.linalg.norm(a1, axis=1) * np.linalg.norm(a2, axis=1))
    bound = float(np.max((w1 + w2) ** 2)) * s.dt ** 2 / (2 * ERROR_CORRECTION)
    gap_bound = float(np.max(w1 ** 2 + w2 ** 2)) * UJ_ARM * s.dt ** 2 / (2 * ERROR_CORRECTION) + ROUNDING
    gap = anchor_gap(tr, "Upper", "Lower", UJ_ANCHOR, UJ_UPPER, UJ_LOWER)
    return [Measure("Cross |body1Axis . body2Axis|", float(np.max(cos)), honoured(bound + ROUNDING, 1.0), "",
                    PERPENDICULAR, bound + ROUNDING),
            Measure("Cross anchor point as Upper and as Lower carry it: gap", float(np.max(gap)),
                    honoured(gap_bound, UJ_ARM), "m", LIKE_BALL, gap_bound),
            anchor_outputs(tr, "Cross", "Upper", "Lower", UJ_ANCHOR, UJ_UPPER, UJ_LOWER)]


CASE = Case("universal_joint", "universal_joint.x3d",
            "UniversalJoint axis1 0.8 0.6 0 / axis2 -0.6 0.8 0: body1Axis stays perpendicular to body2Axis",
            (Settings(1.5, 1 / 240, None),), expect,
            exercises=("UniversalJoint.axis1", "UniversalJoint.axis2", "UniversalJoint.anchorPoint"),
            # the default 0 1 0: 53 degrees from axis1, not a cross
            mutations=((" axis2='-0.6 0.8 0'", ""),
                       (" axis1='0.8 0.6 0'", ""),  # the default 1 0 0: 127 degrees from axis2
                       (" anchorPoint='0.6 -0.8 0'", ""),  # the cross at the shoulder: the arms part at 0.6 -0.8 0
                       ("<RigidBody USE='Upper' containerField='body1'/>\n        <RigidBody USE='Lower'",
                        "<RigidBody USE='Lower'"),  # Lower held by the world, Upper swings away
                       ))
