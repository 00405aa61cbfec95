"""`x3drbp report`: the main job. Every measurement x3drbp makes, on every installed backend,
as one static HTML page with its plots, and the same in markdown.

    x3drbp report [--out DIR] [--backends LIST] [--scenes DIR_OR_FILE] [--quick] [--x-ite] [--no-cache]

Each step is the command of its name, run into a folder of DIR (--scenes: your scenes,
files or folders, go into compare, advise and sweep beside the bundled examples):

    conformance  every case on every backend                 DIR/conformance/matrix.json, matrix.md
    compare      each example scene (and yours) on every     DIR/compare/SCENE.json, SCENE.rrd,
                 backend                                     SCENE.divergence.png
    advise       which backend and step for each example     DIR/advice/advice.json
                 scene (and yours), with the verdicts just measured
    sweep        speed against error (its default scope,     DIR/sweep/sweep.json, sweep.md, sweep_*.png
                 and your scenes)
    stability    the hard cases at 1/60 and 1/240 s          DIR/stability/stability.json, stability.md,
                                                             traces/
    features     each backend's declared table against the verdicts of the cases that
                 exercise each feature                       DIR/features.json
    x_ite        with --x-ite only: the X_ITE browser on every case, judged (needs
                 `make x-ite-install`)                       DIR/x_ite/x_ite.json, x_ite.md

then reports/report_page.py writes DIR/report.md and DIR/index.html from those files alone.
--quick leaves out the sweep (the longest step). DIR defaults to out/report. A scene of
yours that does not load, or has nothing to simulate, is left out of every step, its first
error on stderr, on the page and in report.json's `left_out`. Exit status 0 whatever the
verdicts (they are results); 1 where a step could not run at all (its log in DIR/logs/ says
why) or a scene of yours was left out; 2 on bad usage; 130 or 143 when interrupted by SIGINT or SIGTERM (the
step's runs stopped, one line). A named backend that cannot run is one line on stderr.
"""

from __future__ import annotations

import argparse
import contextlib
import datetime
import json
import os
import sys
import time
from collections.abc import Callable
from typing import TextIO

from x3d_core.files import atomic
from x3d_core.files.paths import none_under, scene_files
from x3d_core.semantics.outcome import EMPTY, simulates

from conformance import cases as C
from conformance import expectations
from conformance.results import ACCURACY, CONVENTIONS, PASS, UNSUPPORTED
from conformance.runner import children, probe
from conformance.analyses import sweep as S

from x3drbp import CACHED, as_typed, options

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2
EXIT_SCENE_RESULT = 1  # compare and advise: a scene compared nothing or did not load, said in its log
EXAMPLES = os.path.join(C.ROOT, "scenes", "examples")
COMPARE_SECONDS = 5.0


def stems(paths: list[str]) -> list[str]:
    """A file name for each scene's results: its own stem, numbered where two share one."""
    return S.numbered([os.path.splitext(os.path.basename(p))[0] for p in paths])


def _steps(out: str, backends: list[str], quick: bool, x_ite: bool, yours: list[str]
           ) -> list[tuple[str, list[list[str]]]]:
    """(step, the x3drbp command lines it runs)."""
    chosen = ["--backends", ",".join(backends)]
    examples = sorted(os.path.join(EXAMPLES, f) for f in os.listdir(EXAMPLES))
    scenes = [os.path.relpath(p) for p in examples + yours]  # as the page names them
    compare = os.path.join(out, "compare")
    sweep_scenes = ["--scenes", ",".join(map(options.escaped, [*S.DEFAULT_SCENES, *yours]))] if yours else []
    steps = [("conformance", [["conformance", *chosen, "--out", os.path.join(out, "conformance")]]),
             ("compare", [["compare", path, *chosen, "--duration", f"{COMPARE_SECONDS:g}",
                           "--json", os.path.join(compare, stem + ".json"), "--rerun", os.path.join(compare, stem + ".rrd")]
                          for path, stem in zip(scenes, stems(scenes))]),
             ("advise", [["advise", *scenes, *chosen, "--verdicts", os.path.join(out, "conformance", "matrix.json"),
                          "--json", os.path.join(out, "advice", "advice.json")]]),
             ("sweep", [["sweep", *chosen, *sweep_scenes, "--out", os.path.join(out, "sweep")]]),
             ("stability", [["stability", *chosen, "--out", os.path.join(out, "stability")]]),
             ("x_ite", [["x-ite", "cases", "--against", ",".join(backends), "--out", os.path.join(out, "x_ite")]])]
    return [s for s in steps if not (quick and s[0] == "sweep") and (x_ite or s[0] != "x_ite")]


