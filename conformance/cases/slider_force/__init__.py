"""slider_force: SliderJoint sliderForce: equal and opposite forces on the two bodies along the axis."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, convention, spec

# slider_force.x3d: Block (body1) and Carriage (body2), free, at rest; no gravity
SF_AXIS = np.array([1.0, 0.0, 0.0])
SF_FORCE, SF_M1, SF_M2 = 1.2, 2.0, 3.0
FORCE = spec("37.4.13 SliderJoint: The sliderForce field value is used to apply a force along the axis of the slider "
             "in equal and opposite directions to the two bodies.")
ODE_FORCE = convention("body1 gets +sliderForce along the axis and body2 its opposite (ODE's dJointAddSliderForce); "
                       "alternative: the other way round")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Nothing but the slider's force acts along the axis, and it is constant: the relative rate
    r = axis . (v1 - v2) = a t, a = F (1/m1 + 1/m2), exact for every one-step scheme (ROUNDING),
    and the pair's momentum 0 to rounding. The relative slide is first order: every scheme in use
    keeps it within a t h / 2 of a t^2 / 2 (closed_forms' argument for a constant acceleration).

    Spec tolerances (closed_forms.honoured): half the misreading's error at the end: the force
    ignored (r = 0, no slide: a T and a T^2 / 2 off), on one body only (momentum F T).
    Convention: ODE's sense, body1 along +axis (twice the closed form for the other)."""
    tr, s = traces[0], settings[0]
    t, p1 = tr.series("Block", "position")
    _, p2 = tr.series("Carriage", "position")
    _, v1 = tr.series("Block", "linearVelocity")
    _, v2 = tr.series("Carriage", "linearVelocity")
    tp = physics_time(t, s.dt)
    T = float(tp[-1])
    a = SF_FORCE * (1 / SF_M1 + 1 / SF_M2)
    r = (v1 - v2) @ SF_AXIS
    slide = ((p1 - p2) - (p1[0] - p2[0])) @ SF_AXIS
    rounding = ROUNDING * (1 + a * T)
    bound_slide = 0.5 * a * T * s.dt + ROUNDING
    momentum = SF_M1 * v1 + SF_M2 * v2
    return [Measure("m1 Block.linearVelocity + m2 Carriage.linearVelocity", max_norm(momentum),
                    honoured(rounding, SF_FORCE * T), "kg m/s", FORCE, rounding),
            Measure(f"|axis . (v1 - v2)| - {a:g} t", max_norm(np.abs(r) - a * tp), honoured(rounding, a * T), "m/s",
                    FORCE, rounding),
            Measure(f"|relative slide| at the end - {a:g} T^2 / 2", abs(abs(float(slide[-1])) - 0.5 * a * T * T),
                    honoured(bound_slide, 0.5 * a * T * T), "m", FORCE, bound_slide),
            Measure(f"axis . (v1 - v2) - {a:g} t", max_norm(r - a * tp), honoured(rounding, 2 * a * T), "m/s",
                    ODE_FORCE, rounding)]


CASE = Case("slider_force", "slider_force.x3d",
            "SliderJoint sliderForce 1.2 between free bodies (2 and 3 kg): the relative rate grows at F (1/m1 + 1/m2) "
            "= 1 m/s^2, the pair's momentum stays 0",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("SliderJoint.sliderForce", "SliderJoint.minSeparation"),
            mutations=((" sliderForce='1.2'", ""),))  # nothing pushes
