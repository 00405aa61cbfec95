"""The sweep's measures, on plain data: error against a finer-step reference run, the
sampling that makes two runs comparable, and the Pareto front of speed against error, with
ties (speeds within the repeats' spread, errors within the reference's own error).

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
    """Every body's pose at each frame of a run."""
    times: np.ndarray  # (frames,) s
    bodies: tuple[str, ...]
    values: np.ndarray  # (frames, bodies, 3) m
    orientations: np.ndarray | None = None  # (frames, bodies, 4) axis-angle, as the trace writes them


def comparison_interval(dts: Sequence[float]) -> float:
    """The shortest time, at least MIN_INTERVAL, that is a whole number of every step: frames
    that far apart find every run at the same physics time (the evaluator records the state
    after floor(t / dt) steps), so that no run's error includes the lag of its last step."""
    common = Fraction(0)
    for dt in dts:
        f = Fraction(dt).limit_denominator(10 ** 9)
        if f == 0:  # was 'no steps' (a --dts of 1e-300)
            raise ValueError(f"a step of {dt:g} s is finer than 1e-9 s, the resolution at which steps are compared")
        common = f if common == 0 else Fraction(math.lcm(common.numerator, f.numerator),
                                                math.gcd(common.denominator, f.denominator))
    if common == 0:
        raise ValueError("no steps")
    return float(common * max(1, math.ceil(MIN_INTERVAL / common - 1e-9)))


def shared_frames(a: Positions, b: Positions) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The frame times two runs both recorded, and where each holds them: (times, in a, in b);
    ValueError where the runs hold different bodies."""
    if a.bodies != b.bodies:
        raise ValueError(f"the runs have different bodies, so they share no body to compare: {a.bodies} and {b.bodies}")
    return np.intersect1d(np.round(a.times, _TIME_DIGITS), np.round(b.times, _TIME_DIGITS), return_indices=True)


def window_error(run: Positions, reference: Positions, window: float) -> float:
    """The largest distance of any body from its place in the reference, over the frames both
    runs recorded up to `window` seconds (m)."""
    common, i, j = shared_frames(run, reference)
    keep = common <= window + 10.0 ** -_TIME_DIGITS
    if not keep.any():
        raise ValueError("the runs share no frame within the window")
    gap = run.values[i[keep]] - reference.values[j[keep]]
    return float(np.max(np.linalg.norm(gap, axis=-1)))


# Errors that differ by less than this fraction of themselves are one error. Rounding alone
# moves a run by ~1e-12 (1e4 steps at ~1e-16 each), but solver settings that change nothing a
# user could act on move it further: pymunk's pendulum_period error at 10 and 50 iterations
# differs by 1.5e-9 of itself (and bounce_apex's by 1e-17 m). A front ranks configurations;
# the seventh digit of an error ranks none, so the tie is one part in a million.
TIE_RELATIVE = 1e-6


@dataclass(frozen=True)
class Cost:
    """A speed measured by repeats: the median and the spread (lowest, highest)."""
    median: float
    low: float
    high: float

    @classmethod
    def of(cls, samples: Sequence[float]) -> Cost:
        return cls(float(np.median(samples)), float(min(samples)), float(max(samples)))

    def ties(self, other: Cost) -> bool:
        """Whether the two spreads overlap: repeats cannot tell them apart."""
        return self.low <= other.high and other.low <= self.high

    def scaled(self, g: float) -> Cost:
        """The same speed, median and spread, g times as costly."""
        return Cost(self.median * g, self.low * g, self.high * g)


def same_error(a: float, b: float, tolerance: float) -> bool:
    """Whether two errors are one within the reference's own error (tolerance) or rounding."""
    return abs(a - b) <= tolerance + TIE_RELATIVE * max(abs(a), abs(b))


def dominates(q: tuple[Cost, float], p: tuple[Cost, float], tolerance: float) -> bool:
    """Whether point q beats p: no slower by median, no worse in error beyond the ties, and
    better in one beyond them (faster beyond both spreads, or more accurate beyond the
    tolerance). Requiring q's median no higher makes the relation acyclic: a front exists."""
    (qc, qe), (pc, pe) = q, p
    if qc.median > pc.median or not (qe <= pe or same_error(qe, pe, tolerance)):
        return False
    return qc.high < pc.low or (qe < pe and not same_error(qe, pe, tolerance))


def pareto(costs: Sequence[Cost | None], errors: Sequence[float | None], tolerance: float = 0.0
           ) -> list[int | None]:
    """The Pareto front of cost against error (both lower is better), ties merged. For each
    point: None when off the front (or without a finite cost and error), else the index of the
    front point that stands for it: itself, or a faster-by-median point it ties with in both
    speed (spreads overlap) and error (same_error)."""
    pts = [(c, e) if c is not None and e is not None and math.isfinite(c.median) and math.isfinite(e) else None
           for c, e in zip(costs, errors)]
    on = [k for k, p in enumerate(pts)
          if p is not None and not any(q is not None and dominates(q, p, tolerance) for q in pts)]
    out: list[int | None] = [None] * len(pts)
    heads: list[int] = []
    for k in sorted(on, key=lambda k: (pts[k][0].median, pts[k][1], k)):
        c, e = pts[k]
        head = next((h for h in heads if pts[h][0].ties(c) and same_error(pts[h][1], e, tolerance)), None)
        if head is None:
            heads.append(k)
        out[k] = k if head is None else head
    return out
