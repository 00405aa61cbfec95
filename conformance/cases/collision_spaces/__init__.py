"""collision_spaces: CollisionSpaces nested in CollisionSpaces, spaces against spaces, and useGeometry TRUE: the
geometry, not its bounds.

What the clause says of spaces, each sentence shown by a ball: a space's group holds nested collections
(37.4.6: OnNested rests on a box two spaces deep), a collection's spaces collide against each other (37.4.4:
InSpace, its shape in one space, rests on a box in another), and where two spaces meet the system goes down to the
objects they hold to find which collided (37.4.6: Gap, inside Outer's bounds but clear of every box in it, falls);
a nested space that is disabled takes no part (37.3.1: OffNested falls through its box).

useGeometry. 37.4.6: the field "indicates whether the collision detection code should check for collisions down to
the level of geometry or only make approximations using the bounds of the geometry". TRUE asks for the geometry: a
ball passing through a corner of a Sphere's or a Cylinder's bounding box, clear of the shape itself, is not stopped
(spec; in such a space this fixes what 37.4.3 leaves implementation-dependent for a Shape without a bounding box,
which cylinder_cone_shape checks outside one as a convention). FALSE allows the bounds and does not require them:
the ball past Knob keeping its velocity (the geometry tested, as x3drbp and every engine here do whatever the field
says: x3d_core/semantics/collision.py) is a convention, a ball stopped at Knob's bounding box conforms too."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import ROUNDING, falls, honoured, max_norm, rests
from conformance.results import Measure, Settings, convention, spec

# collision_spaces.x3d, World: balls of radius 0.1 m, 1 kg, put down touching y = 0
CS_RESTING = {"InSpace": (-1.5, 0.1, 0.0), "OnNested": (0.0, 0.1, 0.0)}
CS_FALLING = {"Gap": (-0.75, 0.1, 0.0), "OffNested": (1.5, 0.1, 0.0)}
# Drift: balls of radius 0.05 m drifting at (sqrt 2, -sqrt 2, 0) m/s past obstacles of radius 0.3 m
CS_V0 = np.array([math.sqrt(2.0), -math.sqrt(2.0), 0.0])
CS_PAST = ("PastDome", "PastDrum", "PastKnob")
CS_R, CS_BALL = 0.3, 0.05  # Dome's and Knob's radius, Drum's radius and half-height; the balls' radius

NESTED = spec("37.4.6 CollisionSpace: A group consists of both collidable objects as well as nested collections.")
SPACES = spec("37.4.4 CollisionCollection: A group consists of both collidable objects as well as spaces that may be "
              "collided against each other.")
TRAVERSE = spec("37.4.6 CollisionSpace: If there is some intersection between two spaces, or between a collidable "
                "space and a collidable object, the system will traverse into the contained objects looking for finer "
                "resolution on exactly which objects collided together.")
NESTED_OFF = spec("37.3.1 X3DNBodyCollisionSpaceNode: The enabled field specifies whether the collision space is to be "
                  "considered during collision processing.")
GEOMETRY = spec("37.4.6 CollisionSpace: The useGeometry field indicates whether the collision detection code should "
                "check for collisions down to the level of geometry or only make approximations using the bounds of "
                "the geometry.")
BOUNDS_ALLOWED = convention(
    "a CollisionSpace with useGeometry FALSE still tests its shapes' geometry (x3drbp's reading, x3d_core/semantics/collision.py, "
    "and every engine here, whatever the field says); FALSE lets the collision code 'only make approximations using "
    "the bounds of the geometry', so a ball stopped at Knob's bounding box conforms too")
BASES = {"InSpace": SPACES, "OnNested": NESTED, "Gap": TRAVERSE, "OffNested": NESTED_OFF}


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """InSpace and OnNested rest on their floors, Gap and OffNested fall (closed_forms.rests and
    falls argue the bounds: one step of unresisted fall and ODE's softness; free fall exact but for
    rounding); the tolerances are half the misreading's error: a resting ball whose floor does not
    collide (a nested space or a space's ball left out: it falls g T^2 / 2), and a falling ball
    held (Gap by the space's bounds, OffNested by a disabled space's box: its acceleration 0, not g).

    PastDome, PastDrum and PastKnob touch nothing: their velocity stays (sqrt 2, -sqrt 2, 0), exact
    but for rounding (nothing acts in Drift: ROUNDING (1 + |v|) the bound). The tolerance is half what
    the bounds would take: a ball stopped on its obstacle's bounding box loses the velocity across
    the box's top face, |v| / sqrt 2 = 1.41 m/s; for PastDrum also a bounding sphere, where it differs
    from the shape (Drum's, radius 0.424 m: the ball passes 0.424 m from its centre, a ball's radius
    inside it, meeting it at 0.89 m/s across: the nearer misreading)."""
    tr, s = traces[0], settings[0]
    out = []
    for name, start in CS_RESTING.items():
        out += rests(tr, s, name, start, BASES[name])
    for name, start in CS_FALLING.items():
        out += falls(traces, settings, name, start, BASES[name])
    speed = float(np.linalg.norm(CS_V0))
    bound = ROUNDING * (1.0 + speed)
    stopped = speed / math.sqrt(2.0)
    reach = math.hypot(CS_R, CS_R) + CS_BALL  # Drum's bounding sphere, radius sqrt(r^2 + (h/2)^2), and the ball's
    across = speed * math.sqrt(reach ** 2 - (2 * CS_R ** 2)) / reach  # the path passes sqrt(2) r from its centre
    for name in CS_PAST:
        _, v = tr.series(name, "linearVelocity")
        out.append(Measure(f"{name}.linearVelocity - its start, past the bounding box's corner, clear of the shape",
                           max_norm(v - CS_V0), honoured(bound, stopped, *((across,) if name == "PastDrum" else ())),
                           "m/s",
                           BOUNDS_ALLOWED if name == "PastKnob" else GEOMETRY, bound))
    return out


CASE = Case("collision_spaces", "collision_spaces.x3d",
            "CollisionSpace: a box in a space nested in a space holds a ball, a ball in one space rests on a box in "
            "another, a ball inside a space's bounds but clear of its boxes falls, a disabled nested space's box "
            "lets its ball fall; useGeometry TRUE: balls through a Sphere's and a Cylinder's bounding-box corner, "
            "clear of the shapes, keep their velocity (FALSE's the same: a convention)",
            (Settings(0.5, 1 / 240),), expect,
            exercises=("CollisionSpace", "CollisionSpace.enabled", "CollisionSpace.useGeometry",
                       "CollidableShape.geometry.Cylinder"),
            mutations=(
                ("<CollidableShape DEF='NestedFloor' containerField='collidables' translation='0 -0.1 0'>\n"
                 "              <Shape containerField='shape'><Box size='1 0.2 1'/></Shape>\n"
                 "            </CollidableShape>", ""),
                ("DEF='NestedOff' containerField='collidables' enabled='false'",
                 "DEF='NestedOff' containerField='collidables'"),
                ("<CollidableShape USE='InSpaceShape' containerField='collidables'/>", ""),
                # NestedFloor moved under Gap: what a space colliding as its bounds does to it
                ("translation='0 -0.1 0'", "translation='-0.5 -0.1 0'"),
                # Dome, Drum and Knob collide as their bounding boxes (37.4.3: a Shape's bboxSize is what collides)
                ("<CollidableShape DEF='Dome' containerField='collidables' translation='4 0 0'>\n"
                 "            <Shape containerField='shape'>",
                 "<CollidableShape DEF='Dome' containerField='collidables' translation='4 0 0'>\n"
                 "            <Shape containerField='shape' bboxSize='0.6 0.6 0.6'>"),
                ("rotation='1 0 0 1.5707963267948966'>\n            <Shape containerField='shape'>",
                 "rotation='1 0 0 1.5707963267948966'>\n            <Shape containerField='shape' bboxSize='0.6 0.6 0.6'>"),
                Mutation("<CollidableShape DEF='Knob' containerField='collidables' translation='8 0 0'>\n"
                         "            <Shape containerField='shape'>",
                         "<CollidableShape DEF='Knob' containerField='collidables' translation='8 0 0'>\n"
                         "            <Shape containerField='shape' bboxSize='0.6 0.6 0.6'>", spec=False),
            ))
