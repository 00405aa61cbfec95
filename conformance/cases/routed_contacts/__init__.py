"""routed_contacts: CollisionSensor contacts ROUTEd to set_contacts: they are the collection's contacts."""

from __future__ import annotations

from conformance.cases.case import Case
from conformance.cases.closed_forms import kept_rests_ghost_falls
from conformance.results import Settings


CASE = Case("routed_contacts", "routed_contacts.x3d",
            "CollisionSensor contacts ROUTEd to set_contacts: the body whose shape the sensor watches rests on "
            "the floor, the other falls through it",
            (Settings(1.0, 1 / 240),), kept_rests_ghost_falls,
            exercises=("RigidBodyCollection.set_contacts.fromSensor", "CollisionSensor"),
            # nothing collides
            mutations=(("<ROUTE fromNode='Sensor' fromField='contacts' toNode='World' toField='set_contacts'/>", ""),))
