"""`x3drbp x-ite`: the X_ITE browser, headless, as an implementation under test.

    x3drbp x-ite cases [--cases NAMES] [--against LIST] [--out DIR] [--timeout S]
    x3drbp x-ite record SCENE --trace OUT.csv [--frame-rate F] [--duration S]

`cases` records every conformance case (or those named) in X_ITE and judges each with the
suite's ordinary checks (conformance/browsers/x_ite/judge.py): right, ignores (the fields
measured to have no effect) or wrong, with X_ITE's traces in DIR/traces/, a rerun
recording of each case where X_ITE and a backend part in DIR/recordings/, and
DIR/x_ite.json and x_ite.md (DIR defaults to out/x_ite). `record` writes X_ITE's trace of
any scene, for `x3drbp validate` (it prints the --dt to pass: the step X_ITE takes).

Needs node, Debian's chromium and the npm packages in conformance/browsers/x_ite: `make
x-ite-install` installs them. Exit status 0 whatever the verdicts (they are results); 1
when X_ITE cannot run here at all, or `record` could not record, or the scene blew up in
X_ITE (its trace then holds the frames before the first value that is not finite); 2 on
bad usage.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import subprocess
import sys
import time

from x3d_core.files import atomic
from x3d_core.files.paths import shown
from x3d_core.model.scene import Scene
from x3d_core.traces.trace import TraceView

from conformance import cases as C
from conformance.runner import children, probe
from conformance.browsers.x_ite.harness import CHROMIUM, HERE, NotRecordable, Recording, outputs, record, step, unavailable
from conformance.browsers.x_ite.judge import Recorder, run_cases
from conformance.results import PairComparison

from x3drbp import options

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2


def versions() -> dict[str, str]:
    with open(os.path.join(HERE, "node_modules", "x_ite", "package.json"), encoding="utf-8") as f:
        x_ite = json.load(f)["version"]
    chromium = subprocess.run([CHROMIUM, "--version"], capture_output=True, text=True).stdout.strip()
    return {"x_ite": x_ite, "chromium": chromium}


def _say(text: str) -> None:
    print(f"x3drbp x-ite: {text}", file=sys.stderr, flush=True)


def _recorder(folder: str) -> Recorder:
    """The judge's recorder: a case's rerun recording, FOLDER/CASE.rrd."""
    def write(name: str, scene: Scene, runs: list[tuple[str, TraceView]], pairs: list[PairComparison]) -> str:
        from reports.rerun_recording import write_recording  # rerun is imported when a recording is written
        os.makedirs(folder, exist_ok=True)
        out = os.path.join(folder, f"{name}.rrd")
        write_recording(out, scene, runs, pairs)
        return out
    return write


@children.interruptible
def cmd_cases(args: argparse.Namespace) -> int:
    from reports.x_ite_text import render  # reports render results: imported when there are some
    try:
        chosen = C.select(options.given(args.cases, "--cases", "case") or None)
        info, named = probe.chosen(options.given(args.against, "--against", "backend"))
        backends = [b for b in named if info[b].usable]
        thresholds = options.thresholds(args.threshold)
    except (KeyError, ValueError) as e:  # an unknown case, backend or threshold
        _say(str(e.args[0]))
        return EXIT_USAGE
    reason = unavailable()
    if reason:
        _say(f"X_ITE cannot run here: {reason}")
        return EXIT_FAILED
    traces = os.path.join(args.out, "traces")
    try:
        os.makedirs(traces, exist_ok=True)
    except OSError as e:
        _say(f"--out {args.out}: {e.strerror}")
        return EXIT_USAGE
    started = time.perf_counter()
    verdicts, clocks = run_cases(chosen, traces, backends, info, thresholds, args.timeout,
                                 _recorder(os.path.join(args.out, "recordings")), _say)
    for v in verdicts:  # paths in the results are relative to the folder they are in
        if v.recording:
            v.recording = os.path.relpath(v.recording, args.out)
    data = {"generated": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            "versions": versions(), "backends": backends, "thresholds": thresholds,
            "wall_s": round(time.perf_counter() - started, 1), "clock": [k.to_json() for k in clocks],
            "cases": [v.to_json() for v in verdicts]}
    atomic.write_json(os.path.join(args.out, "x_ite.json"), data)
    text = render(data)
    atomic.write_text(os.path.join(args.out, "x_ite.md"), text)
    sys.stdout.write(text)
    return EXIT_OK


class _NotRecorded(Exception):
    """X_ITE gave no whole trace; the message says why."""


@children.interruptible
def cmd_record(args: argparse.Namespace) -> int:
    scene = options.load_scene(args.scene)  # its errors as check says them: a scene with errors was recorded
    if scene is None:
        return EXIT_USAGE
    try:
        what = outputs(scene)
    except NotRecordable as e:
        _say(f"{shown(args.scene)}: {e}")
        return EXIT_USAGE
    reason = unavailable()
    if reason:
        _say(f"X_ITE cannot run here: {reason}")
        return EXIT_FAILED
    try:
        with atomic.replacing(args.trace) as part:  # node writes the temporary; moved over OUT.csv once whole
            run = Recording(args.scene, part, args.frame_rate, args.duration, what)
            record([run], args.timeout)
            if not run.ok:
                raise _NotRecorded(run.error)
    except _NotRecorded as e:  # the temporary is gone, OUT.csv as it was
        _say(f"{args.scene}: X_ITE did not record it: {e}")
        return EXIT_FAILED
    for m in run.messages:
        _say(f"X_ITE said: {m}")
    if run.blew_up:  # the trace holds the frames before it: readable, and cut short
        _say(f"{shown(args.scene)}: X_ITE blew up: {run.blew_up}; {shown(args.trace)} holds the {run.frames} "
             f"frames before it")
        return EXIT_FAILED
    _say(f"wrote {args.trace}: {run.frames} frames in {run.wall_s:.2f} s; "
         f"X_ITE's step here is {step(scene, args.frame_rate)!r} s (validate with --dt {step(scene, args.frame_rate)!r})")
    return EXIT_OK


def add_command(sub) -> None:
    p = sub.add_parser("x-ite", help="run the X_ITE browser headless on the conformance cases or a scene, "
                                     "and judge its traces", description=__doc__,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    modes = p.add_subparsers(dest="mode", required=True)
    c = modes.add_parser("cases", help="every conformance case in X_ITE: right, ignores or wrong, measured")
    c.add_argument("--cases", action="append", metavar="NAMES", help="cases, comma-separated (default: all)")
    c.add_argument("--against", action="append", metavar="LIST",
                   help="backends to compare with, comma-separated (default: every installed one)")
    c.add_argument("--threshold", action="append", metavar="KIND=VALUE",
                   help="divergence thresholds, as for x3drbp compare")
    c.add_argument("--out", default=os.path.join("out", "x_ite"), metavar="DIR",
                   help="folder for x_ite.json, x_ite.md, traces/ and recordings/ (default out/x_ite)")
    c.add_argument("--timeout", type=options.positive, default=children.DEFAULT_TIMEOUT, metavar="S",
                   help="seconds per run, for X_ITE's and each backend's")
    c.set_defaults(func=cmd_cases)
    r = modes.add_parser("record", help="X_ITE's trace of a scene, for x3drbp validate")
    r.add_argument("scene")
    r.add_argument("--trace", required=True, metavar="OUT.csv")
    r.add_argument("--frame-rate", type=options.positive, default=60.0, metavar="F", help="frames per second (default 60)")
    r.add_argument("--duration", type=options.positive, default=5.0, metavar="S", help="seconds (default 5)")
    r.add_argument("--timeout", type=options.positive, default=children.DEFAULT_TIMEOUT, metavar="S")
    r.set_defaults(func=cmd_record)
