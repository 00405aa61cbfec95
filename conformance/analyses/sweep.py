"""Speed against error: scenes with a reference, swept over the physics step, the solver's
iterations and preferAccuracy on each backend.

Error, against one reference per scene, common to every backend:
- closed form: a conformance case with a `convergence` measure; the error is that measure's
  (the case's own expectation, run at the swept step);
- common reference: any other scene (a case without such a measure, or a scene file); the
  error is the largest distance of a body from where the reference run puts it over the
  first `window` seconds (sweep_metrics says why one window). Which run that is, in order:
  1. Drake's error-controlled integration, wherever the drake backend is usable (whether or
     not it is among the backends compared) and runs the scene in its continuous mode (no
     collisions, no joint stops, no loops, nothing refused): RK3 at its tighter target
     accuracy (preferAccuracy TRUE, 1e-11), steps capped at the finest swept step. Why Drake:
     a backend's own finer run favours that backend (its scheme, its reading of the scene),
     where an error-controlled integrator converges to the equations of motion themselves,
     and Drake's joints are exact generalized coordinates (no constraint drift). Its own
     error: the distance from the same run at the looser target (preferAccuracy FALSE, 1e-6,
     1e5 times looser). Where the global error scales with the target (measured on the double
     pendulum over 1 s at 1/240: 5.8e-8 m at 1e-6, 1.3e-12 m at 1e-11), |run(A) - run(a)| >=
     |e(A)| - |e(a)| >= |e(a)| as long as e(A) >= 2 e(a): an upper bound. The integrator, not
     the cap, sets the step at 1/240 (437 steps at 1e-6 and 14,600 at 1e-11 against 240
     boundaries); at 1/1000 and 1/4000 the cap binds the looser run (1,000 and 4,994 steps),
     which makes it more accurate than its target and the estimate smaller (1.8e-9 and 2.9e-11
     m against 5.8e-8), yet still some 35 times the tighter run's error. A cap fine enough to
     bind both runs (below about 1/15,000 s there, the tighter run's own step) may make the
     estimate too small, but only where the tighter run then steps finer than its target asks,
     so its error is at most what the target gives (1.3e-12 m there, rounding). The mode is
     picked per world inside the backend, so the child says whether every world was
     error-controlled (x3d_core.semantics.engine.target_accuracy, in `run --timing`'s file): a run
     Drake stepped in discrete mode is never taken for this reference.
  2. Else, the fine run (what stood for every scene before): every backend runs the scene at
     a step REFINEMENT times finer than the finest swept, with the most iterations swept and
     preferAccuracy on (MuJoCo's selects RK4, fourth order where the others are first), and
     again at twice that step; the difference estimates the fine run's own error (for an
     integrator of order p >= 1, |run(2h) - run(h)| = (2^p - 1) |run(h) - exact| >= that
     error, asymptotically). The reference is the fine run of the first backend of
     REFERENCE_ORDER that ran both, and it says why Drake's was not used. On contacts
     MuJoCo's soft constraint is tuned to the step, so refining it moves it: its own error is
     then large, and so is what the comparison cannot tell apart.
  Each Reference states which (method, said, to_json), and so do sweep.json, sweep.md and
  advise's text and JSON.
  Scenes with events (contacts, joint stops; has_events): the trajectory is not smooth, a
  run does not converge to the others' contact model by refining its own, and no engine's
  contact model is the spec's (it names none), so a finer run of one engine is no truth for
  the others. What accuracy can mean there is agreement: the reference's uncertainty
  (Reference.error) is the larger of its own error and the spread of the compared backends'
  fine runs around it (the farthest one's distance over the window), each such run being
  as good a reading of the scene as the reference's. Errors within it tie on the fronts
  (mark_pareto), and advise says accuracy cannot be ranked where it exceeds the tolerance,
  ranking by speed what it cannot tell apart. Measured (1 s, mujoco reference at 1/1920):
  bounce_apex, own error 21 mm, ODE's fine run 20 mm from it, PhysX's 19, Bullet's 16;
  a 0.2 m box dropped 0.3 m onto a floor, own error 3.4 mm, DART's 5.5 mm, Drake's 5.2,
  PhysX's and pymunk's 4.7, ODE's 63 mm (ODE's run at 1/960 is as far from its own: not
  settled, but still what ODE makes of the scene at that step, so it is not discounted).
  A scene with events and one backend has no spread, and its reference says so. advise,
  which knows the verdicts, leaves out of the spread the fine run of a backend that fails
  (breaks the clause in) a case exercising a feature the scene uses while another backend
  passes it (Reference.without): such a run is no reading of the scene, and on the limited
  pendulum pymunk's, past its stops, set the spread at 0.43 m where the others reach 0.10 m. Event
  measures (first impact time, rebound apex, rest pose) are not taken: the pose error over
  the window already holds each (a late impact leaves the body elsewhere, a low apex or a
  wrong rest pose is a distance), where an event measure would need to know, per scene,
  which body's which contact is the event.
Self-consistency, beside it: each backend against its own run at that fine step, as a
backend's convergence says nothing of whether it converges to what the others do. advise
(reference_as_fine) takes Drake's error-controlled reference run for Drake's fine run where it
is the reference, rather than run Drake's fine pair: both are Drake's RK3 at its tighter target
over the window, their caps (the finest step; an eighth of it) only bounding the steps its
error control picks, and on a 10-link ball-joint chain that pair cost 9.3 s of CPU of advise's 76.

Speed: CPU time per simulated second, the child's own measure (`x3drbp run --timing`) of
the time spent in the engine's steps, over the run's simulated seconds: the integration cost
that a long simulation pays; the median of REPEATS runs in the child, with their spread.
CPU time, not wall time, ranks: runs share the machine with each other (as many at a time as
the executor has workers) and with whatever else runs, and that load stretches and reorders
wall times where a process's own CPU time stays (advise ranks by it too); the wall time of
the same steps is kept beside it. Not counted: interpreter start-up, imports, loading the
scene, building the engine model (which dominates short runs at coarse steps: 20-50 ms on
Bullet against microseconds a step), the evaluator's per-frame state reads and outputs,
writing the trace. The whole simulation's wall time (build, steps, reads) is kept beside it.

Fronts: points whose speeds' spreads overlap and whose errors differ by less than the
reference's uncertainty (its own error, or on a scene with events the backends' spread
where larger; or rounding) are ties, one front point (sweep_metrics.pareto).

Only what a backend honours is varied: one that declares RigidBodyCollection.iterations or
preferAccuracy unsupported runs the scene's own value (it would refuse another).
"""

