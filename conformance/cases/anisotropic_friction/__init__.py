"""anisotropic_friction: frictionCoefficients with FRICTION_COEFFICIENT-2, a friction per friction direction.

The spec applies frictionCoefficients (37.2.5.3: the collection's coefficients, "for the primary
direction for the first value and secondary direction for the second value") along two friction
directions that the system computes (USER_FRICTION's entry in the UOM: "The system will normally
calculate the friction direction vector that is perpendicular to the contact normal"). Systems compute them differently: fixed by the
normal (ODE's dPlaneSpace: -x and +z for an upward normal; Xj3D), or with direction 1 along the
sliding velocity (Bullet's), where a sliding box meets mu1 whichever way it goes and mu2 only
resists sideways loads. So the spec measure asks each box, on its own, to slow at mu1 g or at
mu2 g (FRICTION): a box without friction, or slowed by a coefficient the scene does not give,
fails it. That the two boxes meet one coefficient each is a convention of systems whose
directions follow the normal (NORMAL_DIRECTIONS), and which box meets mu1 is ODE's
(FRICTION_DIRECTIONS). Ignoring FRICTION_COEFFICIENT-2 (mu2 taken as mu1, both boxes at mu1)
looks, in sliding, exactly like directions that follow the motion: that mutation can only fail a
convention. Not covered: directions fixed at another angle to the world axes (no implementation
found), under which a box pushed along x meets a mix of the two.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import FRICTION, FRICTION_DIRECTIONS, G, friction_fit, honoured
from conformance.results import Measure, Settings, convention


# anisotropic_friction.x3d: boxes pushed at 3 m/s along ODE's two friction directions of an
# upward normal (-x, +z)
AF_MU, AF_V0 = (0.2, 0.6), 3.0
# the friction coefficient an engine uses where a browser passes it none: Bullet's, PhysX's and
# X_ITE's (Ammo) 0.5, MuJoCo's 1
ENGINE_DEFAULTS = (0.5, 1.0)
AF_BOXES = {"Along1": (0, np.array([-1.0, 0.0, 0.0])), "Along2": (1, np.array([0.0, 0.0, 1.0]))}
NORMAL_DIRECTIONS = convention(
    "the friction directions are fixed by the contact normal, not by the motion, so boxes sent along the two "
    "directions meet one coefficient each (ODE, Xj3D, MuJoCo's contact frame); alternative: direction 1 along the "
    "sliding velocity (Bullet's), where every sliding box meets mu1")


def _apart(mu_a: float, mu_b: float, duration: float) -> float:
    """The most two boxes sliding from AF_V0 and slowing at mu_a g and mu_b g differ by in speed
    over the run: when the rougher stops (or at the end)."""
    rough, smooth = max(mu_a, mu_b), min(mu_a, mu_b)
    t = min(AF_V0 / (rough * G), duration)
    return (rough - smooth) * G * t


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each box against friction_fit() with mu1 and with mu2. Spec: the better of the two, each box
    on its own. Conventions: the better of the two assignments that give the boxes one coefficient
    each, and ODE's assignment (Along1 mu1, Along2 mu2).

    friction_fit()'s tolerances are the accuracy bounds. The tolerances (closed_forms.honoured)
    are half the nearest misreading's error (_apart: how far two decelerations' velocities get):
    for the spec, the field ignored: X3D's default coefficients 0 (the box keeps v0), or an
    engine's own default in their place (ENGINE_DEFAULTS), and the two coefficients made one
    (their mean, as an engine with one coefficient per contact has it); for the conventions, the
    other assignment."""
    tr, s = traces[0], settings[0]
    graded = {name: [friction_fit(tr, s, name, mu, AF_V0, 0.0, d) for mu in AF_MU]
              for name, (_, d) in AF_BOXES.items()}
    wrong = (0.0, sum(AF_MU) / len(AF_MU), *ENGINE_DEFAULTS)
    fits = {name: [(e, honoured(b, *(_apart(mu, w, s.duration) for w in wrong)), b)
                   for (e, b), mu in zip(pair, AF_MU)] for name, pair in graded.items()}
    swapped = _apart(*AF_MU, s.duration)
    assigned = {name: [(e, honoured(b, swapped), b) for e, b in pair] for name, pair in graded.items()}

    def better(pair: list[tuple[float, float, float]]) -> tuple[float, float, float]:
        return min(pair, key=lambda fit: fit[0] / fit[2])
    swap = min((0, 1), key=lambda sw: max(e / b for e, b in (graded[n][k ^ sw] for n, (k, _) in AF_BOXES.items())))
    out = [Measure(f"{name}.linearVelocity slows at mu1 g or mu2 g", *better(fits[name])[:2], "m/s", FRICTION,
                   better(fits[name])[2]) for name in AF_BOXES]
    out += [Measure(f"{name}.linearVelocity, the two boxes one coefficient each (the better assignment)",
                    *assigned[name][k ^ swap][:2], "m/s", NORMAL_DIRECTIONS, assigned[name][k ^ swap][2])
            for name, (k, _) in AF_BOXES.items()]
    out += [Measure(f"{name}.linearVelocity (mu{k + 1} = {AF_MU[k]:g} along ODE's friction direction {k + 1}, "
                    f"{d.tolist()})", *assigned[name][k][:2], "m/s", FRICTION_DIRECTIONS, assigned[name][k][2])
            for name, (k, d) in AF_BOXES.items()]
    return out


CASE = Case("anisotropic_friction", "anisotropic_friction.x3d",
            "frictionCoefficients 0.2 0.6 with FRICTION_COEFFICIENT-2: each box slows at mu1 g or mu2 g; with "
            "directions fixed by the normal one each, ODE's give mu1 to the one pushed along -x, mu2 along +z",
            (Settings(2.0, 1 / 240),), expect,
            exercises=("CollisionCollection.frictionCoefficients",
                       "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2", "RigidBody.linearVelocity"),
            mutations=(
                # mu2 taken as mu1: in sliding, the same as directions that follow the motion
                Mutation("appliedParameters='\"BOUNCE\" \"FRICTION_COEFFICIENT-2\"'", "appliedParameters='\"BOUNCE\"'",
                         spec=False),
                (" frictionCoefficients='0.2 0.6'", ""),
            ))
