"""sweep.md: the Pareto fronts of a sweep (sweep.json's document), as markdown tables."""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass

from .text import escape, link, num, untemporary

NO_RESULTS = "no run gave both an error and a speed"  # what "no results" means, wherever it is said


def measured(points: list[dict]) -> list[dict]:
    """The points that can be drawn and ranked: those with an error and a speed (a refused,
    crashed or timed-out run has neither)."""
    return [p for p in points if p["error"] is not None and p["cpu_per_sim_s"] is not None]


def variation(p: dict) -> str:
    """A point's iterations and preferAccuracy, '-' where the backend keeps the scene's own."""
    its = "-" if p["iterations"] is None else str(p["iterations"])
    acc = "-" if p["prefer_accuracy"] is None else ("TRUE" if p["prefer_accuracy"] else "FALSE")
    return f"{its} | {acc}"


def speed(p: dict) -> str:
    """A point's median speed (CPU time) and its repeats' spread."""
    if p.get("cpu_low") is None or p["cpu_low"] == p["cpu_high"]:
        return num(p["cpu_per_sim_s"])
    return f"{num(p['cpu_per_sim_s'])} ({num(p['cpu_low'])}-{num(p['cpu_high'])})"


def _rows(points: list[dict], unit: str, front: str, every: list[dict]) -> list[str]:
    """The front's points (flag `front`: pareto_scene or pareto_backend), ties folded into the
    point that stands for them."""
    unit = f" ({unit})" if unit else ""
    tie = "tie_scene" if front == "pareto_scene" else "tie_backend"
    lines = ["| backend | dt | iterations | preferAccuracy | CPU s per simulated s (spread) | error" + unit +
             " | self-consistency | ties |", "|---|---|---:|---|---:|---:|---:|---|"]
    heads = [p for p in points if p[front] and p[tie] is None]
    for p in sorted(heads, key=lambda p: (p["backend"], p["cpu_per_sim_s"])):
        ties = ", ".join(q["label"] for q in every if q[tie] == p["label"])
        lines.append(f"| {p['backend']} | {p['dt_label']} | {variation(p)} | {speed(p)} | {num(p['error'])} | "
                     f"{num(p.get('self_error'))} | {escape(ties)} |")
    return lines


def reference(scene: dict) -> str:
    """What a scene's error is measured against, in words."""
    if scene["reference"] != "common reference":
        return f"closed form ({escape(scene['quantity'])})"
    if scene.get("reference_backend") is None:
        return f"none: {escape(scene.get('reference_why_none', ''))}"
    return f"{escape(scene['reference_said'])}; {escape(scene['quantity'])}"


def timing(doc: dict) -> str:
    """How often the points were timed (conformance/analyses/sweep_timing.py), in words."""
    repeats = doc["settings"].get("repeats", 1)
    again = sum(1 for p in doc["points"] if p.get("timed", repeats) > 1)
    if repeats == 1:
        return "each point timed once"
    return (f"each point timed once, and {repeats} times in all where its speed could change a front "
            f"({again} of {len(doc['points'])})")


def markdown(doc: dict) -> str:
    s = doc["settings"]
    lines = ["# x3drbp sweep", "",
             f"Speed: {doc['measured']['speed']}.", "",
             f"Error: {doc['measured']['error']}. Self-consistency: {doc['measured']['self_error']}.", "",
             f"Steps {', '.join(p for p in dict.fromkeys(q['dt_label'] for q in doc['points'])) or '-'}; "
             f"iterations {', '.join(map(str, s['iterations']))}; preferAccuracy {s['accuracy']}; "
             f"{timing(doc)}; "
             f"fine step at the finest step / {s['reference_refinement']}, window {s['window']:g} s. "
             f"{len(doc['points'])} runs in {doc['wall_s']:g} s.", "",
             "Backends: " + "; ".join(
                 f"{n} {b['version']}" + "".join(f" ({f} unsupported: the scene's own)" for f, ok in
                                                 (("iterations", b["iterations"]),
                                                  ("preferAccuracy", b["preferAccuracy"])) if not ok)
                 for n, b in doc["backends"].items()), "",
             "A point is on a Pareto front when no other point is as fast by median and as accurate and "
             f"better in one beyond the ties; {doc['measured']['ties']}. '-' in iterations or preferAccuracy: "
             "the backend does not honour the field and ran the scene's own value."]
    for scene in doc["scenes"]:
        part = scene_parts(doc, scene)
        lines += ["", f"## {escape(scene['name'])}", "", part.reference + f" Plot: {link(plot(scene['name']))}", ""]
        lines += part.front
        if part.own:
            lines += ["", "Each backend's own front:", "", *part.own]
        if part.missing:
            lines += ["", "Without an error:", "", *part.missing]
    return "\n".join(lines) + "\n"


def plot(name: str) -> str:
    """A scene's plot, beside sweep.json (x3drbp/sweep.py writes it)."""
    return f"sweep_{name}.png"


@dataclass
class SceneParts:
    """One scene's part of sweep.md, each piece markdown: what its error is measured against, its
    Pareto front over every backend (its title and table, or that there are no results), each
    backend's own front (its table, or nothing) and the runs without an error (a list)."""
    reference: str
    front: list[str]
    own: list[str]
    missing: list[str]


def scene_parts(doc: dict, scene: dict) -> SceneParts:
    points = [p for p in doc["points"] if p["scene"] == scene["name"]]
    if measured(points):
        front = ["Pareto front over every backend:", "", *_rows(points, scene["unit"], "pareto_scene", points)]
        own = _rows(points, scene["unit"], "pareto_backend", points)
    else:
        front, own = [f"No results: {NO_RESULTS}."], []
    missing = Counter((p["backend"], p["verdict"], p["reason"]) for p in points if p["error"] is None)
    return SceneParts(f"Reference: {reference(scene)}.", front, own,
                      [f"- {backend}: {n} run(s) {verdict}" + (f": {escape(untemporary(reason))}" if reason else "")
                       for (backend, verdict, reason), n in missing.items()])
