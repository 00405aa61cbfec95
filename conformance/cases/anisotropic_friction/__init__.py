"""anisotropic_friction: frictionCoefficients with FRICTION_COEFFICIENT-2, a friction per ODE direction."""

from __future__ import annotations

import numpy as np

from conformance.cases.case import Case
from conformance.cases.closed_forms import friction_velocity
from conformance.results import Settings


# anisotropic_friction.x3d: boxes pushed at 3 m/s along ODE's two friction directions of an
# upward normal (-x, +z)
AF_MU, AF_V0 = (0.2, 0.6), 3.0
AF_BOXES = {"Along1": (0, np.array([-1.0, 0.0, 0.0])), "Along2": (1, np.array([0.0, 0.0, 1.0]))}


CASE = Case("anisotropic_friction", "anisotropic_friction.x3d",
            "frictionCoefficients 0.2 0.6 with FRICTION_COEFFICIENT-2: a box pushed along -x (ODE's first friction "
            "direction) slows at mu1 g, one pushed along +z at mu2 g",
            (Settings(2.0, 1 / 240),),
            friction_velocity({name: (AF_MU[k], AF_V0, 0.0, d) for name, (k, d) in AF_BOXES.items()}),
            exercises=("CollisionCollection.frictionCoefficients",
                       "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2", "RigidBody.linearVelocity"),
            mutations=(
                ("appliedParameters='\"BOUNCE\" \"FRICTION_COEFFICIENT-2\"'", "appliedParameters='\"BOUNCE\"'"),
                (" frictionCoefficients='0.2 0.6'", ""),
            ))
