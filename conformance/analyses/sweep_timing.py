"""How many times the sweep times each point: once, and `repeats` times in all only where its
speed could change what the sweep states (unsettled), advise's rule (conformance/analyses/
advice.py) applied to the sweep's fronts.

What the sweep states from speed: each point's Pareto marks (sweep.mark_pareto: on its
scene's front and on its backend's, and the front point a tie stands behind), which also set
the order of the fronts' tables and the report's fastest and most accurate front points
(two front points of one front swapping speeds would make one beat the other, a change of
marks); and the speed of each point a front's table lists (a front point that no other stands
for), with its repeats' spread. So a point is unsettled where it heads a front, or where its
speed anywhere a single timing may put it (a factor 1 + SPEED_RELATIVE either way, SPEED_NOISE
under SPEED_RESOLUTION: advice.py's margins) would change any point's marks, the others as
measured. Those are timed again (sweep.time_again) and the marks set again, until none is left.
A point off every front and far from every other point's speed, measured once, cannot move
any mark, and its median of three would say nothing more: on the default scope that is most
points (their three simulations a point cost a third of the sweep's CPU time).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from conformance.analyses import sweep as S
from conformance.analyses.advice import margin
from conformance.analyses.sweep_metrics import Cost, dominates, pareto


def tolerances(sweep: S.Sweep) -> dict[str, float]:
    """Per scene, the error within which its points tie: its common reference's uncertainty (0
    for a closed form, or where there is no reference)."""
    return {s: r.error if isinstance(r, S.Reference) else 0.0 for s, r in sweep.references.items()}


def _heads(p: S.Point) -> bool:
    """Whether a front's table lists the point, stating its speed: on a front, no tie of another."""
    return (p.pareto_scene and p.tie_scene is None) or (p.pareto_backend and p.tie_backend is None)


class _Front:
    """One group that mark_pareto marks (a scene's points, or a scene's on one backend), with who
    beats whom as measured (sweep_metrics.dominates): moving one point's speed changes only its
    own row and column of that, so what a move changes costs a pass over the group, not a front
    made again (n^2: 0.8 s a call on the default scope, three calls a sweep)."""

    def __init__(self, points: Sequence[S.Point], tolerance: float):
        self.tolerance = tolerance
        self.labels = [p.label for p in points]
        self.ranked = [(p.cost, p.error) if p.cost is not None and p.error is not None
                       and math.isfinite(p.cost.median) and math.isfinite(p.error) else None for p in points]
        self.beats = [[q is not None and r is not None and dominates(q, r, tolerance) for r in self.ranked]
                      for q in self.ranked]
        self.beaten = [sum(column) for column in zip(*self.beats)]  # by how many points each is beaten
        self.on = self._on(None, None)
        self.marks = self._marks(self.ranked, self.on)

    def _on(self, at: int | None, moved: tuple[Cost, float] | None) -> list[int]:
        """The front (the points no point beats), point `at` moved to `moved` (None: as measured)."""
        if at is None:
            return [j for j, r in enumerate(self.ranked) if r is not None and not self.beaten[j]]
        out = []
        for j, r in enumerate(self.ranked):
            if r is None:
                continue
            if j == at:
                on = not any(q is not None and i != at and dominates(q, moved, self.tolerance)
                             for i, q in enumerate(self.ranked))
            else:
                on = self.beaten[j] == self.beats[at][j] and not dominates(moved, r, self.tolerance)
            if on:
                out.append(j)
        return out

    def _marks(self, ranked: list, on: list[int]) -> dict[int, str | None]:
        """The front's points and the label of each one's head (None: it heads), as mark_pareto sets
        them: pareto over the front alone (no point of it beats another) gives the heads pareto
        gives over the whole group, which it picks among the front's points only."""
        heads = pareto([ranked[j][0] for j in on], [ranked[j][1] for j in on], self.tolerance)
        return {j: None if on[h] == j else self.labels[on[h]] for j, h in zip(on, heads)}

    def moves(self, at: int, cost: Cost) -> bool:
        """Whether point `at` at `cost`, the others as measured, changes any point's marks."""
        moved = (cost, self.ranked[at][1])
        on = self._on(at, moved)
        if on != self.on:
            return True
        if at not in on:  # the same front without it: the same heads
            return False
        ranked = list(self.ranked)
        ranked[at] = moved
        return self._marks(ranked, on) != self.marks


def _near(a: Cost, b: Cost, f: float) -> bool:
    """Whether a's spread, moved by a factor up to f either way, can meet b's: elsewhere every
    relation between the two (which is faster, which beats which, whether they tie) holds
    whatever the move, so a move of a changes no mark through b."""
    return a.low / f <= b.high and b.low <= a.high * f


def unsettled(points: Sequence[S.Point], tolerances: dict[str, float]) -> list[int]:
    """The points (indices) whose speed could change what the sweep states (module docstring),
    their marks as mark_pareto set them: each front point a table lists, and each ranked point
    that, its speed moved by its margin either way, the others as measured, would change any
    point's marks. Points without a speed and an error are ranked nowhere and never listed."""
    groups: dict[tuple[str, str | None], list[int]] = {}
    for k, p in enumerate(points):
        groups.setdefault((p.scene, p.backend), []).append(k)
        groups.setdefault((p.scene, None), []).append(k)
    fronts: dict[tuple[str, str | None], _Front] = {}
    out = []
    for k, p in enumerate(points):
        if p.cost is None or p.error is None or not (math.isfinite(p.cost.median) and math.isfinite(p.error)):
            continue
        if _heads(p):
            out.append(k)
            continue
        f = margin(p.cost)
        for g in ((p.scene, p.backend), (p.scene, None)):
            members = groups[g]
            if not any(j != k and points[j].cost is not None and _near(p.cost, points[j].cost, f) for j in members):
                continue
            if g not in fronts:
                fronts[g] = _Front([points[j] for j in members], tolerances.get(p.scene, 0.0))
            at = members.index(k)
            if any(fronts[g].moves(at, p.cost.scaled(m)) for m in (1 / f, f)):
                out.append(k)
                break
    return out


def settle(sweep: S.Sweep, repeats: int, scheduler: str | None = None, workers: int | None = None,
           progress: bool = False) -> None:
    """The sweep's points, each timed once, timed `repeats` times in all where unsettled, until
    none is left, and their marks set again from those speeds (a point timed again moves the
    fronts, and may unsettle another)."""
    limits = tolerances(sweep)
    again: set[int] = set()
    while repeats > 1:
        picked = [k for k in unsettled(sweep.points, limits) if k not in again]
        if not picked:
            break
        S.time_again(sweep, picked, repeats - 1, scheduler, workers, progress)
        again.update(picked)
        S.mark_pareto(sweep.points, limits)


def timed(sweep: S.Sweep) -> list[int]:
    """How many timings each point's speed is the median of (0: the run gave none), in the points' order."""
    return [len(res.cpu_s) for _, res in sweep.runs]
