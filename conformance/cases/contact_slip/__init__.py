"""contact_slip: CollisionCollection slipFactors with SLIP-1 / SLIP-2: pushed balls slide at slip times the friction force.

The clause gives slipFactors no prose; Table 37.2 (as the UOM carries it) says SLIP-1 and SLIP-2
"Apply first (second) component of slipFactors array", and the UOM that the factors are "used
for computing surface drag" (a description). What the factor does is ODE's force-dependent slip
(the friction row's constraint force mixing: the contact slides at slip times the force it
carries), x3drbp's reading and a convention: only ODE has it; the other engines refuse the flags."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import CFM_DEFAULT, ERP_DEFAULT, G, ROUNDING, honoured, max_norm, steps
from conformance.results import Measure, Settings, convention, description


SLIPS = description('CollisionCollection appliedParameters "SLIP-1": "Apply first component of slipFactors array."; '
                    '"SLIP-2": "Apply second component of slipFactors array."; slipFactors: "slipFactors used for '
                    'computing surface drag."')
FDS = convention(
    "ODE's force-dependent slip: slipFactors component n is the constraint force mixing of friction direction n's row "
    "(dContactSlip1/2), so the contact slides along it at slip times the friction force; direction 1 is ODE's "
    "dPlaneSpace of the normal (-x, then +z, for an upward normal); alternative: no slip model (Bullet, MuJoCo, DART, "
    "Chipmunk have none), or the factors along other tangents")

# contact_slip.x3d: ball -> (slip factor, push direction); each 1 kg, r 0.1, I 0.004, pushed by CS_F
CS_M, CS_R, CS_I, CS_F = 1.0, 0.1, 0.004, 5.0
CS_SLIP = (0.1, 0.05)
CS_BALLS = {"Slip1": (0, np.array([1.0, 0.0, 0.0])), "Slip2": (1, np.array([0.0, 0.0, 1.0]))}
CS_SETTLED = 0.5  # s: from here on, the slide is steady (17 and 35 time constants)


def steady_slide(slip: float) -> float:
    """The ball's speed once friction carries the push F: the contact slides at u = slip F, of which
    the ball's centre takes (1/m) / k, k = 1/m + r^2/I the friction row's inverse effective mass
    (the torque r F keeps the spin from changing then)."""
    k = 1 / CS_M + CS_R ** 2 / CS_I
    return slip * CS_F / (CS_M * k)


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each ball's velocity from CS_SETTLED on against the steady slide along its push. The slide
    reaches it as u_n = slip F (1 - a^n), a = slip / (h k + slip) (ODE's step solves the row
    implicitly; an explicit one gets there faster): the speed times a^n at CS_SETTLED. And a
    soft contact lets the ball rest d = CFM m g h / ERP deep (closed_forms' contact argument), so
    friction acts r - d below the centre: the torque r F outweighs its moment by F d, and the
    slide slows at r F d / (I m k) (the spin speeds up to keep u): that times T. The bound is the
    two, plus rounding.

    Description tolerance (closed_forms.honoured): half the steady speed, the slip ignored (the
    friction holds the ball). Convention tolerance: half the difference from the other
    direction's factor (the two read along each other's direction)."""
    tr, s = traces[0], settings[0]
    h = s.dt
    k = 1 / CS_M + CS_R ** 2 / CS_I
    sunk = CFM_DEFAULT * CS_M * G * h / ERP_DEFAULT
    out = []
    for name, (n, push) in CS_BALLS.items():
        t, v = tr.series(name, "linearVelocity")
        settled = t >= CS_SETTLED
        first = float(steps(t[settled][0], h))
        slip, other = CS_SLIP[n], CS_SLIP[1 - n]
        speed = steady_slide(slip)
        drift = CS_R * CS_F * sunk * float(t[-1]) / (CS_I * CS_M * k)
        bound = speed * (slip / (h * k + slip)) ** first + drift + ROUNDING * (1 + speed)
        error = max_norm(v[settled] - speed * push)
        quantity = f"{name}.linearVelocity (t >= {CS_SETTLED:g} s) - slip F / (m k) along the push"
        out += [Measure(quantity + " (slides)", error, honoured(bound, speed), "m/s", SLIPS, bound),
                Measure(quantity, error, honoured(bound, speed - steady_slide(other)), "m/s", FDS, bound)]
    return out


CASE = Case("contact_slip", "contact_slip.x3d",
            "CollisionCollection slipFactors 0.1 0.05 with SLIP-1, SLIP-2: balls pushed by 5 N slide steadily at "
            "slip F / (m k) = 0.143 and 0.071 m/s (ODE's force-dependent slip)",
            (Settings(2.0, 1 / 240),), expect,
            exercises=("CollisionCollection.slipFactors", "CollisionCollection.appliedParameters.SLIP-1",
                       "CollisionCollection.appliedParameters.SLIP-2", "CollisionCollection.frictionCoefficients",
                       "CollidableShape.geometry.Sphere"),
            # without the flags the factors are not applied (the collection's default, "BOUNCE", with bounce 0)
            mutations=(Mutation(" appliedParameters='\"SLIP-1\" \"SLIP-2\"'", "", spec=False),
                       # no slip: Coulomb's cone (mu 2) holds both balls, pushed at 5 N
                       Mutation(" slipFactors='0.1 0.05'", "", spec=False)))
