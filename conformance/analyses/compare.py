"""How far two runs of one scene part: body poses, velocities and joint outputs, frame by frame.

The metrics work on traces already parsed (x3d_core.traces.trace.TraceView: one array per (node, field)),
in bulk over (frames, bodies) arrays. Two runs are compared at the frame times both
recorded (the same settings give the same frames) and on the bodies and joint outputs
both traces hold; what only one holds is listed, not an error.

- position divergence: |p1 - p2| per body and frame, in m;
- orientation divergence: the angle of q1^-1 q2 in rad, in [0, pi] whichever sign each
  trace's quaternion takes (q and -q are one rotation);
- per frame the RMS and the max over bodies, over the run the RMS and the max over
  every (frame, body), and the first frame at which some body passes the threshold,
  with the bodies over it then, the worst first;
- joint outputs: every output field the traces share (angle, separation, anchor points,
  axes...), the difference's magnitude (angles wrapped to (-pi, pi]: a hinge at pi and
  one at -pi agree), RMS and max per (joint, field).

Default thresholds, 1 mm and 1 mrad: Bullet, MuJoCo, DART and ODE step semi-implicit Euler
(backends.base.Backend.integration), so between them free motion agrees to rounding (1 s of
free fall: 0 m apart, 6e-15 m from the closed form); what separates their runs is how each
solves its constraints and contacts. pymunk moves positions before it adds the step's loads
to the velocities, so its free motion trails theirs by dt |v - v0| (g dt^2 n after n steps of
a fall: 1.7e-4 m a step at 1/240 s, past 1 mm by the second frame at 60 Hz), as `x3drbp
compare`'s text notes for such a pair. 1 mm is where a difference becomes visible at the
scale the component's scenes are built (metres: about a pixel at 1000 px/m), and 1 mrad
turns the end of a 1 m body by that same 1 mm. Scenes at other scales should pass their own.
The velocities (linearVelocity, angularVelocity: every body output a run records besides
the pose) are compared as the positions are, |v1 - v2| and |w1 - w2| per body and frame
(world frame vectors, as the trace writes them), each against its own threshold. A joint
output is held to the threshold of its unit: m to the position one, rad and unit axes to
the orientation one, m/s and rad/s to the velocities' (a hinge's angleRate is its bodies'
angularVelocity along the axis: the two are held alike).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping, Sequence

import numpy as np


from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.results import (ANGULAR_VELOCITY, JOINT_OUTPUTS, LINEAR_VELOCITY, ORIENTATION, POSITION, UNITS,
                                 VELOCITIES, BackendRun, Crossing, Divergence, JointDifference, PairComparison)

# position and orientation: 1 mm and 1 mrad (the module's docstring says why). The velocities:
# 1 mm/s and 1 mrad/s, the pose's thresholds over 1 s, the time scale of the component's scenes
# (their runs last 1-2 s): a velocity off by that for the run moves a body by the position
# threshold, and the joint rates (angleRate, separationRate...) are held to the same. Where two
# engines resolve a contact or a stop a step apart, their velocities part for a moment by up
# to one step's impulse while their poses stay within 1 mm (hinge_limits, Bullet against DART:
# 0.018 m/s, poses 7.6e-5 m apart): such a pair differs in its velocities, the kind named, and
# `--threshold linearVelocity=V` loosens that kind alone.
DEFAULT_THRESHOLDS = {POSITION: 1e-3, ORIENTATION: 1e-3, LINEAR_VELOCITY: 1e-3, ANGULAR_VELOCITY: 1e-3}

_HELD_TO = {"m": POSITION, "m/s": LINEAR_VELOCITY, "rad": ORIENTATION, "rad/s": ANGULAR_VELOCITY, "1": ORIENTATION}


def _opt(x: float | None) -> float | None:
    return None if x is None else float(x)


# -- metrics ------------------------------------------------------------------------------


def _common_times(series: Sequence[np.ndarray]) -> np.ndarray:
    return functools.reduce(np.intersect1d, series) if series else np.empty(0)


def _at(times: np.ndarray, values: np.ndarray, when: np.ndarray) -> np.ndarray:
    """values at the frame times `when` (each one of `times`, which are sorted)."""
    return values[np.searchsorted(times, when)]


def divergence(quantity: str, threshold: float, times: np.ndarray, names: Sequence[str],
               d: np.ndarray) -> Divergence:
    """The statistics of d (frames, bodies), a divergence per frame and body."""
    unit = UNITS[quantity]
    if d.size == 0:
        return Divergence(quantity, unit, threshold)
    sq = d * d
    frame_max = d.max(axis=1)
    f, k = np.unravel_index(int(np.argmax(d)), d.shape)
    over = np.flatnonzero(frame_max > threshold)
    first = None
    if over.size:
        row = d[over[0]]
        worst = np.flatnonzero(row > threshold)
        worst = worst[np.argsort(-row[worst], kind="stable")]
        first = Crossing(float(times[over[0]]), [names[i] for i in worst], [float(x) for x in row[worst]])
    return Divergence(quantity, unit, threshold, float(np.sqrt(sq.mean())), float(d[f, k]), float(times[f]),
                      names[k], first, np.sqrt(sq.mean(axis=1)), frame_max, np.sqrt(sq.mean(axis=0)), d.max(axis=0))


def _stack(trace: TraceView, names: Sequence[str], fld: str, times: np.ndarray) -> np.ndarray:
    """(frames, bodies, width): one field of every named node at the given times."""
    return np.stack([_at(*trace.series(n, fld), times) for n in names], axis=1)


def joint_differences(ta: TraceView, tb: TraceView, thresholds: Mapping[str, float]) -> list[JointDifference]:
    """Every joint output both traces hold, in the first trace's order."""
    in_b = set(tb.keys())
    out = []
    for node, fld in ta.keys():
        unit = JOINT_OUTPUTS.get(fld)
        if unit is None or (node, fld) not in in_b:
            continue
        (t1, v1), (t2, v2) = ta.series(node, fld), tb.series(node, fld)
        times = np.intersect1d(t1, t2)
        if not times.size:
            continue
        diff = _at(t1, v1, times) - _at(t2, v2, times)
        if unit == "rad":  # an angle: pi and -pi are one position of the joint
            diff = np.remainder(diff + math.pi, 2.0 * math.pi) - math.pi
        mag = np.linalg.norm(diff, axis=1)
        k = int(np.argmax(mag))
        out.append(JointDifference(node, fld, unit, thresholds[_HELD_TO[unit]], float(np.sqrt(np.mean(mag * mag))),
                                   float(mag[k]), float(times[k])))
    return out


