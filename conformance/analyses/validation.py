"""Judges a trace written by another implementation (a browser) of a scene x3drbp knows.

Two judgements, each reusing what judges x3drbp's own backends:

- the conformance case, where the scene is one (conformance.cases.CASES, matched by
  path): its expectation on their trace(s), one per run of the case, in the case's order,
  a verdict per measure (verdicts.evaluate);
- the backends: each runs the scene with the settings read off their trace (duration: the
  last time; frame rate: the median spacing of the times; dt: 1/240 unless given), and
  their trace is compared with each run as two backends are (conformance.analyses.compare): body
  position, orientation, linearVelocity and angularVelocity divergence, joint outputs. A
  backend agrees when the pair has a frame in common and every divergence stays within its
  threshold (joint outputs: the threshold of their unit).

The rule (docs/implementers.md): a scene that is a conformance case conforms when the
case's expectation passes, the backends' verdicts shown for information (engines part
ways in chaotic scenes, and the case is the specification's answer); any other scene
conforms when at least one backend agrees on every trace (the backends differ from each
other where the specification leaves room, and agreeing with one of them is agreeing
with a reading of it).
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence

import numpy as np

from x3d_core.traces.trace import Row, TraceView

from conformance import results
from conformance.runner import verdicts
from conformance.cases import CASES
from conformance.cases.case import Case
from conformance.results import THEIRS, Settings, TraceComparison
from conformance.analyses.compare import compare_pair
from conformance.analyses.compare_runs import run_backends

# their frame times within this of a backend's frame time are that frame: a browser that
# sums 1/60 each frame drifts by ~1e-13 s, far below any frame period
SNAP = 1e-6  # s


def find_case(scene: str) -> Case | None:
    """The conformance case whose scene file this is."""
    real = os.path.realpath(scene)
    return next((c for c in CASES if os.path.realpath(c.path) == real), None)


def _tidy(x: float) -> float:
    """Nine significant digits: 60.00000000000001 frames/s is 60."""
    return float(f"{x:.9g}")


def _view(rows: Sequence[Row] | TraceView) -> TraceView:
    return rows if isinstance(rows, TraceView) else TraceView(rows)


def trace_settings(rows: Sequence[Row] | TraceView, dt: float) -> Settings:
    """The run their trace describes: until its last time, at its median frame spacing."""
    times = _view(rows).times()
    gaps = np.diff(times)
    period = float(np.median(gaps)) if gaps.size else float(times[-1])
    return Settings(_tidy(float(times[-1])), dt, _tidy(1.0 / period))


def frame_period(views: Sequence[TraceView]) -> float | None:
    """Their frames' period where every trace has the same one (None: they differ): the step of
    an implementation that steps once per frame."""
    rates = {trace_settings(v, 1.0).frame_rate for v in views}
    return 1.0 / rates.pop() if len(rates) == 1 else None


def _aligned(rows: Sequence[Row] | TraceView, times: np.ndarray) -> TraceView:
    """Their trace with each time moved onto the backend's frame time within SNAP of it."""
    def snap(t: np.ndarray) -> np.ndarray:
        if not times.size or not t.size:
            return t
        i = np.clip(np.searchsorted(times, t), 0, times.size - 1)
        j = np.maximum(i - 1, 0)
        near = np.where(np.abs(times[j] - t) < np.abs(times[i] - t), times[j], times[i])
        return np.where(np.abs(near - t) <= SNAP, near, t)
    return _view(rows).retimed(snap)


def _frame_times(view: TraceView) -> np.ndarray:
    return np.unique(np.concatenate([view.series(*k)[0] for k in view.keys()] or [np.empty(0)]))


def check_case(case: Case, views: Sequence[TraceView], dt: float | None,
               frame_rates: Sequence[float] | None = None) -> results.Result:
    """The case's expectation on their traces (its runs' settings, at their dt and frame
    rates where given: a browser that cannot draw the case's frame rate records at another)."""
    rates = frame_rates or [s.frame_rate for s in case.runs]
    settings = [Settings(s.duration, dt or s.dt, r) for s, r in zip(case.runs, rates)]
    return verdicts.evaluate(case, THEIRS, views, settings)


def compare_with_backends(scene: str, trace: str, rows: Sequence[Row] | TraceView, dt: float, backends: Sequence[str],
                          info: Mapping[str, results.BackendInfo], thresholds: Mapping[str, float],
                          timeout: float, name: str = THEIRS) -> TraceComparison:
    """Each backend's run of the scene, with the settings of their trace, against it (their
    trace goes by `name` in the pairs; rows: its rows, or check_trace's view of them)."""
    rows = _view(rows)
    settings = trace_settings(rows, dt)
    runs = run_backends(scene, backends, settings, info, timeout, jobs=os.cpu_count() or 1)
    pairs = {r.backend: compare_pair(name, _aligned(rows, _frame_times(v)), r.backend, v, thresholds)
             for r, v in runs if v is not None}
    return TraceComparison(trace, settings, [r for r, _ in runs], pairs, {r.backend: v for r, v in runs if v is not None})

