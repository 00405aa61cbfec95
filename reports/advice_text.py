"""`x3drbp advise` as text and as markdown, from its JSON document (advice.json) alone."""

from __future__ import annotations

from conformance.results import dt_label

from .text import escape, num, one_line, untemporary

# advice.json's `rule`, the branch that decided (docs/commands/advise.md)
WITHIN, CANNOT_RANK, MOST_ACCURATE = ("within the tolerance", "accuracy cannot be ranked",
                                      "none within the tolerance: the most accurate")


def _find(scene: dict, key: dict | None) -> dict | None:
    if key is None:
        return None
    return next(o for o in scene["options"] if o["backend"] == key["backend"] and o["dt"] == key["dt"])


def _run(o: dict) -> str:
    return f"{o['backend']} at dt {dt_label(o['dt'])}"


def length(m: float) -> str:
    """A tolerance in the unit a reader thinks in: 1 mm, not 0.001 m."""
    return f"{num(m * 1e3)} mm" if m < 1 else f"{num(m)} m"


def decided(scene: dict, settings: dict) -> str:
    """What chose the scene's run, first: the branch of the rule in plain words (the fastest within
    the tolerance of the reference; the most accurate, none being within it; the fastest of what
    the reference cannot tell apart), then how a tie on speed was broken (advice.json's `settled`)."""
    rule, settled, tol = scene["rule"], scene.get("settled") or "", length(settings["tolerance"])
    tie = settled if settled.startswith("tied") else ""
    if scene["recommended"] is None:
        return f"none: {rule}"
    if rule == WITHIN:
        said = f"within {tol} of the reference, {tie}" if tie else f"fastest within {tol} of the reference"
    elif rule == CANNOT_RANK:
        said = ((tie or "fastest") + f"; accuracy cannot be ranked (the reference's uncertainty, "
                f"{num(scene['reference']['error'])} m, exceeds {tol})")
    elif rule == MOST_ACCURATE:
        said = f"most accurate: none within {tol} of the reference" + (f"; {tie}" if tie else "")
    else:  # a branch this text does not know: the rule's own words
        said = "; ".join(filter(None, (rule, settled)))
    return said


def rule_line(settings: dict) -> str:
    """The rule in one sentence, first: what decides every scene's answer."""
    return (f"What decides: the fastest run within {length(settings['tolerance'])} of the scene's reference (over "
            f"the first {settings['window']:g} s); where none is, the most accurate; of the runs that fit the budget "
            f"({settings['budget']:g} CPU s per simulated s) on backends that refuse nothing the scene uses. Speeds "
            "too close to tell apart tie, and a tie-break decides. \"chosen as\" says which decided each scene.")


def _backend(name: str, scopes: dict[str, str]) -> str:
    """A backend's name, with what it is limited to where it is (pymunk: planar scenes only)."""
    return f"{name} ({scopes[name]})" if name in scopes else name


def _speed(o: dict) -> str:
    median = o["cpu_per_sim_s"]
    factor = f", {1 / median:,.0f}x real time" if median > 0 else ""
    return f"{num(median)} CPU s per simulated s ({num(o['cpu_low'])}-{num(o['cpu_high'])}){factor}"


def _reference(scene: dict) -> str:
    ref = scene["reference"]
    if ref["backend"] is None:
        return f"no reference: {ref['why_none']}"
    return f"reference: {ref['said']}"


def _agreement(o: dict, duration: float) -> str:
    if not o["parts"]:
        return "no other backend ran at this step"
    stays = [b for b, t in o["parts"].items() if t is None]
    parts = [f"{b} at {t:.3g} s" for b, t in sorted(((b, t) for b, t in o["parts"].items() if t is not None),
                                                     key=lambda p: p[1])]
    said = []
    if stays:
        said.append(f"within 1 mm / 1 mrad of {', '.join(stays)} for all {duration:g} s")
    if parts:
        said.append(f"parts from {', '.join(parts)}")
    return "; ".join(said)


def _cases(j: dict) -> str:
    failing = ", ".join(f"{c} ({v})" for c, v in j["failing"].items())
    if not j["passing"] and not failing:
        return "no case exercises them"
    beyond = j.get("beyond_bound") or []
    return (f"{j['passing']} pass" + (f"; not: {failing}" if failing else "")
            + (f"; accuracy beyond its bound: {', '.join(beyond)}" if beyond else ""))


def _flaws(j: dict) -> str:
    """A runner-up's cases failed (the spec broken) and approximations, counted: why it is not first
    may be either, and a reader must see both."""
    fails = [c for c, v in j["failing"].items() if v == "fail"]
    return ((f"; fails {', '.join(fails)}" if fails else "")
            + (f"; {len(j['approximated'])} approximation(s)" if j["approximated"] else ""))


def _versus(o: dict, best: dict) -> str:
    cost = o["cpu_per_sim_s"] / best["cpu_per_sim_s"] if best["cpu_per_sim_s"] > 0 else float("inf")
    return (f"{_run(o)}: {num(cost)}x the cost, error {num(o['error'])} m "
            f"({'+' if o['error'] >= best['error'] else '-'}{num(abs(o['error'] - best['error']))} m)")


