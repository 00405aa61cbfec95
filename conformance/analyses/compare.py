"""How far two runs of one scene part: body poses and joint outputs, frame by frame.

The metrics work on traces already parsed (x3d_core.trace.TraceView: one array per (node, field)),
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
A joint output is held to the threshold of its unit: m and m/s to the position one,
rad, rad/s and unit axes to the orientation one (rates: that much per second).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping, Sequence

import numpy as np


from x3d_core import rotation as R
from x3d_core.trace import TraceView

from conformance.results import (JOINT_OUTPUTS, ORIENTATION, POSITION, BackendRun, Crossing, Divergence,
                                 JointDifference, PairComparison)

DEFAULT_THRESHOLDS = {POSITION: 1e-3, ORIENTATION: 1e-3}  # m, rad
UNITS = {POSITION: "m", ORIENTATION: "rad"}

_HELD_TO = {"m": POSITION, "m/s": POSITION, "rad": ORIENTATION, "rad/s": ORIENTATION, "1": ORIENTATION}


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
    """Backend a's trace against backend b's."""
    in_a, in_b = ta.bodies(), tb.bodies()
    names = [n for n in in_a if n in in_b]
    times = _common_times([t.series(n, f)[0] for t in (ta, tb) for n in names for f in (POSITION, ORIENTATION)])
    if names and times.size:
        dp, do = pose_gaps(_stack(ta, names, POSITION, times), _stack(ta, names, ORIENTATION, times),
                           _stack(tb, names, POSITION, times), _stack(tb, names, ORIENTATION, times))
    else:
        dp = do = np.empty((times.size, 0))
    ja, jb = _joint_keys(ta), _joint_keys(tb)
    return PairComparison(
        a, b, times, names, _missing(in_a, in_b), _missing(in_b, in_a),
        divergence(POSITION, thresholds[POSITION], times, names, dp),
        divergence(ORIENTATION, thresholds[ORIENTATION], times, names, do),
        joint_differences(ta, tb, thresholds), _missing(ja, jb), _missing(jb, ja))


def _missing(names: Sequence[str], other: Sequence[str]) -> list[str]:
    """The names not in other, in their order."""
    there = set(other)
    return [n for n in names if n not in there]


def compare_all(runs: Sequence[tuple[BackendRun, TraceView | None]],
                thresholds: Mapping[str, float] = DEFAULT_THRESHOLDS) -> list[PairComparison]:
    """Every pair of runs that wrote a trace, in the runs' order."""
    ran = [(r.backend, t) for r, t in runs if t is not None]
    return [compare_pair(a, ta, b, tb, thresholds) for i, (a, ta) in enumerate(ran) for b, tb in ran[i + 1:]]
