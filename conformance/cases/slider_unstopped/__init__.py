"""slider_unstopped: SliderJoint minSeparation > maxSeparation: no stops at all, the block slides on freely."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import ROUNDING, SLIDER_STOPS, G, honoured, max_norm, physics_time
from conformance.results import Measure, Settings

# slider_unstopped.x3d: a 1 kg block (body1) on a fixed rail (body2) along the axis, from rest;
# minSeparation 0.3 > maxSeparation 0
UNSTOPPED_AXIS = np.array([0.6, -0.8, 0.0])
UNSTOPPED_MIN, UNSTOPPED_MAX = 0.3, 0.0
SLIDE = "Block slide along the axis at the end - a T^2 / 2"


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Nothing stops the block: gravity along the axis, a = g |axis . (0,-1,0)| = 7.848 m/s^2,
    moves it s = a t^2 / 2 along the axis (3.92 m in 1 s, 13 times the 0.3 m between the two
    separations), at the rate a t. Read from its position, so that the separation's sign (a
    convention, slider_stops) does not count.

    Accuracy: the rate is exact for every one-step scheme (ROUNDING); the slide within a T h / 2
    of a T^2 / 2 (closed_forms' argument for a constant acceleration: semi-implicit Euler above,
    a position-first step below). Spec tolerances (closed_forms.honoured): half the error of the
    misreading "stops swapped", the stops at 0 and 0.3: the block held at 0.3 m along the axis
    (ODE's sign) or where it starts (the other), its rate 0 at the end."""
    tr, s = traces[0], settings[0]
    t, p = tr.series("Block", "position")
    _, v = tr.series("Block", "linearVelocity")
    tp = physics_time(t, s.dt)
    T = float(tp[-1])
    a = G * abs(UNSTOPPED_AXIS @ np.array([0.0, -1.0, 0.0]))
    free = 0.5 * a * T * T
    slide = float((p[-1] - p[0]) @ UNSTOPPED_AXIS)
    bound_slide = 0.5 * a * T * s.dt + ROUNDING * (1 + free)
    swapped = [free - UNSTOPPED_MIN, free - UNSTOPPED_MAX]  # held at either stop
    rounding = ROUNDING * (1 + a * T)
    return [Measure(SLIDE, abs(slide - free), honoured(bound_slide, *swapped), "m", SLIDER_STOPS, bound_slide),
            Measure(f"Block.linearVelocity along the axis - {a:g} t", max_norm(v @ UNSTOPPED_AXIS - a * tp),
                    honoured(rounding, a * T), "m/s", SLIDER_STOPS, rounding)]


CASE = Case("slider_unstopped", "slider_unstopped.x3d",
            "SliderJoint minSeparation 0.3 > maxSeparation 0, axis 0.6 -0.8 0: no stops, the block slides "
            "a t^2 / 2 = 3.92 m in 1 s (stops swapped would hold it at 0.3 m)",
            (Settings(1.0, 1 / 240),), expect, convergence=SLIDE, expected_order=1.0,
            exercises=("SliderJoint.minSeparation", "SliderJoint.maxSeparation", "SliderJoint.axis"),
            mutations=(Mutation("minSeparation='0.3' maxSeparation='0'", "minSeparation='0' maxSeparation='0.3'"),))
