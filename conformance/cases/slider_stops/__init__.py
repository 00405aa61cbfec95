"""slider_stops: SliderJoint maxSeparation: the separation stays within the stops and rests at one."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import SLIDER_STOPS, G, honoured, stop_overshoot
from conformance.results import Measure, Settings, convention


# slider_stops.x3d: the stops in X3D 3.3's range [0, inf); the block starts at separation 0, the
# min stop, and gravity takes it toward the max stop
SLIDE_AXIS = np.array([0.6, -0.8, 0.0])
SLIDE_MIN, SLIDE_MAX, SLIDE_ERP = 0.0, 0.3, 1.0  # SliderJoint.stopErrorCorrection default is 1
SLIDE_DEFAULT_MAX = 1.0  # SliderJoint.maxSeparation default
ODE_SEPARATION = convention(
    "separation of body1 relative to body2 along the axis, from the initial configuration (ODE's "
    "dJointGetSliderPosition): the block starts at 0 and slides to the max stop; alternatives: body2 relative "
    "to body1, or the axis's other sense (the block then held where it starts, at the min stop), or the "
    "separation measured from the bodies' origins")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Gravity along the axis a = g |axis . (0,-1,0)| = 7.848 m/s^2; with ODE's sign the block
    leaves the min stop (where it starts) and hits the max stop at v = sqrt(2 a maxSeparation) =
    2.17 m/s. Tolerance: stop_overshoot (v dt + a dt^2, about 9.2 mm at dt = 1/240), read from a
    frame after every step.

    Spec: the reported separation stays within [minSeparation, maxSeparation], and ends at a stop.
    Which stop is the sign's business: with the other sign (body2 relative to body1) the block's
    fall makes the separation fall, and the min stop holds it where it starts. A block that slid
    on to the default 1 m stop, or without stops, fails both. Convention (ODE's sign): the block
    ends at the max stop.

    stop_overshoot is the accuracy bound (a rigid stop acting a step late). The tolerances
    (closed_forms.honoured) are half the misreading's error: maxSeparation ignored (X3D's
    default 1 m: the block slides 0.7 m on), and for the convention the other sign (the block
    held at the min stop, 0.3 m from the max)."""
    tr, s = traces[0], settings[0]
    _, sep = tr.series("Slide", "separation")
    sep = sep[:, 0]
    a = G * abs(SLIDE_AXIS @ np.array([0.0, -1.0, 0.0]))
    bound = stop_overshoot(math.sqrt(2 * a * (SLIDE_MAX - SLIDE_MIN)), a, s.dt, SLIDE_ERP)
    tol = honoured(bound, SLIDE_DEFAULT_MAX - SLIDE_MAX)
    beyond = max(float(np.max(sep)) - SLIDE_MAX, SLIDE_MIN - float(np.min(sep)), 0.0)
    end = float(sep[-1])
    return [Measure("Slide.separation beyond stops", beyond, tol, "m", SLIDER_STOPS, bound),
            Measure("Slide.separation at the end - the nearer stop", min(abs(end - SLIDE_MIN), abs(end - SLIDE_MAX)),
                    tol, "m", SLIDER_STOPS, bound),
            Measure("Slide.separation at the end - maxSeparation", abs(end - SLIDE_MAX),
                    honoured(bound, SLIDE_MAX - SLIDE_MIN), "m", ODE_SEPARATION, bound)]


CASE = Case("slider_stops", "slider_stops.x3d",
            "SliderJoint minSeparation 0 / maxSeparation 0.3, axis 0.6 -0.8 0: separation stays within "
            "the stops, ends at one (ODE's sign: at maxSeparation)",
            (Settings(1.0, 1 / 240, None),), expect,
            exercises=("SliderJoint.maxSeparation", "SliderJoint.axis"),
            mutations=((" maxSeparation='0.3'", ""),))
