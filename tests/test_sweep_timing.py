"""conformance/analyses/sweep_timing.py: which of a sweep's points are timed again (the fronts'
points, and those a single timing's margin could move a mark with), on synthetic points, and
the rounds until none is left."""

from __future__ import annotations

from dataclasses import replace

import pytest

from conformance.analyses import sweep as S
from conformance.analyses import sweep_timing as T
from conformance.analyses.advice import SPEED_RELATIVE, SPEED_RESOLUTION
from conformance.analyses.sweep_job import Job, JobResult
from conformance.results import Settings


def _point(backend: str, dt: float, cpu: float | None, error: float | None, its: int | None = None) -> S.Point:
    p = S.Point("s", backend, dt, its, None, error=error)
    if cpu is not None:
        p.cpu_per_sim_s = p.cpu_low = p.cpu_high = cpu
    return p


def _marked(points: list[S.Point], tolerance: float = 0.0) -> list[S.Point]:
    S.mark_pareto(points, {"s": tolerance})
    return points


def test_a_front_point_is_timed_again_and_one_far_from_every_speed_is_not():
    # a: fast and coarse, b: slow and accurate, both heads; c: slower than b (3x) and less accurate
    # than a: beaten by both whatever a single timing's margin does to it
    a, b, c = _marked([_point("x", 1 / 60, 0.01, 1e-2), _point("x", 1 / 1000, 0.1, 1e-4),
                       _point("x", 1 / 4000, 0.3, 5e-2)])
    assert (a.pareto_scene, b.pareto_scene, c.pareto_scene) == (True, True, False)
    assert T.unsettled([a, b, c], {"s": 0.0}) == [0, 1]


def test_a_point_within_the_margin_of_a_tie_is_timed_again():
    # b has a's error and is 20% slower: a single timing 30% off would make it the faster, and a
    # tie of a's or a's head; 40% slower (beyond 1.3x) it stays beaten either way
    for slower, unsettled in ((1.2, [0, 1]), (1 + SPEED_RELATIVE + 0.1, [0])):
        points = _marked([_point("x", 1 / 240, 0.01, 1e-3, 10), _point("x", 1 / 240, 0.01 * slower, 1e-3, 50)])
        assert not points[1].pareto_backend
        assert T.unsettled(points, {"s": 0.0}) == unsettled, slower


def test_below_the_resolution_the_margin_is_the_noise_factor():
    # 1.75x apart: within SPEED_NOISE (2) below SPEED_RESOLUTION, beyond 1 + SPEED_RELATIVE above it
    for scale, unsettled in ((SPEED_RESOLUTION / 10, [0, 1]), (SPEED_RESOLUTION * 10, [0])):
        points = _marked([_point("x", 1 / 60, scale, 1e-3, 10), _point("x", 1 / 60, 1.75 * scale, 1e-3, 50)])
        assert T.unsettled(points, {"s": 0.0}) == unsettled, scale


def test_a_point_without_an_error_or_a_speed_is_ranked_nowhere_and_never_timed_again():
    points = _marked([_point("x", 1 / 60, 0.01, 1e-3), _point("x", 1 / 240, 0.011, None),
                      _point("x", 1 / 1000, None, None)])
    assert T.unsettled(points, {"s": 0.0}) == [0]


def test_errors_within_the_reference_s_uncertainty_tie_for_the_margin_too():
    # 1e-3 against 1.5e-3 ties within a 1e-3 uncertainty: b, 20% slower, beaten by a, would beat it
    # 30% faster; 5x slower, it stays beaten
    points = [_point("x", 1 / 240, 0.01, 1.5e-3, 10), _point("x", 1 / 240, 0.012, 1e-3, 50)]
    assert T.unsettled(_marked([replace(p) for p in points], 1e-3), {"s": 1e-3}) == [0, 1]
    far = [points[0], replace(points[1], cpu_per_sim_s=0.05, cpu_low=0.05, cpu_high=0.05)]
    marked = _marked([replace(p) for p in far], 1e-3)
    assert not marked[1].pareto_scene and T.unsettled(marked, {"s": 1e-3}) == [0]


def _sweep(points: list[S.Point]) -> S.Sweep:
    job = Job("s.x3d", "x", Settings(1.0, 1 / 60))
    runs = [(job, JobResult("measured", cpu_s=(p.cpu_per_sim_s,) if p.cpu_per_sim_s is not None else ()))
            for p in points]
    return S.Sweep(_marked(points), {}, {}, {}, {}, {}, runs)


def test_settle_times_again_the_unsettled_points_in_rounds_and_marks_the_fronts_again(monkeypatch):
    # a and b head the front; c has b's error, 3x slower: beaten by b whatever its margin, until
    # b's further timings put b's median at 0.25, within c's margin, so c is timed in a second round
    sweep = _sweep([_point("x", 1 / 60, 0.01, 1e-2), _point("x", 1 / 1000, 0.1, 1e-4),
                    _point("x", 1 / 4000, 0.3, 1e-4)])
    rounds = []

    def time_again(sweep: S.Sweep, picked, extra, scheduler=None, workers=None, progress=False):
        rounds.append((list(picked), extra))
        for k in picked:
            p = sweep.points[k]
            timings = (p.cpu_per_sim_s, *([0.25 if k == 1 else p.cpu_per_sim_s] * extra))
            p.cpu_per_sim_s, p.cpu_low, p.cpu_high = sorted(timings)[len(timings) // 2], min(timings), max(timings)
            sweep.runs[k] = (sweep.runs[k][0], replace(sweep.runs[k][1], cpu_s=timings))
            p.pareto_scene = p.pareto_backend = False  # marks stale until set again

    monkeypatch.setattr(S, "time_again", time_again)
    T.settle(sweep, 3)
    assert rounds == [([0, 1], 2), ([2], 2)]
    assert T.timed(sweep) == [3, 3, 3]
    assert [p.pareto_scene for p in sweep.points] == [True, True, False]  # set again from the new speeds


def test_one_repeat_times_nothing_again(monkeypatch):
    monkeypatch.setattr(S, "time_again", lambda *a, **k: pytest.fail("timed again"))
    sweep = _sweep([_point("x", 1 / 60, 0.01, 1e-2), _point("x", 1 / 1000, 0.1, 1e-4)])
    T.settle(sweep, 1)
    assert T.timed(sweep) == [1, 1]
