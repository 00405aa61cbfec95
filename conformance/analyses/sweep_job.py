"""One sweep run: a scene, its RigidBodyCollections' iterations and preferAccuracy set as
asked, on one backend at one step, in a child `x3drbp run`; plain data back.

It runs wherever the executor puts it (a local pool process, a Dask worker, perhaps on
another machine with the project at another path), so a Job carries everything by value,
the scene as a path under the project root, and the run writes its scene copy, trace and
timing in a temporary folder of its own.
"""

from __future__ import annotations

import json
import os
import tempfile
from dataclasses import dataclass

import numpy as np

from x3d_core.encodings.load import load
from x3d_core.encodings.xml_writer import write_xml
from x3d_core.files import atomic
from x3d_core.model.scene import LoadError
from x3d_core.traces.trace import TraceView, read_view

from conformance import cases as C
from conformance import results
from conformance.results import Settings
from conformance.runner import children, verdicts
from conformance.analyses.sweep_metrics import Positions

MEASURED = "measured"  # the run ended well; its error is against a finer-step run, no tolerance


@dataclass(frozen=True)
class Job:
    scene: str  # relative to the project root (or absolute)
    backend: str
    settings: Settings
    iterations: int | None = None  # written into every RigidBodyCollection; None keeps the file's
    prefer_accuracy: bool | None = None  # likewise
    case: str | None = None  # judge the run by this case and return its convergence measure; None: positions
    timeout: float = children.DEFAULT_TIMEOUT
    repeats: int = 1  # timed runs in the child (x3drbp run --repeat)


@dataclass
class JobResult:
    verdict: str  # the runner's verdict of a judged run; MEASURED for a run kept for its positions
    reason: str = ""
    step_s: tuple[float, ...] = ()  # the child's own wall time in the engine's steps, each repeat (run --timing)
    simulation_s: float | None = None  # ... the median of the whole simulation (plan, build, steps, reads)
    error: float | None = None  # the case's convergence measure
    unit: str = ""
    positions: Positions | None = None
    cpu_s: tuple[float, ...] = ()  # the child's CPU time in the engine's steps, each repeat: what load does not inflate
    # the target accuracy of the error-controlled integrator every world stepped by (the loosest);
    # None where a world stepped at the fixed step (the engine picks per world: only the child knows)
    target_accuracy: float | None = None


def with_collection_fields(src: str, dst: str, iterations: int | None, prefer_accuracy: bool | None) -> None:
    """Write the scene at src to dst (XML encoding) with every RigidBodyCollection's iterations
    and preferAccuracy set (None: as in the file). LoadError if src does not load."""
    scene = load(src)
    if scene.errors:
        raise LoadError(scene.errors[0])
    for node in scene.of_type("RigidBodyCollection"):
        if iterations is not None:
            node.values["iterations"] = iterations
        if prefer_accuracy is not None:
            node.values["preferAccuracy"] = prefer_accuracy
    atomic.write_bytes(dst, write_xml(scene))


def positions(view: TraceView) -> Positions:
    """Every body's position and orientation series from a trace (bodies in the trace's order)."""
    keys = view.bodies()
    if not keys:
        raise ValueError("the trace has no body positions")
    series = [view.series(node, fld) for fld in ("position", "orientation") for node in keys]
    times = series[0][0]
    if any(len(t) != len(times) for t, _ in series):
        raise ValueError("the bodies' poses are recorded at different frames")
    n = len(keys)
    return Positions(times, tuple(keys), np.stack([v for _, v in series[:n]], axis=1),
                     np.stack([v for _, v in series[n:]], axis=1))


def _controlled(per_world: list[float | None]) -> float | None:
    """The run's target accuracy where every world was error-controlled (the loosest), else None."""
    if not per_world or any(a is None for a in per_world):
        return None
    return max(float(a) for a in per_world)


def run_job(job: Job) -> JobResult:
    """Run the job's scene once in a child process and judge or sample its trace."""
    scene = job.scene if os.path.isabs(job.scene) else os.path.join(C.ROOT, job.scene)
    with tempfile.TemporaryDirectory(prefix="x3drbp-sweep-") as tmp:
        if job.iterations is not None or job.prefer_accuracy is not None:
            copy = os.path.join(tmp, "scene.x3d")
            try:
                with_collection_fields(scene, copy, job.iterations, job.prefer_accuracy)
            except (OSError, LoadError) as e:
                return JobResult(results.ERROR, f"the scene could not be rewritten: {e}")
            scene = copy
        trace, timing = os.path.join(tmp, "trace.npz"), os.path.join(tmp, "timing.json")
        out = children.run_child(scene, job.backend, job.settings, trace, job.timeout,
                                 extra=("--timing", timing, "--repeat", str(job.repeats)))
        if out.verdict is not None:
            return JobResult(out.verdict, out.reason)
        try:
            with open(timing, encoding="utf-8") as f:
                times = json.load(f)
            step_s = tuple(float(x) for x in times["repeats"]["step_wall_s"])
            cpu_s = tuple(float(x) for x in times["repeats"].get("step_cpu_s", ()))
            simulation_s = float(times["simulation_wall_s"])
            accuracy = _controlled(times.get("target_accuracy", []))
            view = read_view(trace)
        except (OSError, ValueError, KeyError) as e:
            return JobResult(results.ERROR, f"unreadable trace or timing: {e}")
    if job.case is None:
        try:
            return JobResult(MEASURED, "", step_s, simulation_s, cpu_s=cpu_s, positions=positions(view),
                             target_accuracy=accuracy)
        except ValueError as e:
            return JobResult(results.ERROR, str(e), step_s, simulation_s)
    case = C.BY_NAME[job.case]
    result = verdicts.evaluate(case, job.backend, [view], [job.settings])
    measure = result.measure(case.convergence) if case.convergence else None
    if measure is None:
        return JobResult(result.verdict if result.verdict == results.ERROR else results.ERROR,
                         result.reason or f"no {case.convergence} measure", step_s, simulation_s)
    return JobResult(result.verdict, result.reason, step_s, simulation_s, measure.error, measure.unit, cpu_s=cpu_s)
