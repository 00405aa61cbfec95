"""`x3drbp compare`'s result as text: markdown tables that read as well in a terminal.

Reads a conformance.results.Comparison (or its JSON, through Comparison.from_json); runs nothing.
A pair whose backends step free motion in different orders (BackendRun.integration) gets a
note of what that order alone parts them by.
"""

from __future__ import annotations

from collections.abc import Callable

from conformance.results import RAN, BackendRun, Comparison, Crossing, Divergence, PairComparison

from x3d_core.semantics.integration import lead

from .text import energy_grew, escape, num, untemporary

_SHOWN_BODIES = 3  # bodies named at a first crossing; the rest counted
_G = 9.8  # m/s^2, X3D's default gravity: the scale of the integration order's note


def _rtf(r: BackendRun) -> str:
    f = r.realtime_factor
    if f is None:
        return "-"
    return f"{f:.3g}x" + (" (child)" if r.realtime_basis == "child" else "")


def rms_max(d: Divergence, text: Callable[[str], str] = escape) -> str:
    """A divergence's cell: RMS / max (the body and time of the max); the body's name through
    `text` (escape() for markdown that becomes HTML, printable() for a terminal)."""
    return "-" if d.max is None else f"{num(d.rms)} / {num(d.max)} ({text(d.max_body)}, {num(d.max_time)} s)"


def _crossing(c: Crossing | None) -> str:
    if c is None:
        return "never"
    named = ", ".join(f"{escape(b)} {num(v)}" for b, v in zip(c.bodies[:_SHOWN_BODIES], c.values))
    more = len(c.bodies) - _SHOWN_BODIES
    return f"{num(c.time)} s: {named}" + (f" +{more} more" if more > 0 else "")


def worst_joint(p: PairComparison, text: Callable[[str], str] = escape) -> str:
    """The cell of the pair's joint output furthest past its threshold (its name through `text`)."""
    j = p.worst_joint()
    if j is None:
        return "-"
    return f"{text(j.node)}.{j.field} {num(j.max)} {j.unit} ({num(j.max_time)} s)"


def _integration(p: PairComparison, schemes: dict[str, str | None], dt: float) -> str | None:
    """Where the two backends step free motion by different schemes, what that alone parts
    them by (x3d_core/semantics/integration.py): a reader should not take one's lag for a fault."""
    sa, sb = schemes.get(p.a), schemes.get(p.b)
    if sa is None or sb is None or sa == sb:
        return None
    said = f"{p.a} steps by {sa}, {p.b} by {sb}: from that alone free motion parts from the first step"
    la, lb = lead(sa), lead(sb)
    if la is None or lb is None:
        return said + ", not a fault of either"
    k = abs(la - lb)
    factor = "" if k == 1 else f"{k:g} "
    return (f"{said}, by {factor}dt |v - v0| in position (dt times the velocity a body has gained: a fall "
            f"under {_G:g} m/s^2 parts by {factor}g dt^2 = {num(k * _G * dt * dt)} m more each step, "
            f"{num(k * _G * dt)} m after 1 s) and by {factor}dt |w - w0| in orientation, not a fault of either")


def _notes(p: PairComparison, schemes: dict[str, str | None], dt: float) -> list[str]:
    notes = []
    order = _integration(p, schemes, dt)
    if order:
        notes.append(order)
    for what, names in (("bodies", p.only_in_a), ("joint outputs", p.joints_only_in_a)):
        if names:
            notes.append(f"{what} only in {p.a}: {escape(', '.join(names))}")
    for what, names in (("bodies", p.only_in_b), ("joint outputs", p.joints_only_in_b)):
        if names:
            notes.append(f"{what} only in {p.b}: {escape(', '.join(names))}")
    if not p.times.size:
        notes.append("no frame time in common")
    return [f"- {p.a} / {p.b}: {n}" for n in notes]


def render(c: Comparison) -> str:
    th = c.thresholds
    lines = [f"# x3drbp compare {escape(c.scene)}", "",
             f"{c.duration:g} s, dt {c.dt:g} s, {c.frame_rate:g} frames/s; thresholds: position "
             f"{num(th['position'])} m, orientation {num(th['orientation'])} rad", "",
             "| backend | version | verdict | real-time factor |", "|---|---|---|---:|"]
    for r in c.runs:
        lines.append(f"| {r.backend} | {r.version or '-'} | {r.verdict} | {_rtf(r)} |")
    lines += ["", "Real-time factor: simulated s / wall s of the simulation itself (plan, engine build, steps, "
              "state readback), as the child timed it; '(child)': of the whole child process."]
    stopped = [r for r in c.runs if r.verdict != RAN]
    if stopped:
        lines += [""] + [f"- {r.backend}: **{r.verdict}**: {escape(untemporary(r.reason))}" for r in stopped]
    grew = [r for r in c.runs if r.energy is not None]
    if grew:
        lines += [""] + [f"- {energy_grew(r.backend, r.energy)}" for r in grew]
    lines.append("")
    if not c.pairs:
        lines.append("No pair compared: fewer than two backends ran.")
        return "\n".join(lines) + "\n"
    lines += ["| pair | bodies | frames | position RMS / max (m) | orientation RMS / max (rad) "
              f"| first position > {num(th['position'])} m | first orientation > {num(th['orientation'])} rad "
              "| worst joint output |", "|---|---:|---:|---|---|---|---|---|"]
    for p in c.pairs:
        lines.append(f"| {p.a} / {p.b} | {len(p.bodies)} | {p.times.size} | {rms_max(p.position)} | "
                     f"{rms_max(p.orientation)} | {_crossing(p.position.first_over)} | "
                     f"{_crossing(p.orientation.first_over)} | {worst_joint(p)} |")
    schemes = {r.backend: r.integration for r in c.runs}
    notes = [n for p in c.pairs for n in _notes(p, schemes, c.dt)]
    lines += ["", "RMS and max: over every frame and body (the max's body and time); first: the first frame a "
              "body passes the threshold, the bodies over it then, worst first; worst joint output: the largest "
              "difference against its unit's threshold (m: position; rad, axes: orientation; m/s: linearVelocity; "
              "rad/s: angularVelocity)."]
    if notes:
        lines += [""] + notes
    return "\n".join(lines) + "\n"
