"""Speed against error: scenes with a reference, swept over the physics step, the solver's
iterations and preferAccuracy on each backend.

Reference, per scene:
- closed form: a conformance case with a `convergence` measure; the error is that measure's
  (the case's own expectation, run at the swept step);
- fine step: any other scene (a case without such a measure, or a scene file); the error is the
  largest distance of a body from where the same backend puts it at a step REFINEMENT times
  finer than the finest swept, with the most iterations swept and preferAccuracy on where the
  backend honours them, over the first `window` seconds (sweep_metrics says why one window).

Speed: wall time per simulated second, the child's own measure (`x3drbp run --timing`) of
the time spent in the engine's steps, over the run's simulated seconds: the integration cost
that a long simulation pays. Not counted: interpreter start-up, imports, loading the scene,
building the engine model (which dominates short runs at coarse steps: 20-50 ms on Bullet
against microseconds a step), the evaluator's per-frame state reads and outputs, writing the
trace. The whole simulation's time (build, steps, reads) is kept beside it. Runs share the
machine with each other (as many at a time as the executor has workers): a speed under that load.

Only what a backend honours is varied: one that declares RigidBodyCollection.iterations or
preferAccuracy unsupported runs the scene's own value (it would refuse another).
"""

from __future__ import annotations

import json
import math
import os
import sys
from collections.abc import Sequence
from concurrent.futures import FIRST_COMPLETED, wait
from dataclasses import asdict, dataclass

from conformance import cases as C
from conformance import results
from conformance.results import Settings
from conformance.runner import children, probe
from conformance.analyses.distribute import executor, guarded
from conformance.analyses.sweep_job import Job, JobResult, run_job
from conformance.analyses.sweep_metrics import comparison_interval, pareto, window_error

REFINEMENT = 8  # the fine-step reference's step: the finest swept over this
DEFAULT_SCENES = ("pendulum_period", "projectile", "bounce_apex",
                  os.path.join("conformance", "cases", "double_pendulum_energy", "double_pendulum_energy.x3d"))
DEFAULT_DTS = (1 / 60, 1 / 240, 1 / 1000, 1 / 4000)
DEFAULT_ITERATIONS = (10, 50)
DEFAULT_WINDOW = 1.0  # s
FIELDS = ("RigidBodyCollection.iterations", "RigidBodyCollection.preferAccuracy")
CLOSED_FORM, FINE_STEP = "closed form", "fine step"


@dataclass(frozen=True)
class Target:
    """A scene to sweep and how its error is measured."""
    name: str
    scene: str  # relative to the project root where it is under it
    settings: Settings  # duration and frames (the step is swept)
    case: str | None  # closed form: this case's convergence measure; None: fine-step reference
    quantity: str

    @property
    def reference(self) -> str:
        return CLOSED_FORM if self.case else FINE_STEP


def targets(names: Sequence[str], dts: Sequence[float], window: float = DEFAULT_WINDOW) -> list[Target]:
    """Targets for case names and scene files (ValueError naming what is wrong). A case with a
    convergence measure is judged by its closed form over its own duration; other cases and
    scene files by the fine-step reference over the window, at frames comparison_interval apart."""
    interval = comparison_interval([*dts, min(dts) / REFINEMENT])
    if interval > window:
        raise ValueError(f"the steps have no common multiple within the {window:g} s window "
                         f"(the shortest is {interval:g} s): choose steps like 1/60, 1/240, 1/1000")
    fine = Settings(window, min(dts), 1.0 / interval)
    out = []
    for name in names:
        case = C.BY_NAME.get(name)
        if case is not None and len(case.runs) != 1:
            raise ValueError(f"case {name} judges several runs together; the sweep varies one")
        if case is not None and case.convergence:
            out.append(Target(name, _relative(case.path), case.runs[0], name, case.convergence))
            continue
        path = case.path if case is not None else name
        if not os.path.isfile(path):
            raise ValueError(f"{name} is neither a case ({', '.join(C.BY_NAME)}) nor a scene file")
        label = name if case is not None else os.path.splitext(os.path.basename(path))[0]
        out.append(Target(label, _relative(path), fine, None,
                          f"max |position - fine-step position| over the first {window:g} s"))
    names_seen = [t.name for t in out]
    if len(set(names_seen)) != len(names_seen):
        raise ValueError(f"two targets share a name: {', '.join(names_seen)}")
    return out


