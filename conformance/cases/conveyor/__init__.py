"""conveyor: CollisionCollection surfaceSpeed with SPEED-1: a box on a static belt reaches its speed.

The spec gives surfaceSpeed as the speed in the two friction directions and leaves friction
direction 1 to the system (any tangent of the belt): that the parcel is driven up to 1.5 m/s along
one fixed horizontal direction is the spec's; that the direction is -x, ODE's first friction
direction of the belt's upward normal, is a convention (FRICTION_DIRECTIONS). The scene applies
FRICTION_COEFFICIENT-2 (equal coefficients), so the friction that drives the parcel applies under
every reading of the UOM's table 37.2; without the flag, applying mu at all would be ODE's reading."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import FRICTION_DIRECTIONS, friction_fit, honoured
from conformance.results import Measure, Settings, spec


# conveyor.x3d: the box ends moving at surfaceSpeed along ODE's first friction direction (-x)
CV_MU, CV_SPEED, CV_ODE = 0.5, 1.5, np.array([-1.0, 0.0, 0.0])
SURFACE_SPEED = spec("37.4.4 CollisionCollection: The surfaceSpeed field defines the speed in the two friction "
                     "directions in metres per second. This is used to indicate if the contact surface is moving "
                     "independently of the motion of the bodies.")


def belt_direction(tr: TraceView) -> np.ndarray:
    """The horizontal direction the parcel ends up moving in (ODE's, where it does not move)."""
    v = tr.series("Parcel", "linearVelocity")[1][-1] * np.array([1.0, 0.0, 1.0])
    n = float(np.linalg.norm(v))
    return v / n if n > 1e-9 else CV_ODE


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """friction_fit() along the direction the parcel ends up in (the spec: some friction direction
    of the belt) and along -x (ODE's first friction direction). friction_fit()'s tolerances are
    the accuracy bounds; the tolerances (closed_forms.honoured) are half the misreading's error:
    surfaceSpeed ignored (the parcel stays put: 1.5 m/s off), and for the convention the other
    friction direction (a quarter turn off: sqrt(2) x 1.5 m/s)."""
    tr, s = traces[0], settings[0]
    d = belt_direction(tr)
    along, bound = friction_fit(tr, s, "Parcel", CV_MU, 0.0, CV_SPEED, d)
    ode, ode_bound = friction_fit(tr, s, "Parcel", CV_MU, 0.0, CV_SPEED, CV_ODE)
    return [Measure(f"Parcel.linearVelocity reaches surfaceSpeed {CV_SPEED:g} at mu g along one horizontal direction "
                    "(the one it ends up in)", along, honoured(bound, CV_SPEED), "m/s", SURFACE_SPEED, bound),
            Measure(f"Parcel.linearVelocity along ODE's first friction direction {CV_ODE.tolist()}", ode,
                    honoured(ode_bound, math.sqrt(2) * CV_SPEED), "m/s", FRICTION_DIRECTIONS, ode_bound)]


CASE = Case("conveyor", "conveyor.x3d",
            "surfaceSpeed 1.5 0 with SPEED-1, mu 0.5, static belt: v = min(mu g t, 1.5) along one horizontal "
            "direction (ODE's motion1 along its first friction direction, -x)",
            (Settings(1.5, 1 / 240),), expect,
            exercises=("CollisionCollection.surfaceSpeed", "CollisionCollection.appliedParameters.SPEED-1",
                       "CollisionCollection.frictionCoefficients"),
            mutations=(
                (" surfaceSpeed='1.5 0'", ""),
                ("appliedParameters='\"SPEED-1\" \"FRICTION_COEFFICIENT-2\"'",
                 "appliedParameters='\"FRICTION_COEFFICIENT-2\"'"),
            ))
