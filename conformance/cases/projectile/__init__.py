"""projectile: RigidBody.linearVelocity: a parabola from an initial velocity."""

from __future__ import annotations

from conformance.cases.case import Case
from conformance.cases.closed_forms import G, ballistic
from conformance.results import Settings, spec


VELOCITY = spec("37.4.10 RigidBody: The velocity fields then report the changed values as a result of the "
                "application of the physics model in each frame.")


CASE = Case("projectile", "projectile.x3d",
            "RigidBody.linearVelocity 3 4 1: p = p0 + v0 t + g t^2/2",
            (Settings(1.0, 1 / 240),),
            ballistic("Shot", (0, 1, 0), (3, 4, 1), (0, -G, 0), VELOCITY),
            convergence="Shot.position", expected_order=1.0, exercises=("RigidBody.linearVelocity",),
            mutations=((" linearVelocity='3 4 1'", ""),))
