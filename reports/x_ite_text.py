"""`x3drbp x-ite cases`' results as markdown: one row per conformance case, X_ITE's verdict
beside the backends' where the conformance matrix is given.

Reads DIR/x_ite.json (and conformance/matrix.json); runs nothing.
"""

from __future__ import annotations

from collections import Counter

from .text import escape, link, num

_SHOWN = {"right": "right", "conventions": "right, other conventions", "ignores": "**ignores**", "wrong": "**wrong**",
          "error": "**error**"}


def _backend_verdicts(matrix: dict | None) -> tuple[list[str], dict[tuple[str, str], str]]:
    if matrix is None:
        return [], {}
    backends = [b for b, d in matrix["backends"].items() if d["run"]]
    return backends, {(r["case"], r["backend"]): r["verdict"] for r in matrix["results"]}


def _engines(case: str, backends: list[str], verdicts: dict[tuple[str, str], str]) -> str:
    """The engines' verdicts on a case, each verdict once with the backends that got it, in the
    matrix's order: "pass: bullet, ode; fail: mujoco"."""
    grouped: dict[str, list[str]] = {}
    for b in backends:
        if (case, b) in verdicts:
            grouped.setdefault(verdicts[(case, b)], []).append(b)
    return "; ".join(f"{v}: {', '.join(bs)}" for v, bs in grouped.items()) or "-"


def _evidence(c: dict) -> str:
    parts = []
    if c["ignored"]:
        parts.append(f"no effect: {', '.join(c['ignored'])}")
    if c.get("inert"):
        parts.append(f"the scene without any {', '.join(c['inert'])} is recorded identical: the joint has no effect "
                     "at all")
        made = sorted({x for f in c["ignored"] for x in c.get("variants", {}).get(f, [])})
        if made:
            parts.append(f"probed on the scene with {'; '.join(made)}")
    if c.get("blew_up_probed"):
        causes = c.get("blow_up_causes", [])
        parts.append(f"runs without its {', '.join(causes)}" if causes else
                     f"blows up without any one of {', '.join(c['blew_up_probed'])} too")
    if c["detail"]:
        parts.append(c["detail"])
    untold = c.get("untold", {})
    parts += [f"the probe of {f} could not tell: {why}" for f, why in untold.items()]
    told = [f for f in c["probed"] if f not in untold and f not in c["ignored"]]
    if c["verdict"] == "wrong" and told:
        parts.append(f"every field its probes could tell has an effect ({', '.join(told)})")
    return escape("; ".join(parts)) or "-"


def _clock(readings: list[dict]) -> list[str]:
    """The clock, read once for every case: what it is, and the sentence it is judged by."""
    if not readings:
        return []
    parts = []
    for k in readings:
        at = (f"at {num(k['frame_rate'])} frames/s, {k.get('iterations', 10)} iterations"
              + (", preferAccuracy" if k.get("prefer_accuracy") else ""))
        if k["lag_s"] is None:
            parts.append(f"{at} not read ({escape(k['error'] or '')})")
        else:
            parts.append(f"{at} it lags the frame clock by up to {num(k['lag_s'])} s "
                         f"({'within' if k['ok'] else 'beyond'} the {num(k['tolerance_s'])} s of one frame and one "
                         "step)")
    failed = [k for k in readings if not k["ok"]]
    verdict = (f"**violates the spec** (\"{escape(readings[0]['basis'])}\")" if failed else "keeps pace")
    return [f"**The physics clock**, read once for every case from a body falling freely in a scene of its own "
            f"(v = g tau gives the physics time X_ITE's state shows at each frame): {'; '.join(parts)}: it "
            f"{verdict}. Each case is judged at the physics time X_ITE's own state shows, so that the clock fails "
            "its sentence here once and never a field's.", ""]


def render(data: dict, matrix: dict | None = None) -> str:
    v = data["versions"]
    backends, verdicts = _backend_verdicts(matrix)
    counts = Counter(c["verdict"] for c in data["cases"])
    lines = [
        "# X_ITE on the conformance cases", "",
        f"X_ITE {v['x_ite']} (npm `x_ite`, Bullet through ammo.js) in {escape(v['chromium'])}, headless, under a "
        "virtual clock: frame k at k / frame rate, runs bit-identical. Each case is recorded at its own frame "
        "rate and duration (a rate beyond the 80 frames/s X_ITE draws at most, its MaximumFrameRate, at the case's "
        "rate / k for the least k under it: every frame on one of the case's) and judged by `x3drbp validate`'s checks at the step X_ITE takes (the frame in "
        "`iterations` substeps). **right**: the case passes (it conforms). **right, other conventions**: only "
        "measures of a convention fail, a reading of a point the spec leaves open that is not ODE's: it conforms "
        "(docs/spec-loose-ends.md). **ignores**: it fails, and recording it again "
        "with a field it exercises at its default leaves X_ITE's trace byte-identical (listed), in a run that "
        "shows what the field acts through (a contact, a body that moves or turns); a probe whose run does not "
        "could not tell, and says so. **wrong**: it fails, and no probe found a field without effect. **error**: "
        "X_ITE did not run it.", "",
        *_clock(data.get("clock", [])),
        f"{counts['right']} right, {counts['conventions']} right with other conventions, {counts['ignores']} ignores, {counts['wrong']} wrong, {counts['error']} error, "
        f"in {data['wall_s']:g} s.", "",
        # the engines' verdicts in one cell, grouped: a column each ran the table off a 1400 px page
        "| case | X_ITE | the engines | frames/s | dt (s) | evidence | agrees with |",
        "|---|---|---|---:|---:|---|---|"]
    for c in data["cases"]:
        rec = f" ({link(c['recording'], 'recording')})" if c["recording"] else ""
        rates = ", ".join(num(r) for r in c.get("frame_rates", [])) or "-"
        lines.append(f"| {c['case']}{rec} | {_SHOWN[c['verdict']]} | {_engines(c['case'], backends, verdicts)} | "
                     f"{rates} | {num(c['dt'])} | {_evidence(c)} | {', '.join(c['agreeing']) or 'none'} |")
    said = sorted({m for c in data["cases"] for m in c["messages"]})
    if said:
        lines += ["", "What X_ITE printed (errors and warnings, each once):", ""]
        lines += [f"- {escape(m[:300])}" for m in said]
    return "\n".join(lines) + "\n"
