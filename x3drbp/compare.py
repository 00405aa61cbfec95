"""`x3drbp compare`: one scene on several backends, and where and how far their runs part.

    x3drbp compare SCENE [--backends LIST] [--duration S] [--dt S] [--frame-rate HZ]
                   [--threshold KIND=VALUE] [--json OUT.json] [--rerun OUT.rrd] [--timeout S] [--jobs N]
                   [-q | -v]

Runs the scene on each backend, each in its own child process with a time limit (a
crash, timeout, blow-up or refusal is that backend's verdict), then compares every pair
that ran: body position (m) and orientation (rad) divergence per frame and over the run,
the first frame a body passes the threshold and the bodies over it, the joint outputs
both runs hold (conformance/compare.py says how each is measured), and each run's
real-time factor; and a line for each run whose mechanical energy grew with nothing doing
work on the scene (conformance/analyses/energy.py: its energy at the start, its largest and
when, and when it first rose past its bound). Prints the tables; --json writes all of it, the
per-frame series too; --rerun a rerun recording of every run side by side with the divergence
series (reports/rerun_recording.py), and the seconds it took on stderr.

The scene's warnings are printed once on stderr, before any run; what each backend
approximates of it, once per backend after the runs (-v: every run's notes, one per
approximated use; -q: none). While the runs go, a bar of runs done is drawn on stderr where
it is a terminal (not with -q). Exit status: 0 when at
least one pair was compared, whatever the divergences (they are results); 1 when nothing
could be compared: the scene does not load (each error one line), it has nothing to
simulate (no enabled RigidBody in an enabled RigidBodyCollection: one line), or fewer than
two backends ran (the verdicts say why), and when --json or --rerun cannot be written (a
full disk too: `cannot write PATH: REASON`, nothing half-written); 2 on bad usage: an unknown
backend, fewer than two backends named (or installed), a threshold or setting that is
not a positive number; 130 or 143 when interrupted by SIGINT or SIGTERM (every run stopped,
one line). A backend the probe gave no answer on is listed as unavailable, with why.
"""

from __future__ import annotations

import argparse
import sys

from reports.compare_text import render
from x3d_core.files import atomic

from conformance.runner import children, probe
from conformance.results import Settings
from conformance.analyses.compare import compare_all
from conformance.results import Comparison
from conformance.analyses.compare_runs import run_backends
from conformance.analyses import energy

from x3drbp import as_typed, options
from x3drbp.run import scene_to_run

EXIT_OK, EXIT_NOTHING_COMPARED, EXIT_USAGE = 0, 1, 2


def _usage(message: str) -> int:
    print(f"x3drbp compare: {message}", file=sys.stderr)
    return EXIT_USAGE


@children.interruptible
def cmd_compare(args: argparse.Namespace) -> int:
    try:
        thresholds = options.thresholds(args.threshold)
        probe.known(options.names(args.backends))
    except ValueError as e:
        return _usage(str(e))
    problem = options.settings_error(args)
    if problem:
        return _usage(problem)
    shown = as_typed(args.scene, getattr(args, "given", {}))  # made absolute for the children
    loaded = scene_to_run(shown)  # its diagnostics naming it as given
    if loaded is None:
        return EXIT_NOTHING_COMPARED
    scene = loaded[0]
    try:
        info, backends = probe.chosen(options.names(args.backends), args.timeout)
    except ValueError as e:
        return _usage(str(e))
    if len(backends) < 2:
        return _usage(f"needs two backends or more to compare, got {', '.join(backends) or 'none'}")
    settings = Settings(args.duration, args.dt, args.frame_rate)
    with children.notes_shown(options.verbosity(args)):
        prefer = any(c.get("preferAccuracy") for c in scene.of_type("RigidBodyCollection"))
        runs = run_backends(args.scene, backends, settings, info, args.timeout, args.jobs, options.progress(args),
                            prefer)
    bodies = energy.model(scene)  # None where something does work on them
    for r, view in runs:
        if bodies is not None and view is not None:
            r.energy = energy.growth(view, bodies)
    result = Comparison(shown, args.duration, args.dt, args.frame_rate, thresholds,
                        [r for r, _ in runs], compare_all(runs, thresholds))
    sys.stdout.write(render(result))
    if args.json:
        atomic.write_json(args.json, result.to_json())
    if args.rerun:
        from reports.rerun_recording import write_recording  # rerun is imported when a recording is asked for
        seconds = write_recording(args.rerun, scene, [(r.backend, v) for r, v in runs if v is not None], result.pairs)
        ran = sum(r.simulation_wall_s or 0.0 for r in result.runs)
        print(f"x3drbp compare: wrote {args.rerun} in {seconds:.3g} s (the runs' simulations: {ran:.3g} s)",
              file=sys.stderr)
    if not result.pairs:
        print("x3drbp compare: fewer than two backends ran: nothing compared", file=sys.stderr)
        return EXIT_NOTHING_COMPARED
    return EXIT_OK


def add_command(sub) -> None:
    p = sub.add_parser("compare", help="run a scene on several backends and measure where their runs part",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene")
    p.add_argument("--backends", action="append", metavar="LIST",
                   help="backends to run, comma-separated (default: every installed one)")
    options.add_run_settings(p)
    p.add_argument("--threshold", action="append", metavar="KIND=VALUE", help=options.thresholds_help())
    p.add_argument("--json", metavar="OUT.json", help="write the full result, per-frame series included")
    p.add_argument("--rerun", metavar="OUT.rrd",
                   help="write a rerun recording of the runs and their divergence (open it with `rerun OUT.rrd`)")
    p.add_argument("--timeout", type=float, default=children.DEFAULT_TIMEOUT, metavar="S",
                   help=f"time limit per run in seconds (default {children.DEFAULT_TIMEOUT:g})")
    p.add_argument("--jobs", type=options.count, default=1, metavar="N",
                   help="runs in parallel (default 1: runs that share cores skew each other's real-time factor)")
    options.add_run_verbosity(p)
    p.set_defaults(func=cmd_compare)
