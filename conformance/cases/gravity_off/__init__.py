"""gravity_off: RigidBody.useGlobalGravity FALSE: one body floats while its neighbour falls."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, G_DEFAULT, GRAVITY, max_norm, ballistic
from conformance.results import Measure, Settings, also, spec


NO_GRAVITY = spec("37.4.10 RigidBody: The useGlobalGravity field is used to indicate whether this particular body "
                  "should be influenced by the containing RigidBodyCollection's gravity setting. A value of TRUE "
                  "indicates that the gravity is used, a value of FALSE indicates that it is not used.")
# Falling's acceleration: Floating's FALSE taken for the whole collection leaves Falling still, 9.8 m/s^2 off at a
# tolerance of half that
THIS_BODY_ONLY = also(GRAVITY, "37.4.10 RigidBody: This only applies to this body instance.")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Floating: at rest, p = p0 and v = 0 up to ROUNDING (nothing acts on it). Falling: the
    ballistic closed form with the default gravity."""
    tr = traces[0]
    _, p = tr.series("Floating", "position")
    _, v = tr.series("Floating", "linearVelocity")
    rest = [Measure("Floating.position", max_norm(p - np.array([0.0, 2.0, 0.0])), ROUNDING * 3, "m", NO_GRAVITY),
            Measure("Floating.linearVelocity", max_norm(v), ROUNDING, "m/s", NO_GRAVITY)]
    return rest + ballistic("Falling", (1, 2, 0), (0, 0, 0), (0, -G_DEFAULT, 0), THIS_BODY_ONLY)(traces, settings)


CASE = Case("gravity_off", "gravity_off.x3d",
            "RigidBody.useGlobalGravity FALSE: that body stays at rest while its neighbour falls",
            (Settings(1.0, 1 / 240),), expect,
            convergence="Falling.position", expected_order=1.0, exercises=("RigidBody.useGlobalGravity",),
            mutations=((" useGlobalGravity='false'", ""),))