from __future__ import annotations

import functools
import heapq
import itertools
import math
import os
import threading
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import asdict, dataclass, field, replace

from x3d_core.encodings.load import load
from x3d_core.model.scene import Scene
from x3d_core.semantics.analysis import run_features

from conformance import cases as C
from conformance import results
from conformance.results import Settings
from conformance.runner import cache, children, probe
from conformance.analyses.distribute import executor
from conformance.analyses.sweep_job import Job, JobResult, run_job
from conformance.analyses.sweep_metrics import Cost, Positions, comparison_interval, pareto, window_error

REFINEMENT = 8  # the fine-step reference's step: the finest swept over this
REPEATS = 3  # timed runs of each point, in its child: the median and the spread
# whose fine run is the common reference where Drake's error-controlled one is not, the first
# that ran it: MuJoCo's RK4 is fourth order where the others integrate to first order; then
# ODE, the engine the spec's parameters come from; the two newest last
REFERENCE_ORDER = ("mujoco", "ode", "dart", "bullet", "pymunk", "drake", "physx")
DRAKE = "drake"  # whose error-controlled run is the reference wherever it runs the scene as one
ERROR_CONTROLLED, FINE_RUN = "error-controlled", "fine run"  # a common reference's method
# the bundled scene by its path in the project, so that the default finds it from any folder
DEFAULT_SCENES = ("pendulum_period", "projectile", "bounce_apex",
                  os.path.join(C.ROOT, "conformance", "cases", "double_pendulum_energy", "double_pendulum_energy.x3d"))
DEFAULT_DTS = (1 / 60, 1 / 240, 1 / 1000, 1 / 4000)
DEFAULT_ITERATIONS = (10, 50)
DEFAULT_WINDOW = 1.0  # s
FIELDS = ("RigidBodyCollection.iterations", "RigidBodyCollection.preferAccuracy")
CLOSED_FORM, COMMON = "closed form", "common reference"


@dataclass(frozen=True)
class Target:
    """A scene to sweep and how its error is measured."""
    name: str
    scene: str  # relative to the project root where it is under it
    settings: Settings  # duration and frames (the step is swept)
    case: str | None  # closed form: this case's convergence measure; None: the common reference
    quantity: str
    window: float = DEFAULT_WINDOW  # s compared with the common reference
    events: bool = False  # contacts or joint stops: its trajectory is not smooth (common reference only)

    @property
    def reference(self) -> str:
        return CLOSED_FORM if self.case else COMMON


def targets(names: Sequence[str], dts: Sequence[float], window: float = DEFAULT_WINDOW,
            duration: float | None = None, loaded: Mapping[str, Scene] | None = None) -> list[Target]:
    """Targets for case names and scene files (ValueError naming what is wrong). A case with a
    convergence measure is judged by its closed form over its own duration; other cases and
    scene files by the common reference over the window, run for `duration` (default: the
    window), at frames comparison_interval apart. loaded: scenes the caller has loaded already,
    by name (a large scene takes as long to load again as to run)."""
    interval = comparison_interval([*dts, min(dts) / REFINEMENT, 2 * min(dts) / REFINEMENT])
    if interval > window:
        raise ValueError(f"the steps have no common multiple within the {window:g} s window "
                         f"(the shortest is {interval:g} s): choose steps like 1/60, 1/240, 1/1000")
    fine = Settings(max(window, duration or window), min(dts), 1.0 / interval)
    out = []
    for name in names:
        case = C.BY_NAME.get(name)
        if case is not None and len(case.runs) != 1:
            raise ValueError(f"case {name} judges several runs together; the sweep varies one")
        if case is not None and case.convergence:
            out.append(Target(name, relative(case.path), case.runs[0], name, case.convergence))
            continue
        path = case.path if case is not None else name
        if not os.path.isfile(path):
            raise ValueError(f"{name} is neither a case ({', '.join(C.BY_NAME)}) nor a scene file")
        label = name if case is not None else os.path.splitext(os.path.basename(path))[0]
        scene = (loaded or {}).get(name)
        out.append(Target(label, relative(path), fine, None,
                          f"max |position - reference position| over the first {window:g} s", window,
                          has_events(load(path) if scene is None else scene)))
    # two scene files of one stem: numbered, as their plots are named after them
    return [replace(t, name=name) for t, name in zip(out, numbered([t.name for t in out]))]


