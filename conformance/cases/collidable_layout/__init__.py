"""collidable_layout: CollidableOffset placement, CollisionSpace grouping, and enabled FALSE collidables."""

from __future__ import annotations

from collections.abc import Sequence

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import falls, rests
from conformance.results import Measure, Settings, spec

# collidable_layout.x3d: five 1 kg balls of radius 0.1, each put down touching its own floor
ON_OFFSET, ON_SPACE = (-2.7, 0.4, 0.0), (0.0, 0.1, 0.0)
OFF = {"OffOffset": (-1.5, 0.1, 0.0), "OffSpace": (1.5, 0.1, 0.0), "OffShape": (3.0, 0.1, 0.0)}
OFFSET = spec("37.4.2 CollidableOffset: The CollidableOffset node is used to reposition a piece of geometry relative "
              "to the center of the owning body while keeping it consistent within the geometry space.")
SPACE = spec("37.4.6 CollisionSpace: The CollisionSpace node holds a collection of objects in the collidables field "
             "that can be considered as a single entity for resolution of inter-object collisions with other groups "
             "of collidable objects.")
ELIGIBLE = spec("37.3.1 X3DNBodyCollidableNode: The enabled field is used to specify whether a collidable object is "
                "eligible for collision detection interactions.")
SPACE_ENABLED = spec("37.3.1 X3DNBodyCollisionSpaceNode: The enabled field specifies whether the collision space is to "
                     "be considered during collision processing.")
BASES = {"OffOffset": ELIGIBLE, "OffSpace": SPACE_ENABLED, "OffShape": ELIGIBLE}


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """OnOffset and OnSpace rest on their floors, the other three fall through theirs
    (closed_forms.rests and falls argue the bounds: one step of unresisted fall and ODE's
    softness; free fall exact but for rounding). The tolerances are half the misreading's error:
    a resting ball whose floor does not collide where the scene puts it (the offset's
    translation or rotation ignored: the box is then far off, or 0.2 m wide under a ball 0.3 m
    off its centre, and the ball falls), and a falling ball held by a floor that should not
    collide (its acceleration 0, not g). OffSpace's disabled space is held to the enabled sentence
    of X3DNBodyCollisionSpaceNode (the text prints it as a second 37.3.1)."""
    tr, s = traces[0], settings[0]
    out = rests(tr, s, "OnOffset", ON_OFFSET, OFFSET) + rests(tr, s, "OnSpace", ON_SPACE, SPACE)
    for name, start in OFF.items():
        out += falls(traces, settings, name, start, BASES[name])
    return out


CASE = Case("collidable_layout", "collidable_layout.x3d",
            "static collidables: a CollidableOffset translated and turned holds a ball where it puts its box; a "
            "CollisionSpace's box holds one; boxes in a disabled CollidableOffset, CollisionSpace or CollidableShape "
            "let theirs fall",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("CollidableOffset.translation", "CollidableOffset.rotation", "CollidableOffset.enabled",
                       "CollisionSpace", "CollisionSpace.enabled", "CollidableShape.enabled"),
            mutations=(
                (" translation='-3 0.2 0'", ""),
                ("rotation='0 0 1 1.5707963267948966'", ""),
                ("<CollidableShape DEF='RaisedFloor' containerField='collidable'>\n"
                 "            <Shape containerField='shape'><Box size='0.2 1 1'/></Shape>\n"
                 "          </CollidableShape>", ""),
                ("DEF='Dropped' containerField='collidables' enabled='false'",
                 "DEF='Dropped' containerField='collidables'"),
                ("<CollidableShape DEF='GroupedFloor' containerField='collidables' translation='0 -0.1 0'>\n"
                 "            <Shape containerField='shape'><Box size='1 0.2 1'/></Shape>\n"
                 "          </CollidableShape>", ""),
                Mutation("DEF='Ignored' containerField='collidables' enabled='false'",
                         "DEF='Ignored' containerField='collidables'", spec=False),
                (" translation='3 -0.1 0' enabled='false'", " translation='3 -0.1 0'"),
            ))
