"""slider_bounce: SliderJoint stopBounce between free bodies: the stop sends the slide back part way."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import (CFM_DEFAULT, ROUNDING, SLIDER_BOUNCE, SLIDER_STOPS, honoured, max_norm,
                                            stop_rebound)
from conformance.results import Measure, Settings, convention, spec

# slider_bounce.x3d: Shuttle (body1) leaves its min stop at v0 along the axis, Sled (body2) at rest
SB_AXIS = np.array([0.8, 0.0, 0.6])
SB_V0, SB_BOUNCE, SB_ERP, SB_MIN, SB_MAX, SB_M1, SB_M2 = 2.0, 0.5, 0.2, -0.2, 0.31, 1.0, 3.0
SB_DEFAULT_MIN, SB_DEFAULT_MAX = 0.0, 1.0  # the separations' defaults
SLIDE = spec("37.4.13 SliderJoint: The SliderJoint node represents a joint where all movement between the bodies "
             "specified by the body1 and body2 fields is constrained to a single dimension along a user-defined axis.")
SEPARATION = spec("37.4.13 SliderJoint: The separation output field is used to indicate the final separation of the "
                  "two bodies.")
RATE = spec("37.4.13 SliderJoint: The separationRate output field is used to indicate the change in separation over "
            "time since the last update.")
LINEAR = convention("ODE's stop bounce: the stop's row targets the rebound rate -stopBounce x the impact rate, the "
                    "stop's error correction adding nothing to it (docs/spec-loose-ends.md, 13); the clause fixes "
                    "only the ends, 0 no bounce and 1 equal and opposite")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The first impact: the first step after which r = axis . (v1 - v2) changes sign (nothing but
    the stops acts on r, so it is v0 until then, in either sense); before = |r| before it, after
    = |r| after it.

    Accuracy bounds. ODE's stop acts on the step after the one that crosses it and targets
    -e x before exactly; its row yields by CFM times its force (the world's default 1e-4; the
    pair's reduced mass m1 m2/(m1 + m2) turned through (1 + e) v0 in a step: CFM m (1 + e) v0 /
    h, 0.054 m/s); the relative motion stays on the axis, the pair's momentum m1 v0 axis to
    rounding (the joint's forces are internal), and the outputs are the bodies' relative
    displacement and rate along the axis, to rounding. The slide reaches each stop (in 0.8 s,
    in either sense) and goes past it by at most a step's travel v0 h.

    Spec: stopBounce 0.5 sends the slide back part way: faster than the error correction alone
    could, were it a velocity as ODE's StopERP makes it (a step's depth at most v0 h, corrected at
    stopErrorCorrection per step: ERP v0), and slower than it came. The law between the ends is
    ODE's (convention): after = e x before, held to half the distance to no bounce or a full one.
    The momentum's tolerance is half its error where body2 is not on the joint (the world takes
    the stop's impulse: (1 + e) m1 v0); the outputs', their not being reported (0); the stops',
    half the distance to the stop's default (0 and 1 m), where the slide turns if the field is
    ignored."""
    tr, s = traces[0], settings[0]
    h = s.dt
    t, p1 = tr.series("Shuttle", "position")
    _, p2 = tr.series("Sled", "position")
    _, v1 = tr.series("Shuttle", "linearVelocity")
    _, v2 = tr.series("Sled", "linearVelocity")
    _, sep = tr.series("Track", "separation")
    _, sep_rate = tr.series("Track", "separationRate")
    sep, sep_rate = sep[:, 0], sep_rate[:, 0]
    r = (v1 - v2) @ SB_AXIS
    moved = ((p1 - p2) - (p1[0] - p2[0])) @ SB_AXIS
    reduced = SB_M1 * SB_M2 / (SB_M1 + SB_M2)
    softness = CFM_DEFAULT * reduced * (1 + SB_BOUNCE) * SB_V0 / h
    pop = SB_ERP * SB_V0
    rounding = ROUNDING * (1 + SB_V0)
    travel = SB_V0 * h + ROUNDING
    momentum = SB_M1 * v1 + SB_M2 * v2 - SB_M1 * SB_V0 * SB_AXIS
    out = [Measure(f"Track.separation farthest out - maxSeparation {SB_MAX:g}", abs(float(np.max(sep)) - SB_MAX),
                   honoured(travel, SB_DEFAULT_MAX - SB_MAX), "m", SLIDER_STOPS, travel),
           Measure(f"Track.separation farthest in - minSeparation {SB_MIN:g}", abs(float(np.min(sep)) - SB_MIN),
                   honoured(travel, SB_DEFAULT_MIN - SB_MIN), "m", SLIDER_STOPS, travel),
           Measure("m1 Shuttle.linearVelocity + m2 Sled.linearVelocity - m1 v0 axis", max_norm(momentum),
                   honoured(rounding, (1 + SB_BOUNCE) * SB_M1 * SB_V0), "kg m/s", SLIDE, rounding),
           Measure("|Track.separation| - |axis . relative displacement|", max_norm(np.abs(sep) - np.abs(moved)),
                   honoured(rounding, SB_MAX), "m", SEPARATION, rounding),
           Measure("|Track.separationRate| - |axis . (v1 - v2)|", max_norm(np.abs(sep_rate) - np.abs(r)),
                   honoured(rounding, SB_V0), "m/s", RATE, rounding)]
    return out + stop_rebound(r, SB_BOUNCE, pop, softness, "m/s", "the slide", SLIDER_BOUNCE, LINEAR)


CASE = Case("slider_bounce", "slider_bounce.x3d",
            "SliderJoint stopBounce 0.5, stopErrorCorrection 0.2, stops -0.2 and 0.31, axis 0.8 0 0.6, two free "
            "bodies: each stop is reached, and sends the slide back part way (ODE's law: at 0.5 x the impact "
            "rate); the pair's momentum kept; separation and separationRate report the relative slide",
            (Settings(0.8, 1 / 240, None),), expect,
            exercises=("SliderJoint.stopBounce", "SliderJoint.stopErrorCorrection", "SliderJoint.axis",
                       "SliderJoint.minSeparation", "SliderJoint.maxSeparation", "SliderJoint.forceOutput"),
            mutations=(
                (" stopBounce='0.5'", ""),
                (" minSeparation='-0.2'", ""),  # the slide turns at 0
                (" axis='0.8 0 0.6'", ""),  # along y, across the Shuttle's velocity: nothing slides
                ("<RigidBody USE='Sled' containerField='body2'/>", ""),  # the world takes the stop's impulse
                ("<RigidBody USE='Shuttle' containerField='body1'/>", ""),  # nothing between the Shuttle and a stop
            ))
