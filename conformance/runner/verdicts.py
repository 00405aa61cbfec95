"""Runs conformance cases on backends, each run in its own process, and gives verdicts.

Each (case, backend) runs `python -m x3drbp run SCENE --backend NAME ... --trace TMP`
in a child process with a time limit, so that an engine's segfault or endless loop is a
verdict, not a lost suite. The expectation is evaluated here, in the parent, on the trace
the child wrote. Verdicts:

- pass: every measured error within its tolerance;
- fail: some error beyond its tolerance (each Measure says which, by how much);
- unsupported: the backend refused a feature the scene needs (exit 3; the reason is the
  backend's own, from the child's stderr);
- crashed: the child died by a signal (negative return code), or raised an uncaught exception;
- timed out: no result within the time limit (the child's process group is killed);
- blew up: a body's state became non-finite (the evaluator says 'blew up');
- error: the run could not start for reasons that are not the engine's: the scene does not
  load, the backend is unknown or not installed, the trace lacks what the expectation reads.

A trace the child could not write (a full disk, a kept trace's folder removed) is no verdict
but the command's failure: atomic.CannotWrite naming it (the command says `cannot write
PATH: REASON` and exits 1), and no pair starts after it.

Pairs run in parallel, at most os.cpu_count() at a time. The pool is of threads, each
waiting on its child process: the children are the processes that do the work, and a
thread pool spares a second interpreter per pair and any pickling.
"""

from __future__ import annotations

import os
import tempfile
import time
import traceback
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import TypeVar

from x3d_core.files import atomic
from x3d_core.traces.trace import TraceView, read_view

from conformance.cases.case import Case
from conformance.results import ERROR, Convergence, Result, Settings, judge
from conformance.runner import children
from conformance.runner.children import DEFAULT_TIMEOUT, Outcome, run_child

T = TypeVar("T")  # what run_many's jobs return


def evaluate(case: Case, backend: str, traces: Sequence[TraceView], settings: Sequence[Settings]) -> Result:
    """Apply the case's expectation to traces already read. One cell, one fault: whatever the
    expectation raises (a trace without the rows it reads, an engine's result that breaks its
    assumptions, a fault of its own) is this cell's ERROR verdict with the reason, never the
    command's end."""
    dt = settings[0].dt if settings else None
    try:
        measures = case.expect(traces, settings)
    except (KeyError, ValueError, IndexError) as e:
        msg = e.args[0] if isinstance(e, KeyError) and e.args else str(e)
        return Result(case.name, backend, ERROR, f"the expectation could not read the trace: {msg}", dt=dt)
    except Exception as e:  # noqa: BLE001 -- any fault of the expectation is this cell's verdict
        where = traceback.extract_tb(e.__traceback__)[-1]
        return Result(case.name, backend, ERROR,
                      f"the expectation failed: {type(e).__name__}: {e} "
                      f"({os.path.basename(where.filename)}:{where.lineno})", dt=dt)
    result = Result(case.name, backend, judge(measures), "", measures, dt=dt)
    result.reason = "; ".join(("[convention] " if m.convention else "") + f"{m.quantity}: {m.figure()}"
                              for m in result.failing())
    return result


def _unwritten(out: Outcome, trace: str) -> atomic.CannotWrite | None:
    """The child's own `x3drbp run: cannot write TRACE: REASON` (its last line, so the end of
    the reason) as the command's failure; None for any other outcome."""
    said = f"x3drbp run: cannot write {trace}: "
    if out.verdict == ERROR and said in out.reason:
        return atomic.CannotWrite(trace, out.reason.rsplit(said, 1)[1])
    return None


