"""cylinder_cone_shape: a Cylinder and a Cone collide where they are, not where their bounding boxes are; a Shape's
explicit bboxSize is what collides.

The clause fixes the box: "If the containing shape node is given an explicit bounding box size, the geometry shall be
approximated using that shape for the purposes of collision detection." Without one it leaves the shape open: "If
there is no bounding box, the results are implementation-dependent." So a ball over a corner of a Cylinder's or a
Cone's bounding box falling past them (the geometry itself, as every engine here collides it and x3drbp reads it) is a
convention, which a browser colliding them as their boxes differs from, and cylinder_cone_rest, which their boxes pass,
cannot show."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import CFM_DEFAULT, ERP_DEFAULT, G, ROUNDING, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, convention, spec

# OnBox's: Boxed collides as its shape field's Shape (its Cylinder, approximated by the explicit box); a collidable
# that collides as anything else fails (as nothing: OnBox falls past, 4.7 m below; as a stand-in of its own, unless
# its top is within the tolerance, 0.1 m, of the box's)
BOUNDING_BOX = spec("37.4.3 CollidableShape: If the containing shape node is given an explicit bounding box size, the "
                    "geometry shall be approximated using that shape for the purposes of collision detection.",
                    also=("37.4.3 CollidableShape: The shape field uses the geometry proxy for specifying which "
                          "geometry best represents the collidable object.",))
ITSELF = convention("a collidable Cylinder or Cone whose Shape gives no bounding box collides as itself (x3drbp's "
                    "reading, and every engine here: ODE's, Bullet's, MuJoCo's, DART's, PhysX's and Drake's own "
                    "cylinder or a 64-gon hull of the cone); the clause: \"If there is no bounding box, the results are "
                    "implementation-dependent\", so its bounding box, or another approximation, conforms too")

# cylinder_cone_shape.x3d: shapes radius 0.5 m, height 1 m, centred at y = 0; balls radius 0.05 m, 1 kg, from rest
CCS_H, CCS_BALL, CCS_M, CCS_Y0 = 1.0, 0.05, 1.0, 0.7
CCS_PAST = ("PastDrum", "PastSpire")  # from y = 0.7 over a bounding box's corner, clear of the shape
CCS_TOP = CCS_H / 2 + CCS_BALL  # a ball at rest on a bounding box's top (0.55)
CCS_BOX_START = np.array([1.95, 1.0, 0.45])  # OnBox
CCS_BOX_REST = np.array([1.95, 1.4 / 2 + CCS_BALL, 0.45])  # on Boxed's bboxSize 1 1.4 1


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """PastDrum and PastSpire touch nothing: v = -g t, exact for every one-step scheme, ROUNDING.
    OnSlope meets the cone's slope and runs off it: by the end it is below the cone's base
    (y < -h/2); nothing closer is fixed (its path depends on the contact's friction and solve), and
    nothing short of a shape that holds it fails that. OnBox lands on Boxed's box top (0.25 m of
    fall, 0.23 s) and rests there by the end within the contact argument of closed_forms (a step
    of unresisted gravity, g h^2, and ODE's softness, CFM m g h / ERP; the impact's depth, at most
    a step at the landing speed, is corrected at ERP 0.8 a step over the 0.77 s left). Those are
    the accuracy bounds; the tolerances (closed_forms.honoured) are half the misreading's error:
    each ball held on a bounding box's top, at rest from its landing (the velocity g (T - 0.175 s)
    off at the end; OnSlope h + r above the base); for OnBox, Boxed's bboxSize ignored (its
    cylinder lets the ball fall past: 4.7 m below) or replaced by the cylinder's own bounds (the
    ball held 0.2 m lower)."""
    tr, s = traces[0], settings[0]
    t, _ = tr.series("PastDrum", "linearVelocity")
    tp = physics_time(t, s.dt)
    T = float(tp[-1])
    v_bound = ROUNDING * (1 + G * T)
    held = G * (T - np.sqrt(2 * (CCS_Y0 - CCS_TOP) / G))  # the speed a ball held from its landing lacks at the end
    out = []
    for name in CCS_PAST:
        _, v = tr.series(name, "linearVelocity")
        out.append(Measure(f"{name}.linearVelocity - free fall past the bounding box's corner, -g t",
                           max_norm(v - np.outer(-G * tp, [0.0, 1.0, 0.0])), honoured(v_bound, held), "m/s", ITSELF,
                           v_bound))
    _, slope = tr.series("OnSlope", "position")
    out.append(Measure("OnSlope height at the end above the cone's base (ran off the slope: below it)",
                       max(float(slope[-1, 1]) + CCS_H / 2, 0.0), honoured(ROUNDING, CCS_TOP + CCS_H / 2), "m", ITSELF))
    _, p = tr.series("OnBox", "position")
    rest = G * s.dt ** 2 + CFM_DEFAULT * CCS_M * G * s.dt / ERP_DEFAULT + ROUNDING
    fell = CCS_BOX_REST[1] - (CCS_BOX_START[1] - 0.5 * G * T * T)
    out.append(Measure("OnBox position at the end - at rest on Boxed's bboxSize box", max_norm(p[-1:] - CCS_BOX_REST),
                       honoured(rest, fell, CCS_BOX_REST[1] - CCS_TOP), "m", BOUNDING_BOX, rest))
    return out


CASE = Case("cylinder_cone_shape", "cylinder_cone_shape.x3d",
            "Cylinder and Cone (r 0.5, h 1) without a bounding box: balls over their bounding boxes' corners fall past "
            "(v = -g t), one over the cone's slope runs off (convention: the clause leaves them implementation-"
            "dependent); a Cylinder whose Shape gives bboxSize 1 1.4 1 holds a ball on that box's top (spec)",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("CollidableShape.geometry.Cylinder", "CollidableShape.geometry.Cone", "CollisionCollection"),
            # Boxed's bounding box dropped: its cylinder collides, and OnBox falls past; Drum and Spire made their
            # bounding boxes (a reading the clause allows: conventions)
            mutations=(Mutation(" bboxSize='1 1.4 1'", ""),
                       Mutation("<Cylinder height='1' radius='0.5'/>", "<Box size='1 1 1'/>", spec=False),
                       Mutation("<Cone bottomRadius='0.5' height='1'/>", "<Box size='1 1 1'/>", spec=False)))
