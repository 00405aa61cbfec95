"""relative_turns: UniversalJoint: the two bodies' turns about axis1 x axis2 equal; SingleAxisHingeJoint: angle and
angleRate the bodies' relative turn."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ERROR_CORRECTION, ROUNDING, ROUNDING_ANGLE, honoured, max_norm
from conformance.results import Measure, Settings, also, spec

# relative_turns.x3d: no gravity; each pair's two free, isotropic bodies sit on their joint's anchor, unturned
UT_AXIS1, UT_AXIS2 = np.array([0.0, 0.6, 0.8]), np.array([0.0, 0.8, -0.6])  # axis1 x axis2 = (-1, 0, 0)
UT_I1, UT_I2 = 0.2, 0.05  # Yoke (body1), Fork (body2)
UT_W1, UT_W2 = 1.5 * UT_AXIS1, np.array([2.0, 0.8, -0.6])  # Fork's: 1 about axis2 and 2 about -(axis1 x axis2)
UT_SPLIT = 2.0  # the rates' difference about axis1 x axis2 at the start, which the joint takes out
HG_AXIS = np.array([0.0, 0.6, 0.8])
HG_I1, HG_I2 = 0.02, 0.03  # Door (body1), Frame (body2)
HG_W1, HG_W2 = 1.0, -1.5  # their spins about the axis: the relative rate 2.5 rad/s
PERPENDICULAR = spec("37.4.14 UniversalJoint: Given the axis specified by the axis1 field on the body specified by "
                     "the body1 field, and the axis specified by the axis2 field on body2 that is perpendicular "
                     "to axis1, the UniversalJoint node keeps the axes perpendicular to each other.")
EQUAL_TURNS = spec("37.4.14 UniversalJoint: Given the axis specified by the axis1 field on the body specified by "
                   "the body1 field, and the axis specified by the axis2 field on body2 that is perpendicular to "
                   "axis1, the UniversalJoint node keeps the axes perpendicular to each other. Thus, rotation of the "
                   "two bodies about the direction perpendicular to the two axes will be equal.")
HINGE_ANGLE = spec("37.4.12 SingleAxisHingeJoint: The angle output field reports the current relative angle between "
                   "the two bodies in radians and the angleRate field describes the rate at which that angle is "
                   "currently changing in radians per second.")
# Swing's bodies both turn, so the angle and rate measures, held to the relative turn, fail with either side off the
# hinge (body2 ignored: Door's turn against the world, 1 of the relative 2.5 rad/s)
HINGE_SIDES = also(HINGE_ANGLE, "37.4.12 SingleAxisHingeJoint: The objects on each side of the hinge are specified by "
                   "the body1 and body2 fields.")


def _universal(tr: TraceView, s: Settings) -> list[Measure]:
    """Cross's two measures (expect's docstring)."""
    h = s.dt
    _, q1 = tr.series("Yoke", "orientation")
    _, q2 = tr.series("Fork", "orientation")
    _, w1 = tr.series("Yoke", "angularVelocity")
    _, w2 = tr.series("Fork", "angularVelocity")
    a1 = R.rotate(R.from_axis_angle(q1), UT_AXIS1)  # the axes as the bodies carry them (both readings share them)
    a2 = R.rotate(R.from_axis_angle(q2), UT_AXIS2)
    n = np.cross(a1, a2)
    with np.errstate(invalid="ignore", divide="ignore"):  # axes fallen parallel: NaN, a failure
        n = n / np.linalg.norm(n, axis=1, keepdims=True)
    energy = 0.5 * UT_I1 * float(UT_W1 @ UT_W1) + 0.5 * UT_I2 * float(UT_W2 @ UT_W2)
    r1 = np.minimum(np.linalg.norm(w1, axis=1), math.sqrt(2 * energy / UT_I1))
    r2 = np.minimum(np.linalg.norm(w2, axis=1), math.sqrt(2 * energy / UT_I2))
    after = slice(1, None)  # the start's own split is the joint's to take out in its first step
    split = np.abs(np.einsum("ni,ni->n", w1 - w2, n))[after]
    cos = np.abs(np.einsum("ni,ni->n", a1, a2))
    rates = float(np.max((r1 + r2) ** 2))
    turn_bound = 1.5 * h * rates + ROUNDING * (1 + UT_SPLIT)
    drift = rates * h ** 2 / (2 * ERROR_CORRECTION) + ROUNDING
    return [Measure("Yoke, Fork: |(w1 - w2) . (axis1 x axis2)|, the axes as each body carries them",
                    float(np.max(split)) if split.size else math.inf, honoured(turn_bound, UT_SPLIT), "rad/s",
                    EQUAL_TURNS, turn_bound),
            Measure("Yoke, Fork: |axis1 . axis2|, the axes as each body carries them", float(np.max(cos)),
                    honoured(drift, 1.0), "", PERPENDICULAR, drift)]


def _hinge(tr: TraceView) -> list[Measure]:
    """Swing's outputs against Door's turn relative to Frame (expect's docstring)."""
    _, q1 = tr.series("Door", "orientation")
    _, q2 = tr.series("Frame", "orientation")
    _, w1 = tr.series("Door", "angularVelocity")
    _, w2 = tr.series("Frame", "angularVelocity")
    _, angle = tr.series("Swing", "angle")
    _, rate = tr.series("Swing", "angleRate")
    turn = R.twist_angle(R.multiply(R.conjugate(R.from_axis_angle(q2)), R.from_axis_angle(q1)), HG_AXIS)
    r = (w1 - w2) @ HG_AXIS
    relative = abs(HG_W1 - HG_W2)
    share = min(abs(HG_W2), abs(HG_W1)) / relative  # one body's own turn misses at least this share of it
    rounding = ROUNDING * (1 + relative)
    return [Measure("Swing |angle| - |Door's turn relative to Frame|", max_norm(np.abs(angle[:, 0]) - np.abs(turn)),
                    honoured(ROUNDING_ANGLE, share * float(np.max(np.abs(turn)))), "rad", HINGE_SIDES,
                    ROUNDING_ANGLE),
            Measure("Swing |angleRate| - |axis . (w1 - w2)|", max_norm(np.abs(rate[:, 0]) - np.abs(r)),
                    honoured(rounding, share * relative), "rad/s", HINGE_SIDES, rounding)]


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Cross (UniversalJoint, axis1 0 0.6 0.8 on Yoke, axis2 0 0.8 -0.6 on Fork, their cross product -x):
    Fork starts turning 2 rad/s about -(axis1 x axis2) beside its 1 rad/s about axis2, Yoke 1.5 rad/s
    about axis1, so the joint must share the first between them and keep the two bodies' rates about
    the direction perpendicular to both axes equal from then on, while both axes turn. The axes and
    that direction are read from the bodies' poses (each axis as its body carries it), which every
    reading of the joint's axis outputs shares.

    Accuracy. A joint of generalized coordinates holds both to rounding. One of velocity-level rows
    (ODE) holds the rates' difference to 0 about the direction at the step's start; by the step's end
    the axes have turned by up to (|w1| + |w2|) h, which leaves |w1 - w2| (|w1| + |w2|) h, and the
    error correction's push against the axes' drift adds up to h (|w1| + |w2|)^2 / 2 (the drift
    universal_joint bounds, dt^2 / (2 ERP) (|w1| + |w2|)^2, corrected at ERP / h): at most
    1.5 h (|w1| + |w2|)^2, with the rates read from the trace (capped by the pair's energy). The
    axes' cosine: universal_joint's drift bound. Spec tolerances half the nearest misreading's
    error: the rates about that direction not tied (a BallJoint; or the joint about other axes, as
    4.0's default axis1 1 0 0 gives): the start's 2 rad/s split kept; the axes not kept apart at
    all (their cosine up to 1).

    Swing (SingleAxisHingeJoint, axis 0 0.6 0.8, no stops): Door (body1) spins 1 rad/s and Frame
    (body2) -1.5 rad/s about the axis, which the hinge leaves free: |angle| is Door's turn relative
    to Frame (2.5 t rad, from the poses) and |angleRate| the relative rate 2.5 rad/s, to rounding
    (the sign is the joint's convention); the tolerances half the nearest misreading's error: one
    body's own turn or rate in place of the relative one (Frame's: 0.4 of it short), or none."""
    tr, s = traces[0], settings[0]
    return _universal(tr, s) + _hinge(tr)


CASE = Case("relative_turns", "relative_turns.x3d",
            "UniversalJoint between free bodies, one started turning about axis1 x axis2: the two bodies' rates "
            "about that direction equal from the first step, the carried axes perpendicular; SingleAxisHingeJoint "
            "between two spinning bodies: |angle| and |angleRate| their relative turn and rate",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("UniversalJoint.axis1", "UniversalJoint.axis2", "SingleAxisHingeJoint.axis",
                       "SingleAxisHingeJoint.forceOutput", "RigidBody.angularVelocity"),
            mutations=(
                (" axis1='0 0.6 0.8'", ""),  # 4.0's default 1 0 0: the joint ties the rates about 0 0.6 0.8 instead
                # body2 ignored: the angle Door's against the world, 1 t of the relative 2.5 t
                ("<RigidBody USE='Frame' containerField='body2'/>", ""),
            ))
