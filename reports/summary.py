"""The report's first screen: the answers, generated from the results in DIR alone.

What conforms (the conformance matrix per backend), which backend and step for each kind of
scene (advice.json), and the findings, each stated from what the runs measured: where the
example scenes' runs (and yours) part, what the hard cases did on every backend, which point of each
sweep is the most accurate and which the fastest, and what a backend declares native yet
fails.
"""

from __future__ import annotations

import json
import os
from collections import Counter
from collections.abc import Collection

from conformance.results import PASS, Comparison

from .advice_text import markdown as advice_markdown
from .text import escape, num

SURVIVED = "survived"


def _load(path: str) -> dict | None:
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def conformance_lines(matrix: dict) -> list[str]:
    """Per backend: how many cases pass, and how the others end."""
    by_backend: dict[str, Counter] = {}
    for r in matrix["results"]:
        by_backend.setdefault(r["backend"], Counter())[r["verdict"]] += 1
    lines = []
    for backend, counts in by_backend.items():
        total = sum(counts.values())
        rest = ", ".join(f"{n} {v}" for v, n in counts.most_common() if v != PASS)
        lines.append(f"- **{backend}**: {counts[PASS]} of {total} cases pass" + (f"; {rest}" if rest else ""))
    return lines


def scopes(out: str) -> dict[str, str]:
    """What each backend of the conformance run is limited to, where it is (its matrix.json's
    `scope`: pymunk, planar scenes only): said wherever it is recommended."""
    matrix = _load(os.path.join(out, "conformance", "matrix.json")) or {}
    return {b: d["scope"] for b, d in (matrix.get("backends") or {}).items() if d.get("scope")}


def yours(out: str) -> set[str]:
    """The user's own scenes of the report in out (report.json's `scenes`, `report --scenes`),
    as absolute paths: they are no example scenes, and the page must not call them so."""
    meta = _load(os.path.join(out, "report.json")) or {}
    return {os.path.abspath(p) for p in meta.get("scenes") or ()}


def scene_name(scene: str, mine: Collection[str]) -> str:
    """A scene's file name, marked (yours) where it is one of the user's."""
    return os.path.basename(scene) + (" (yours)" if os.path.abspath(scene) in mine else "")


def compare_findings(comparisons: list[Comparison], mine: Collection[str] = ()) -> list[str]:
    """Per scene (the examples, and the user's: `mine`, marked so): the pairs that stay within
    the thresholds, and the first to part."""
    out = []
    for c in comparisons:
        name = scene_name(c.scene, mine)
        parted = [(min(x.time for x in (p.position.first_over, p.orientation.first_over) if x is not None), p)
                  for p in c.pairs if p.position.first_over is not None or p.orientation.first_over is not None]
        apart = {id(p) for _, p in parted}
        together = [f"{p.a}/{p.b}" for p in c.pairs if id(p) not in apart]
        if not c.pairs:
            out.append(f"{name}: fewer than two backends ran it")
            continue
        said = f"{name}: " + (f"{', '.join(together)} stay within {num(c.thresholds['position'])} m and "
                              f"{num(c.thresholds['orientation'])} rad for all {c.duration:g} s" if together
                              else "every pair parts")
        if parted:
            when, first = min(parted, key=lambda x: x[0])
            said += f"; first to part: {first.a}/{first.b} at {when:.3g} s"
            schemes = {r.backend: r.integration for r in c.runs}
            if None not in (schemes.get(first.a), schemes.get(first.b)) and schemes[first.a] != schemes[first.b]:
                said += (f" ({first.a} steps by {schemes[first.a]}, {first.b} by {schemes[first.b]}: "
                         "free motion alone parts them)")
        out.append(said)
    return out


def stability_findings(doc: dict) -> list[str]:
    """Hard cases every backend that ran ended the same way at every step (what no engine
    handles, or all do), and each backend's count of runs that held."""
    by_case: dict[str, set[str]] = {}
    held: Counter = Counter()
    ran: Counter = Counter()
    for r in doc["results"]:
        if r["verdict"] == "unsupported":
            continue
        by_case.setdefault(r["case"], set()).add(r["verdict"])
        ran[r["backend"]] += 1
        held[r["backend"]] += r["verdict"] == SURVIVED
    out = [f"{case}: {verdicts.pop()} on every backend that ran it, at every step"
           for case, verdicts in by_case.items() if len(verdicts) == 1]
    out.append("runs that held: " + ", ".join(f"{b} {held[b]} of {ran[b]}" for b in ran))
    return out


def sweep_findings(doc: dict) -> list[str]:
    """Per swept scene: the most accurate and the fastest point of its front over every backend."""
    out = []
    for scene in doc["scenes"]:
        front = [p for p in doc["points"] if p["scene"] == scene["name"] and p["pareto_scene"]
                 and p.get("tie_scene") is None]
        if not front:
            continue
        unit = f" {scene['unit']}" if scene["unit"] else ""
        best = min(front, key=lambda p: p["error"])
        fast = min(front, key=lambda p: p["cpu_per_sim_s"])
        out.append(f"{scene['name']}: most accurate {best['label']} (error {num(best['error'])}{unit}, "
                   f"{num(best['cpu_per_sim_s'])} CPU s per simulated s); fastest {fast['label']} "
                   f"({num(fast['cpu_per_sim_s'])} CPU s per simulated s, error {num(fast['error'])}{unit})")
    return out


