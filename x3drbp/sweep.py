"""`x3drbp sweep`: speed against error per scene and backend, over the step, iterations and
preferAccuracy (conformance/sweep.py says what is measured).

    x3drbp sweep [--scenes NAMES] [--backends LIST] [--dts LIST] [--iterations LIST]
                 [--accuracy both|false|true] [--window S] [--repeats N] [--out DIR]
                 [--scheduler ADDRESS] [--workers N] [--timeout S] [--quiet]

Writes DIR/sweep.json (every point), DIR/sweep.md (the Pareto fronts, ties merged) and
DIR/sweep_SCENE.png (error against the scene's one reference, closed form, Drake's
error-controlled run or a backend's fine run, each scene saying which, over the median CPU
time in the engine's steps per simulated second with its spread, one line per backend and variation); DIR
defaults to out/sweep. Runs on local threads (each waits on its run), or on a Dask cluster with
--scheduler SCHEME://HOST:PORT (tcp://host:8786), given up on where it does not answer in time.
Exit status 0 whatever the verdicts (where no run gave a result, the files and one line on
stderr say "no results"); 1 where the scheduler cannot be reached, or a scene file does not
load or has nothing to simulate (each error one line, before any run; nothing written); 2 on
bad usage; 130 or 143 when interrupted by SIGINT or SIGTERM (every run stopped).

Each point is timed once, and the points whose speed could change the fronts (the fronts'
points, and those a single timing's margin could move a mark with: conformance/analyses/
sweep_timing.py) --repeats times in all, their speed the median; sweep.json's `timed` says how
many. The default scope (4 scenes, 4 steps, iterations 10 and 50, preferAccuracy both ways, the
seven backends: 384 points, 28 fine-step runs and Drake's 4 error-controlled reference runs)
took 205 s on 2 cores when it held 288 points, each timed 3 times (163 s with --repeats 1); a
long sweep names more:
    x3drbp sweep --dts 1/60,1/120,1/240,1/500,1/1000,1/2000,1/4000,1/8000 \\
                 --iterations 5,10,20,50,100 --scenes pendulum_period,projectile,torque_free,...
"""

from __future__ import annotations

import argparse
import datetime
import os
import sys
import time
from collections.abc import Mapping

from x3d_core.files import atomic
from x3d_core.model.scene import Scene

from conformance import cases as C
from conformance.runner import children, probe
from conformance.analyses import distribute
from conformance.analyses import sweep as S
from conformance.analyses import sweep_timing as timing

from x3drbp import options

EXIT_OK, EXIT_UNREACHABLE, EXIT_SCENE, EXIT_USAGE = 0, 1, 1, 2
ACCURACY = {"both": (False, True), "false": (False,), "true": (True,)}


def steps(values: list[str] | None, default: tuple[float, ...] = S.DEFAULT_DTS) -> list[float]:
    """--dts (options.steps), else the default; finest last."""
    return sorted(set(options.steps(values) or default), reverse=True)


SFINT32_MAX = 2**31 - 1


def iteration_counts(values: list[str] | None) -> list[int]:
    """--iterations as whole numbers in RigidBodyCollection.iterations' range, [0, 2^31 - 1]
    (SFInt32), ascending; ValueError naming one that is not (-1 ran every point to fail
    alike, 'abc' said int()'s own words), or a --iterations that names none."""
    counts = []
    for v in options.given(values, "--iterations", "count"):
        try:
            n = int(v)
        except ValueError:
            n = -1
        if not 0 <= n <= SFINT32_MAX:
            raise ValueError(f"--iterations must be whole numbers from 0 to {SFINT32_MAX}, not {v!r}")
        counts.append(n)
    return sorted(set(counts) or set(S.DEFAULT_ITERATIONS))


def targets(names: list[str], dts: list[float], window: float, duration: float | None = None,
            loaded: Mapping[str, Scene] | None = None) -> list[S.Target]:
    """S.targets, each target's finest run (its fine-step reference) within a run's bounds
    (options.too_long): ValueError saying what it would make otherwise."""
    chosen = S.targets(names, dts, window, duration, loaded)
    for t in chosen:
        fine = t.settings.with_dt(min(dts) / S.REFINEMENT)
        too = options.too_long(fine.duration, fine.dt, fine.rate)
        if too:
            raise ValueError(f"{t.name}: its reference run: {fine.duration:g} s at a step of {fine.dt:g} s (the "
                             f"finest of the steps / {S.REFINEMENT}) and {fine.rate:g} frames/s makes {too}")
    return chosen


