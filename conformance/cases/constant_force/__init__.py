"""constant_force: RigidBody.forces: two forces summed, a constant acceleration."""

from __future__ import annotations

from conformance.cases.case import Case
from conformance.cases.closed_forms import FORCES, G_DEFAULT, ballistic
from conformance.results import Settings


CASE = Case("constant_force", "constant_force.x3d",
            "RigidBody.forces (4 0 0) + (0 0 -2) N on 2 kg: a = F/m + g",
            (Settings(1.0, 1 / 240),),
            # misread: either force dropped (a browser applying the first set only), or no force at all
            ballistic("Pushed", (0, 5, 0), (0, 0, 0), (2.0, -G_DEFAULT, -1.0), FORCES,
                      misread=((0.0, -G_DEFAULT, -1.0), (2.0, -G_DEFAULT, 0.0), (0.0, -G_DEFAULT, 0.0))),
            convergence="Pushed.position", expected_order=1.0, exercises=("RigidBody.forces",),
            mutations=(("forces='4 0 0, 0 0 -2'", "forces='4 0 0'"),))
