"""The mutation score as people read it (a markdown table, to paste into docs/mutation-score.md) and as
other tools read it (JSON)."""

from __future__ import annotations

import os

from conformance.results import CONVENTION, SPEC

from conformance.mutants.score import REFUSED, Fate, Score, worse

TURNED = {SPEC: "a spec measure", CONVENTION: "a convention alone", REFUSED: "a refusal or crash alone"}

SHOWN = 3  # case names shown per verdict change; the rest counted


def _by(fate: Fate) -> str:
    """The kills grouped by verdict change: `free_fall, projectile (pass → fail)`."""
    groups: dict[str, list[str]] = {}
    for r, base in fate.kills:
        groups.setdefault(f"{base} → {r.verdict}", []).append(r.case)
    parts = []
    for change, cases in groups.items():
        more = f" +{len(cases) - SHOWN} more" if len(cases) > SHOWN else ""
        parts.append(f"{', '.join(cases[:SHOWN])}{more} ({change})")
    return "; ".join(parts)


def _minutes(seconds: float) -> str:
    m, s = divmod(round(seconds), 60)
    return f"{m} min {s} s" if m else f"{s} s"


def markdown(score: Score, cases: int) -> str:
    passing = ", ".join(f"{b} ({sum(r.verdict in ('pass', 'conventions') for r in rs)} of {len(rs)} cases "
                        "pass or differ in conventions only)" for b, rs in score.bases.items())
    unfaithful = [f for f in score.controls if f.killed]
    controls = ("the identity mutants changed no verdict" if not unfaithful else
                "**the wrapping is not faithful**: " + "; ".join(f"{f.mutant.name}: {_by(f)}" for f in unfaithful))
    how = ", ".join(f"{len(score.turning(k))} by {v}" for k, v in TURNED.items())
    lines = [f"**Mutation score: {score.killed} of {len(score.fates)} mutants killed ({score.percent:.0f}%)**, "
             f"{how}, over {cases} cases, in {_minutes(score.wall_s)} on {os.cpu_count()} cores; bases {passing}; "
             f"{controls}.", "",
             "| mutant | base | bug | stands for | killed by (base → mutant) | turned |", "|---|---|---|---|---|---|"]
    for f in score.fates:
        m = f.mutant
        by = _by(f) if f.killed else f"**survived**: {m.gap or 'no case kills it'}"
        lines.append(f"| {m.name} | {m.base} | {m.bug} | {m.models} | {by} | {TURNED.get(f.turned, '-')} |")
    conventional = score.turning(CONVENTION)
    if conventional:
        lines += ["", "Killed by a convention alone (an implementer with this bug is told it differs in "
                  "conventions): why the clause has no sentence to judge it by, or **needs a spec measure**:", ""]
        lines += [f"- {f.mutant.name}: {_by(f)}; {f.mutant.silent or '**needs a spec measure**'}" for f in conventional]
    survivors = [f for f in score.fates if not f.killed]
    if survivors:
        lines += ["", "Survivors (gaps of the suite: the case that would kill each):", ""]
        lines += [f"- {f.mutant.name}: {f.mutant.gap or 'no case kills it, though none is missing'}" for f in survivors]
    return "\n".join(lines) + "\n"


def _fate_json(f: Fate) -> dict:
    m = f.mutant
    return {"name": m.name, "backend": m.backend, "base": m.base, "bug": m.bug, "models": m.models,
            "expected_kills": list(m.kills), "gap": m.gap, "killed": f.killed, "turned": f.turned, "silent": m.silent,
            "runs": [{"case": r.case, "base": base, "mutant": r.verdict, "kills": worse(r.verdict, base),
                      "reason": r.reason, "wall_s": round(r.wall_s, 3)} for r, base in f.runs]}


def to_json(score: Score, cases: list[str]) -> dict:
    return {"killed": score.killed, "mutants": len(score.fates), "percent": round(score.percent, 1),
            **{f"by_{k}": len(score.turning(k)) for k in TURNED},
            "wall_s": round(score.wall_s, 1), "cases": cases,
            "bases": {b: {r.case: r.verdict for r in rs} for b, rs in score.bases.items()},
            "fates": [_fate_json(f) for f in score.fates], "controls": [_fate_json(f) for f in score.controls]}
