"""`x3drbp conformance`: every conformance case on every backend, as a matrix.

    x3drbp conformance [--backends LIST] [--cases NAMES] [--out DIR] [--convergence]
                       [--timeout S] [--jobs N] [--keep-traces]

Writes DIR/matrix.md and DIR/matrix.json (DIR defaults to out/conformance) and prints the
markdown. Exit status 0 whatever the verdicts (they are results, not errors); 2 on bad
usage (an unknown case or backend name). With --convergence it also runs each closed-form
case at dt = 1/60, 1/120, 1/240, 1/480 per backend and reports the error per dt and the
fitted order (the slope of log error against log dt).
"""

from __future__ import annotations

import argparse
import datetime
import math
import os
import sys

from reports.text import escape as _escape
from reports.text import num as _num
from x3d_core import atomic

from . import cases as C
from . import runner

EXIT_OK, EXIT_USAGE = 0, 2


def _names(values: list[str] | None) -> list[str]:
    """Comma- or space-separated names, the option possibly given several times."""
    out: list[str] = []
    for v in values or []:
        out.extend(n for n in v.replace(",", " ").split() if n)
    return list(dict.fromkeys(out))


def _dt_label(dt: float) -> str:
    inv = 1.0 / dt
    return f"1/{round(inv)}" if abs(inv - round(inv)) < 1e-6 * inv else f"{dt:g}"


def _cell(r: runner.Result) -> str:
    if r.verdict == runner.PASS:
        w = r.worst()
        return f"pass ({w.ratio:.2g})" if w is not None and math.isfinite(w.ratio) else "pass"
    if r.verdict == runner.FAIL:
        w = r.worst()
        return f"**fail** ({w.ratio:.3g}x)" if w is not None and math.isfinite(w.ratio) else "**fail**"
    return r.verdict


def markdown(results: list[runner.Result], cases: list[C.Case], backends: list[str],
             info: dict[str, runner.BackendInfo], convergence: list[runner.Convergence] | None = None) -> str:
    by = {(r.case, r.backend): r for r in results}
    lines = ["# x3drbp conformance", ""]
    def describe(n: str) -> str:
        i = info.get(n)
        if i is None or not i.usable:
            return f"{n} (unavailable: {i.unavailable if i else 'unknown'})"
        return f"{n} {i.version}" + ("" if n in backends else " (not run)")
    lines.append("Backends: " + "; ".join(describe(n) for n in dict.fromkeys([*backends, *info])))
    lines.append("")
    lines.append("Cell: verdict (worst error / tolerance over the case's measures; pass means every one <= 1; "
                 "1 means at the bound, as semi-implicit Euler is on the constant-acceleration cases).")
    lines.append("")
    lines.append("| case | checks | " + " | ".join(backends) + " |")
    lines.append("|---|---|" + "---|" * len(backends))
    for c in cases:
        cells = [_cell(by[(c.name, b)]) if (c.name, b) in by else "-" for b in backends]
        lines.append(f"| {c.name} | {_escape(c.checks)} | " + " | ".join(cells) + " |")
    lines.append("")
    counts = {v: sum(r.verdict == v for r in results) for v in runner.VERDICTS}
    lines.append("Totals: " + ", ".join(f"{n} {v}" for v, n in counts.items() if n))
    not_pass = [r for r in results if r.verdict != runner.PASS]
    if not_pass:
        lines += ["", "## Not passing", ""]
        for r in not_pass:
            lines.append(f"- {r.case} on {r.backend}: **{r.verdict}**: {_escape(r.reason)}")
    lines += ["", "## Measures", "", "| case | backend | quantity | error | tolerance | ok |",
              "|---|---|---|---:|---:|---|"]
    for r in results:
        for m in r.measures:
            unit = f" {m.unit}" if m.unit else ""
            lines.append(f"| {r.case} | {r.backend} | {_escape(m.quantity)} | {_num(m.error)}{unit} | "
                         f"{_num(m.tolerance)}{unit} | {'yes' if m.ok else '**no**'} |")
    if convergence is not None:
        lines += ["", "## Convergence", "",
                  "Error of each case's closed-form quantity against its continuous closed form, per step size, "
                  "and the fitted order (slope of log error against log dt; '-' where the errors are at rounding "
                  "level, i.e. the backend is exact for that case). Expected: what semi-implicit Euler gives.", ""]
        dts = convergence[0].dts if convergence else list(C.CONVERGENCE_DTS)
        lines.append("| case | quantity | backend | " + " | ".join(f"dt={_dt_label(d)}" for d in dts)
                     + " | order | expected |")
        lines.append("|---|---|---|" + "---:|" * len(dts) + "---:|---:|")
        for cv in convergence:
            cells = []
            for e, r in zip(cv.errors(), cv.results):
                cells.append(_num(e) if e is not None else r.verdict)
            order = cv.order()
            lines.append(f"| {cv.case} | {_escape(cv.quantity)} | {cv.backend} | " + " | ".join(cells)
                         + f" | {'-' if order is None else f'{order:.2f}'} | {_num(cv.expected_order)} |")
    return "\n".join(lines) + "\n"


