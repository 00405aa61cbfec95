"""`x3drbp conformance`: every conformance case on every backend, as a matrix.

    x3drbp conformance [--backends LIST] [--cases NAMES] [--out DIR] [--convergence]
                       [--timeout S] [--jobs N] [--keep-traces] [-q | -v]

Writes DIR/matrix.md and DIR/matrix.json (DIR defaults to out/conformance) and prints the
markdown. The command holds DIR while it runs (DIR/.x3drbp.lock): a second x3drbp command
into it says `DIR is in use by another x3drbp command (pid N)` and exits 1 at once. Exit
status 0 whatever the verdicts (they are results, not errors); 1 when an output cannot be
written: DIR in use, or `cannot write PATH: REASON` for the matrix or a run's trace (a full
disk, DIR/traces removed mid-run: the command's failure, never a pair's verdict; no run
starts after it and no matrix is written); 2 on bad usage (an unknown case or backend
name); 130 or 143 when interrupted by SIGINT or SIGTERM (every run stopped, one line).
With --convergence it also runs each closed-form case at dt = 1/60, 1/120, 1/240, 1/480 per
backend and reports the error per dt and the fitted order (the slope of log error against
log dt).

While the runs go, a bar of runs done is drawn on stderr where it is a terminal (not with -q).
What a backend approximates of a case's scene is one note per case and backend on stderr,
after the runs, however many runs the case takes (-v: every run's notes; -q: none).
"""

from __future__ import annotations

import argparse
import datetime
import os
import sys

from reports.matrix_table import markdown

from x3d_core.files import atomic

from conformance import cases as C
from conformance import results
from conformance.runner import children, verdicts

from x3drbp import as_typed, options

EXIT_OK, EXIT_IN_USE, EXIT_USAGE = 0, 1, 2


def to_json(outcomes: list[results.Result], cases: list[C.Case], backends: list[str],
            info: dict[str, results.BackendInfo], convergence: list[results.Convergence] | None = None) -> dict:
    return {
        "generated": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "backends": {n: {"version": i.version, "unavailable": i.unavailable, "run": n in backends, "scope": i.scope}
                     for n, i in info.items()},
        "cases": [{"name": c.name, "scene": os.path.relpath(c.path, C.ROOT), "checks": c.checks,
                   "runs": [{"duration": s.duration, "dt": s.dt, "frame_rate": s.rate} for s in c.runs],
                   "convergence": c.convergence} for c in cases],
        "results": [r.to_json() for r in outcomes],
        "convergence": None if convergence is None else [cv.to_json() for cv in convergence],
    }


@children.interruptible
def cmd_conformance(args: argparse.Namespace) -> int:
    try:
        cases, info, backends = options.chosen(args, C.select)
    except ValueError as e:
        print(f"x3drbp conformance: {e}", file=sys.stderr)
        return EXIT_USAGE
    if not backends:
        print("x3drbp conformance: no backend is available here: "
              + "; ".join(f"{n}: {i.unavailable}" for n, i in info.items()), file=sys.stderr)
    try:
        with atomic.holding(args.out):  # no other command's files meet this one's (InUse only on entry)
            return _run(args, cases, info, backends)
    except atomic.InUse as e:
        print(f"x3drbp conformance: {as_typed(args.out, getattr(args, 'given', {}))} is in use by another x3drbp "
              f"command" + (f" (pid {e.pid})" if e.pid else ""), file=sys.stderr)
        return EXIT_IN_USE


def _run(args: argparse.Namespace, cases: list[C.Case], info: dict[str, results.BackendInfo],
         backends: list[str]) -> int:
    """The matrix, DIR held."""
    keep = os.path.join(args.out, "traces") if args.keep_traces else None
    if keep:
        os.makedirs(keep, exist_ok=True)
    runnable = [b for b in backends if info[b].usable]
    progress = options.progress(args)
    with children.notes_shown(options.verbosity(args)):  # a case's notes once, convergence runs included
        outcomes = verdicts.run_matrix(cases, runnable, args.timeout, args.jobs, keep, progress)
        convergence = None
        if args.convergence:
            convergence = verdicts.run_convergence(cases, runnable, C.CONVERGENCE_DTS, args.timeout, args.jobs,
                                                   progress)
    if keep and not os.path.isdir(keep):  # removed after its last trace was written: the matrix would cite none
        raise atomic.CannotWrite(keep, "the folder was removed while the command ran")
    for b in backends:  # named on the command line but not installed: say so in every cell
        if not info[b].usable:
            outcomes += [results.Result(c.name, b, results.ERROR, f"backend unavailable: {info[b].unavailable}")
                        for c in cases]
    order = {(c.name, b): k for k, (c, b) in enumerate((c, b) for c in cases for b in backends)}
    outcomes.sort(key=lambda r: order[(r.case, r.backend)])
    text = markdown(outcomes, [(c.name, c.checks) for c in cases], backends, info, convergence)
    options.publish(args.out, "matrix", text, to_json(outcomes, cases, backends, info, convergence))
    return EXIT_OK


def add_command(sub) -> None:
    p = sub.add_parser("conformance", help="run the conformance cases on the backends and write the matrix",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    options.add_matrix_options(p, "run", list(C.BY_NAME), children.DEFAULT_TIMEOUT)
    p.add_argument("--out", default=os.path.join("out", "conformance"), metavar="DIR",
                   help="folder for matrix.md and matrix.json (default out/conformance)")
    p.add_argument("--convergence", action="store_true",
                   help="also run each closed-form case at dt = 1/60, 1/120, 1/240, 1/480 and fit the order")
    p.add_argument("--keep-traces", action="store_true", help="keep every run's trace under DIR/traces")
    options.add_run_verbosity(p)
    p.set_defaults(func=cmd_conformance)