def has_events(scene: Scene) -> bool:
    """Whether a run of the scene has events (contacts or joint stops), where its trajectory is
    not smooth; False where it does not load (its runs will say why)."""
    if scene.errors:
        return False
    return any(f.startswith("CollisionCollection") or f.endswith(".limits") for f in run_features(scene))


def numbered(names: Sequence[str]) -> list[str]:
    """Each name as given, numbered from its second use on (NAME, NAME-2, NAME-3), a number
    taken by a name given (a scene called NAME-2) skipped: results named after scenes that
    share a file name, or that are named like another's number, do not overwrite each other."""
    taken, out = set(names), []
    for name in names:
        if name in out:
            k = 2
            while f"{name}-{k}" in taken:
                k += 1
            name = f"{name}-{k}"
            taken.add(name)
        out.append(name)
    return out


def relative(path: str) -> str:
    """A path relative to the project root where it lies under it (where the children run), else absolute."""
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
print("x3drbp-answer " + json.dumps({n: [base.load(n).support(f).support is not base.Support.UNSUPPORTED
                                          for f in fields] for n in sys.argv[1].split(",")}))
"""


def backend_plans(names: Sequence[str], timeout: float = children.DEFAULT_TIMEOUT
                  ) -> tuple[dict[str, BackendPlan], dict[str, str]]:
    """What each usable named backend (default: every one) honours of FIELDS, asked in a child
    process (importing an engine can crash) once probe.backend_table has said which engines
    load; and why the others cannot run (all of them, where that child gave no answer).
    ValueError naming unknown backends."""
    info = probe.backend_table(timeout, names)  # unusable ones listed as skipped
    usable = [n for n, i in info.items() if i.usable]
    skipped = {n: i.unavailable or "" for n, i in info.items() if not i.usable}
    if not usable:
        return {}, skipped
    declared, why = _declarations(usable, timeout)
    if declared is None:
        return {}, {**skipped, **{n: f"its declarations could not be read: {why}" for n in usable}}
    return {n: BackendPlan(n, info[n].version, *declared[n]) for n in usable}, skipped


def _declarations(usable: Sequence[str], timeout: float) -> tuple[dict | None, str]:
    """What each backend declares of FIELDS, asked in a child: (the answer, or None and why not)."""
    return probe.ask(_DECLARED, [",".join(usable), *FIELDS], timeout, "the declarations' child")


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
    error: float | None = None  # against the scene's reference (closed form or the common one)
    self_error: float | None = None  # against the same backend at the fine step (no closed form only)
    wall_per_sim_s: float | None = None  # the engine's steps: the median of the repeats
    wall_low: float | None = None  # ... the repeats' spread
    wall_high: float | None = None
    simulation_per_sim_s: float | None = None  # the whole simulation: build, steps, per-frame reads
    cpu_per_sim_s: float | None = None  # the engine's steps in CPU time (what load does not reorder): the median
    cpu_low: float | None = None  # ... the repeats' spread
    cpu_high: float | None = None
    pareto_backend: bool = False  # on the front of this scene's points on this backend
    pareto_scene: bool = False  # on the front of this scene's points on every backend
    tie_backend: str | None = None  # on that front as a tie of this point (its label)
    tie_scene: str | None = None

    @property
    def cost(self) -> Cost | None:
        """What speed is ranked by: the engine's steps' CPU time per simulated second, with its
        spread (None before it is measured). Not wall time: runs share the machine with each
        other and with whatever else runs, and load reorders wall times but not CPU times."""
        return None if self.cpu_per_sim_s is None else Cost(self.cpu_per_sim_s, self.cpu_low, self.cpu_high)

    @property
    def wall(self) -> Cost | None:
        """The same steps in wall time, kept beside it: what a user waits, under this run's load."""
        if self.wall_per_sim_s is None:
            return None
        return Cost(self.wall_per_sim_s, self.wall_low, self.wall_high)

    @property
    def label(self) -> str:
        its = "" if self.iterations is None else f" it={self.iterations}"
        acc = "" if self.prefer_accuracy is None else f" acc={'TRUE' if self.prefer_accuracy else 'FALSE'}"
        return f"{self.backend} {results.dt_label(self.dt)}{its}{acc}"

    def to_json(self) -> dict:
        d = asdict(self)
        d["dt_label"] = results.dt_label(self.dt)
        d["label"] = self.label
        for k in ("error", "self_error"):
            d[k] = None if d[k] is None or not math.isfinite(d[k]) else d[k]
        return d


def variations(plan: BackendPlan, iterations: Sequence[int], accuracy: Sequence[bool]
               ) -> list[tuple[int | None, bool | None]]:
    """The (iterations, preferAccuracy) pairs a backend is run at: None where it does not
    honour the field, or where none are asked (the scene's own)."""
    its: Sequence[int | None] = iterations if plan.iterations and iterations else (None,)
    acc: Sequence[bool | None] = accuracy if plan.prefer_accuracy and accuracy else (None,)
    return [(i, a) for i in its for a in acc]


