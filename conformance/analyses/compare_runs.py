"""One scene on several backends for `x3drbp compare`, each run in its own child process.

Each run is children.run_child's `x3drbp run` with its time limit, so that a crash, a
timeout, a blow-up or a refusal becomes that backend's verdict (children.classify) and the
other backends still compare. The child times the simulation itself (plan, engine
build, steps, state readback: `x3drbp run --timing`), which the real-time factor divides
by; the whole child's wall time (interpreter start, imports, load, trace writing) is
kept beside it, and is the factor's basis only where the child's own timing is missing.
"""

from __future__ import annotations

import json
import os
import tempfile
import time
from collections.abc import Mapping, Sequence

from x3d_core.traces.trace import TraceView, read_view

from conformance import results
from conformance.results import RAN, BackendRun, Settings
from conformance.runner import children, verdicts


def _simulation_wall(path: str) -> float | None:
    try:
        with open(path, encoding="utf-8") as f:
            return float(json.load(f)["simulation_wall_s"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def run_backend(scene: str, backend: str, settings: Settings, folder: str,
                timeout: float = children.DEFAULT_TIMEOUT) -> tuple[BackendRun, TraceView | None]:
    """Run the scene on one backend; the trace parsed, or None with the verdict that stopped it."""
    trace, timing = (os.path.join(folder, f"{backend}{suffix}") for suffix in (".npz", ".timing.json"))
    started = time.perf_counter()
    out = children.run_child(os.path.abspath(scene), backend, settings, trace, timeout, extra=("--timing", timing))
    child_s = time.perf_counter() - started
    if out.verdict is not None:
        return BackendRun(backend, out.verdict, out.reason, child_wall_s=child_s), None
    try:
        view = read_view(trace)
    except (OSError, ValueError) as e:
        return BackendRun(backend, results.ERROR, f"unreadable trace: {e}", child_wall_s=child_s), None
    return BackendRun(backend, RAN, simulated_s=settings.duration, simulation_wall_s=_simulation_wall(timing),
                      child_wall_s=child_s), view


def run_backends(scene: str, backends: Sequence[str], settings: Settings,
                 info: Mapping[str, results.BackendInfo], timeout: float = children.DEFAULT_TIMEOUT,
                 jobs: int = 1, progress: bool = False, prefer_accuracy: bool = False
                 ) -> list[tuple[BackendRun, TraceView | None]]:
    """Every backend's run in the given order, `jobs` at a time (with `progress`, a bar of
    runs done on stderr); a backend `info` marks unavailable gets that as its error without a
    run. prefer_accuracy: a collection of the scene prefers accuracy (the scheme a run steps by)."""
    with tempfile.TemporaryDirectory(prefix="x3drbp-compare-") as folder:
        def one(name: str) -> tuple[BackendRun, TraceView | None]:
            i = info.get(name)
            if i is not None and not i.usable:
                return BackendRun(name, results.ERROR, f"backend unavailable: {i.unavailable}"), None
            run, view = run_backend(scene, name, settings, folder, timeout)
            if i is not None:
                run.version, run.integration = i.version, i.integration_for(prefer_accuracy)
            return run, view
        return verdicts.run_many([lambda b=b: one(b) for b in backends], jobs, progress)