def _relative(path: str) -> str:
    rel = os.path.relpath(os.path.abspath(path), C.ROOT)
    return os.path.abspath(path) if rel.startswith("..") else rel


@dataclass(frozen=True)
class BackendPlan:
    name: str
    version: str | None
    iterations: bool  # honours RigidBodyCollection.iterations (native or approximate)
    prefer_accuracy: bool


_DECLARED = """
import json, sys
from backends import base
fields = sys.argv[2:]
print("x3drbp-declared " + json.dumps({n: [base.load(n).support(f).support is not base.Support.UNSUPPORTED
                                            for f in fields] for n in sys.argv[1].split(",")}))
"""


def backend_plans(names: Sequence[str], timeout: float = children.DEFAULT_TIMEOUT
                  ) -> tuple[dict[str, BackendPlan], dict[str, str]]:
    """What each usable named backend (default: every one) honours of FIELDS, asked in a child
    process (importing an engine can crash) once probe.backend_table has said which engines
    load; and why the others cannot run (all of them, where that child gave no answer).
    ValueError naming unknown backends."""
    info = probe.backend_table(timeout)
    named = probe.named_backends(names, info) if names else list(info)  # unusable ones listed as skipped
    usable = [n for n in named if info[n].usable]
    skipped = {n: info[n].unavailable or "" for n in named if not info[n].usable}
    if not usable:
        return {}, skipped
    declared, why = _declarations(usable, timeout)
    if declared is None:
        return {}, {**skipped, **{n: f"its declarations could not be read: {why}" for n in usable}}
    return {n: BackendPlan(n, info[n].version, *declared[n]) for n in usable}, skipped


def _declarations(usable: Sequence[str], timeout: float) -> tuple[dict | None, str]:
    """What each backend declares of FIELDS, asked in a child: (the answer, or None and why not)."""
    try:
        done = children.call([sys.executable, "-c", _DECLARED, ",".join(usable), *FIELDS], timeout)
    except OSError as e:
        return None, str(e)
    if done.returncode is None:
        return None, f"no answer within {timeout:g} s"
    found = [ln for ln in done.stdout.splitlines() if ln.startswith("x3drbp-declared ")]
    if done.returncode != 0 or not found:
        return None, children.classify(done.returncode, done.stderr).reason or "the child printed nothing"
    return json.loads(found[-1].split(" ", 1)[1]), ""


@dataclass
class Point:
    """One run of the sweep, as sweep.json holds it."""
    scene: str
    backend: str
    dt: float
    iterations: int | None  # None: the scene's own (the backend does not honour the field)
    prefer_accuracy: bool | None
    verdict: str = ""
    reason: str = ""
    error: float | None = None
    wall_per_sim_s: float | None = None  # the engine's steps
    simulation_per_sim_s: float | None = None  # the whole simulation: build, steps, per-frame reads
    pareto_backend: bool = False  # on the front of this scene's points on this backend
    pareto_scene: bool = False  # on the front of this scene's points on every backend

    def to_json(self) -> dict:
        d = asdict(self)
        d["dt_label"] = results.dt_label(self.dt)
        d["error"] = None if self.error is None or not math.isfinite(self.error) else self.error
        return d


def variations(plan: BackendPlan, iterations: Sequence[int], accuracy: Sequence[bool]
               ) -> list[tuple[int | None, bool | None]]:
    """The (iterations, preferAccuracy) pairs a backend is run at: None where it does not honour the field."""
    its: Sequence[int | None] = iterations if plan.iterations else (None,)
    acc: Sequence[bool | None] = accuracy if plan.prefer_accuracy else (None,)
    return [(i, a) for i in its for a in acc]


def _reference_job(t: Target, plan: BackendPlan, dts: Sequence[float], iterations: Sequence[int],
                   timeout: float) -> Job:
    return Job(t.scene, plan.name, t.settings.with_dt(min(dts) / REFINEMENT),
               max(iterations) if plan.iterations else None, True if plan.prefer_accuracy else None,
               None, timeout)


