"""slider_stops: SliderJoint minSeparation / maxSeparation: the separation stays within the stops."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import G, stop_overshoot
from conformance.results import Measure, Settings


# slider_stops.x3d
SLIDE_AXIS = np.array([0.6, -0.8, 0.0])
SLIDE_MIN, SLIDE_MAX, SLIDE_ERP = -0.2, 0.3, 1.0  # SliderJoint.stopErrorCorrection default is 1


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Gravity along the axis a = g |axis . (0,-1,0)| = 7.848 m/s^2; the block hits the stop at
    v = sqrt(2 a maxSeparation) = 2.17 m/s. Tolerance: stop_overshoot (v dt + a dt^2, about
    9.2 mm at dt = 1/240), read from a frame after every step. The block must also be at
    the stop at the end (within the same tolerance): a block that never moved, or stopped at
    the default 1 m, fails."""
    tr, s = traces[0], settings[0]
    _, sep = tr.series("Slide", "separation")
    sep = sep[:, 0]
    a = G * abs(SLIDE_AXIS @ np.array([0.0, -1.0, 0.0]))
    tol = stop_overshoot(math.sqrt(2 * a * SLIDE_MAX), a, s.dt, SLIDE_ERP)
    beyond = max(float(np.max(sep)) - SLIDE_MAX, SLIDE_MIN - float(np.min(sep)), 0.0)
    return [Measure("Slide.separation beyond stops", beyond, tol, "m"),
            Measure("Slide.separation at the end - maxSeparation", abs(float(sep[-1]) - SLIDE_MAX), tol, "m")]


CASE = Case("slider_stops", "slider_stops.x3d",
            "SliderJoint minSeparation -0.2 / maxSeparation 0.3, axis 0.6 -0.8 0: separation stays within "
            "the stops",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("SliderJoint.minSeparation", "SliderJoint.maxSeparation", "SliderJoint.axis"),
            mutations=((" maxSeparation='0.3'", ""),))