def to_json(results: list[runner.Result], cases: list[C.Case], backends: list[str],
            info: dict[str, runner.BackendInfo], convergence: list[runner.Convergence] | None = None) -> dict:
    return {
        "generated": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "backends": {n: {"version": i.version, "unavailable": i.unavailable, "run": n in backends}
                     for n, i in info.items()},
        "cases": [{"name": c.name, "scene": os.path.relpath(c.path, C.ROOT), "checks": c.checks,
                   "runs": [{"duration": s.duration, "dt": s.dt, "frame_rate": s.rate} for s in c.runs],
                   "convergence": c.convergence} for c in cases],
        "results": [r.to_json() for r in results],
        "convergence": None if convergence is None else [cv.to_json() for cv in convergence],
    }


def cmd_conformance(args: argparse.Namespace) -> int:
    try:
        cases = C.select(_names(args.cases))
    except KeyError as e:
        print(f"x3drbp conformance: {e.args[0]}", file=sys.stderr)
        return EXIT_USAGE
    info = runner.backend_table(args.timeout)
    try:
        backends = runner.named_backends(_names(args.backends), info)
    except ValueError as e:
        print(f"x3drbp conformance: {e}", file=sys.stderr)
        return EXIT_USAGE
    if not backends:
        print("x3drbp conformance: no backend is available here: "
              + "; ".join(f"{n}: {i.unavailable}" for n, i in info.items()), file=sys.stderr)
    keep = os.path.join(args.out, "traces") if args.keep_traces else None
    runnable = [b for b in backends if info[b].usable]
    results = runner.run_matrix(cases, runnable, args.timeout, args.jobs, keep=keep)
    for b in backends:  # named on the command line but not installed: say so in every cell
        if not info[b].usable:
            results += [runner.Result(c.name, b, runner.ERROR, f"backend unavailable: {info[b].unavailable}")
                        for c in cases]
    order = {(c.name, b): k for k, (c, b) in enumerate((c, b) for c in cases for b in backends)}
    results.sort(key=lambda r: order[(r.case, r.backend)])
    convergence = None
    if args.convergence:
        convergence = runner.run_convergence(cases, runnable, C.CONVERGENCE_DTS, args.timeout, args.jobs)
    text = markdown(results, cases, backends, info, convergence)
    os.makedirs(args.out, exist_ok=True)
    atomic.write_text(os.path.join(args.out, "matrix.md"), text)
    atomic.write_json(os.path.join(args.out, "matrix.json"), to_json(results, cases, backends, info, convergence))
    sys.stdout.write(text)
    print(f"\nwrote {os.path.join(args.out, 'matrix.md')} and matrix.json")
    return EXIT_OK


def add_command(sub) -> None:
    p = sub.add_parser("conformance", help="run the conformance cases on the backends and write the matrix",
                       description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--backends", action="append", metavar="LIST",
                   help="backends to run, comma-separated (default: every installed one)")
    p.add_argument("--cases", action="append", metavar="NAMES",
                   help=f"cases to run, comma-separated (default: all: {', '.join(C.BY_NAME)})")
    p.add_argument("--out", default=os.path.join("out", "conformance"), metavar="DIR",
                   help="folder for matrix.md and matrix.json (default out/conformance)")
    p.add_argument("--convergence", action="store_true",
                   help="also run each closed-form case at dt = 1/60, 1/120, 1/240, 1/480 and fit the order")
    p.add_argument("--timeout", type=float, default=runner.DEFAULT_TIMEOUT, metavar="S",
                   help=f"time limit per run in seconds (default {runner.DEFAULT_TIMEOUT:g})")
    p.add_argument("--jobs", type=int, default=None, metavar="N",
                   help="runs in parallel (default: the number of CPUs)")
    p.add_argument("--keep-traces", action="store_true", help="keep every run's trace under DIR/traces")
    p.set_defaults(func=cmd_conformance)