@dataclass(frozen=True)
class Reference:
    """A scene's common reference (no closed form): whose run, how it was made, its own error,
    and on a scene with events the backends' spread around it."""
    backend: str
    dt: float  # s: its step (Drake's: the largest its integrator may take)
    own_error: float  # m: the estimate of its own error (module docstring)
    runs: Positions
    accuracy: float | None = None  # Drake's target accuracy (error-controlled); None: a fine fixed-step run
    check: str = ""  # what its own error is the distance from
    instead: str = ""  # a fine run: why Drake's error-controlled run is not the reference
    events: bool = False  # the scene has contacts or joint stops: its trajectory is not smooth
    gaps: tuple[tuple[str, float], ...] = ()  # scenes with events: each other backend's fine run's distance from it
    left_out: str = ""  # backends whose fine runs the spread leaves out, and why (Reference.without)

    @property
    def method(self) -> str:
        return FINE_RUN if self.accuracy is None else ERROR_CONTROLLED

    @property
    def _farthest(self) -> tuple[float, str | None]:
        return max(((g, b) for b, g in self.gaps), default=(0.0, None))

    @property
    def spread(self) -> float:
        """m: scenes with events: the farthest other backend's fine run from it (0 without one)."""
        return self._farthest[0]

    @property
    def spread_backend(self) -> str | None:
        """... whose it is; None: no other backend's fine run."""
        return self._farthest[1]

    @property
    def error(self) -> float:
        """m: how far the reference may be from what the scene means, what errors tie within: its
        own error, or on a scene with events the backends' spread around it where larger."""
        return max(self.own_error, self.spread)

    @property
    def said(self) -> str:
        """The reference in words: what it is, its own error and how that was estimated, and
        what bounds it on a scene with events."""
        if self.accuracy is not None:  # never on a scene with events: Drake steps those at a fixed step
            return (f"{self.backend}'s error-controlled RK3 at target accuracy {self.accuracy:g} (steps of at most "
                    f"{results.dt_label(self.dt)} s), own error {self.own_error:.3g} m ({self.check})")
        text = (f"{self.backend}'s run at dt {results.dt_label(self.dt)} s, own error {self.own_error:.3g} m "
                f"({self.check})" + (f"; not Drake's error-controlled run: {self.instead}" if self.instead else ""))
        if not self.events:
            return text
        if self.spread_backend is None:
            return text + "; the scene has events (contacts or stops), and no other backend's fine run to measure it by"
        return (text + f"; the scene has events (contacts or stops): the other backends' fine runs lie up to "
                f"{self.spread:.3g} m from it ({self.spread_backend}"
                + (f"; left out: {self.left_out}" if self.left_out else "")
                + f"), so errors within {self.error:.3g} m of each other tie")

    def without(self, why: dict[str, str]) -> Reference:
        """The same reference, its spread taken over the other backends' fine runs but those of
        `why` (backend -> the reason, said): a backend that breaks the clause on a feature the
        scene uses is no reading of the scene, and its run must not widen what ties."""
        out = [b for b, _ in self.gaps if b in why]
        if not out:
            return self
        return replace(self, gaps=tuple((b, g) for b, g in self.gaps if b not in why),
                       left_out="; ".join(f"{b}'s fine run, {why[b]}" for b in out))

    def to_json(self) -> dict:
        return {"method": self.method, "backend": self.backend, "dt": self.dt, "accuracy": self.accuracy,
                "own_error": self.own_error, "check": self.check, "instead": self.instead or None,
                "events": self.events, "spread": self.spread, "spread_backend": self.spread_backend,
                "spread_left_out": self.left_out or None,
                "error": self.error, "said": self.said}


def _controlled_jobs(t: Target, dts: Sequence[float], timeout: float) -> tuple[Job, Job]:
    """Drake's run of the target over the window at its tighter target accuracy
    (preferAccuracy TRUE), and at its looser one (FALSE), for its own error; its steps capped
    at the finest swept step (module docstring)."""
    window = Settings(t.window, min(dts), t.settings.frame_rate)
    return (Job(t.scene, DRAKE, window, None, True, None, timeout, repeats=1),
            Job(t.scene, DRAKE, window, None, False, None, timeout, repeats=1))


def _fine_jobs(t: Target, plan: BackendPlan, dts: Sequence[float], iterations: Sequence[int],
               timeout: float) -> tuple[Job, Job]:
    """The backend's most accurate run of the target over the window, and the same at twice
    its step (for its own error)."""
    window = Settings(t.window, min(dts) / REFINEMENT, t.settings.frame_rate)
    its = max(iterations) if plan.iterations and iterations else None
    acc = True if plan.prefer_accuracy else None
    return (Job(t.scene, plan.name, window, its, acc, None, timeout, repeats=1),
            Job(t.scene, plan.name, window.with_dt(2 * window.dt), its, acc, None, timeout, repeats=1))


