"""`x3drbp validate`: does another implementation's trace of a scene conform?

    x3drbp validate SCENE --trace THEIRS.csv [--trace THEIRS2.csv ...] [--against LIST]
                    [--dt S] [--threshold KIND=VALUE] [--json OUT.json] [--timeout S]

Reads their trace and checks its format (conformance/analyses/trace_check.py); applies the
conformance case's expectation where SCENE is a case's scene (a case of several runs takes
one --trace per run, in the case's order); runs each backend (--against, default every
installed one) with the settings read off their trace and measures how far their trace is
from each run (conformance/analyses/validation.py says how, and the rule).

A trace that does not conform, whose frames are all one period apart that is not the step it
was judged at, gets one line more: an implementation that steps once per frame took that
period as its step, so `--dt` with it is what to try. The trace is judged at that step too
where that is cheap: the case's expectation (no run), or the backends' runs at a step no finer
than the one just judged (no more steps than those runs took). The exit status stays the
judgement at the step stated (--dt, else the default): the period is a guess at the step,
which only the implementation knows.

Exit status: 0 when the trace conforms: the case's expectation passes, or, for a scene
that is no case, the trace agrees with at least one backend within the thresholds; 1 when
it does not; 2 when it cannot be judged: the trace is unreadable (one line per problem,
FILE:LINE: ..., at most MAX_SHOWN), lacks what the expectation reads, or the usage is
wrong (the scene does not load, an unknown backend, the wrong number of traces, a --dt
at which a backend's run of the trace would pass a run's steps or frames); 3 when nothing
judged it: the scene is no case and no backend ran it (each refused, failed or timed out),
so there is nothing it could agree with, and "does not conform" would accuse it unmeasured.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable, Sequence

from reports.validate_text import render
from x3d_core.files import atomic

from conformance import results
from conformance.runner import children, probe
from conformance.cases.case import Case
from x3d_core.files.paths import printable
from x3d_core.traces.trace import TraceView
from conformance.analyses.trace_check import Problem, check_trace
from conformance.analyses.validation import check_case, compare_with_backends, find_case, frame_period, trace_settings
from conformance.results import FrameStep, TraceComparison, Validation

from x3drbp import options

EXIT_CONFORMS, EXIT_DOES_NOT, EXIT_UNREADABLE, EXIT_NOT_JUDGED = 0, 1, 2, 3
MAX_SHOWN = 20  # problems printed; the rest counted


def _unreadable(lines: Sequence[str]) -> int:
    """Each line printed as text (a trace's or scene's name may hold a terminal escape or a newline)."""
    for line in lines[:MAX_SHOWN]:
        print(printable(line), file=sys.stderr)
    if len(lines) > MAX_SHOWN:
        print(f"... and {len(lines) - MAX_SHOWN} more problems", file=sys.stderr)
    return EXIT_UNREADABLE


def _usage(message: str) -> int:
    return _unreadable([f"x3drbp validate: {message}"])


def _coverage(path: str, rows: TraceView, case: Case | None, k: int) -> list[Problem]:
    """A trace without frames, or shorter than the case's run k by more than half a frame."""
    end = rows.end()
    if end <= 0:
        return [Problem(path, 0, "no frame after time 0")]
    run = case.runs[k] if case is not None else None
    if run is not None and end < run.duration - 0.5 / run.rate:
        return [Problem(path, 0, f"ends at {end:g} s; case {case.name}'s run {k + 1} lasts {run.duration:g} s")]
    return []


def _too_long(paths: Sequence[str], traces: Sequence[TraceView], dt: float) -> str | None:
    """Why the backends cannot run a trace as it reads at step dt (past a run's frames or steps),
    in one line; None when they can. Said before any run: each backend's run was refused in its
    row, and the trace judged 'does not conform' (exit 1) for a setting of the command line."""
    for path, rows in zip(paths, traces):
        s = trace_settings(rows, dt)
        too = options.too_long(s.duration, s.dt, s.frame_rate)
        if too:
            return (f"{path} reads as {s.duration:g} s at {s.frame_rate:g} frames/s: at --dt {dt:g} a backend's "
                    f"run of it makes {too}")
    return None


