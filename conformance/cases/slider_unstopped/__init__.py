"""slider_unstopped: SliderJoint minSeparation > maxSeparation: no stops at all, the block slides on freely."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import ERROR_CORRECTION, ROUNDING, SLIDER_STOPS, G, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, spec

# slider_unstopped.x3d: a 1 kg block (body1) on a fixed rail (body2) along the axis, from rest;
# minSeparation 0.3 > maxSeparation 0
UNSTOPPED_AXIS = np.array([0.6, -0.8, 0.0])
UNSTOPPED_MIN, UNSTOPPED_MAX = 0.3, 0.0
SLIDE = "Block slide along the axis at the end - a T^2 / 2"
ALONG_AXIS = spec("37.4.13 SliderJoint: The axis field indicates which axis along which the two bodies will act.")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Nothing stops the block: gravity along the axis, a = g |axis . (0,-1,0)| = 7.848 m/s^2,
    moves it s = a t^2 / 2 along the axis (3.92 m in 1 s, 13 times the 0.3 m between the two
    separations), at the rate a t. Read from its position, so that the separation's sign (a
    convention, slider_stops) does not count.

    Accuracy: the rate is exact for every one-step scheme (ROUNDING); the slide within a T h / 2
    of a T^2 / 2 (closed_forms' argument for a constant acceleration: semi-implicit Euler above,
    a position-first step below). Spec tolerances (closed_forms.honoured): half the error of the
    misreading "stops swapped", the stops at 0 and 0.3: the block held at 0.3 m along the axis
    (ODE's sign) or where it starts (the other), its rate 0 at the end.

    Across the axis (ALONG_AXIS): the block's displacement from its start less its part along the
    axis, max over the run, is 0: the rail is fixed, and gravity's part across the axis,
    g_perp = 0.6 g, is the joint's to cancel. Accuracy: a solve that lets one step's g_perp through
    (g_perp dt^2 of position) and an error correction that takes ERP of the drift out each step
    leaves at most g_perp dt^2 / ERP, plus rounding. Spec tolerance half the misreading's error:
    axis ignored (its default 0 1 0, or no joint at all), the block falls straight down, g T^2 / 2
    along -y, of which 0.6 lies across the axis, 2.94 m at 1 s; its slide along the axis and rate,
    0.8 of the fall's, are the same as the scene's, so only this measure sees it."""
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
    d = p - p[0]
    across = d - np.outer(d @ UNSTOPPED_AXIS, UNSTOPPED_AXIS)
    g_perp = G * float(np.linalg.norm(np.array([0.0, -1.0, 0.0]) - (-UNSTOPPED_AXIS[1]) * UNSTOPPED_AXIS))
    bound_across = g_perp * s.dt ** 2 / ERROR_CORRECTION + ROUNDING * (1 + free)
    fall_across = 0.5 * g_perp * T * T  # axis ignored: the free fall's part across the axis
    return [Measure(SLIDE, abs(slide - free), honoured(bound_slide, *swapped), "m", SLIDER_STOPS, bound_slide),
            Measure(f"Block.linearVelocity along the axis - {a:g} t", max_norm(v @ UNSTOPPED_AXIS - a * tp),
                    honoured(rounding, a * T), "m/s", SLIDER_STOPS, rounding),
            Measure("Block displacement across the axis", max_norm(across), honoured(bound_across, fall_across), "m",
                    ALONG_AXIS, bound_across)]


CASE = Case("slider_unstopped", "slider_unstopped.x3d",
            "SliderJoint minSeparation 0.3 > maxSeparation 0, axis 0.6 -0.8 0: no stops, the block slides "
            "a t^2 / 2 = 3.92 m in 1 s (stops swapped would hold it at 0.3 m)",
            (Settings(1.0, 1 / 240),), expect, convergence=SLIDE, expected_order=1.0,
            exercises=("SliderJoint.minSeparation", "SliderJoint.maxSeparation", "SliderJoint.axis"),
            mutations=(Mutation("minSeparation='0.3' maxSeparation='0'", "minSeparation='0' maxSeparation='0.3'"),
                       # axis ignored (4.0's default 0 1 0): the block falls straight down, 2.94 m across the axis
                       Mutation(" axis='0.6 -0.8 0'", "")))