@dataclass
class Sweep:
    points: list[Point]
    fine: dict[tuple[str, str], tuple[Job, JobResult, JobResult]]  # (scene, backend) -> fine run, at 2x its step
    references: dict[str, Reference | str]  # scene (no closed form) -> its common reference, or why there is none
    controlled: dict[str, tuple[Job, JobResult, JobResult]]  # scene -> Drake's reference run, at the looser target
    units: dict[str, str]  # scene -> the error's unit
    positions: dict[tuple[str, str, float], Positions]  # (scene, backend, dt) -> a run's poses (no variation asked)
    runs: list[tuple[Job, JobResult]]  # each point's job and what it gave, in the points' order (time_again)
    # point index -> its further timings started as soon as its run ended (run_sweep's `again`): how many, and
    # the run giving them, which time_again takes where it asks as many, and drops (Pool.drop) where not
    ahead: dict[int, tuple[int, Future]] = field(default_factory=dict)


def run_sweep(chosen: Sequence[Target], plans: dict[str, BackendPlan], dts: Sequence[float],
              iterations: Sequence[int], accuracy: Sequence[bool], timeout: float = children.DEFAULT_TIMEOUT,
              scheduler: str | None = None, workers: int | None = None, progress: bool = False,
              repeats: int = REPEATS, controlled: bool | None = None, reference_as_fine: bool = False,
              pool: Pool | None = None, again: tuple[int, Callable[[Cost], bool]] | None = None) -> Sweep:
    """Every target on every planned backend at every step and variation, on the executor (or
    `pool`), and each target without a closed form's reference runs: every backend's fine run
    and, where `controlled` (None: wherever the drake backend is usable, compared or not),
    Drake's error-controlled one. Empty iterations or accuracy: the scene's own. reference_as_fine
    (advise): where Drake's error-controlled run is the reference, it is Drake's fine run too,
    and Drake's own fine pair is not run (_fine_or_reference). again (advise, with a pool):
    (EXTRA, near): a point whose run's cost `near` says is likely to be timed again has EXTRA
    further timings started in the pool as soon as it ends (Sweep.ahead, which time_again takes
    or drops), and each point runs as early as if its steps were taken 1 + EXTRA times, so that
    those timings, the longest jobs, start early rather than after every other run."""
    common = [t for t in chosen if t.case is None]
    if controlled is None:  # asked of a child only where some scene needs a reference run
        controlled = bool(common) and drake_usable(plans, timeout)
    # Drake's fine pair, left for after where its error-controlled run may stand for it: a scene
    # without events, which Drake steps in continuous mode (one with events it steps at the fixed step)
    deferred = {t.name: t for t in common if reference_as_fine and controlled and DRAKE in plans and not t.events}
    fine_jobs = {(t.name, b): _fine_jobs(t, plan, dts, iterations, timeout)
                 for t in common for b, plan in plans.items() if not (b == DRAKE and t.name in deferred)}
    drake_jobs = {t.name: _controlled_jobs(t, dts, timeout) for t in common} if controlled else {}
    keyed = [(Point(t.name, plan.name, dt, its, acc),
              Job(t.scene, plan.name, t.settings.with_dt(dt), its, acc, t.case, timeout, repeats), t)
             for t in chosen for plan in plans.values() for dt in dts
             for its, acc in variations(plan, iterations, accuracy)]
    by_name = {t.name: t for t in chosen}
    pairs = [*fine_jobs.values(), *drake_jobs.values()]
    scenes = [by_name[key[0] if isinstance(key, tuple) else key] for key in [*fine_jobs, *drake_jobs]]
    extra, near = again if again is not None and pool is not None else (0, None)
    own = [_steps(job, controlled and not t.events) for _, job, t in keyed]
    steps = [*(_steps(j, controlled and not t.events) for t, pair in zip(scenes, pairs) for j in pair),
             *((1 + extra) * n for n in own)]
    first = len(steps) - len(keyed)  # the points' jobs come after the reference runs'
    ahead: dict[int, tuple[int, Future]] = {}

    def timed_again(k: int, res: JobResult) -> None:
        """A job ended: a point's further timings started at once where `near` says of its cost
        (never as a run of one repeat, the point's own for the run cache: time_again)."""
        if k < first or not res.cpu_s:
            return
        job = keyed[k - first][1]
        more = replace(job, repeats=extra)
        if more != job and near(Cost.of([c / job.settings.duration for c in res.cpu_s])):
            ahead[k - first] = (extra, pool.submit(more, extra * own[k - first]))

    done = iter(execute([*(j for pair in pairs for j in pair), *(job for _, job, _ in keyed)], scheduler, workers,
                        progress, steps, pool, timed_again if near is not None else None))
    ran = [(pair[0], next(done), next(done)) for pair in pairs]
    fine, drake = dict(zip(fine_jobs, ran[:len(fine_jobs)])), dict(zip(drake_jobs, ran[len(fine_jobs):]))
    if deferred:
        fine.update(_fine_or_reference(deferred, drake, plans[DRAKE], dts, iterations, timeout, scheduler, workers,
                                       progress, pool))
    references = {t.name: common_reference(t.name, plans, fine, drake.get(t.name), t.events) for t in common}
    points, units, poses, runs = [], {}, {}, []
    for key, job, _ in keyed:
        res = next(done)
        _fill(key, job, res, references.get(key.scene), fine.get((key.scene, key.backend)))
        points.append(key)
        runs.append((job, res))
        if res.unit:
            units.setdefault(key.scene, res.unit)
        if res.positions is not None and job.iterations is None and job.prefer_accuracy is None:
            poses[(key.scene, key.backend, key.dt)] = res.positions
    for t in chosen:
        units.setdefault(t.name, "m" if t.case is None else "")
    tolerances = {s: r.error if isinstance(r, Reference) else 0.0 for s, r in references.items()}
    mark_pareto(points, tolerances)
    return Sweep(points, fine, references, drake, units, poses, runs, ahead)


