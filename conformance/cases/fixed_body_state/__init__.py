"""fixed_body_state: RigidBody.fixed: a fixed body hit by a falling ball and pulled by a joint reports its file state.

"This body does not move": its position and orientation stay the file's and its velocities
zero, exactly, whatever collides with it or hangs from it; and it still "can be collided with":
the ball lands on its slab, turned as its orientation turns it."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import (CFM_DEFAULT, ERP_DEFAULT, G, ROUNDING, ROUNDING_ANGLE, honoured,
                                            max_norm)
from conformance.results import Measure, Settings, spec


FIXED = spec("37.4.10 RigidBody: The fixed field is used to indicate that this body does not move. Any calculations "
             "involving collisions with this body should take into account that this body does not move. This is "
             "useful for representing objects such as the ground, walls etc that can be collided with, have an "
             "effect on other objects, but are not capable of moving themselves.")

# fixed_body_state.x3d
FB_POSITION, FB_ORIENTATION = np.array([0.0, 2.0, 0.0]), np.array([0.0, 0.0, 1.0, math.pi / 2])
FB_TOP, FB_UNTURNED_TOP = 2.1, 2.5  # the slab's top face; the box's, were its orientation ignored
FB_BALL_R, FB_BALL_M, FB_DROP = 0.1, 1.0, 0.2  # the ball starts FB_DROP above the slab


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Base: position, orientation and both velocities against the file's state over the run, held
    to rounding: a body that does not move has nothing to integrate (a misreading, the field
    ignored, lets it fall g T^2/2; no solver error is owed here).

    Ball: its height at the end against resting on the slab (top + r). Accuracy bound: a contact
    acting a step late lets it land up to v_in h + g h^2 deep (v_in = sqrt(2 g drop)), ODE's soft
    contact sinks it CFM m g h / ERP more (closed_forms' contact argument). Spec tolerance
    (closed_forms.honoured): half the nearest misreading: Base's box collided unturned (its top at
    2.5: the ball starts inside it and is pushed out above, 0.4 m off) or not collided at all (the
    ball falls through: y = 2.4 - g T^2/2)."""
    tr, s = traces[0], settings[0]
    h = s.dt
    t, p = tr.series("Base", "position")
    _, q = tr.series("Base", "orientation")
    _, v = tr.series("Base", "linearVelocity")
    _, w = tr.series("Base", "angularVelocity")
    T = float(t[-1])
    out = [Measure("Base.position - its file value", max_norm(p - FB_POSITION),
                   ROUNDING * (1 + float(np.linalg.norm(FB_POSITION))), "m", FIXED),
           Measure("Base.orientation - its file value",
                   float(np.max(R.angle_between(R.from_axis_angle(q), R.from_axis_angle(FB_ORIENTATION)))),
                   ROUNDING_ANGLE, "rad", FIXED),
           Measure("Base.linearVelocity", max_norm(v), ROUNDING, "m/s", FIXED),
           Measure("Base.angularVelocity", max_norm(w), ROUNDING, "rad/s", FIXED)]
    _, ball = tr.series("Ball", "position")
    rest = FB_TOP + FB_BALL_R
    v_in = math.sqrt(2 * G * FB_DROP)
    bound = v_in * h + G * h * h + CFM_DEFAULT * FB_BALL_M * G * h / ERP_DEFAULT
    through = rest + FB_DROP - 0.5 * G * T * T
    out.append(Measure("Ball height at the end - resting on Base's slab (top + r)", abs(float(ball[-1, 1]) - rest),
                       honoured(bound, FB_UNTURNED_TOP - FB_TOP, rest - through), "m", FIXED, bound))
    return out


CASE = Case("fixed_body_state", "fixed_body_state.x3d",
            "RigidBody.fixed TRUE, hit by a ball and pulled by a BallJoint: Base keeps its file position and "
            "orientation and zero velocities exactly; the ball rests on its slab",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.fixed", "RigidBody.orientation", "BallJoint", "CollidableShape.geometry.Box",
                       "CollidableShape.geometry.Sphere"),
            mutations=((" fixed='true'", ""),))
