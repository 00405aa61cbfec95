"""collection_auto_disable: RigidBodyCollection autoDisable and its thresholds, for bodies that set none."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import ROUNDING, honoured, max_norm, physics_time, stops_at
from conformance.results import Measure, Settings, convention, spec

# collection_auto_disable.x3d: body -> (start, linear and angular velocity); disableTime 0.25 s
CD_TIME = 0.25
CD_BODIES = {"Slow": ((0.0, 0.0, 0.0), (0.05, 0.0, 0.0), (0.0, 0.0, 0.05)),
             "Coasting": ((0.0, 1.0, 0.0), (0.05, 0.0, 0.0), (0.0, 0.0, 0.5)),
             "Turning": ((0.0, 2.0, 0.0), (0.5, 0.0, 0.0), (0.0, 0.0, 0.05)),
             "OwnRules": ((0.0, 3.0, 0.0), (0.5, 0.0, 0.0), (0.0, 0.0, 0.05))}
# the collection's own disable fields (37.4.11; closed_forms.AT_REST is RigidBody's sentence)
AT_REST = spec("37.4.11 RigidBodyCollection: These values define tolerances for which the physics model should start "
               "to ignore this object in any calculation, thus resulting in them being actually at rest and not "
               "subject to these instability conditions. Once any one of these values is achieved, the body is "
               "considered as being at rest, unless acted upon by an external force (e. g., collision or action of "
               "connected joint).",
               # Slow's: the collection's autoDisable TRUE ignored, it drifts on at its own speeds, twice the tolerance
               also=("37.4.11 RigidBodyCollection: It may be enabled by setting the autoDisable field to TRUE.",))
ANY_ONE = convention("any one speed under its threshold, held for disableTime, stops a body (x3drbp, the literal "
                     "reading of 'Once any one of these values is achieved'), the collection's thresholds for a body "
                     "that sets no autoDisable of its own; ODE, Xj3D: both speeds under their thresholds for the time "
                     "(Coasting, Turning and OwnRules never stop)")


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Slow: both its speeds are under the collection's thresholds from the start, so under either
    reading it is at rest once disableTime has passed: its velocities 0 (to ROUNDING) over the last
    half of the run (0.5 s to 1 s, a quarter second after disableTime); the tolerance half its own
    speeds (the collection's autoDisable ignored: it drifts on).

    The others (convention ANY_ONE): closed_forms.stops_at, the exact moment, ceil(disableTime/h)
    steps."""
    tr, s = traces[0], settings[0]
    t, v = tr.series("Slow", "linearVelocity")
    _, w = tr.series("Slow", "angularVelocity")
    late = physics_time(t, s.dt) >= 0.5
    _, v0, w0 = CD_BODIES["Slow"]
    out = [Measure("Slow |linearVelocity| from 0.5 s (at rest)", max_norm(v[late]),
                   honoured(ROUNDING, float(np.linalg.norm(v0))), "m/s", AT_REST, ROUNDING),
           Measure("Slow |angularVelocity| from 0.5 s (at rest)", max_norm(w[late]),
                   honoured(ROUNDING, float(np.linalg.norm(w0))), "rad/s", AT_REST, ROUNDING)]
    for name in ("Coasting", "Turning", "OwnRules"):
        out += stops_at(tr, s, name, *CD_BODIES[name], CD_TIME, ANY_ONE)
    return out


CASE = Case("collection_auto_disable", "collection_auto_disable.x3d",
            "RigidBodyCollection autoDisable (0.1 m/s, 0.1 rad/s, 0.25 s) for the bodies that set none: a body "
            "under both thresholds is at rest after disableTime; under one (x3drbp's any-one reading) it stops "
            "there too; a body's own thresholds rule it",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBodyCollection.autoDisable", "RigidBodyCollection.disableLinearSpeed",
                       "RigidBodyCollection.disableAngularSpeed", "RigidBodyCollection.disableTime",
                       "RigidBody.autoDisable", "RigidBody.disableAngularSpeed"),
            mutations=(
                (" gravity='0 0 0' autoDisable='true'", " gravity='0 0 0'"),  # Slow drifts on
                *(Mutation(old, new, spec=False) for old, new in (
                    (" autoDisable='true' disableLinearSpeed='0.1'", " autoDisable='true'"),  # Coasting never stops
                    ("\n        disableAngularSpeed='0.1' disableTime='0.25'>", "\n        disableTime='0.25'>"),
                    ("\n        disableAngularSpeed='0.1' disableTime='0.25'>", "\n        disableAngularSpeed='0.1'>"),
                    ("\n          disableAngularSpeed='0.1' disableTime='0.25'/>", "\n          disableTime='0.25'/>"),
                )),
            ))