def run_pair(case: Case, backend: str, timeout: float = DEFAULT_TIMEOUT,
             settings: Sequence[Settings] | None = None, keep: str | None = None) -> Result:
    """Run one case on one backend (every run of the case, one child each) and judge it.
    `settings` overrides the case's runs (convergence studies); `keep`, a folder that exists,
    keeps the traces there as CASE-BACKEND[-k].csv (one gone mid-run is not made again: the
    traces kept before it would be missing). atomic.CannotWrite where a trace could not be written."""
    settings = tuple(settings or case.runs)
    started = time.perf_counter()
    dt = settings[0].dt
    if not os.path.exists(case.path):
        return Result(case.name, backend, ERROR, f"no scene file {case.path}", dt=dt)
    with tempfile.TemporaryDirectory(prefix="x3drbp-conf-") as tmp:
        folder = keep or tmp
        traces = []
        for k, s in enumerate(settings):
            suffix = f"-{k}" if len(settings) > 1 else ""
            # a kept trace is for people and other tools (CSV); else the binary form, read back at once
            path = os.path.join(folder, f"{case.name}-{backend}{suffix}.{'csv' if keep else 'npz'}")
            if os.path.exists(path):
                os.unlink(path)
            out = run_child(case.path, backend, s, path, timeout)
            unwritten = _unwritten(out, path)
            if unwritten is not None:
                raise unwritten
            if out.verdict is not None:
                return Result(case.name, backend, out.verdict, out.reason, dt=dt,
                              wall_s=time.perf_counter() - started)
            try:
                traces.append(read_view(path))
            except (OSError, ValueError) as e:
                return Result(case.name, backend, ERROR, f"unreadable trace: {e}", dt=dt,
                              wall_s=time.perf_counter() - started)
        result = evaluate(case, backend, traces, settings)
    result.wall_s = time.perf_counter() - started
    return result


def run_many(jobs: Sequence[Callable[[], T]], workers: int | None = None, progress: bool = False) -> list[T]:
    """Run independent jobs in parallel (results in the jobs' order); with `progress`, a bar
    of jobs done on stderr (the commands ask for it where stderr is a terminal). Once a job
    could not write (atomic.CannotWrite: a full disk fails every run after it), no job starts;
    those running end, and such a failure is raised."""
    workers = max(1, min(workers or os.cpu_count() or 1, len(jobs) or 1))
    unwritten: list[atomic.CannotWrite] = []  # list.append is atomic under the GIL

    def unless_unwritten(job: Callable[[], T]) -> T | None:
        if unwritten:
            return None
        try:
            return job()
        except atomic.CannotWrite as e:
            unwritten.append(e)
            raise

    with ThreadPoolExecutor(max_workers=workers) as pool:
        futures = [pool.submit(unless_unwritten, job) for job in jobs]
        children.wait_all(futures, progress)
        return [f.result() for f in futures]  # a job was skipped (None) only once another raised: raised here


def run_matrix(cases: Sequence[Case], backends: Sequence[str], timeout: float = DEFAULT_TIMEOUT,
               workers: int | None = None, keep: str | None = None, progress: bool = False) -> list[Result]:
    """Every case on every backend; results case-major."""
    jobs = [(lambda c=c, b=b: run_pair(c, b, timeout, keep=keep)) for c in cases for b in backends]
    return run_many(jobs, workers, progress)


def run_convergence(cases: Sequence[Case], backends: Sequence[str], dts: Sequence[float],
                    timeout: float = DEFAULT_TIMEOUT, workers: int | None = None,
                    progress: bool = False) -> list[Convergence]:
    """Each closed-form case (one with a `convergence` quantity) at every dt, per backend."""
    chosen = [c for c in cases if c.convergence]
    keys = [(c, b, dt) for c in chosen for b in backends for dt in dts]
    results = run_many([(lambda c=c, b=b, dt=dt: run_pair(c, b, timeout, settings=c.at_dt(dt)))
                        for c, b, dt in keys], workers, progress)
    out = []
    for i in range(0, len(keys), len(dts)):
        c, b, _ = keys[i]
        out.append(Convergence(c.name, b, c.convergence, list(dts), results[i:i + len(dts)], c.expected_order))
    return out