def _joint_keys(trace: TraceView) -> list[str]:
    return [f"{n}.{f}" for n, f in trace.keys() if f in JOINT_OUTPUTS]


def pose_gaps(pa: np.ndarray, oa: np.ndarray, pb: np.ndarray, ob: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per frame and body, how far apart two runs' bodies are (m) and the angle between their
    orientations (rad), from positions (..., 3) and axis-angle orientations (..., 4)."""
    return np.linalg.norm(pa - pb, axis=-1), R.angle_between(R.from_axis_angle(oa), R.from_axis_angle(ob))


def compare_pair(a: str, ta: TraceView, b: str, tb: TraceView,
                 thresholds: Mapping[str, float] = DEFAULT_THRESHOLDS) -> PairComparison:
    """Backend a's trace against backend b's (a kind thresholds does not name: its default)."""
    thresholds = {**DEFAULT_THRESHOLDS, **thresholds}
    in_a, in_b = ta.bodies(), tb.bodies()
    names = [n for n in in_a if n in in_b]
    shared = set(ta.keys()) & set(tb.keys())
    velocities = [k for k in VELOCITIES if names and all((n, k) in shared for n in names)]
    kinds = [POSITION, ORIENTATION, *velocities]
    times = _common_times([t.series(n, f)[0] for t in (ta, tb) for n in names for f in kinds])
    gaps = dict.fromkeys(kinds, np.empty((times.size, 0)))
    if names and times.size:
        gaps[POSITION], gaps[ORIENTATION] = pose_gaps(
            _stack(ta, names, POSITION, times), _stack(ta, names, ORIENTATION, times),
            _stack(tb, names, POSITION, times), _stack(tb, names, ORIENTATION, times))
        for k in velocities:
            gaps[k] = np.linalg.norm(_stack(ta, names, k, times) - _stack(tb, names, k, times), axis=-1)
    body = [divergence(k, thresholds[k], times, names, gaps[k]) for k in kinds]
    ja, jb = _joint_keys(ta), _joint_keys(tb)
    return PairComparison(
        a, b, times, names, _missing(in_a, in_b), _missing(in_b, in_a), body[0], body[1],
        joint_differences(ta, tb, thresholds), _missing(ja, jb), _missing(jb, ja), body[2:])


def _missing(names: Sequence[str], other: Sequence[str]) -> list[str]:
    """The names not in other, in their order."""
    there = set(other)
    return [n for n in names if n not in there]


def compare_all(runs: Sequence[tuple[BackendRun, TraceView | None]],
                thresholds: Mapping[str, float] = DEFAULT_THRESHOLDS) -> list[PairComparison]:
    """Every pair of runs that wrote a trace, in the runs' order."""
    ran = [(r.backend, t) for r, t in runs if t is not None]
    return [compare_pair(a, ta, b, tb, thresholds) for i, (a, ta) in enumerate(ran) for b, tb in ran[i + 1:]]
