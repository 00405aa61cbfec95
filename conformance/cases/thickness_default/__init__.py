"""thickness_default: RigidBodyCollection contactSurfaceThickness defaults to 0: a collection that gives none runs as
one that gives 0."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, honoured, max_norm
from conformance.results import Measure, Settings, spec

# thickness_default.x3d: the two balls' starts, mirrored in x; the nearest default a browser might take instead
TD_STATED, TD_DEFAULTED = np.array([-1.0, 0.095, 0.0]), np.array([1.0, 0.095, 0.0])
TD_NOTE_LAYER = 0.001  # m: "a very small value of 0.001 may be useful" (the clause's NOTE)
ZERO = spec("37.4.11 RigidBodyCollection: The contactSurfaceThickness field represents how far bodies may "
            "interpenetrate after a collision.",
            also=("37.4.11 RigidBodyCollection: The default value is zero.",))


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """How far DefaultedBall's motion strays from StatedBall's, mirrored in x: max over the frames of
    |p_Defaulted - p_Stated - (2, 0, 0)|. The two collections differ in nothing but the field written
    out at its default, so an engine runs them alike: to rounding (the bound: ROUNDING on the
    positions' scale; an engine that solves both in one system, or in single precision, may differ
    more, graded). The misreading, a default surface layer L > 0 (the NOTE's 1 mm the nearest one a
    browser might take), leaves L of the 5 mm unpushed, so that the ball ends its push-out L lower
    than the other (an engine that corrects by moving the body) or is thrown slower by ERP L / h
    (ODE, which throws it: 0.19 m/s slower, 2.8 cm apart at the farthest): at least L apart at some frame.
    The tolerance (closed_forms.honoured) is half that, L / 2. Only what the default is, is judged
    here: how deep a ball rests at thickness 0 is resting_penetration's and the contact cases'."""
    tr = traces[0]
    _, stated = tr.series("StatedBall", "position")
    _, defaulted = tr.series("DefaultedBall", "position")
    n = min(len(stated), len(defaulted))
    apart = max_norm(defaulted[:n] - stated[:n] - (TD_DEFAULTED - TD_STATED))
    bound = ROUNDING * (1 + float(np.linalg.norm(TD_DEFAULTED)))
    return [Measure("DefaultedBall's motion - StatedBall's (mirrored in x)", apart, honoured(bound, TD_NOTE_LAYER),
                    "m", ZERO, bound)]


CASE = Case("thickness_default", "thickness_default.x3d",
            "RigidBodyCollection contactSurfaceThickness left out: a ball started 5 mm into its floor moves as one "
            "in a collection that gives contactSurfaceThickness 0 (within 0.5 mm, half the NOTE's 1 mm layer)",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("CollisionCollection", "CollidableShape.geometry.Sphere"),
            # the default read as the NOTE's 1 mm
            mutations=(("DEF='Defaulted' gravity='0 -9.81 0'",
                        "DEF='Defaulted' gravity='0 -9.81 0' contactSurfaceThickness='0.001'"),))