def _fine_or_reference(deferred: Mapping[str, Target], drake: dict[str, tuple[Job, JobResult, JobResult]],
                       plan: BackendPlan, dts: Sequence[float], iterations: Sequence[int], timeout: float,
                       scheduler: str | None, workers: int | None, progress: bool, pool: Pool | None = None
                       ) -> dict[tuple[str, str], tuple[Job, JobResult, JobResult]]:
    """Drake's fine run of each deferred scene: its error-controlled reference run (with its check
    at the looser target) where that is the reference, as Drake's own finer run: at the target
    accuracy its fine run would have (preferAccuracy TRUE), over the same window, capped at the
    finest swept step rather than an eighth of it, a cap that only bounds the steps its error
    control picks for that target (module docstring). Else (Drake stepped the scene at the fixed
    step after all, or the run failed) its fine pair, run now, as for every other backend."""
    out, missing = {}, []
    for name, t in deferred.items():
        ran = drake[name]
        if isinstance(error_controlled(*ran), str):
            missing.append(t)
        else:
            out[(name, DRAKE)] = ran
    pairs = [_fine_jobs(t, plan, dts, iterations, timeout) for t in missing]
    done = iter(execute([j for pair in pairs for j in pair], scheduler, workers, progress, None, pool) if pairs else ())
    out.update({(t.name, DRAKE): (pair[0], next(done), next(done)) for t, pair in zip(missing, pairs)})
    return out


def time_again(sweep: Sweep, picked: Sequence[int], extra: int, scheduler: str | None = None,
               workers: int | None = None, progress: bool = False, pool: Pool | None = None) -> None:
    """Time the picked points (indices into sweep.points) `extra` more times, in one child each
    (`x3drbp run --repeat EXTRA`), the longest measured first, and set their speeds to the median
    and spread of every timing, the point's own included. A point whose further run did not end
    well keeps its own timings (the run that ended well measured them). advise times each point
    once, and again only the runs whose speed could change its advice. The run cache
    (conformance/runner/cache.py) keys a run by its options: a run of EXTRA repeats is another
    than the point's own, but one of a single repeat is the same, and reading it back would count
    the point's one timing twice, so that one is neither read back nor kept. A picked point whose
    `extra` timings were started ahead (Sweep.ahead: run_sweep's `again`) takes those; one started
    ahead and not picked is dropped where it has not ended (Pool.drop: a later call starts it
    again), so that it holds no worker."""
    ahead = {k: future for k, (n, future) in sweep.ahead.items() if k in picked and n == extra}
    for k, (_, future) in list(sweep.ahead.items()):  # the rest dropped, where they have not ended
        if k in ahead or future.cancel() or (pool is not None and pool.drop(future)):
            del sweep.ahead[k]
    rest = [k for k in picked if k not in ahead]
    jobs = [replace(sweep.runs[k][0], repeats=extra) for k in rest]
    expected = [sum(sweep.runs[k][1].cpu_s) for k in rest]
    with cache.turned_off(any(job == sweep.runs[k][0] for k, job in zip(rest, jobs))):
        done = dict(zip(rest, execute(jobs, scheduler, workers, progress, expected, pool) if jobs else []))
    children.wait_all(list(ahead.values()))
    done.update((k, future.result()) for k, future in ahead.items())
    for k, res in ((k, done[k]) for k in picked):
        if not res.cpu_s:
            continue
        job, first = sweep.runs[k]
        more = replace(first, step_s=first.step_s + res.step_s, cpu_s=first.cpu_s + res.cpu_s)
        sweep.runs[k] = (replace(job, repeats=len(more.cpu_s)), more)
        _time(sweep.points[k], job, more)


def drake_usable(plans: dict[str, BackendPlan], timeout: float) -> bool:
    """Whether the drake backend can run here: planned, or found usable by the probe (in a child)."""
    return DRAKE in plans or probe.backend_table(timeout, [DRAKE])[DRAKE].usable


def common_reference(scene: str, plans: dict[str, BackendPlan],
                     fine: dict[tuple[str, str], tuple[Job, JobResult, JobResult]],
                     controlled: tuple[Job, JobResult, JobResult] | None = None, events: bool = False
                     ) -> Reference | str:
    """The scene's common reference: Drake's error-controlled run where it ran as one
    (controlled: its run and its check at the looser target), else the fine run of the first
    backend in REFERENCE_ORDER that ran both it and its check, saying why not Drake's; on a
    scene with events, with the other backends' spread around it. Else why none could be."""
    ref = error_controlled(*controlled) if controlled is not None else "the drake backend is not available"
    if isinstance(ref, str):
        ref = fine_reference(scene, plans, fine, ref)
    if isinstance(ref, str) or not events:
        return ref
    others = {b: (job.settings.duration, run.positions) for (s, b), (job, run, _) in fine.items()
              if s == scene and b != ref.backend and run.positions is not None}
    return with_spread(ref, others)


