"""`x3drbp stability`: the hard cases on every backend at every step size.

    x3drbp stability [--backends LIST] [--cases NAMES] [--dts 1/60,1/240,1/1000] [--out DIR]
                     [--timeout S] [--jobs N] [-q | -v]

Writes DIR/stability.json and DIR/stability.md (DIR defaults to out/stability) and prints the
markdown. Each (case, backend, dt) runs in its own child process under the time limit (cases
of one scene and duration judge one run: the two spinning wheels; finest step first); its
verdict is survived (stopped, for the impact), what gave way first and when (energy grew past
bound, momentum drifted past bound, joint drifted past bound, drifted past bound, tunnelled,
blew up), or unsupported, crashed, timed out, error; and a line for each run whose mechanical
energy grew with nothing doing work on its scene (conformance/analyses/energy.py: its energy at
the start, its largest and when, and when it first rose past its bound). Exit status 0 whatever
the verdicts (they are results, not errors); 2 on bad usage; 130 or 143 when interrupted by
SIGINT or SIGTERM (every run stopped, one line).

The trace of each run that did not hold and left one (it broke a bound, or blew up: the frames
before) is kept as DIR/traces/CASE-BACKEND-DT.csv (DT as 1_240), which the table's reasons
link; a trace there from an earlier run of a (case, backend, dt) that now holds or left none is
removed. While the runs go, a bar of runs done is drawn on stderr where it is a terminal (not
with -q). What a backend approximates of a case's scene is one note per case and backend on
stderr after the runs (-v: every run's notes; -q: none).
"""

from __future__ import annotations

import argparse
import datetime
import os
import sys
import time

from reports.stability_table import markdown

from conformance import results
from conformance.analyses import stability as S
from conformance.runner import children

from x3drbp import options

EXIT_OK, EXIT_USAGE = 0, 2


def _within_bounds(cases: list[S.HardCase], dts: list[float]) -> None:
    """ValueError naming the first run of a case at a step past a run's bounds (options.too_long):
    a `--dts 1e-300` ran every case to be refused by its child, then stopped on a trace name of
    300 digits."""
    for c in cases:
        for dt in dts:
            settings = results.Settings(c.duration, dt)
            too = options.too_long(settings.duration, dt, settings.rate)
            if too:
                raise ValueError(f"{c.name}: {c.duration:g} s at a step of {dt:g} s makes {too}")


def to_json(outcomes: list[S.StabilityResult], cases: list[S.HardCase], backends: list[str], dts: list[float],
            info: dict[str, results.BackendInfo], jobs: int, wall_s: float) -> dict:
    return {
        "generated": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "backends": {n: {"version": i.version, "unavailable": i.unavailable, "run": n in backends}
                     for n, i in info.items()},
        "dts": [{"dt": dt, "label": results.dt_label(dt)} for dt in dts],
        "jobs": jobs, "wall_s": round(wall_s, 1),
        "cases": [{"name": c.name, "scene": os.path.relpath(c.path, S.ROOT), "stresses": c.stresses,
                   "duration": c.duration, "held": c.held,
                   "monitors": [{"monitor": type(m).__name__, **vars(m)} for m in c.monitors]} for c in cases],
        "results": [r.to_json() for r in outcomes],
    }


@children.interruptible
def cmd_stability(args: argparse.Namespace) -> int:
    try:
        dts = options.steps(args.dts) or list(S.DEFAULT_DTS)
        cases, info, backends = options.chosen(args, S.select)
        _within_bounds(cases, dts)
    except ValueError as e:
        print(f"x3drbp stability: {e}", file=sys.stderr)
        return EXIT_USAGE
    runnable = [b for b in backends if info[b].usable]
    jobs = max(1, args.jobs or os.cpu_count() or 1)
    started = time.perf_counter()
    with children.notes_shown(options.verbosity(args)):
        outcomes = S.run_suite(cases, runnable, dts, args.timeout, jobs, args.out, options.progress(args))
    wall_s = time.perf_counter() - started
    for b in backends:  # named on the command line but not installed: say so in every cell
        if not info[b].usable:
            outcomes += [S.StabilityResult(c.name, b, dt, results.ERROR, reason=f"backend unavailable: "
                                          f"{info[b].unavailable}") for c in cases for dt in dts]
    data = to_json(outcomes, cases, backends, dts, info, jobs, wall_s)
    text = markdown(data)
    options.publish(args.out, "stability", text, data)
    return EXIT_OK


def add_command(sub) -> None:
    p = sub.add_parser("stability", help="run the hard cases per backend and step size: survived or what gave way",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    options.add_matrix_options(p, "run", list(S.BY_NAME), S.DEFAULT_TIMEOUT)
    p.add_argument("--dts", action="append", metavar="LIST",
                   help="physics steps, comma-separated, as 1/240 or 0.004 (default "
                        f"{','.join(results.dt_label(dt) for dt in S.DEFAULT_DTS)})")
    p.add_argument("--out", default=os.path.join("out", "stability"), metavar="DIR",
                   help="folder for stability.md, stability.json and the traces the reasons cite (default "
                        "out/stability)")
    options.add_run_verbosity(p)
    p.set_defaults(func=cmd_stability)