def _frame_step(v: Validation, case: Case | None, views: Sequence[TraceView], judged: set[float],
                compare: Callable[[float], list[TraceComparison]]) -> FrameStep | None:
    """Their frames' period as the step, where it is none of the steps the trace was judged at;
    judged at it where cheap (the module's docstring), `compare` running the backends at a step."""
    period = frame_period(views)
    if period is None or any(math.isclose(period, d, rel_tol=1e-9) for d in judged):
        return None
    if case is not None:
        at = Validation(v.scene, v.traces, v.thresholds, check_case(case, views, period))
    elif period >= max(judged):
        at = Validation(v.scene, v.traces, v.thresholds, None, compare(period))
    else:
        return FrameStep(period, None)
    return FrameStep(period, at.conforms if at.judged else None, at.agreeing())


@children.interruptible
def cmd_validate(args: argparse.Namespace) -> int:
    try:
        thresholds = options.thresholds(args.threshold)
    except ValueError as e:
        return _usage(str(e))
    problem = options.read_step(args)
    if problem:
        return _usage(problem)
    if not (math.isfinite(args.timeout) and args.timeout > 0):
        return _usage(f"--timeout must be a positive number, not {args.timeout:g}")
    scene = options.load_scene(args.scene)
    if scene is None:
        return EXIT_UNREADABLE
    case = find_case(args.scene)
    wanted = len(case.runs) if case is not None else 1
    if len(args.trace) != wanted:
        runs = "" if case is None else ": " + ", ".join(f"{s.rate:g} frames/s" for s in case.runs)
        return _usage(f"{args.scene} takes {wanted} trace(s) (--trace, in this order{runs}), got {len(args.trace)}")
    traces, problems = [], []
    for k, path in enumerate(args.trace):
        rows, found = check_trace(path, scene)
        if rows and not found:
            found = _coverage(path, rows, case, k)
        traces.append(rows)
        problems += found
    if problems:
        return _unreadable([str(p) for p in problems])
    dt = args.dt or 1.0 / 240.0
    too = _too_long(args.trace, traces, dt)
    if too:
        return _usage(too)
    result = None
    if case is not None:
        result = check_case(case, [TraceView(r) for r in traces], args.dt)
        if result.verdict == results.ERROR:
            return _unreadable([f"{', '.join(args.trace)}: case {case.name}: {result.reason}"])
    try:
        info, backends = probe.chosen(options.given(args.against, "--against", "backend"), args.timeout)
    except ValueError as e:
        return _usage(str(e))

    def compare(step: float) -> list[TraceComparison]:
        return [compare_with_backends(args.scene, path, rows, step, backends, info, thresholds, args.timeout)
                for path, rows in zip(args.trace, traces)]
    validation = Validation(args.scene, list(args.trace), thresholds, result, compare(dt))
    if validation.judged and not validation.conforms:
        judged = {args.dt or s.dt for s in case.runs} if case is not None else {dt}
        validation.frame_step = _frame_step(validation, case, [TraceView(r) for r in traces], judged, compare)
    sys.stdout.write(render(validation))
    if args.json:
        atomic.write_json(args.json, validation.to_json())
    if not validation.judged:
        return EXIT_NOT_JUDGED
    return EXIT_CONFORMS if validation.conforms else EXIT_DOES_NOT


def add_command(sub) -> None:
    p = sub.add_parser("validate", help="check another implementation's trace of a scene: format, the "
                       "conformance case's expectation, divergence from each backend",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("scene")
    p.add_argument("--trace", action="append", required=True, metavar="THEIRS.csv",
                   help="their trace; once per run of a case with several (in the case's order)")
    p.add_argument("--against", action="append", metavar="LIST",
                   help="backends to compare with, comma-separated (default: every installed one)")
    p.add_argument("--dt", default=None, metavar="S",
                   help="the physics step their implementation took, as 1/60 or 0.004 (default: the case's, "
                        "else 1/240)")
    p.add_argument("--threshold", action="append", metavar="KIND=VALUE", help=options.thresholds_help())
    p.add_argument("--json", metavar="OUT.json", help="write the full result, per-frame series included")
    p.add_argument("--timeout", type=float, default=children.DEFAULT_TIMEOUT, metavar="S",
                   help=f"time limit per backend run in seconds (default {children.DEFAULT_TIMEOUT:g})")
    p.set_defaults(func=cmd_validate)