def with_spread(ref: Reference, fine: dict[str, tuple[float, Positions]]) -> Reference:
    """The reference of a scene with events, with the spread of the other backends' fine runs
    (backend -> window, poses) around it: the largest distance of one from it over the window
    (module docstring: what accuracy means on a scene with contacts). A run with other bodies
    or frames says nothing of it and is left out."""
    gaps = []
    for b, (window, runs) in sorted(fine.items()):
        try:
            gaps.append((b, window_error(runs, ref.runs, window)))
        except ValueError:
            continue
    return replace(ref, events=True, gaps=tuple(gaps))


def error_controlled(job: Job, run: JobResult, check: JobResult) -> Reference | str:
    """Drake's run at its tighter target accuracy as the reference, its own error the distance
    from the same at the looser one; or why it cannot be: a run that did not end well, or one
    that the child says stepped a world at the fixed step (Drake's discrete mode)."""
    for r in (run, check):
        if r.positions is None:
            return f"drake: {r.verdict}" + (f" ({r.reason})" if r.reason else "")
    if run.target_accuracy is None or check.target_accuracy is None:
        return "drake stepped it at the fixed step (discrete mode: the scene collides or has a stop)"
    if run.target_accuracy >= check.target_accuracy:
        return (f"drake's preferAccuracy TRUE did not tighten its target accuracy ({run.target_accuracy:g}, "
                f"{check.target_accuracy:g} without)")
    try:
        own = window_error(check.positions, run.positions, job.settings.duration)
    except ValueError as e:
        return f"drake: {e}"
    return Reference(DRAKE, job.settings.dt, own, run.positions, run.target_accuracy,
                     f"its distance from the same at target accuracy {check.target_accuracy:g}")


def fine_reference(scene: str, plans: dict[str, BackendPlan],
                   fine: dict[tuple[str, str], tuple[Job, JobResult, JobResult]], instead: str) -> Reference | str:
    """The fine run of the first backend in REFERENCE_ORDER whose fine run and its check at
    twice the step both ran, with its own error; else why none could be. Not the smallest own
    error: that measures how fast an engine converges to its own contact model, not how close
    it is to the others, and on a contact scene it chose pymunk, whose coarse runs then beat
    four engines that agreed with each other."""
    order = [b for b in REFERENCE_ORDER if b in plans] + [b for b in plans if b not in REFERENCE_ORDER]
    why = []
    for b in order:
        job, run, check = fine[(scene, b)]
        if run.positions is None or check.positions is None:
            bad = run if run.positions is None else check
            why.append(f"{b}: {bad.verdict}" + (f" ({bad.reason})" if bad.reason else ""))
            continue
        try:
            return Reference(b, job.settings.dt, window_error(check.positions, run.positions, job.settings.duration),
                             run.positions, check="its distance from the same at twice the step", instead=instead)
        except ValueError as e:
            why.append(f"{b}: {e}")
    return f"not Drake's error-controlled run ({instead}), and no backend's fine-step run ended well: " + "; ".join(why)


def _fill(p: Point, job: Job, res: JobResult, reference: Reference | str | None,
          fine: tuple[Job, JobResult, JobResult] | None) -> None:
    p.verdict, p.reason = res.verdict, res.reason
    _time(p, job, res)
    if res.positions is None:
        p.error = res.error
        return
    window = fine[0].settings.duration
    own = fine[1].positions
    try:
        p.self_error = None if own is None else window_error(res.positions, own, window)
        if isinstance(reference, str):
            p.verdict, p.reason = results.ERROR, f"no common reference: {reference}"
            return
        p.error = window_error(res.positions, reference.runs, window)
    except ValueError as e:
        p.verdict, p.reason = results.ERROR, str(e)


def _time(p: Point, job: Job, res: JobResult) -> None:
    """The point's speeds from its run's timings: the median of the repeats and their spread."""
    if res.step_s:
        cost = Cost.of([s / job.settings.duration for s in res.step_s])
        p.wall_per_sim_s, p.wall_low, p.wall_high = cost.median, cost.low, cost.high
        p.simulation_per_sim_s = res.simulation_s / job.settings.duration
    if res.cpu_s:
        cpu = Cost.of([s / job.settings.duration for s in res.cpu_s])
        p.cpu_per_sim_s, p.cpu_low, p.cpu_high = cpu.median, cpu.low, cpu.high


def execute(jobs: Sequence[Job], scheduler: str | None, workers: int | None, progress: bool,
            expected: Sequence[float] | None = None, pool: Pool | None = None,
            then: Callable[[int, JobResult], None] | None = None) -> list[JobResult]:
    """Run the jobs on the executor (or in `pool`, local), longest first (a long job last would
    leave workers idle): by `expected` cost (a job timed before: its CPU s; run_sweep's: _steps),
    by default its duration over its step; results in the jobs' order. then(k, result) (a pool
    only) as job k ends, before its result counts as come. The bar goes to stderr, and only
    when asked."""
    length = expected or [job.settings.duration / job.settings.dt for job in jobs]
    order = sorted(range(len(jobs)), key=lambda k: -length[k])
    if pool is not None:
        futures = {k: pool.submit(jobs[k], length[k], None if then is None else functools.partial(then, k))
                   for k in order}
        children.wait_all(list(futures.values()), progress)
        return [futures[k].result() for k in range(len(jobs))]
    with executor(scheduler, workers) as ex:
        futures = {k: ex.submit(run_job, jobs[k]) for k in order}
        children.wait_all(list(futures.values()), progress)
        return [futures[k].result() for k in range(len(jobs))]