WHY_LEAD = 160  # characters of a pin's `why` a finding quotes: its lead, the cause (the pins file has the rest)


def cause(why: str) -> str:
    """The lead of a pin's `why`, the clause before its first colon ("Chipmunk's solver, 10
    iterations: the stop fights the pivot ..."), cut at a word to WHY_LEAD characters."""
    lead = why.split(": ", 1)[0]
    return lead if len(lead) <= WHY_LEAD else lead[:WHY_LEAD].rsplit(" ", 1)[0] + " ..."


def declared_findings(doc: dict) -> list[str]:
    """Cases that do not pass on a backend declaring native every feature they exercise, each
    blamed on what was measured (its failing measures, its pin's why), not on a feature it
    merely uses (every case uses RigidBody.mass); a case a declared approximation explains is none."""
    out = []
    for backend, cases in doc["not_passing"].items():
        for case, said in cases.items():
            support = {row["backends"][backend]["support"] for row in doc["features"]
                       if any(c["case"] == case for c in row["backends"][backend]["cases"])}
            if support != {"native"}:
                continue
            measures = f" on {', '.join(said['measures'])}" if said["measures"] else ""
            why = f"; its pin says: {cause(said['why'])}" if said["why"] else ""
            out.append(f"{backend}: {case}: {said['verdict']}{measures}{why} (every feature it exercises "
                       "declared native)")
    return out


FIELDS_LISTED = 6  # fields without effect named in X_ITE's line; more are folded beneath it


def x_ite_line(data: dict) -> str:
    """X_ITE's verdicts counted, its clock's reading, and the fields its probes found ignored."""
    counts = {k: sum(c["verdict"] == k for c in data["cases"]) for k in ("right", "conventions", "ignores", "wrong",
                                                                          "error")}
    conforms = counts["right"] + counts["conventions"]
    clock = data.get("clock", [])
    lag = max((k["lag_s"] for k in clock if k["lag_s"] is not None), default=None)
    ignored = sorted({f for c in data["cases"] for f in c["ignored"]})
    return (f"X_ITE {data['versions']['x_ite']} conforms in {conforms} of {len(data['cases'])} cases "
            f"({counts['conventions']} of them differing in conventions); it ignores a field in {counts['ignores']}, "
            f"is wrong in {counts['wrong']}, and could not run {counts['error']}"
            + ("" if lag is None else f"; its physics clock lags the frames by up to {num(lag)} s"
               + (" (37.2.2.1)" if not all(k["ok"] for k in clock) else ""))
            + (f"; fields without effect: {', '.join(ignored)}" if 0 < len(ignored) <= FIELDS_LISTED else
               f"; {len(ignored)} fields without effect (listed below)" if ignored else "") + ".")


def answers(out: str, comparisons: list[Comparison]) -> str:
    """The page's first section, from the files in out."""
    parts = ["## Answers", ""]
    matrix = _load(os.path.join(out, "conformance", "matrix.json"))
    parts += ["**What conforms** (every case on every backend; [details](#conformance)):", ""]
    parts += conformance_lines(matrix) if matrix else ["Not run."]
    # beside the engines: how a browser's author gets the same answer for theirs
    parts += ["", "**How to judge your own browser** (or any implementation): record its trace of a scene, one row "
                  "per frame and output (the format: docs/implementers.md), then", "",
              "    x3drbp validate SCENE --trace THEIRS.csv --dt STEP", "",
              "says whether it conforms, measure by measure (the case's closed form where SCENE is a case's), and "
              "how far it is from each engine's run of the scene."]
    x_ite = _load(os.path.join(out, "x_ite", "x_ite.json"))
    if x_ite:
        parts += ["", f"**How X_ITE conforms** ([details](#x_ite)): {escape(x_ite_line(x_ite))}"]
        ignored = sorted({f for c in x_ite["cases"] for f in c["ignored"]})
        if len(ignored) > FIELDS_LISTED:
            parts += ["", f'<details markdown="1"><summary>The {len(ignored)} fields without effect in X_ITE</summary>',
                      "", escape(", ".join(ignored)), "", "</details>"]
    advice = _load(os.path.join(out, "advice", "advice.json"))
    parts += ["", "**Which backend, at which step, for each kind of scene** (`x3drbp advise`; "
                  "[the details](#which-backend-for-which-scene)):", ""]
    parts.append(advice_markdown(advice, details=False, scopes=scopes(out)) if advice else "Not run.")
    mine = yours(out)
    title = "Where the runs of the example scenes" + (" and of yours" if mine else "") + " part"
    findings = [(title, compare_findings(comparisons, mine), "where-the-backends-part")]
    stability = _load(os.path.join(out, "stability", "stability.json"))
    findings.append(("The hard cases", stability_findings(stability) if stability else [], "stability"))
    sweep = _load(os.path.join(out, "sweep", "sweep.json"))
    findings.append(("Speed against error", sweep_findings(sweep) if sweep else [], "speed-against-error"))
    features = _load(os.path.join(out, "features.json"))
    findings.append(("Declared native, measured failing", declared_findings(features) if features else [],
                     "declared-against-measured"))
    parts += ["", "**Findings**, each from the results below:", ""]
    for title, lines, anchor in findings:
        if lines:
            parts.append(f"- {title} ([details](#{anchor})):")
            parts += [f"    - {escape(line)}" for line in lines]
    return "\n".join(parts) + "\n"

