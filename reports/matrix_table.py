"""The conformance matrix as markdown: `x3drbp conformance`'s matrix.md."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from conformance.results import CONVENTIONS, FAIL, PASS, VERDICTS, BackendInfo, Convergence, Result, dt_label

from .text import basis_cell, escape, grade_cell, num


def _cell(r: Result) -> str:
    """'verdict (worst judged error / tolerance); accuracy Kx' (the worst graded error over its bound)."""
    if r.verdict not in (PASS, CONVENTIONS, FAIL):
        return r.verdict
    label = {PASS: "pass", CONVENTIONS: "conventions", FAIL: "**fail**"}[r.verdict]
    judged = [m.ratio for m in r.measures if not m.graded]
    w = max(judged, default=None)
    cell = f"{label} ({w:.2g})" if w is not None and math.isfinite(w) else label
    acc = r.accuracy()
    return cell if acc is None else cell + f"; accuracy {'within' if acc <= 1 else f'{acc:.2g}x'}"


def markdown(outcomes: Sequence[Result], cases: Sequence[tuple[str, str]], backends: list[str],
             info: Mapping[str, BackendInfo], convergence: Sequence[Convergence] | None = None) -> str:
    """The matrix page: cases by backends, the cases not passing, every measure, and the
    convergence study where one was run. `cases`: (name, what it checks) in row order."""
    by = {(r.case, r.backend): r for r in outcomes}
    lines = ["# x3drbp conformance", ""]
    def describe(n: str) -> str:
        i = info.get(n)
        if i is None or not i.usable:
            return f"{n} (unavailable: {i.unavailable if i else 'unknown'})"
        return f"{n} {i.version}" + ("" if n in backends else " (not run)")
    lines.append("Backends: " + "; ".join(describe(n) for n in dict.fromkeys([*backends, *info])))
    lines.append("")
    lines.append("Cell: verdict (worst error / tolerance over the case's judged measures; pass means every one "
                 "<= 1), then the accuracy grade (the worst error over its accuracy bound, from the step and the "
                 "integrator's order: 'within', or how many times the bound). Each judged measure holds a sentence "
                 "of clause 37, with a tolerance any consistent integrator and solver meets at the scene's "
                 "settings, or a convention where the clause is silent, or a description from outside it: pass "
                 "conforms; conventions conforms, differing only from x3drbp's readings (docs/spec-loose-ends.md) "
                 "or a description; **fail** violates the spec. Accuracy never changes a verdict.")
    lines.append("")
    lines.append("| case | checks | " + " | ".join(backends) + " |")
    lines.append("|---|---|" + "---|" * len(backends))
    for name, checks in cases:
        cells = [_cell(by[(name, b)]) if (name, b) in by else "-" for b in backends]
        lines.append(f"| {name} | {escape(checks)} | " + " | ".join(cells) + " |")
    lines.append("")
    counts = {v: sum(r.verdict == v for r in outcomes) for v in VERDICTS}
    lines.append("Totals: " + ", ".join(f"{n} {v}" for v, n in counts.items() if n))
    not_pass = [r for r in outcomes if r.verdict != PASS]
    if not_pass:
        lines += ["", "## Not passing", ""]
        for r in not_pass:
            lines.append(f"- {r.case} on {r.backend}: **{r.verdict}**: {escape(r.meaning())}")
    lines += ["", "## Measures", "", "| case | backend | quantity | basis | error | tolerance | ok | accuracy (bound) |",
              "|---|---|---|---|---:|---:|---|---|"]
    for r in outcomes:
        for m in r.measures:
            unit = f" {m.unit}" if m.unit else ""
            ok = "graded" if m.graded else ("yes" if m.ok else "**no**")
            lines.append(f"| {r.case} | {r.backend} | {escape(m.quantity)} | {basis_cell(m)} | {num(m.error)}{unit} | "
                         f"{'-' if m.graded else num(m.tolerance) + unit} | {ok} | {grade_cell(m)} |")
    if convergence:
        lines += ["", "## Convergence", "",
                  "Error of each case's closed-form quantity against its continuous closed form, per step size, "
                  "and the fitted order (slope of log error against log dt; '-' where the errors are at rounding "
                  "level, i.e. the backend is exact for that case). Expected: what semi-implicit Euler gives.", ""]
        dts = convergence[0].dts
        lines.append("| case | quantity | backend | " + " | ".join(f"dt={dt_label(d)}" for d in dts)
                     + " | order | expected |")
        lines.append("|---|---|---|" + "---:|" * len(dts) + "---:|---:|")
        for cv in convergence:
            cells = []
            for e, r in zip(cv.errors(), cv.results):
                cells.append(num(e) if e is not None else r.verdict)
            order = cv.order()
            lines.append(f"| {cv.case} | {escape(cv.quantity)} | {cv.backend} | " + " | ".join(cells)
                         + f" | {'-' if order is None else f'{order:.2f}'} | {num(cv.expected_order)} |")
    return "\n".join(lines) + "\n"
