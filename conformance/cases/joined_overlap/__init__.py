"""joined_overlap: bodies joined by a joint do not collide, though their collidables overlap.

Clause 37 says nothing of joined bodies and collisions, so the case holds runs to a convention:
x3drbp's rule (x3d_core/semantics/collision.py), ODE's usual one (a near callback that skips
dAreConnected pairs) and X_ITE's (Bullet's disableCollisionsBetweenLinkedBodies). Each bar turns
through the cube it is hinged in; the hinge carries no load, so a bar that does not collide
with its cube keeps turning at its start rate.

Rotor on Hub (two moving bodies) is what the mutation checks. Arm on Post, a fixed body, is the
same pair with the cube fixed: x3drbp's collision plan records a joint to a fixed body as one to
the static environment (world.py maps the fixed end to STATIC), so it skips Arm against shapes
on no body (a static floor) instead of against Post's own cube, and Arm collides with Post; the
case reports that on every backend. No mutation for it: removing its joint makes no difference
while that lasts."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import ROUNDING, ROUNDING_ANGLE, infinitesimal_lag, max_norm, physics_time
from conformance.results import Measure, Settings, accuracy, convention


APART = convention(
    "the collidables of two bodies joined by a joint never collide with each other (x3drbp; ODE's usual near "
    "callback, which skips dAreConnected pairs; X_ITE's Bullet constraints added with "
    "disableCollisionsBetweenLinkedBodies); the clause says nothing of it: alternative, they collide as any pair")
UNLOADED = accuracy("a hinge through the bar's centre of mass along a principal axis carries no load: the hub it is "
                    "hinged to stays at rest, to rounding")

# joined_overlap.x3d: bar -> the cube it is hinged in; each bar spins at JO_OMEGA about z; Hub's place
JO_PAIRS = {"Rotor": "Hub", "Arm": "Post"}
JO_HUB = np.array([0.3, 3.0, 0.0])
JO_OMEGA = 2.0
Z = np.array([0.0, 0.0, 1.0])


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each bar's angular velocity against (0, 0, w), and its angle about z (twist, unwrapped frame
    to frame: 1/30 rad a frame) against w t. A spin about a principal axis through the centre, with
    a hinge that carries no load, keeps its rate to rounding, and the exponential map turns the
    bar by it exactly; the infinitesimal update (ODE without useFiniteRotation) lags by
    closed_forms.infinitesimal_lag a second. Those are the bounds, and the tolerances: a run that
    keeps the pair apart moves each bar exactly as if it were alone, and any contact between the
    bar and the cube, which it crosses off the hinge's axis, changes its rate (how much depends
    on the engine's contact response: no closed form to halve)."""
    tr, s = traces[0], settings[0]
    out = []
    for bar, cube in JO_PAIRS.items():
        t, rot = tr.series(bar, "orientation")
        _, w = tr.series(bar, "angularVelocity")
        tp = physics_time(t, s.dt)
        twist = np.unwrap(R.twist_angle(R.from_axis_angle(rot), Z))
        rate = ROUNDING * (1 + JO_OMEGA)
        angle = ROUNDING_ANGLE + infinitesimal_lag(JO_OMEGA, s.dt) * float(tp[-1])
        out += [Measure(f"{bar}.angularVelocity - (0, 0, w) (turning through {cube})", max_norm(w - JO_OMEGA * Z),
                        rate, "rad/s", APART, rate),
                Measure(f"{bar} angle about z - w t (turning through {cube})",
                        float(np.max(np.abs(twist - JO_OMEGA * tp))), angle, "rad", APART, angle)]
    _, p = tr.series("Hub", "position")
    out.append(Measure("Hub.position moved", max_norm(p - JO_HUB), ROUNDING * (1 + float(np.linalg.norm(JO_HUB))), "m",
                       UNLOADED))
    return out


HUB_HINGE = ("<SingleAxisHingeJoint DEF='HubHinge' anchorPoint='0 3 0' axis='0 0 1'><RigidBody USE='Rotor' "
             "containerField='body1'/><RigidBody USE='Hub' containerField='body2'/></SingleAxisHingeJoint>")

CASE = Case("joined_overlap", "joined_overlap.x3d",
            "SingleAxisHingeJoint between overlapping collidables in the collider: joined bodies do not collide, each "
            "bar keeps turning at 2 rad/s through the cube it is hinged in (ODE's convention)",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("SingleAxisHingeJoint", "SingleAxisHingeJoint.anchorPoint", "SingleAxisHingeJoint.axis",
                       "CollisionCollection", "CollidableShape.geometry.Box", "RigidBody.fixed"),
            # unjoined, Rotor and Hub collide (x3drbp's rule for any other pair) and nothing else changes: the hinge
            # carried no load. What a backend that collides joined bodies does
            mutations=(Mutation(HUB_HINGE, "", spec=False),))
