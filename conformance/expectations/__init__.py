"""Every conformance verdict pinned, one file per backend, as web-platform-tests' metadata.

`conformance/expectations/BACKEND.toml` lists each case whose verdict on that backend is
not a pass; a case it does not name must pass. An entry says the verdict and what makes
it that verdict, so that a backend that changes in any way turns the conformance test red:

    [box_stack]
    verdict = "fail"
    failing = ["Box1.displacement", "Box5.displacement"]  # the measures beyond tolerance
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
import tomllib
from collections.abc import Iterable, Mapping

from conformance.results import CONVENTIONS, FAIL, PASS, UNSUPPORTED, VERDICTS, Expected, Result

FOLDER = os.path.dirname(os.path.abspath(__file__))


def pinned(r: Result, why: str = "") -> Expected:
    """What a result pins: its verdict and what makes it that verdict."""
    if r.verdict in (FAIL, CONVENTIONS):
        return Expected(r.verdict, tuple(sorted(m.quantity for m in r.failing())), why=why)
    if r.verdict == UNSUPPORTED:
        return Expected(UNSUPPORTED, reason=r.reason, why=why)
    return Expected(r.verdict, why=why if r.verdict != PASS else "")


def path(backend: str, folder: str | None = None) -> str:
    return os.path.join(folder or FOLDER, f"{backend}.toml")


def load(backend: str, folder: str | None = None) -> dict[str, Expected]:
    """The pinned non-passes of one backend (no file: every case must pass); ValueError
    naming the file and entry where it is malformed."""
    file = path(backend, folder)
    if not os.path.exists(file):
        return {}
    with open(file, "rb") as f:
        try:
            data = tomllib.load(f)
        except tomllib.TOMLDecodeError as e:
            raise ValueError(f"{file}: {e}") from None
    out = {}
    for case, entry in data.items():
        if not isinstance(entry, dict) or entry.get("verdict") not in VERDICTS or entry["verdict"] == PASS:
            raise ValueError(f"{file}: [{case}]: verdict must be one of {', '.join(VERDICTS[1:])}")
        unknown = set(entry) - {"verdict", "failing", "reason", "why"}
        if unknown:
            raise ValueError(f"{file}: [{case}]: unknown key(s) {', '.join(sorted(unknown))}")
        out[case] = Expected(entry["verdict"], tuple(sorted(entry.get("failing", ()))), entry.get("reason", ""),
                             entry.get("why", ""))
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
    return None


def regenerate(outcomes: Iterable[Result], previous: Mapping[str, Expected]) -> dict[str, Expected]:
    """The pins of a run, each keeping the previous `why` while it still describes the result."""
    out = {}
    for r in outcomes:
        if r.verdict == PASS:
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
        if e.reason:
            lines.append(f"reason = {json.dumps(e.reason, ensure_ascii=False)}")
        if e.why:
            lines.append(f"why = {json.dumps(e.why, ensure_ascii=False)}")
        lines.append("")
    return "\n".join(lines)
