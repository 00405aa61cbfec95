"""Every conformance verdict pinned, one file per backend, as web-platform-tests' metadata.

`conformance/expectations/BACKEND.toml` lists each case whose verdict on that backend is
not a pass, or whose accuracy is graded beyond a bound; a case it does not name must pass
within every bound. An entry says the verdict and what makes it that verdict, so that a
backend that changes in any way turns the conformance test red:

    [box_stack]
    verdict = "fail"
    failing = ["Box1.displacement", "Box5.displacement"]  # the measures beyond tolerance
    over_bound = ["Box3 rotation angle"]  # graded beyond their accuracy bound (any verdict)
    why = "..."  # a person's explanation, kept when the file is regenerated

    [hinge_bounce]
    verdict = "unsupported"
    reason = "..."  # the backend's declared reason, word for word

`x3drbp expectations` regenerates the files from a run; a `why` survives while its
entry's verdict and failing measures stay as they were. Crashed, timed out, blew up and
error are pinned by the verdict alone (their reasons carry addresses and timings).
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterable, Mapping

from x3d_core.files.documents import read_toml
from x3d_core.files.inputs import InputRefused, require_folder

from conformance.results import CONVENTIONS, FAIL, PASS, UNSUPPORTED, VERDICTS, Expected, Result

FOLDER = os.path.dirname(os.path.abspath(__file__))


def pinned(r: Result, why: str = "") -> Expected:
    """What a result pins: its verdict and what makes it that verdict, and the accuracy grades
    beyond their bound."""
    over = tuple(sorted(m.quantity for m in r.over_bound())) if r.verdict in (PASS, CONVENTIONS, FAIL) else ()
    if r.verdict in (FAIL, CONVENTIONS):
        return Expected(r.verdict, tuple(sorted(m.quantity for m in r.failing())), why=why, over_bound=over)
    if r.verdict == UNSUPPORTED:
        return Expected(UNSUPPORTED, reason=r.reason, why=why)
    return Expected(r.verdict, why=why if r.verdict != PASS or over else "", over_bound=over)


def path(backend: str, folder: str | None = None) -> str:
    return os.path.join(folder or FOLDER, f"{backend}.toml")


PINS_LIMIT = 1 << 20  # bytes of one BACKEND.toml (x3drbp's own are under 6 KB)
_KEYS = ("verdict", "failing", "reason", "why", "over_bound")


def load(backend: str, folder: str | None = None) -> dict[str, Expected]:
    """The pinned non-passes of one backend (a folder without its file: every case must pass);
    ValueError naming the file and line (x3d_core.files.documents.BadDocument) where it is malformed,
    or the folder where it is none."""
    if folder is not None:
        try:
            require_folder(folder)
        except InputRefused as e:
            raise ValueError(f"{folder}: {e}") from None
    file = path(backend, folder)
    if not os.path.lexists(file):
        return {}
    doc = read_toml(file, PINS_LIMIT)
    out = {}
    for case, entry in doc.data.items():
        if not isinstance(entry, dict):
            raise doc.error(case, None, f"[{case}] must be a table")
        if entry.get("verdict") not in VERDICTS or (entry["verdict"] == PASS and not entry.get("over_bound")):
            raise doc.error(case, "verdict", f"[{case}]: verdict must be one of {', '.join(VERDICTS[1:])} "
                                             f"(or {PASS} with over_bound)")
        unknown = set(entry) - set(_KEYS)
        if unknown:
            raise doc.error(case, min(unknown), f"[{case}]: unknown key(s) {', '.join(sorted(unknown))}")
        for k in ("failing", "over_bound"):
            v = entry.get(k, [])
            if not isinstance(v, list) or not all(isinstance(q, str) for q in v):
                raise doc.error(case, k, f"[{case}]: {k} must be a list of measure names (strings)")
        for k in ("reason", "why"):
            if not isinstance(entry.get(k, ""), str):
                raise doc.error(case, k, f"[{case}]: {k} must be a string")
        out[case] = Expected(entry["verdict"], tuple(sorted(entry.get("failing", []))), entry.get("reason", ""),
                             entry.get("why", ""), tuple(sorted(entry.get("over_bound", []))))
    return out


def mismatch(r: Result, expected: Expected) -> str | None:
    """How a result differs from its pin, in one line; None when it is as pinned."""
    got = pinned(r)
    if got.verdict != expected.verdict:
        return f"{r.case} on {r.backend}: expected {expected.verdict}, got {r.verdict}" + (
            f": {r.reason}" if r.reason else "")
    if got.failing != expected.failing:
        return (f"{r.case} on {r.backend}: fails on {', '.join(got.failing)}, pinned "
                f"{', '.join(expected.failing)} ({r.reason})")
    if got.reason != expected.reason:
        return f"{r.case} on {r.backend}: unsupported for {got.reason!r}, pinned {expected.reason!r}"
    if got.over_bound != expected.over_bound:
        return (f"{r.case} on {r.backend}: accuracy beyond its bound in {', '.join(got.over_bound) or 'nothing'}, "
                f"pinned {', '.join(expected.over_bound) or 'nothing'} ({r.accuracy_text()})")
    return None


def regenerate(outcomes: Iterable[Result], previous: Mapping[str, Expected]) -> dict[str, Expected]:
    """The pins of a run, each keeping the previous `why` while it still describes the result."""
    out = {}
    for r in outcomes:
        if r.verdict == PASS and not r.over_bound():
            continue
        old = previous.get(r.case)
        out[r.case] = pinned(r, old.why if old is not None and mismatch(r, old) is None else "")
    return out


def dumps(backend: str, version: str, table: Mapping[str, Expected]) -> str:
    """The file's text (TOML; strings as JSON writes them, which TOML reads alike)."""
    lines = [f"# The conformance verdicts of {backend} (engine {version}) that are not a pass; any case not named",
             "# here must pass. Checked exactly by tests/test_conformance.py; regenerate from a run with",
             f"# `x3drbp expectations --backends {backend}` (conformance/expectations/__init__.py says how).", ""]
    for case in sorted(table):
        e = table[case]
        lines.append(f"[{case}]")
        lines.append(f"verdict = {json.dumps(e.verdict)}")
        if e.failing:
            lines.append("failing = [" + ", ".join(json.dumps(q) for q in e.failing) + "]")
        if e.over_bound:
            lines.append("over_bound = [" + ", ".join(json.dumps(q) for q in e.over_bound) + "]")
        if e.reason:
            lines.append(f"reason = {json.dumps(e.reason, ensure_ascii=False)}")
        if e.why:
            lines.append(f"why = {json.dumps(e.why, ensure_ascii=False)}")
        lines.append("")
    return "\n".join(lines)
