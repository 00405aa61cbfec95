"""The sweep's measures, on plain data: error against a finer-step run of the same engine,
the sampling that makes two runs comparable, and the Pareto front of speed against error.

Error without a closed form follows Erez, Tassa and Todorov (ICRA 2015): a run is compared
with the same engine at a much finer step, over a short window, so that chaos (which parts
two accurate runs anyway) is not counted as error. They restart both runs from the reference
state at every window; x3drbp cannot: a run is a scene file, and its joints' anchors and axes
are given in world coordinates at the start, so a restart would mean rewriting every body and
joint from the reference state (the evaluator has no set-state input). The restart-free
variant kept here compares the first window only: over a window shorter than the time two
runs take to part by chaos, what separates them is the integrators' error.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

MIN_INTERVAL = 1.0 / 60.0  # s: no need to compare more often than a display frame
_TIME_DIGITS = 9  # frame times equal to a nanosecond are the same frame


@dataclass
class Positions:
    """Every body's position at each frame of a run."""
    times: np.ndarray  # (frames,) s
    bodies: tuple[str, ...]
    values: np.ndarray  # (frames, bodies, 3) m


def comparison_interval(dts: Sequence[float]) -> float:
    """The shortest time, at least MIN_INTERVAL, that is a whole number of every step: frames
    that far apart find every run at the same physics time (the evaluator records the state
    after floor(t / dt) steps), so that no run's error includes the lag of its last step."""
    common = Fraction(0)
    for dt in dts:
        f = Fraction(dt).limit_denominator(10 ** 9)
        common = f if common == 0 else Fraction(math.lcm(common.numerator, f.numerator),
                                                math.gcd(common.denominator, f.denominator))
    if common == 0:
        raise ValueError("no steps")
    return float(common * max(1, math.ceil(MIN_INTERVAL / common - 1e-9)))


def window_error(run: Positions, reference: Positions, window: float) -> float:
    """The largest distance of any body from its place in the reference, over the frames both
    runs recorded up to `window` seconds (m)."""
    if run.bodies != reference.bodies:
        raise ValueError(f"the runs have different bodies: {run.bodies} and {reference.bodies}")
    mine = np.round(run.times, _TIME_DIGITS)
    theirs = np.round(reference.times, _TIME_DIGITS)
    common, i, j = np.intersect1d(mine, theirs, return_indices=True)
    keep = common <= window + 10.0 ** -_TIME_DIGITS
    if not keep.any():
        raise ValueError("the runs share no frame within the window")
    gap = run.values[i[keep]] - reference.values[j[keep]]
    return float(np.max(np.linalg.norm(gap, axis=-1)))


def pareto(costs: Sequence[float | None], errors: Sequence[float | None]) -> list[bool]:
    """Which points are on the Pareto front of cost against error (both lower is better): no
    other point is at least as fast and as accurate and better in one of the two. Points equal
    in both are all on it; a point without a finite cost and error is on nothing."""
    pts = [(c, e) if c is not None and e is not None and math.isfinite(c) and math.isfinite(e) else None
           for c, e in zip(costs, errors)]
    front = []
    for p in pts:
        front.append(p is not None and not any(
            q is not None and q[0] <= p[0] and q[1] <= p[1] and q != p for q in pts))
    return front
