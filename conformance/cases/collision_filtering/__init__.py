"""collision_filtering: CollisionCollection collidables: only the listed shapes collide."""

from __future__ import annotations

from conformance.cases.case import Case
from conformance.cases.closed_forms import kept_rests_ghost_falls
from conformance.results import Settings, spec

# the floor and Kept's shape are in the collection, Ghost's is not
COLLIDABLES = spec("37.4.4 CollisionCollection: The CollisionCollection node holds a collection of objects in the "
                   "collidables field that can be managed as a single entity for resolution of inter-object "
                   "collisions with other groups of collidable objects.")


CASE = Case("collision_filtering", "collision_filtering.x3d",
            "CollisionCollection collidables: a body whose shape is in the collider rests on the floor, one whose "
            "shape is not falls through it",
            (Settings(1.0, 1 / 240),), kept_rests_ghost_falls(COLLIDABLES),
            exercises=("CollisionCollection", "CollidableShape.geometry.Sphere"),
            mutations=(
                ("<CollidableShape containerField='collidables' USE='KeptShape'/>", ""),  # emptied
                ("<CollidableShape containerField='collidables' USE='KeptShape'/>",
                 "<CollidableShape containerField='collidables' USE='KeptShape'/>"
                 "<CollidableShape containerField='collidables' USE='GhostShape'/>"),  # every body collides
                # Kept's collidable without its geometry: nothing of Kept to collide
                ("<CollidableShape DEF='KeptShape' containerField='geometry'>\n"
                 "          <Shape containerField='shape'><Sphere radius='0.1'/></Shape>",
                 "<CollidableShape DEF='KeptShape' containerField='geometry'>"),
                # no collider: nothing collides, and Kept falls too
                ("      <CollisionCollection DEF='Contacts'>\n"
                 "        <CollidableShape containerField='collidables' USE='KeptShape'/>\n"
                 "        <CollidableShape containerField='collidables' DEF='Floor' translation='0 -0.1 0'>\n"
                 "          <Shape containerField='shape'><Box size='4 0.2 2'/></Shape>\n"
                 "        </CollidableShape>\n"
                 "      </CollisionCollection>\n", ""),
            ))
