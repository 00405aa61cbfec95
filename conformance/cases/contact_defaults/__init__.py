"""contact_defaults: a CollisionSensor's Contact nodes carry the collection's contact parameters."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import (CFM_DEFAULT, ERP_DEFAULT, SENSOR_CONTACTS, G, applied_names, honoured,
                                            rests, sensor_contacts, steps)
from conformance.results import Measure, Settings, convention, spec

# contact_defaults.x3d: the collection's parameters, as every reported Contact must carry them
CD_START, CD_R, CD_M = (0.0, 0.1, 0.0), 0.1, 1.0
CD_VALUES = {"bounce": 0.3, "minBounceSpeed": 0.5, "frictionCoefficients": (0.4, 0.6),
             "softnessErrorCorrection": 0.6, "softnessConstantForceMix": 0.001, "slipCoefficients": (0.0, 0.0),
             "surfaceSpeed": (0.0, 0.0)}
CD_APPLIED = {"BOUNCE", "FRICTION_COEFFICIENT-2", "ERROR_REDUCTION", "CONSTANT_FORCE"}
DEFAULTS = spec("37.4.4 CollisionCollection: A set of parameters are provided that specify default values that will "
                "be assigned to all Contact nodes generated from the CollisionSensor node.")
DIRECTION = spec("37.4.7 Contact: The frictionDirection field is used to control the vector that describes which "
                 "way friction is to be applied to the contact location. If there is no friction, the direction "
                 "should be set to 0, 0, 0.")
SOFT = convention("ODE's contact softness with ERROR_REDUCTION and CONSTANT_FORCE: the contact's rows take "
                  "softnessErrorCorrection as ERP and softnessConstantForceMix as CFM, a spring that rests a body "
                  "m g h CFM / ERP deep; the clause says only that the force mix makes the surfaces 'appear to be "
                  "somewhat soft'")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Counts, exact: frames after the first step with no contact reported (the ball rests on the
    floor throughout: closed_forms.rests), contacts whose parameters are not the collection's (each
    the field's value as the scene gives it; the collection's slipFactors and surfaceSpeed at their
    defaults, 0 0, as slipCoefficients and surfaceSpeed), and contacts whose frictionDirection is
    not a unit vector across the contact normal (there is friction) to 1e-9.

    Convention (ODE's soft contact): the ball rests m g h CFM / ERP = 6.8e-5 m deep at the end
    (the spring-damper's transient, decaying at k/c = 360 /s, long gone; bound 0.1 % of the depth
    for the contact solve's residual: ODE's quick-step leaves 3e-5 of it); the tolerance half the
    depth's change where the softness is ignored (the world's CFM and ERP: 5e-7 m)."""
    tr, s = traces[0], settings[0]
    contacts = sensor_contacts(tr, "Sensor", values=tuple(CD_VALUES) + ("frictionDirection",),
                               texts=("appliedParameters",))
    t, _ = tr.series("Ball", "position")
    missing = sum(1 for time, n in zip(t.tolist(), steps(t, s.dt).tolist()) if n >= 1 and not contacts.get(time))
    wrong = skewed = 0
    for found in contacts.values():
        for c in found:
            carried = (c["bounce"], c["minBounceSpeed"], c["frictionCoefficients"], c["softnessErrorCorrection"],
                       c["softnessConstantForceMix"], c["slipCoefficients"], c["surfaceSpeed"])
            wrong += any(value is None or not np.allclose(np.ravel(value), np.ravel(want), rtol=1e-6, atol=0.0)
                         for value, want in zip(carried, CD_VALUES.values()))
            wrong += applied_names(c["appliedParameters"]) != CD_APPLIED
            d = c["frictionDirection"]
            skewed += (d is None or abs(float(np.linalg.norm(d)) - 1.0) > 1e-9
                       or abs(float(d @ c["contactNormal"])) > 1e-9)
    _, p = tr.series("Ball", "position")
    h = s.dt
    soft = CD_M * G * h * CD_VALUES["softnessConstantForceMix"] / CD_VALUES["softnessErrorCorrection"]
    stiff = CD_M * G * h * CFM_DEFAULT / ERP_DEFAULT
    depth = CD_R - float(p[-1, 1])
    return (rests(tr, s, "Ball", CD_START, SENSOR_CONTACTS)
            + [Measure(f"Ball depth at the end - m g h CFM / ERP ({soft:.3g} m)", abs(depth - soft),
                       honoured(1e-3 * soft, soft - stiff), "m", SOFT, 1e-3 * soft)]
            + [Measure("frames after the first step with no contact reported", missing, 0, basis=SENSOR_CONTACTS),
               Measure("contacts whose parameters are not the collection's", wrong, 0, basis=DEFAULTS),
               Measure("contacts whose frictionDirection is not a unit vector across the normal", skewed, 0,
                       basis=DIRECTION)])


CASE = Case("contact_defaults", "contact_defaults.x3d",
            "CollisionSensor Contacts carry the collection's appliedParameters, bounce 0.3, minBounceSpeed 0.5, "
            "frictionCoefficients 0.4 0.6, softnessErrorCorrection 0.6, softnessConstantForceMix 0.001 (and its "
            "default slip and surface speed); frictionDirection across the normal",
            (Settings(0.5, 1 / 240),), expect,
            exercises=("CollisionCollection.softnessErrorCorrection", "CollisionCollection.softnessConstantForceMix",
                       "CollisionCollection.bounce", "CollisionCollection.minBounceSpeed",
                       "CollisionCollection.frictionCoefficients", "CollisionSensor"),
            mutations=(
                (" softnessErrorCorrection='0.6'", ""),
                (" softnessConstantForceMix='0.001'", ""),
                (" minBounceSpeed='0.5'", ""),
                ("appliedParameters='\"BOUNCE\" \"FRICTION_COEFFICIENT-2\" \"ERROR_REDUCTION\" \"CONSTANT_FORCE\"'",
                 "appliedParameters='\"BOUNCE\" \"FRICTION_COEFFICIENT-2\"'"),
            ))