@dataclass
class Sweep:
    points: list[Point]
    references: dict[tuple[str, str], tuple[Job, JobResult]]  # (scene, backend) -> the fine-step run
    units: dict[str, str]  # scene -> the error's unit


def run_sweep(chosen: Sequence[Target], plans: dict[str, BackendPlan], dts: Sequence[float],
              iterations: Sequence[int], accuracy: Sequence[bool], timeout: float = children.DEFAULT_TIMEOUT,
              scheduler: str | None = None, workers: int | None = None, progress: bool = False) -> Sweep:
    """Every target on every planned backend at every step and variation, on the executor."""
    keyed: list[tuple[Point | tuple[str, str], Job]] = []
    for t in chosen:
        for plan in plans.values():
            if t.case is None:
                keyed.append(((t.name, plan.name), _reference_job(t, plan, dts, iterations, timeout)))
            for dt in dts:
                for its, acc in variations(plan, iterations, accuracy):
                    keyed.append((Point(t.name, plan.name, dt, its, acc),
                                  Job(t.scene, plan.name, t.settings.with_dt(dt), its, acc, t.case, timeout)))
    results = execute([job for _, job in keyed], scheduler, workers, progress)
    references = {key: (job, res) for (key, job), res in zip(keyed, results) if isinstance(key, tuple)}
    points, units = [], {}
    for (key, job), res in zip(keyed, results):
        if isinstance(key, Point):
            _fill(key, job, res, references.get((key.scene, key.backend)))
            points.append(key)
            if res.unit:
                units.setdefault(key.scene, res.unit)
    for t in chosen:
        units.setdefault(t.name, "m" if t.case is None else "")
    mark_pareto(points)
    return Sweep(points, references, units)


def _fill(p: Point, job: Job, res: JobResult, reference: tuple[Job, JobResult] | None) -> None:
    p.verdict, p.reason = res.verdict, res.reason
    if res.step_s is not None and res.simulation_s is not None:
        p.wall_per_sim_s = res.step_s / job.settings.duration
        p.simulation_per_sim_s = res.simulation_s / job.settings.duration
    if res.positions is None:
        p.error = res.error
        return
    ref_job, ref = reference  # a run kept for its positions always has its reference
    if ref.positions is None:
        p.verdict, p.reason = results.ERROR, f"the reference run (dt {ref_job.settings.dt:g}) {ref.verdict}: {ref.reason}"
        return
    try:
        p.error = window_error(res.positions, ref.positions, job.settings.duration)
    except ValueError as e:
        p.verdict, p.reason = results.ERROR, str(e)


def execute(jobs: Sequence[Job], scheduler: str | None, workers: int | None, progress: bool) -> list[JobResult]:
    """Run the jobs on the executor, longest first (a long job last would leave workers idle);
    results in the jobs' order. The bar goes to stderr, and only when asked."""
    from tqdm import tqdm
    order = sorted(range(len(jobs)), key=lambda k: -jobs[k].settings.duration / jobs[k].settings.dt)
    with executor(scheduler, workers) as ex:
        futures = {k: ex.submit(guarded, run_job, jobs[k]) for k in order}
        with tqdm(total=len(jobs), unit="run", file=sys.stderr, disable=not progress) as bar:
            pending = set(futures.values())
            while pending:  # in slices, as children._communicate waits: a signal is handled within one
                done, pending = wait(pending, timeout=children.SLICE, return_when=FIRST_COMPLETED)
                bar.update(len(done))
        return [futures[k].result() for k in range(len(jobs))]


def mark_pareto(points: Sequence[Point]) -> None:
    """Set each point's Pareto flags: per scene and backend, and per scene over all backends."""
    groups: dict[tuple[str, str | None], list[Point]] = {}
    for p in points:
        groups.setdefault((p.scene, p.backend), []).append(p)
        groups.setdefault((p.scene, None), []).append(p)
    for (_, backend), group in groups.items():
        flags = pareto([p.wall_per_sim_s for p in group], [p.error for p in group])
        for p, flag in zip(group, flags):
            if backend is None:
                p.pareto_scene = flag
            else:
                p.pareto_backend = flag