def uncached(steps: list[tuple[str, list[list[str]]]]) -> list[tuple[str, list[list[str]]]]:
    """The steps with --no-cache on each command that takes it: so a step's log line, run alone, runs as it did."""
    return [(step, [[*argv, "--no-cache"] if argv[0] in CACHED else argv for argv in commands])
            for step, commands in steps]


def _run(main: Callable[[list[str]], int], argv: list[str], log: str, bars: TextIO | None = None) -> int:
    """One x3drbp command in this process (`main`, the command line's own), its output into the
    log line by line, its progress bars (if any) on `bars`. The logs are the one output x3drbp
    writes in place, not through x3d_core/files/atomic.py: they are read while a step runs, and keep
    what a killed step said."""
    with (open(log, "a", encoding="utf-8", buffering=1) as f, contextlib.redirect_stdout(f),
          contextlib.redirect_stderr(f)):
        print(f"$ x3drbp {' '.join(argv)}", flush=True)
        children.BARS = bars
        try:
            return main(argv)
        except SystemExit as e:  # argparse's own exit on usage
            return int(e.code or 0)
        finally:
            children.BARS = None


_TABLES = """
import json, sys
from backends import base
out = {}
for name in sys.argv[1].split(","):
    b = base.load(name)
    out[name] = {"support": {f: [b.support(f).support.value, b.support(f).note] for f in sys.argv[2:]},
                 "declared": {s.value: sum(1 for d in b.table().values() if d.support is s) for s in base.Support}}
print("x3drbp-answer " + json.dumps(out))
"""


def declarations(backends: list[str], timeout: float = children.DEFAULT_TIMEOUT) -> tuple[dict | None, str]:
    """Each backend's declaration of every feature a case exercises, and its table's counts,
    asked in a child (the tables live in the engines' modules: importing one can crash, and
    pybullet prints its build time on import); (the answer, or None and why not)."""
    return probe.ask(_TABLES, [",".join(backends), *sorted(C.exercising())], timeout, "the declarations' child")


def not_passing(matrix: dict, backends: list[str]) -> dict:
    """Per backend, each case that does not pass: its verdict, the measures beyond tolerance
    that decide it (accuracy grades decide none) and its pin's `why` (conformance/expectations):
    what was measured to fail, so that a finding blames that and not a feature the case uses."""
    pins = {b: expectations.load(b) for b in backends}
    out: dict[str, dict] = {b: {} for b in backends}
    for r in matrix["results"]:
        if r["backend"] in out and r["verdict"] not in (PASS, CONVENTIONS, UNSUPPORTED):
            pin = pins[r["backend"]].get(r["case"])
            out[r["backend"]][r["case"]] = {
                "verdict": r["verdict"], "why": pin.why if pin is not None else "",
                "measures": [m["quantity"] for m in r["measures"] if not m["ok"] and m["basis"] != ACCURACY]}
    return out


def features(matrix: dict, tables: dict) -> dict:
    """Per backend and feature exercised by a case: what the backend declares (tables:
    declarations()), and the verdicts of the cases that exercise it; per backend, what its
    cases that do not pass measured (a case whose every feature is declared native yet fails
    is a finding)."""
    verdicts = {(r["case"], r["backend"]): r["verdict"] for r in matrix["results"]}
    exercised = C.exercising()
    rows = []
    for feature in sorted(exercised):
        cells = {}
        for b, table in tables.items():
            support, note = table["support"][feature]
            cells[b] = {"support": support, "note": note,
                        "cases": [{"case": c, "verdict": verdicts.get((c, b), "not run")} for c in exercised[feature]]}
        rows.append({"feature": feature, "backends": cells})
    return {"features": rows, "declared": {b: table["declared"] for b, table in tables.items()},
            "not_passing": not_passing(matrix, list(tables))}


@children.interruptible
def cmd_report(args: argparse.Namespace) -> int:
    with probe.remembered():  # the steps ask the backends and their declarations the report asked
        return _report(args)


