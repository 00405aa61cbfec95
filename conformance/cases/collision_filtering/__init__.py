"""collision_filtering: CollisionCollection collidables: only the listed shapes collide."""

from __future__ import annotations

from conformance.cases.case import Case
from conformance.cases.closed_forms import kept_rests_ghost_falls
from conformance.results import Settings


CASE = Case("collision_filtering", "collision_filtering.x3d",
            "CollisionCollection collidables: a body whose shape is in the collider rests on the floor, one whose "
            "shape is not falls through it",
            (Settings(1.0, 1 / 240),), kept_rests_ghost_falls,
            exercises=("CollisionCollection", "CollidableShape.geometry.Sphere"),
            mutations=(
                ("<CollidableShape containerField='collidables' USE='KeptShape'/>", ""),  # emptied
                ("<CollidableShape containerField='collidables' USE='KeptShape'/>",
                 "<CollidableShape containerField='collidables' USE='KeptShape'/>"
                 "<CollidableShape containerField='collidables' USE='GhostShape'/>"),  # every body collides
            ))
