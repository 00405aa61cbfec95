"""conveyor: CollisionCollection surfaceSpeed with SPEED-1: a box on a static belt reaches its speed."""

from __future__ import annotations

import numpy as np

from conformance.cases.case import Case
from conformance.cases.closed_forms import friction_velocity
from conformance.results import Settings


# conveyor.x3d: the box ends moving at surfaceSpeed along ODE's first friction direction (-x)
CV_MU, CV_SPEED = 0.5, 1.5


CASE = Case("conveyor", "conveyor.x3d",
            "surfaceSpeed 1.5 0 with SPEED-1, mu 0.5, static belt: v = (-min(mu g t, 1.5), 0, 0) (ODE's motion1 "
            "along its first friction direction, -x)",
            (Settings(1.5, 1 / 240),),
            friction_velocity({"Parcel": (CV_MU, 0.0, CV_SPEED, np.array([-1.0, 0.0, 0.0]))}),
            exercises=("CollisionCollection.surfaceSpeed", "CollisionCollection.appliedParameters.SPEED-1",
                       "CollisionCollection.frictionCoefficients"),
            mutations=(
                (" surfaceSpeed='1.5 0'", ""),
                ("\n          appliedParameters='\"SPEED-1\"'", ""),
            ))
