"""routed_contacts: CollisionSensor contacts ROUTEd to set_contacts: they are the collection's contacts."""

from __future__ import annotations

from conformance.cases.case import Case
from conformance.cases.closed_forms import kept_rests_ghost_falls
from conformance.results import Settings, spec

SET_CONTACTS = spec("37.4.11 RigidBodyCollection: The set_contacts input field is used to provide per-frame sets "
                    "of information about contacts between bodies in this frame. These contacts are then used to "
                    "modify the location of the bodies within the scene graph when the physics model is evaluated "
                    "at the end of the frame.")


CASE = Case("routed_contacts", "routed_contacts.x3d",
            "CollisionSensor contacts ROUTEd to set_contacts: the body whose shape the sensor watches rests on "
            "the floor, the other falls through it",
            (Settings(1.0, 1 / 240),), kept_rests_ghost_falls(SET_CONTACTS),
            exercises=("RigidBodyCollection.set_contacts.fromSensor", "CollisionSensor"),
            mutations=(("<ROUTE fromNode='Sensor' fromField='contacts' toNode='World' toField='set_contacts'/>",
                        ""),  # nothing collides
                       # Kept's shape on no body: it collides, but moves nothing, and Kept falls
                       ("<CollidableShape USE='KeptShape' containerField='geometry'/>", "")))