def scene_lines(scene: dict, settings: dict, scopes: dict[str, str] | None = None) -> list[str]:
    """One scene's advice as indented lines; scopes: what a backend is limited to, where it is
    (the conformance matrix's `scope`), said beside it when it is recommended."""
    best = _find(scene, scene["recommended"])
    head = f"{scene['scene']} ({scene['kind']}): "
    lines = []
    if best is None:
        ran = [o for o in scene["options"] if o.get("cpu_per_sim_s") is not None and o["error"] is not None]
        fastest = min(ran, key=lambda o: o["cpu_per_sim_s"]) if ran else None
        lines.append(head + f"no recommendation: {scene['rule']}" + (
            f"; the fastest run, {_run(fastest)}, costs {_speed(fastest)} against a budget of "
            f"{settings['budget']:g}" if fastest else ""))
    else:
        j = scene["judged"][best["backend"]]
        own = (f" (the reference is this backend's own run ({scene['reference']['method']}), which favours it: "
               "weigh its agreement with the others)" if scene["reference"]["backend"] == best["backend"] else "")
        ref_error = scene["reference"]["error"]
        if ref_error > settings["tolerance"]:
            own += (f"; the reference's uncertainty ({num(ref_error)} m) exceeds the tolerance: errors under it "
                    "cannot be told apart")
        lines += [head + f"{_backend(best['backend'], scopes or {})} at dt {dt_label(best['dt'])} ({scene['said']})",
                  f"  error {num(best['error'])} m from the reference over the first {settings['window']:g} s "
                  f"({_reference(scene)}){own}; self-consistency {num(best['self_error'])} m",
                  f"  speed {_speed(best)}; budget {settings['budget']:g} CPU s per simulated s",
                  f"  agreement at this step: {_agreement(best, settings['duration'])}",
                  "  approximates: " + ("; ".join(j["approximated"]) or "nothing the scene uses"),
                  f"  cases exercising the features it uses: {_cases(j)}"]
        runners = [_find(scene, k) for k in scene["runners_up"]]
        if runners:
            lines.append("  runners-up:")
            lines += [f"    {_versus(o, best)}; {_agreement(o, settings['duration'])}" + _flaws(scene["judged"][o["backend"]])
                      for o in runners]
    refused = {b: j["refused"] for b, j in scene["judged"].items() if j["refused"]}
    for b, why in refused.items():
        lines.append(f"  cannot run it: {b}: {why[0]}" + (f" (and {len(why) - 1} more)" if len(why) > 1 else ""))
    bad = [o for o in scene["options"] if o["error"] is None]
    for o in bad:
        why = f": {untemporary(o['reason'])}" if o["reason"] else ""  # its temporary files are gone: said so
        lines.append(f"  did not end well: {_run(o)}: {o['verdict']}{why}")
    return lines


def render(doc: dict) -> str:
    """The terminal text: each scene's advice, then the rule's settings."""
    s = doc["settings"]
    out = []
    for scene in doc["scenes"]:
        out += scene_lines(scene, s) + [""]
    # advise times a run once where its speed cannot change the advice (each option's "timed")
    once = s["repeats"] > 1 and any(o.get("timed") == 1 for scene in doc["scenes"] for o in scene["options"])
    out.append(f"steps {', '.join(dt_label(d) for d in s['dts'])}; runs of {s['duration']:g} s, error over the first "
               f"{s['window']:g} s; tolerance {s['tolerance']:g} m; budget {s['budget']:g} CPU s per simulated s; "
               f"speed the engine's steps' CPU time, the median of {s['repeats']} repeats"
               + (" for each run whose speed could change the advice, one timed run for the others" if once else "")
               + "; the rule: docs/commands/advise.md")
    return "\n".join(out) + "\n"


def markdown(doc: dict, details: bool = True, scopes: dict[str, str] | None = None) -> str:
    """advice.json as markdown: what decides, a table of the answers and the rule's settings, then
    (details) each scene's reasons, folded; scopes as scene_lines takes them."""
    s, scopes = doc["settings"], scopes or {}
    lines = [rule_line(s), "",
             "| scene | kind | recommended | error (m) | CPU s per simulated s | chosen as | runner-up |",
             "|---|---|---|---:|---:|---|---|"]
    for scene in doc["scenes"]:
        best = _find(scene, scene["recommended"])
        runner = _find(scene, scene["runners_up"][0]) if scene["runners_up"] else None
        name = escape(scene["scene"])
        if best is None:
            lines.append(f"| {name} | {scene['kind']} | - | - | - | {escape(decided(scene, s))} | - |")
            continue
        # beside a runner-up that may be cheaper or closer: its failed cases and approximations
        versus = _versus(runner, best) + _flaws(scene["judged"][runner["backend"]]) if runner else "-"
        lines.append(f"| {name} | {scene['kind']} | {escape(_backend(best['backend'], scopes))} at dt "
                     f"{dt_label(best['dt'])} | {num(best['error'])} | {num(best['cpu_per_sim_s'])} | "
                     f"{escape(decided(scene, s))} | {escape(versus)} |")
    lines += ["", f"Budget {s['budget']:g} CPU s per simulated second, tolerance {s['tolerance']:g} m over the first "
                  f"{s['window']:g} s, steps {', '.join(dt_label(d) for d in s['dts'])}, runs of {s['duration']:g} s "
                  "(the rule: docs/commands/advise.md)."]
    if details:
        lines += ["", "<details markdown=\"1\"><summary>Why, per scene: error, speed, agreement, approximations, the cases, "
                      "the runners-up</summary>", "", "```"]
        for scene in doc["scenes"]:
            lines += [*map(one_line, scene_lines(scene, s, scopes)), ""]  # a name's line break would end the block
        lines += ["```", "", "</details>"]
    return "\n".join(lines) + "\n"
