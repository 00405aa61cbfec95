"""free_fall: RigidBodyCollection.gravity: a ball falls at g = 9.81."""

from __future__ import annotations

from conformance.cases.case import Case
from conformance.cases.closed_forms import G, GRAVITY, ballistic
from conformance.results import Settings


CASE = Case("free_fall", "free_fall.x3d",
            "RigidBodyCollection.gravity 0 -9.81 0: y = y0 - g t^2/2, v = -g t",
            (Settings(1.0, 1 / 240),),
            ballistic("Ball", (0, 10, 0), (0, 0, 0), (0, -G, 0), GRAVITY),
            convergence="Ball.position", expected_order=1.0, exercises=("RigidBodyCollection.gravity",),
            mutations=((" gravity='0 -9.81 0'", ""),))
