"""`x3drbp validate`'s result as text for a terminal: markdown tables that read as well there.

Reads a conformance.results.Validation; runs nothing. It is terminal text, not markup: what
comes from a user's file (a name, a reason that quotes one) and the clause's words are printed
as they are, `>` as `>` and a name's `_` as `_`, through printable() alone (a control character
as its escape, so a name can neither move the cursor nor start a line). Nothing puts this text
into an HTML page; a page would take escape() (reports/text.py), as the report's pages do.
"""

from __future__ import annotations

from conformance.results import ORIENTATION, POSITION, RAN, UNITS, FrameStep, TraceComparison, Validation, dt_label
from x3d_core.files.paths import printable

from .compare_text import rms_max, worst_joint
from .text import basis_cell, grade_cell, num


def _case(v: Validation) -> list[str]:
    r = v.case
    if r is None:
        return ["No conformance case has this scene: the trace conforms when it agrees with at least one backend.", ""]
    lines = [f"## Case {r.case}: **{printable(r.meaning())}**", "",
             "| measure | basis | error | tolerance | verdict | accuracy (bound) |", "|---|---|---:|---:|---|---|"]
    lines += [f"| {printable(m.quantity)} | {basis_cell(m, printable)} | {num(m.error)} {m.unit} | "
              f"{'-' if m.graded else f'{num(m.tolerance)} {m.unit}'} | "
              f"{'graded' if m.graded else 'pass' if m.ok else '**fail**'} | {grade_cell(m)} |" for m in r.measures]
    return lines + [""]


def _comparison(c: TraceComparison) -> list[str]:
    """A row per backend: a column per body kind compared (UNITS: the pose, then the velocities),
    and a differing one's verdict naming each kind and joint output past its threshold."""
    s = c.settings
    compared = {d.quantity for p in c.pairs.values() for d in p.divergences}
    kinds = [k for k in UNITS if k in (POSITION, ORIENTATION) or k in compared]
    lines = [f"## {printable(c.trace)} against the backends", "",
             f"Run as the trace reads: {s.duration:g} s, dt {s.dt:g} s, {s.frame_rate:g} frames/s.", "",
             "| backend | verdict | frames | " + "".join(f"{k} RMS / max ({UNITS[k]}) | " for k in kinds)
             + "worst joint output |", "|---|---|---:|" + "---|" * (len(kinds) + 1)]
    for r in c.runs:
        p = c.pairs.get(r.backend)
        if p is None:
            lines.append(f"| {r.backend} | {r.verdict}: {printable(r.reason)} | - | " + "- | " * (len(kinds) + 1))
            continue
        over = p.diverged()
        verdict = c.verdict(r.backend) + (f": {printable(', '.join(over))}" if over else "")
        by = {d.quantity: d for d in p.divergences}
        lines.append(f"| {r.backend} | {verdict} | {p.times.size} | "
                     + "".join(f"{rms_max(by[k], printable) if k in by else '-'} | " for k in kinds)
                     + f"{worst_joint(p, printable)} |")
    missing = [f"- {p.b}: {what} it records that the trace lacks: {printable(', '.join(names))}"
               for p in c.pairs.values()
               for what, names in (("bodies", p.only_in_b), ("joint outputs", p.joints_only_in_b)) if names]
    return lines + ([""] + missing if missing else []) + [""]


def _typed(dt: float) -> str:
    """A step as one types it for --dt: 1/60, else with every digit it needs."""
    label = dt_label(dt)
    return label if "/" in label else f"{dt:.9g}"


def _frame_step(f: FrameStep) -> str:
    step = _typed(f.dt)
    said = f"Their frames are {step} s apart: if the implementation steps once per frame, try --dt {step}"
    if f.conforms is None:
        return said + "."
    if not f.conforms:
        return said + ": at that step it does not conform either."
    return said + ": at that step it conforms" + (f" (agrees with {', '.join(f.agreeing)})." if f.agreeing else ".")


def render(v: Validation) -> str:
    th = ", ".join(f"{k} {num(x)} {UNITS.get(k, '')}".rstrip() for k, x in v.thresholds.items())
    lines = [f"# x3drbp validate {printable(v.scene)}", "", f"Traces: {printable(', '.join(v.traces))}; "
             f"thresholds: {th}.", ""]
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
    if v.frame_step is not None:
        lines.append(_frame_step(v.frame_step))
    return "\n".join(lines) + "\n"
