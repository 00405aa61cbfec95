"""The stability suite's results (stability.json, as x3drbp.stability writes it)
as markdown: a verdict per (case, dt, backend), then each case's drift figures, then a line for
each run whose energy grew with nothing doing work on its scene, then why each run that did not
hold gave way, linking its kept trace (a path relative to stability.md)."""

from __future__ import annotations

from conformance.results import EnergyGrowth

from .text import energy_grew, escape, link, num, untemporary

HELD = ("survived", "stopped")
PLAIN = (*HELD, "unsupported", "error")  # not a breakdown: no bold


def _label(verdict: str) -> str:
    return verdict.removesuffix(" past bound")


def _cell(r: dict) -> str:
    """The verdict, bold where the run broke down, with the time it did."""
    v = r["verdict"]
    if v in PLAIN:
        return v
    when = f" at {r['at']:.3g} s" if r.get("at") is not None else ""
    return f"**{_label(v)}**{when}"


def _figure(f: dict | None) -> str:
    if f is None:
        return "-"
    v = f["value"]
    text = num(v) if isinstance(v, float) else str(v)
    return text + (f" ({f['where']})" if f.get("where") else "")


def _run(r: dict, label: dict[float, str]) -> str:
    return f"{r['case']} on {r['backend']} at dt {label[r['dt']]}"


def markdown(data: dict) -> str:
    backends = [n for n, b in data["backends"].items() if b["run"]]
    label = {d["dt"]: d["label"] for d in data["dts"]}
    dts = list(label)
    results = {(r["case"], r["dt"], r["backend"]): r for r in data["results"]}
    lines = ["# x3drbp stability", ""]

    def describe(n: str) -> str:
        b = data["backends"][n]
        if b["unavailable"]:
            return f"{n} (unavailable: {b['unavailable']})"
        return f"{n} {b['version']}" + ("" if b["run"] else " (not run)")
    lines += ["Backends: " + "; ".join(describe(n) for n in data["backends"]), "",
              f"{len(data['results'])} runs, {data['jobs']} at a time: {data['wall_s']:.1f} s wall.", "",
              "Cell: the verdict; where a run did not hold, what gave way first and when (simulated time). "
              "Bounds and their arguments: conformance/analyses/stability.py and each scene's leading comment.", "",
              "| case | dt | " + " | ".join(backends) + " |", "|---|---|" + "---|" * len(backends)]
    for c in data["cases"]:
        for dt in dts:
            cells = [_cell(results[(c["name"], dt, b)]) if (c["name"], dt, b) in results else "-" for b in backends]
            lines.append(f"| {c['name']} | {label[dt]} | " + " | ".join(cells) + " |")
    lines += ["", "## Cases", ""]
    for c in data["cases"]:
        lines.append(f"- **{c['name']}** ({c['scene']}, {c['duration']:g} s): {escape(c['stresses'])}")
    lines += ["", "## Drift figures", "",
              "Each monitored quantity's worst value over the run (its bound in the header; none: reported only). "
              "'-': the run gave no trace to measure (it blew up, was refused or did not finish)."]
    for c in data["cases"]:
        mine = [results[k] for k in ((c["name"], dt, b) for dt in dts for b in backends) if k in results]
        heads: dict[str, str] = {}
        for r in mine:
            for f in r["figures"]:
                bound = f"; bound {f['bound']:g}" if f["bound"] is not None else ""
                heads.setdefault(f["quantity"], f"{f['quantity']} ({f['unit']}{bound})")
        lines += ["", f"### {c['name']}", "",
                  "| " + " | ".join(["backend", "dt", "verdict", *map(escape, heads.values()), "wall s"]) + " |",
                  "|---|---|---|" + "---:|" * (len(heads) + 1)]
        for r in mine:
            by = {f["quantity"]: f for f in r["figures"]}
            cells = [_figure(by.get(q)) for q in heads]
            lines.append("| " + " | ".join([r["backend"], label[r["dt"]], _cell(r), *cells, f"{r['wall_s']:.1f}"])
                         + " |")
    grew = [r for r in data["results"] if r.get("energy_growth")]  # absent from results written before it
    if grew:
        lines += ["", "## Energy made", ""]
        lines += [f"- {energy_grew(_run(r, label), EnergyGrowth.from_json(r['energy_growth']))}" for r in grew]
    others = [r for r in data["results"] if r["verdict"] not in HELD]
    if others:
        lines += ["", "## Why", ""]
        for r in others:
            trace = f" (trace: {link(r['trace'])})" if r.get("trace") else ""
            lines.append(f"- {_run(r, label)}: {_label(r['verdict'])}: {escape(untemporary(r['reason']))}{trace}")
    return "\n".join(lines) + "\n"
