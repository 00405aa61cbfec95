"""contact_unapplied: a CollisionSensor's Contact nodes carry the collection's parameters that its
appliedParameters do not apply, and no friction direction where there is no friction.

37.4.4 makes the collection's parameters the defaults "assigned to all Contact nodes generated
from the CollisionSensor node", and its appliedParameters say which of them act: a Contact
carries the values and the names both (the clause lets an individual contact override "which
values are applicable" by its field of the same name). So a Contact reports bounce 0.5 though
BOUNCE is not applied, not the 0 the physics uses. The flag the scene gives,
FRICTION_COEFFICIENT-2 with frictionCoefficients 0 0, leaves the contacts without friction under
every reading of it (docs/spec-loose-ends.md, section 3: the flag as mu2, or as "apply
frictionCoefficients values"), where 37.4.7 has the direction 0, 0, 0.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import SENSOR_CONTACTS, applied_names, rests, sensor_contacts, steps
from conformance.results import Measure, Settings, spec

# contact_unapplied.x3d: the collection's parameters, as every reported Contact must carry them
CU_START = (0.0, 0.1, 0.0)
CU_VALUES = {"bounce": 0.5, "minBounceSpeed": 0.1, "frictionCoefficients": (0.0, 0.0), "surfaceSpeed": (0.3, -0.7),
             "slipCoefficients": (0.01, 0.02), "softnessErrorCorrection": 0.8, "softnessConstantForceMix": 0.0001}
CU_APPLIED = {"FRICTION_COEFFICIENT-2"}
DEFAULTS = spec("37.4.4 CollisionCollection: A set of parameters are provided that specify default values that will "
                "be assigned to all Contact nodes generated from the CollisionSensor node.")
APPLIED = spec("37.4.4 CollisionCollection: The appliedParameters indicates globally which parameters are to be "
               "applied to the collision outputs when passing information into the the rigid body physics system. "
               "These parameters specify a series of defaults that apply to all contacts generated. Individual "
               "contacts may override which values are applicable, if needed, by setting the field of the same "
               "name in the contact itself.")
NO_FRICTION = spec("37.4.7 Contact: The frictionDirection field is used to control the vector that describes which "
                   "way friction is to be applied to the contact location. If there is no friction, the direction "
                   "should be set to 0, 0, 0.")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Counts, exact: frames after the first step with no contact reported (the ball rests on the
    floor throughout: closed_forms.rests); contacts whose parameters are not the collection's (each
    to 1e-6 of the value, a browser's float32; the collection's slipFactors as slipCoefficients);
    contacts whose appliedParameters are not the collection's names (in any order and either
    spelling); and contacts whose frictionDirection is not 0 0 0."""
    tr, s = traces[0], settings[0]
    contacts = sensor_contacts(tr, "Sensor", values=tuple(CU_VALUES) + ("frictionDirection",),
                               texts=("appliedParameters",))
    t, _ = tr.series("Ball", "position")
    missing = sum(1 for time, n in zip(t.tolist(), steps(t, s.dt).tolist()) if n >= 1 and not contacts.get(time))
    found = [c for frame in contacts.values() for c in frame]
    # each read by name, in CU_VALUES' order (conformance.coverage finds the Contact fields a case judges so)
    carried = [(c["bounce"], c["minBounceSpeed"], c["frictionCoefficients"], c["surfaceSpeed"], c["slipCoefficients"],
                c["softnessErrorCorrection"], c["softnessConstantForceMix"]) for c in found]
    wrong = sum(any(value is None or not np.allclose(np.ravel(value), np.ravel(want), rtol=1e-6, atol=0.0)
                    for value, want in zip(values, CU_VALUES.values())) for values in carried)
    unnamed = sum(applied_names(c["appliedParameters"]) != CU_APPLIED for c in found)
    directed = sum(c["frictionDirection"] is None or bool(np.any(c["frictionDirection"])) for c in found)
    return (rests(tr, s, "Ball", CU_START, SENSOR_CONTACTS)
            + [Measure("frames after the first step with no contact reported", missing, 0, basis=SENSOR_CONTACTS),
               Measure("contacts whose parameters are not the collection's", wrong, 0, basis=DEFAULTS),
               Measure("contacts whose appliedParameters are not the collection's", unnamed, 0, basis=APPLIED),
               Measure("contacts without friction whose frictionDirection is not 0 0 0", directed, 0,
                       basis=NO_FRICTION)])


CASE = Case("contact_unapplied", "contact_unapplied.x3d",
            "CollisionSensor Contacts carry the collection's bounce 0.5, surfaceSpeed 0.3 -0.7 and slipFactors "
            "0.01 0.02 though appliedParameters (FRICTION_COEFFICIENT-2 alone) applies none of them, and those "
            "appliedParameters; frictionCoefficients 0 0: no friction, frictionDirection 0 0 0",
            (Settings(0.5, 1 / 240),), expect,
            exercises=("CollisionCollection.bounce", "CollisionCollection.surfaceSpeed",
                       "CollisionCollection.slipFactors", "CollisionSensor"),
            mutations=(
                (" bounce='0.5'", ""),
                (" surfaceSpeed='0.3 -0.7'", ""),
                (" slipFactors='0.01 0.02'", ""),
                # a Contact reporting its own default appliedParameters, "BOUNCE", not the collection's
                Mutation("appliedParameters='\"FRICTION_COEFFICIENT-2\"'", "appliedParameters='\"BOUNCE\"'"),
            ))
