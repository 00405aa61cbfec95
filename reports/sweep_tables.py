"""sweep.md: the Pareto fronts of a sweep (sweep.json's document), as markdown tables."""

from __future__ import annotations

from collections import Counter

from .text import escape, num

NO_RESULTS = "no run gave both an error and a speed"  # what "no results" means, wherever it is said


def measured(points: list[dict]) -> list[dict]:
    """The points that can be drawn and ranked: those with an error and a speed (a refused,
    crashed or timed-out run has neither)."""
    return [p for p in points if p["error"] is not None and p["wall_per_sim_s"] is not None]


def variation(p: dict) -> str:
    """A point's iterations and preferAccuracy, '-' where the backend keeps the scene's own."""
    its = "-" if p["iterations"] is None else str(p["iterations"])
    acc = "-" if p["prefer_accuracy"] is None else ("TRUE" if p["prefer_accuracy"] else "FALSE")
    return f"{its} | {acc}"


def _rows(points: list[dict], unit: str, mark: bool) -> list[str]:
    unit = f" ({unit})" if unit else ""
    head = "| backend | dt | iterations | preferAccuracy | wall s per simulated s | error" + unit + " |"
    lines = [head + (" on the overall front |" if mark else ""),
             "|---|---|---:|---|---:|---:|" + ("---|" if mark else "")]
    for p in sorted(points, key=lambda p: (p["backend"], p["wall_per_sim_s"])):
        line = f"| {p['backend']} | {p['dt_label']} | {variation(p)} | {num(p['wall_per_sim_s'])} | {num(p['error'])} |"
        lines.append(line + (f" {'yes' if p['pareto_scene'] else ''} |" if mark else ""))
    return lines


def markdown(doc: dict) -> str:
    s = doc["settings"]
    lines = ["# x3drbp sweep", "",
             f"Speed: {doc['measured']['speed']}.", "",
             f"Error: {doc['measured']['error']}.", "",
             f"Steps {', '.join(p for p in dict.fromkeys(q['dt_label'] for q in doc['points'])) or '-'}; "
             f"iterations {', '.join(map(str, s['iterations']))}; preferAccuracy {s['accuracy']}; "
             f"fine-step reference at the finest step / {s['reference_refinement']}, window {s['window']:g} s. "
             f"{len(doc['points'])} runs in {doc['wall_s']:g} s.", "",
             "Backends: " + "; ".join(
                 f"{n} {b['version']}" + "".join(f" ({f} unsupported: the scene's own)" for f, ok in
                                                 (("iterations", b["iterations"]),
                                                  ("preferAccuracy", b["preferAccuracy"])) if not ok)
                 for n, b in doc["backends"].items()), "",
             "A point is on a Pareto front when no other point is at least as fast and as accurate and "
             "better in one. '-' in iterations or preferAccuracy: the backend does not honour the field "
             "and ran the scene's own value."]
    for scene in doc["scenes"]:
        name = scene["name"]
        points = [p for p in doc["points"] if p["scene"] == name]
        lines += ["", f"## {name}", "",
                  f"Reference: {scene['reference']} ({escape(scene['quantity'])}). "
                  f"Plot: [sweep_{name}.png](sweep_{name}.png)", ""]
        if measured(points):
            lines += ["Pareto front over every backend:", ""]
            lines += _rows([p for p in points if p["pareto_scene"]], scene["unit"], mark=False)
            lines += ["", "Each backend's own front:", ""]
            lines += _rows([p for p in points if p["pareto_backend"]], scene["unit"], mark=True)
        else:
            lines.append(f"No results: {NO_RESULTS}.")
        missing = Counter((p["backend"], p["verdict"], p["reason"]) for p in points if p["error"] is None)
        if missing:
            lines += ["", "Without an error:", ""]
            lines += [f"- {backend}: {n} run(s) {verdict}" + (f": {escape(reason)}" if reason else "")
                      for (backend, verdict, reason), n in missing.items()]
    return "\n".join(lines) + "\n"
