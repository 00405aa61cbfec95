"""constant_force: RigidBody.forces: two forces summed, a constant acceleration."""

from __future__ import annotations

from conformance.cases.case import Case
from conformance.cases.closed_forms import FORCES, G_DEFAULT, ballistic
from conformance.results import Settings, also

# F/m with m = 2 kg: a mass read in any other unit (2 g, 2 lb) or ignored (1 kg) is 2.2 m/s^2 off at least, at a
# tolerance of 0.5 m/s^2
FORCES_IN_KG = also(FORCES, "37.2.5.1 Initial coordinate system: Mass is defined in kilograms.",
                    "37.4.10 RigidBody: The mass field indicates the mass of the body in kilograms.")


CASE = Case("constant_force", "constant_force.x3d",
            "RigidBody.forces (4 0 0) + (0 0 -2) N on 2 kg: a = F/m + g",
            (Settings(1.0, 1 / 240),),
            # misread: either force dropped (a browser applying the first set only), or no force at all
            ballistic("Pushed", (0, 5, 0), (0, 0, 0), (2.0, -G_DEFAULT, -1.0), FORCES_IN_KG,
                      misread=((0.0, -G_DEFAULT, -1.0), (2.0, -G_DEFAULT, 0.0), (0.0, -G_DEFAULT, 0.0))),
            convergence="Pushed.position", expected_order=1.0, exercises=("RigidBody.forces",),
            mutations=(("forces='4 0 0, 0 0 -2'", "forces='4 0 0'"),))