def scene_files(names: list[str]) -> dict[str, Scene] | None:
    """The scene files among names (case names aside) loaded, by name, each one's warnings
    said once; None after one line per error where one does not load or has nothing to
    simulate: said before any run, where every point's run would fail alike (a malformed file
    was a traceback, a bad field value a sweep of failed runs and exit 0)."""
    from x3drbp.run import scene_to_run  # the scene's checks as run and advise make them
    scenes, failed = {}, False
    for name in names:
        if name not in C.BY_NAME and os.path.isfile(name):
            loaded = scene_to_run(name)
            failed = failed or loaded is None
            if loaded is not None:
                scenes[name] = loaded[0]
    return None if failed else scenes


def plans(command: str, names: list[str] | None, timeout: float) -> dict[str, S.BackendPlan]:
    """The named backends (default: every installed one) that can run, each that cannot said
    in one line on stderr; ValueError naming unknown ones."""
    found, skipped = S.backend_plans(options.names(names), timeout)
    for name, why in skipped.items():
        print(f"x3drbp {command}: {name} is not run: {why}", file=sys.stderr)
    if not found:
        print(f"x3drbp {command}: no backend is available here", file=sys.stderr)
    return found


def to_json(sweep: S.Sweep, chosen: list[S.Target], planned: dict[str, S.BackendPlan], settings: dict,
            wall_s: float) -> dict:
    return {
        "generated": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "measured": {"speed": "cpu_per_sim_s: the child's CPU time in the engine's steps (x3drbp run --timing) "
                              "over the simulated seconds, the median of its timings (`timed` of them: one, or "
                              "--repeats where the speed could change the fronts; cpu_low and cpu_high: their "
                              "spread), what ranks, as load does not reorder it; wall_per_sim_s (wall_low, "
                              "wall_high): the same steps' wall time; not start-up, loading, the model build, "
                              "per-frame reads or trace writing (simulation_per_sim_s: the whole simulation's "
                              "wall time, build and reads included)",
                     "error": "closed form: the case's convergence measure; common reference: the largest distance "
                              "of a body from the scene's reference run (the same for every backend: Drake's "
                              "error-controlled run where Drake runs the scene in continuous mode, else one "
                              "backend's fine run; each scene's reference_method and reference_said say which) "
                              "over the window",
                     "self_error": "the largest distance of a body from the same backend's run at the fine step, "
                                   "over the window (scenes without a closed form)",
                     "ties": "points whose speed spreads overlap and whose errors differ by less than the "
                             "reference's uncertainty (its own error; on a scene with events, the other backends' "
                             "spread around it where larger) or rounding are one front point: the fastest stands "
                             "for them"},
        "settings": {**settings, "reference_refinement": S.REFINEMENT},
        "backends": {n: {"version": p.version, "iterations": p.iterations, "preferAccuracy": p.prefer_accuracy}
                     for n, p in planned.items()},
        "scenes": [{"name": t.name, "scene": t.scene, "reference": t.reference, "case": t.case,
                    "quantity": t.quantity, "unit": sweep.units.get(t.name, ""), "duration": t.settings.duration,
                    "frame_rate": t.settings.frame_rate, **_reference(sweep.references.get(t.name))}
                   for t in chosen],
        "fine_runs": [_reference_run(scene, job, res, check) for (scene, _), (job, res, check) in sweep.fine.items()],
        "error_controlled_runs": [_reference_run(scene, job, res, check)
                                  for scene, (job, res, check) in sweep.controlled.items()],
        "points": [{**p.to_json(), "timed": n} for p, n in zip(sweep.points, timing.timed(sweep))],
        "wall_s": round(wall_s, 1),
    }


def _reference_run(scene: str, job: S.Job, res: S.JobResult, check: S.JobResult) -> dict:
    """A run that may be a scene's reference, and its check, as sweep.json lists them."""
    return {"scene": scene, "backend": job.backend, "dt": job.settings.dt, "iterations": job.iterations,
            "prefer_accuracy": job.prefer_accuracy, "verdict": res.verdict, "reason": res.reason,
            "target_accuracy": res.target_accuracy, "check_verdict": check.verdict, "check_reason": check.reason,
            "check_target_accuracy": check.target_accuracy}


def _reference(ref: S.Reference | str | None) -> dict:
    """A scene's common reference as sweep.json states it (nothing for a closed form): its
    fields (Reference.to_json) prefixed reference_."""
    if ref is None:
        return {}
    if isinstance(ref, str):
        return {"reference_backend": None, "reference_method": None, "reference_why_none": ref}
    return {f"reference_{k}": v for k, v in ref.to_json().items()}


