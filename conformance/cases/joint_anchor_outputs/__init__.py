"""joint_anchor_outputs: each joint's body anchor point and body axis outputs report the anchor (and axis) as its
body carries it, in the world or in that body's own frame (the clause says both, docs/spec-loose-ends.md 22.1)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, carried, honoured, max_norm
from conformance.results import Measure, Settings, spec

# joint_anchor_outputs.x3d: no gravity; each joint's two free bodies start unturned 0.3 m either side of its
# anchor (LEVER), drifting together at 0.5 m/s and tumbling; joint -> (body1, body2, anchor, body1's start,
# body2's start, the axis outputs and the file's axes they carry)
LEVER = 0.3
JOINTS = {
    "Ball": ("BallA", "BallB", (-3.0, 1.0, 0.0), (-3.3, 1.0, 0.0), (-2.7, 1.0, 0.0), {}),
    "Hinge": ("HingeA", "HingeB", (-1.0, 1.0, 0.0), (-1.3, 1.0, 0.0), (-0.7, 1.0, 0.0), {}),
    "Hinge2": ("Hinge2A", "Hinge2B", (1.0, 1.0, 0.0), (1.0, 1.3, 0.0), (1.0, 0.7, 0.0),
               {"body1Axis": (0.6, 0.8, 0.0), "body2Axis": (-0.8, 0.6, 0.0)}),
    "Cross": ("CrossA", "CrossB", (3.0, 1.0, 0.0), (3.0, 1.0, 0.3), (3.0, 1.0, -0.3),
              {"body1Axis": (0.0, 0.6, 0.8), "body2Axis": (0.0, 0.8, -0.6)}),
}
BALL = spec("37.4.1 BallJoint: body1AnchorPoint and body2AnchorPoint represent the output that describes where the "
            "anchorPoint is relative to the two bodies local coordinate reference frame.",
            also=("37.2.5.2 Breaking joints: Each joint node will have two output-only fields that indicate the "
                  "calculated location of the relative positions within their own frame of reference.",))
HINGE = spec("37.4.12 SingleAxisHingeJoint: The body anchor point output fields report the current location of the "
             "anchor point relative to the corresponding body.")
HINGE2 = spec("37.4.8 DoubleAxisHingeJoint: The body anchor point and body axis output fields report the current "
              "location of the anchor point relative to the corresponding body.")
UNIVERSAL = spec("37.4.14 UniversalJoint: The body anchor point and body axis output fields report the current "
                 "location of the anchor point relative to the corresponding body.")
BASES = {"Ball": BALL, "Hinge": HINGE, "Hinge2": HINGE2, "Cross": UNIVERSAL}


def _either(reported: np.ndarray, world: np.ndarray, local: np.ndarray) -> float:
    """The output's error under the reading nearer to it, one reading for the whole run: world coordinates
    (as the body carries the point or axis, per frame) or the body's own frame (constant)."""
    return min(max_norm(reported - world), max_norm(reported - local))


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each output against the anchor (or axis) as its own body carries it, from the bodies' poses
    (closed_forms.carried), in either of the two frames the clause gives it (docs/spec-loose-ends.md
    22.1): in world coordinates, moving with the body (x3drbp's, ODE's; closed_forms.ANCHOR_OUTPUTS
    holds that one as a convention), or in the body's own frame, where it stays put (the body
    started unturned, so its frame's coordinates of the anchor are anchor - start, of an axis the
    axis itself). Both readings pass; the reading nearer the output is taken, one for the whole run.
    Exact but for rounding in either (ROUNDING): the joint's own outputs and the trace's poses come
    from one state.

    Spec tolerances half the nearest misreading's error, under the nearer reading as the measure
    takes it: an anchor output that is the anchorPoint field echoed (the bodies start 1 m and more
    from the origin, so their frames' coordinates differ from it by that, and the world reading by
    how far the anchor has travelled), 0, the body's own position (the lever, 0.3 m, off both), or
    the other body's anchor in its frame (0.6 m off); an axis output that is 0, or the other body's
    axis (sqrt 2 off: the joint keeps them perpendicular). The anchor's travel is read from the
    trace, capped by the lever, so a runaway cannot widen its own tolerance."""
    tr = traces[0]
    out = []
    for joint, (b1, b2, anchor, start1, start2, axes) in JOINTS.items():
        basis = BASES[joint]
        for k, (body, start) in enumerate(((b1, start1), (b2, start2)), 1):
            _, reported = tr.series(joint, f"body{k}AnchorPoint")
            world = carried(tr, body, anchor, start)
            local = np.asarray(anchor) - np.asarray(start)
            travel = float(np.max(np.linalg.norm(world - np.asarray(anchor), axis=1)))
            away = min(float(np.linalg.norm(start)), travel)  # the field echoed
            scale = 1.0 + float(np.max(np.linalg.norm(world, axis=1)))
            bound = ROUNDING * scale
            out.append(Measure(f"{joint}.body{k}AnchorPoint - the anchor as {body} carries it (world or its frame)",
                               _either(reported, world, local), honoured(bound, min(away, LEVER)), "m", basis, bound))
        for name, axis in axes.items():
            body = b1 if name == "body1Axis" else b2
            _, reported = tr.series(joint, name)
            _, q = tr.series(body, "orientation")
            world = R.rotate(R.from_axis_angle(q), np.asarray(axis))
            out.append(Measure(f"{joint}.{name} - the axis as {body} carries it (world or its frame)",
                               _either(reported, world, np.asarray(axis)), honoured(ROUNDING, 1.0), "", basis,
                               ROUNDING))
    return out


CASE = Case("joint_anchor_outputs", "joint_anchor_outputs.x3d",
            "BallJoint, SingleAxisHingeJoint, DoubleAxisHingeJoint, UniversalJoint between tumbling free bodies: "
            "body1AnchorPoint / body2AnchorPoint (and body1Axis / body2Axis) the anchor (axis) as each body carries "
            "it, in world coordinates or in the body's own frame",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("BallJoint.anchorPoint", "SingleAxisHingeJoint.anchorPoint", "DoubleAxisHingeJoint.anchorPoint",
                       "UniversalJoint.anchorPoint", "DoubleAxisHingeJoint.axis1", "DoubleAxisHingeJoint.axis2",
                       "UniversalJoint.axis1", "UniversalJoint.axis2", "BallJoint.forceOutput",
                       "SingleAxisHingeJoint.forceOutput", "DoubleAxisHingeJoint.forceOutput",
                       "UniversalJoint.forceOutput"),
            mutations=(
                # the anchor at the origin: the bodies pivot about a point 1 m and more away, and carry it
                (" anchorPoint='-3 1 0'", ""),
                (" anchorPoint='-1 1 0'", ""),
                (" anchorPoint='1 1 0'", ""),
                (" anchorPoint='3 1 0'", ""),
                (" axis2='-0.8 0.6 0'", " axis2='0 0 1'"),  # axis 2 along z: body2Axis neither of its readings
                (" axis1='0 0.6 0.8'", " axis1='1 0 0'"),  # UniversalJoint axis1 along x (still across axis2)
            ))
