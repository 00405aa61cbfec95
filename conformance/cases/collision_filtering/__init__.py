"""collision_filtering: CollisionCollection collidables: only the listed shapes collide."""

from __future__ import annotations

from conformance.cases.case import Case
from conformance.cases.closed_forms import kept_rests_ghost_falls
from conformance.results import Settings, also, spec

# the floor and Kept's shape are in the collection, Ghost's is not
COLLIDABLES = spec("37.4.4 CollisionCollection: The CollisionCollection node holds a collection of objects in the "
                   "collidables field that can be managed as a single entity for resolution of inter-object "
                   "collisions with other groups of collidable objects.")
# Kept's: it rests on the floor only through its geometry field's collidable, in the collider, with no sensor and no
# ROUTE; a body not joined to its collidable, or a collider whose contacts act only routed to set_contacts, lets it
# fall, g T^2 / 2 = 4.9 m at a tolerance of half that (Ghost falls either way)
KEPT = also(COLLIDABLES, "37.4.10 RigidBody: The geometry field is used to connect the body modelled by the physics "
            "engine implementation to the real geometry of the scene through the use of collidable nodes.",
            "37.4.11 RigidBodyCollection: The collider field associates a collision collection with this rigid body "
            "collection allowing seamless updates and integration without the need to use the X3D event model.")


CASE = Case("collision_filtering", "collision_filtering.x3d",
            "CollisionCollection collidables: a body whose shape is in the collider rests on the floor, one whose "
            "shape is not falls through it",
            (Settings(1.0, 1 / 240),), kept_rests_ghost_falls(COLLIDABLES, KEPT),
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