@children.interruptible
def cmd_sweep(args: argparse.Namespace) -> int:
    try:
        scheduler = distribute.address(args.scheduler) if args.scheduler else None
        dts = steps(args.dts)
        iterations = iteration_counts(args.iterations)
        probe.known(options.names(args.backends))
        names = options.listed(args.scenes) or list(S.DEFAULT_SCENES)
        loaded = scene_files(names)
        if loaded is None:
            return EXIT_SCENE
        chosen = targets(names, dts, args.window, loaded=loaded)
        planned = plans("sweep", args.backends, args.timeout)
    except ValueError as e:
        print(f"x3drbp sweep: {e}", file=sys.stderr)
        return EXIT_USAGE
    if not planned:
        return EXIT_OK
    started = time.perf_counter()
    try:
        sweep = S.run_sweep(chosen, planned, dts, iterations, ACCURACY[args.accuracy], args.timeout, scheduler,
                            args.workers, progress=options.progress(args), repeats=1)
        timing.settle(sweep, args.repeats, scheduler, args.workers, options.progress(args))
    except distribute.Unreachable as e:
        print(f"x3drbp sweep: {e}", file=sys.stderr)
        return EXIT_UNREACHABLE
    settings = {"dts": dts, "iterations": iterations, "accuracy": args.accuracy, "window": args.window,
                "repeats": args.repeats, "scheduler": args.scheduler, "workers": args.workers,
                "timeout": args.timeout}
    doc = to_json(sweep, chosen, planned, settings, time.perf_counter() - started)
    from reports.plots import sweep_plot  # matplotlib: only here, not in every `x3drbp run` child
    from reports.sweep_tables import NO_RESULTS, markdown, measured
    os.makedirs(args.out, exist_ok=True)
    atomic.write_json(os.path.join(args.out, "sweep.json"), doc)
    for t in chosen:
        sweep_plot(doc, t.name, os.path.join(args.out, f"sweep_{t.name}.png"))
    text = markdown(doc)
    atomic.write_text(os.path.join(args.out, "sweep.md"), text)
    if not args.quiet:
        sys.stdout.write(text)
    if not measured(doc["points"]):
        print(f"x3drbp sweep: no results: {NO_RESULTS} (sweep.md says why)", file=sys.stderr)
    print(f"wrote {os.path.join(args.out, 'sweep.md')}, sweep.json and {len(chosen)} plot(s) in {doc['wall_s']:g} s")
    return EXIT_OK


def add_command(sub) -> None:
    p = sub.add_parser("sweep", help="speed against error per scene and backend over step, iterations, accuracy",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scenes", "--cases", action="append", metavar="NAMES",
                   help="case names or scene files, comma-separated, or the option repeated; a comma in a "
                        f"file name written \\, (default: {', '.join(map(S.relative, S.DEFAULT_SCENES))})")
    p.add_argument("--backends", action="append", metavar="LIST",
                   help="backends, comma-separated (default: every installed one)")
    p.add_argument("--dts", action="append", metavar="LIST",
                   help="physics steps, comma-separated, as 1/240 or 0.004 (default 1/60,1/240,1/1000,1/4000)")
    p.add_argument("--iterations", action="append", metavar="LIST",
                   help="RigidBodyCollection.iterations values (default 10,50; where the backend honours it)")
    p.add_argument("--accuracy", choices=tuple(ACCURACY), default="both",
                   help="preferAccuracy values (default both; where the backend honours it)")
    p.add_argument("--window", type=options.positive, default=S.DEFAULT_WINDOW, metavar="S",
                   help=f"seconds compared with the reference (default {S.DEFAULT_WINDOW:g})")
    p.add_argument("--repeats", type=options.repeats, default=S.REPEATS, metavar="N",
                   help=f"timed runs of each point whose speed could change the fronts, for the median speed and its "
                        f"spread (default {S.REPEATS}; the others are timed once)")
    p.add_argument("--out", default=os.path.join("out", "sweep"), metavar="DIR",
                   help="folder for sweep.json, sweep.md and the plots (default out/sweep)")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="a Dask scheduler to run on, SCHEME://HOST:PORT (tcp://host:8786), given up on (exit 1) "
                        f"where it is not reached within {distribute.CONNECT_TIMEOUT:g} s; default: local threads")
    p.add_argument("--workers", type=options.count, default=None, metavar="N",
                   help="local processes (default: the number of CPUs; ignored with --scheduler)")
    p.add_argument("--timeout", type=options.positive, default=children.DEFAULT_TIMEOUT, metavar="S",
                   help=f"time limit per run in seconds (default {children.DEFAULT_TIMEOUT:g})")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar and no markdown on stdout")
    p.set_defaults(func=cmd_sweep)