def _report(args: argparse.Namespace) -> int:
    from reports.report_page import dead_links, write_report  # reports read results; imported when there are some
    try:
        info, named = probe.chosen(options.names(args.backends))
    except ValueError as e:
        print(f"x3drbp report: {e}", file=sys.stderr)
        return EXIT_USAGE
    for b in named:
        if not info[b].usable:
            print(f"x3drbp report: {b} is not run: {info[b].unavailable}", file=sys.stderr)
    backends = [b for b in named if info[b].usable]
    if len(backends) < 2:
        print("x3drbp report: needs two installed backends or more", file=sys.stderr)
        return EXIT_USAGE
    out = args.out
    logs = os.path.join(out, "logs")
    missing = [as_typed(p, getattr(args, "given", {})) for p in args.scenes or () if not os.path.exists(p)]
    if missing:  # before any step: a step would fail on it minutes later
        print(f"x3drbp report: --scenes: no such file or folder: {', '.join(missing)}", file=sys.stderr)
        return EXIT_USAGE
    yours = scene_files(args.scenes) if args.scenes else []
    if args.scenes and not yours:
        print(f"x3drbp report: --scenes: {none_under([as_typed(p, getattr(args, 'given', {})) for p in args.scenes])}",
              file=sys.stderr)
        return EXIT_USAGE
    yours = [os.path.abspath(p) for p in yours]
    left_out = _unrunnable(yours)
    for why in left_out.values():
        print(f"x3drbp report: left out of every step: {why}", file=sys.stderr)
    yours = [p for p in yours if p not in left_out]
    for sub in ("logs", "compare", "advice"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    timings, failed = {}, []
    started = time.perf_counter()
    steps = _steps(out, backends, args.quick, args.x_ite, yours)
    for step, commands in uncached(steps) if getattr(args, "no_cache", False) else steps:
        t0 = time.perf_counter()
        log = os.path.join(logs, f"{step}.log")
        open(log, "w").close()
        bars = sys.stderr if options.progress(args) else None  # a step's bar, cleared when it ends
        print(f"report: {step} ...", end="\n" if bars else "", file=sys.stderr, flush=True)
        codes = [_run(args.main, argv, log, bars) for argv in commands]
        if step in ("compare", "advise"):  # a scene that compares nothing or does not load is a result
            bad = [c for c in codes if c not in (EXIT_OK, EXIT_SCENE_RESULT)]
        else:
            bad = [c for c in codes if c != 0]
        timings[step] = round(time.perf_counter() - t0, 1)
        said = f"{timings[step]:g} s" + (f" (FAILED: see {log})" if bad else "")
        print(f"report: {step} {said}" if bars else f" {said}", file=sys.stderr, flush=True)
        if bad:
            failed.append(step)
    matrix_path = os.path.join(out, "conformance", "matrix.json")
    if os.path.exists(matrix_path):
        tables, why = declarations(backends)
        if tables is None:
            print(f"x3drbp report: features: the backends' declarations could not be read: {why}", file=sys.stderr)
            failed.append("features")
        else:
            with open(matrix_path, encoding="utf-8") as f:
                atomic.write_json(os.path.join(out, "features.json"), features(json.load(f), tables))
    timings["total"] = round(time.perf_counter() - started, 1)
    meta = {"generated": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "backends": {b: info[b].version for b in backends}, "cpus": os.cpu_count(), "timings_s": timings,
            "failed": failed, "quick": args.quick, "scenes": [os.path.relpath(p) for p in yours],
            "left_out": {os.path.relpath(p): why for p, why in left_out.items()}}
    atomic.write_json(os.path.join(out, "report.json"), meta)
    page = write_report(out)
    with open(page, encoding="utf-8") as f:
        for link in dead_links(out, f.read()):  # a step that left out a file its text cites
            print(f"x3drbp report: {page} links to {link}, which is not there", file=sys.stderr)
    print(f"report: wrote {page} and report.md in {timings['total']:g} s", file=sys.stderr)
    return EXIT_FAILED if failed or left_out else EXIT_OK


def _unrunnable(paths: list[str]) -> dict[str, str]:
    """Each of the user's scenes no step can run, with the first reason (the line the steps
    would each print): left out of every step and named on the page, where it failed the
    sweep's step whole (a sweep stops at a scene that does not load) and every other step's
    log said it again."""
    out = {}
    for path in paths:
        scene, errors = options.scene_or_errors(path)
        if scene is None:
            out[path] = errors[0] if errors else f"{path}: does not load"
        elif not simulates(scene):
            out[path] = f"{path}: nothing to simulate: {EMPTY}"
    return out


def add_command(sub) -> None:
    p = sub.add_parser("report", help="the main job: conformance, comparisons, sweeps, stability and the feature "
                                      "tables as one HTML page and markdown",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default=os.path.join("out", "report"), metavar="DIR",
                   help="folder for index.html, report.md and every step's results (default out/report)")
    p.add_argument("--backends", action="append", metavar="LIST",
                   help="backends, comma-separated (default: every installed one)")
    p.add_argument("--scenes", action="append", metavar="DIR_OR_FILE",
                   help="your scenes (files, or folders searched for .x3d/.x3dv/.x3dj), compared, advised and swept "
                        "beside the bundled examples (repeatable)")
    p.add_argument("--quick", action="store_true", help="leave out the sweep, the longest step")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bars (each step's line still prints)")
    p.add_argument("--x-ite", action="store_true",
                   help="add the X_ITE browser's column: every case recorded in X_ITE and judged (`make x-ite`)")
    p.set_defaults(func=cmd_report)
