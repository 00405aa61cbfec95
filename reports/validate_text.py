"""`x3drbp validate`'s result as text: markdown tables that read as well in a terminal.

Reads a conformance.results.Validation; runs nothing.
"""

from __future__ import annotations

from conformance.results import RAN, TraceComparison, Validation

from .compare_text import rms_max, worst_joint
from .text import basis_cell, escape, grade_cell, num


def _case(v: Validation) -> list[str]:
    r = v.case
    if r is None:
        return ["No conformance case has this scene: the trace conforms when it agrees with at least one backend.", ""]
    lines = [f"## Case {r.case}: **{escape(r.meaning())}**", "",
             "| measure | basis | error | tolerance | verdict | accuracy (bound) |", "|---|---|---:|---:|---|---|"]
    lines += [f"| {escape(m.quantity)} | {basis_cell(m)} | {num(m.error)} {m.unit} | "
              f"{'-' if m.graded else f'{num(m.tolerance)} {m.unit}'} | "
              f"{'graded' if m.graded else 'pass' if m.ok else '**fail**'} | {grade_cell(m)} |" for m in r.measures]
    return lines + [""]


def _comparison(c: TraceComparison) -> list[str]:
    s = c.settings
    lines = [f"## {escape(c.trace)} against the backends", "",
             f"Run as the trace reads: {s.duration:g} s, dt {s.dt:g} s, {s.frame_rate:g} frames/s.", "",
             "| backend | verdict | frames | position RMS / max (m) | orientation RMS / max (rad) "
             "| worst joint output |", "|---|---|---:|---|---|---|"]
    for r in c.runs:
        p = c.pairs.get(r.backend)
        if p is None:
            lines.append(f"| {r.backend} | {r.verdict}: {escape(r.reason)} | - | - | - | - |")
        else:
            lines.append(f"| {r.backend} | {c.verdict(r.backend)} | {p.times.size} | {rms_max(p.position)} | "
                         f"{rms_max(p.orientation)} | {worst_joint(p)} |")
    missing = [f"- {p.b}: {what} it records that the trace lacks: {escape(', '.join(names))}"
               for p in c.pairs.values()
               for what, names in (("bodies", p.only_in_b), ("joint outputs", p.joints_only_in_b)) if names]
    return lines + ([""] + missing if missing else []) + [""]


def render(v: Validation) -> str:
    th = v.thresholds
    lines = [f"# x3drbp validate {escape(v.scene)}", "", f"Traces: {escape(', '.join(v.traces))}; thresholds: position "
             f"{num(th['position'])} m, orientation {num(th['orientation'])} rad.", ""]
    lines += _case(v)
    for c in v.comparisons:
        lines += _comparison(c)
    ran = any(r.verdict == RAN for c in v.comparisons for r in c.runs)
    agreeing = ", ".join(v.agreeing()) or ("none" if ran else "none ran")
    if not v.judged:
        lines.append(f"Agrees with: {agreeing}. **Not judged**: no backend ran the scene (each row says why), and "
                     "the scene is no conformance case: nothing measured the trace.")
    else:
        lines.append(f"Agrees with: {agreeing}. **{'Conforms' if v.conforms else 'Does not conform'}** ({v.rule}).")
    return "\n".join(lines) + "\n"