# steps per simulated second that Drake's error control takes, by target accuracy (preferAccuracy
# TRUE: 1e-11, else 1e-6), measured on the double pendulum at 1/240 (module docstring): its cap,
# the step, binds little
CONTROLLED_STEPS = {True: 14_600, False: 437}
# fixed steps of the other engines that one of those steps costs about as much as (several
# evaluations of the dynamics and an error estimate): on issue 38's chain 0.3 ms against 6-16 us
# at 1/1000 (MuJoCo, Bullet, DART, PhysX), on the pendulum 18 us against 2 us (MuJoCo)
CONTROLLED_STEP_COST = 20


def _steps(job: Job, controlled: bool) -> float:
    """What a job is expected to cost, in fixed steps, which execute runs the longest first by:
    its duration over its step; where Drake integrates the scene error-controlled (`controlled`:
    Drake usable, no events), the steps its error control takes (CONTROLLED_STEPS), each as
    costly as CONTROLLED_STEP_COST. Ranked by the step alone, Drake's 5 s run at 1/60 of issue
    38's chain (300 steps, 4.3 CPU s) started last, behind 30 runs of milliseconds, and a core
    waited on it."""
    steps = job.settings.duration / job.settings.dt
    if controlled and job.backend == DRAKE:
        steps = max(steps, job.settings.duration * CONTROLLED_STEPS[job.prefer_accuracy is True]) * CONTROLLED_STEP_COST
    return steps


class Pool:
    """Local worker threads for sweep jobs given in several batches (advise's runs, their
    further timings, Drake's fine pair): each worker that frees up takes the longest job
    waiting (the highest priority: execute's length), whichever batch gave it, so that a long
    job given late (a further timing) starts before short ones given early."""

    def __init__(self, workers: int | None = None):
        self._threads = ThreadPoolExecutor(max_workers=max(1, workers or os.cpu_count() or 1))
        self._waiting: list[tuple[float, int, Job, Future, Callable[[JobResult], None] | None]] = []
        self._lock = threading.Lock()
        self._given = itertools.count()  # among equal priorities, the first given first
        self._stops: dict[Future, threading.Event] = {}  # a running job's: set, its run ends (drop)
        self._closed = False

    def submit(self, job: Job, priority: float, then: Callable[[JobResult], None] | None = None) -> Future:
        """The job's future: its result once a worker has run it (and then(result), before it is
        set); cancelled where the pool is closed before it starts."""
        future: Future = Future()
        with self._lock:
            if self._closed:
                future.cancel()
                return future
            heapq.heappush(self._waiting, (-priority, next(self._given), job, future, then))
            self._stops[future] = threading.Event()
            self._threads.submit(self._next)
        return future

    def drop(self, future: Future) -> bool:
        """Nobody wants the job's result: cancelled where it has not started, its run ended
        where it has (children.droppable: its future then raises children.Dropped); False
        where it has ended already."""
        if future.cancel():
            return True
        stop = self._stops.get(future)
        if stop is None or future.done():
            return False
        stop.set()
        return True

    def _next(self) -> None:
        with self._lock:
            _, _, job, future, then = heapq.heappop(self._waiting)
        try:
            if not future.set_running_or_notify_cancel():
                return
            try:
                with children.droppable(self._stops[future]):
                    res = run_job(job)
                if then is not None:
                    then(res)
            except BaseException as e:  # an interrupt included: the waiting command raises it
                future.set_exception(e)
            else:
                future.set_result(res)
        finally:
            self._stops.pop(future, None)

    def __enter__(self) -> Pool:
        return self

    def __exit__(self, *_: object) -> None:
        self.close()

    def close(self) -> None:
        """Cancel what has not started; wait for what has."""
        with self._lock:
            self._closed = True
            for *_, future, _ in self._waiting:
                future.cancel()
        self._threads.shutdown(wait=True)


def mark_pareto(points: Sequence[Point], tolerances: dict[str, float] | None = None) -> None:
    """Set each point's Pareto flags and ties: per scene and backend, and per scene over all
    backends; errors within the scene's tolerance (its reference's own error) tie."""
    groups: dict[tuple[str, str | None], list[Point]] = {}
    for p in points:
        groups.setdefault((p.scene, p.backend), []).append(p)
        groups.setdefault((p.scene, None), []).append(p)
    for (scene, backend), group in groups.items():
        heads = pareto([p.cost for p in group], [p.error for p in group], (tolerances or {}).get(scene, 0.0))
        for p, head in zip(group, heads):
            tie = None if head is None or group[head] is p else group[head].label
            if backend is None:
                p.pareto_scene, p.tie_scene = head is not None, tie
            else:
                p.pareto_backend, p.tie_backend = head is not None, tie
