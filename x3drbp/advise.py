"""`x3drbp advise`: which backend and which step for each of your scenes, and why.

    x3drbp advise SCENE_OR_FOLDER... [--budget S] [--tolerance M] [--backends LIST]
                  [--dts LIST] [--duration S] [--window S] [--repeats N] [--verdicts matrix.json]
                  [--json OUT.json] [--timeout S] [--workers N] [-q]

For each scene (folders are searched for .x3d, .x3dv, .x3dj): what each backend makes of the
features it uses (refused, approximated, and the verdicts of the conformance cases that
exercise them: the pinned ones, or those of a conformance run's matrix.json with
--verdicts), then the scene on every backend that can run it at each step, each run's error
against one common reference over the first --window seconds (Drake's error-controlled run
where Drake runs the scene in continuous mode, else one backend's fine run; said, with its
own error), its speed (the engine's steps' CPU time in the child, so
that other load does not reorder the backends; timed once, and where the speed could change
the advice --repeats times in all, the median), and how long it stays within 1 mm / 1 mrad
of each other backend at that step; then
the recommendation by the rule conformance/analyses/advice.py states (docs/commands/advise.md too): of the
runs that fit --budget (CPU seconds per simulated second, default 1: real time), the
fastest within --tolerance of the reference (default 1 mm), else the most accurate; a tie
said as one, with the tie-break that settled it.

Exit status 0 when every scene got its advice (a scene no backend can run is advice too); 1
when a scene does not load or has nothing to simulate (one line each; the others are still
advised); 2 on bad usage; 3 when the advice could not be made at all (the judgement's child
failed, or a pin file does not parse: `x3drbp report` names the step failed); 130 or 143 when interrupted (every run stopped).
"""

from __future__ import annotations

import argparse
import datetime
import sys
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

from reports.advice_text import render
from x3d_core.files import atomic
from x3d_core.files.documents import BadDocument, read_json
from x3d_core.files.paths import none_under, scene_files

from conformance import expectations
from conformance.results import PASS
from conformance.runner import children, probe
from conformance.analyses import advice as A
from conformance.analyses import sweep as S

from x3drbp import as_typed, options
from x3drbp.run import scene_to_run
from x3drbp.sweep import plans, steps, targets

EXIT_OK, EXIT_SCENE, EXIT_USAGE, EXIT_FAILED = 0, 1, 2, 3


def _usage(message: str) -> int:
    print(f"x3drbp advise: {message}", file=sys.stderr)
    return EXIT_USAGE


def _matrix(path: str | None) -> dict[tuple[str, str], A.Said] | None:
    """(case, backend) -> verdict and accuracy grade from a conformance matrix.json (None
    without one); ValueError naming the file where it is not one."""
    if path is None:
        return None
    try:
        doc = read_json(path)
    except BadDocument as e:  # not a regular file, too large, too deep, not JSON: its path and line
        raise ValueError(f"--verdicts {e}") from None
    try:
        return {(r["case"], r["backend"]): A.Said(r["verdict"], _beyond(r.get("accuracy"))) for r in doc["results"]}
    except (ValueError, KeyError, TypeError) as e:
        raise ValueError(f"--verdicts {path}: not a conformance matrix.json ({type(e).__name__}: {e})") from None


def _beyond(accuracy: float | str | None) -> bool:
    """A matrix's accuracy grade (the worst error over its bound; "inf" as JSON writes it) is beyond the bound."""
    return accuracy is not None and not float(accuracy) <= 1


def _verdict(matrix: dict[tuple[str, str], A.Said] | None, backends: list[str]) -> Callable[[str, str], A.Said]:
    """A case's verdict and accuracy grade on a backend: the matrix's, else the pinned ones
    (conformance/expectations, which the tests hold equal to what a run measures)."""
    if matrix is not None:
        return lambda case, backend: matrix.get((case, backend), A.Said("not run"))
    pinned = {b: expectations.load(b) for b in backends}

    def said(case: str, backend: str) -> A.Said:
        e = pinned[backend].get(case)
        return A.Said(PASS) if e is None else A.Said(e.verdict, bool(e.over_bound))
    return said


def _named(scene: dict, given: dict[str, str]) -> dict:
    """A scene's advice naming it as the command line did (its path was made absolute for the
    children, which run in the project root)."""
    return {**scene, "scene": as_typed(scene["scene"], given)}


