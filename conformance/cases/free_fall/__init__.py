"""free_fall: RigidBodyCollection.gravity: a ball falls at g = 9.81."""

from __future__ import annotations

from conformance.cases.case import Case
from conformance.cases.closed_forms import G, GRAVITY, ballistic
from conformance.results import Settings, also

# the ball is on no joint: a browser that evaluates only jointed bodies leaves it where it is, and its
# acceleration measure, 9.81 m/s^2 off at a tolerance of 5 mm/s^2, fails
STANDALONE = also(GRAVITY, "37.2.3 Bodies: Bodies are not required to be connected by a joint and may exist as a "
                  "standalone entity.")


CASE = Case("free_fall", "free_fall.x3d",
            "RigidBodyCollection.gravity 0 -9.81 0: y = y0 - g t^2/2, v = -g t",
            (Settings(1.0, 1 / 240),),
            ballistic("Ball", (0, 10, 0), (0, 0, 0), (0, -G, 0), STANDALONE),
            convergence="Ball.position", expected_order=1.0, exercises=("RigidBodyCollection.gravity",),
            mutations=((" gravity='0 -9.81 0'", ""),))