@children.interruptible
def cmd_advise(args: argparse.Namespace) -> int:
    try:
        dts = steps(args.dts, A.DEFAULT_DTS)
        matrix = _matrix(args.verdicts)
        probe.known(options.names(args.backends))
    except ValueError as e:
        return _usage(str(e))
    files = scene_files(args.paths)
    if not files:
        return _usage(none_under([as_typed(p, getattr(args, "given", {})) for p in args.paths]))
    scenes, status = {}, EXIT_OK
    given = getattr(args, "given", {})
    for path in files:  # each scene's errors and warnings once, before any run, naming it as given
        loaded = scene_to_run(as_typed(path, given))
        if loaded is None:
            status = EXIT_SCENE
        else:
            scenes[path] = loaded[0]
    if not scenes:
        return status
    with probe.remembered(), ThreadPoolExecutor(1) as beside:  # the probe asked once, for all that follows
        try:
            for path in scenes:  # the steps' common frames, each scene's reference run within a run's bounds
                targets([path], dts, args.window, args.duration, scenes)
            usable = [n for n, i in probe.backend_table(args.timeout, options.names(args.backends)).items()
                      if i.usable]
        except ValueError as e:
            return _usage(str(e))
        try:
            verdict, unpinned = _verdict(matrix, usable), None
        except ValueError as e:  # a pin file that does not parse: its path and entry
            verdict, unpinned = None, e
        started = time.perf_counter()
        # the judgement's child beside the declarations' (each imports every engine: a second apiece),
        # asked of every usable backend: those whose declarations cannot be read leave none planned
        judging = beside.submit(A.judge, list(scenes), usable, verdict, args.timeout) if usable and verdict else None
        planned = plans("advise", args.backends, args.timeout)
        if not planned:
            return EXIT_SCENE
        if unpinned is not None:
            print(f"x3drbp advise: {unpinned}", file=sys.stderr)
            return EXIT_FAILED
        judged, why = judging.result()
        if judged is None:
            print(f"x3drbp advise: the scenes could not be judged: {why}", file=sys.stderr)
            return EXIT_FAILED
        progress = options.progress(args)
        advice = A.advise(list(scenes), scenes, planned, judged, dts, args.duration, args.window, args.budget,
                          args.tolerance, args.timeout, args.workers, progress, args.repeats)
    doc = {"generated": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
           "settings": {"dts": dts, "duration": args.duration, "window": args.window, "budget": args.budget,
                        "tolerance": args.tolerance, "repeats": args.repeats, "verdicts": args.verdicts or "pinned"},
           "backends": {n: p.version for n, p in planned.items()},
           "scenes": [_named(a.to_json(), given) for a in advice],
           "wall_s": round(time.perf_counter() - started, 1)}
    if args.json:
        atomic.write_json(args.json, doc)
    sys.stdout.write(render(doc))
    return status


def add_command(sub) -> None:
    p = sub.add_parser("advise", help="which backend and step for each of your scenes, and why",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("paths", nargs="+", metavar="SCENE_OR_FOLDER",
                   help="scene files, or folders searched for .x3d/.x3dv/.x3dj files")
    p.add_argument("--budget", type=options.positive, default=A.DEFAULT_BUDGET, metavar="S",
                   help=f"CPU seconds the engine's steps may take per simulated second (default "
                        f"{A.DEFAULT_BUDGET:g}: real time; a browser sharing its frame with rendering wants less)")
    p.add_argument("--tolerance", type=options.positive, default=A.DEFAULT_TOLERANCE, metavar="M",
                   help=f"metres from the reference that count as accurate (default {A.DEFAULT_TOLERANCE:g})")
    p.add_argument("--backends", action="append", metavar="LIST",
                   help="backends, comma-separated (default: every installed one)")
    p.add_argument("--dts", action="append", metavar="LIST",
                   help="physics steps, comma-separated, as 1/240 or 0.004 (default 1/60,1/240,1/1000)")
    p.add_argument("--duration", type=options.positive, default=A.DEFAULT_DURATION, metavar="S",
                   help=f"simulated seconds each run is watched for parting (default {A.DEFAULT_DURATION:g})")
    p.add_argument("--window", type=options.positive, default=S.DEFAULT_WINDOW, metavar="S",
                   help=f"seconds compared with the reference (default {S.DEFAULT_WINDOW:g})")
    p.add_argument("--repeats", type=options.repeats, default=S.REPEATS, metavar="N",
                   help=f"timed runs of each run whose speed could change the advice, for the median speed "
                        f"and its spread (default {S.REPEATS}; the others are timed once)")
    p.add_argument("--verdicts", metavar="matrix.json",
                   help="the conformance verdicts of a run (x3drbp conformance --out DIR: DIR/matrix.json) "
                        "instead of the pinned ones")
    p.add_argument("--json", metavar="OUT.json", help="write every figure behind the advice")
    p.add_argument("--timeout", type=options.positive, default=children.DEFAULT_TIMEOUT, metavar="S",
                   help=f"time limit per run in seconds (default {children.DEFAULT_TIMEOUT:g})")
    p.add_argument("--workers", type=options.count, default=None, metavar="N",
                   help="runs in parallel (default: the number of CPUs)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_advise)
