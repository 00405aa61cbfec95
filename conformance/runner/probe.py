"""Which backends are here: the registry asked in a child process with a time limit.

Importing an engine can crash the interpreter or hang it; the suite must survive that too,
and a command pays only for the engines it names.
"""

from __future__ import annotations

import contextlib
import json
import sys
from collections.abc import Iterator, Sequence
from typing import Any

from conformance.results import BackendInfo
from conformance.runner import cache, children
from conformance.runner.children import DEFAULT_TIMEOUT

_PROBE = """
import json, sys
from backends import base
names = sys.argv[1:] or list(base.engines())
print("\\nx3drbp-answer " + json.dumps(names), flush=True)  # what it asks, in order
for name in names:  # one answer line each, as soon as it is known: a crash or hang names its engine
    try:
        b = base.load(name)
    except Exception as e:
        answer = {"unavailable": str(e)}
    else:
        try:
            answer = {"version": str(b.version()), "integration": getattr(b, "integration", None),
                      "accurate_integration": getattr(b, "accurate_integration", None),
                      "scope": getattr(b, "scope", None)}
        except Exception as e:  # a backend whose engine imports but cannot say its version
            answer = {"unavailable": f"version() failed: {type(e).__name__}: {e}"}
    print("\\nx3drbp-answer " + json.dumps({name: answer}), flush=True)
"""


ANSWER = "x3drbp-answer "  # the line an asking script prints its JSON answer on


def answers(script: str, args: Sequence[str], timeout: float, what: str) -> tuple[list[Any], str]:
    """Run a Python script that imports engines in a child (importing one can crash) and read
    the JSON answers it printed, each after ANSWER (engines may print on import: pybullet
    does), those before a crash or a hang included; and why it ended before its end ("" when
    it exited 0), naming `what` was asked."""
    try:
        done = children.call([sys.executable, "-c", script, *args], timeout)
    except OSError as e:
        return [], f"{what} could not start: {e}"
    found = []
    for line in done.stdout.splitlines():
        if line.startswith(ANSWER):
            try:
                found.append(json.loads(line[len(ANSWER):]))
            except json.JSONDecodeError:  # cut off by the crash
                pass
    if done.returncode is None:
        return found, f"{what} gave no answer within {timeout:g} s"
    if done.returncode != 0:
        return found, children.classify(done.returncode, done.stderr).reason or f"{what} printed nothing"
    return found, "" if found else f"{what} printed nothing"


def ask(script: str, args: Sequence[str], timeout: float, what: str) -> tuple[Any, str]:
    """One answer (answers()'s last) of a script that ran to its end: (the answer, or None and why
    there is none). Inside remembered(), one asked before is answered again without a child; so is
    one an earlier command asked of the same x3drbp source, engines and files (cache.question)."""
    if _said is not None and (script, *args) in _said:
        return _said[(script, *args)], ""
    kept = cache.question(script, args)
    said = kept.reused(0.0) if kept is not None else None
    try:
        answer = json.loads(said[1]) if said is not None else None
    except ValueError:  # an entry edited: asked again
        said = None
    if said is None:
        found, why = answers(script, args, timeout, what)
        if not found or why:
            return None, why
        answer = found[-1]
        if kept is not None:
            kept.keep(0, json.dumps(answer), 0.0)
    if _said is not None:
        _said[(script, *args)] = answer
    return answer, ""


_said: dict[tuple[str, ...], Any] | None = None  # inside remembered(): ask()'s answers, by script and arguments
_found: dict[str, BackendInfo] | None = None  # ... and backend_table()'s, by backend (none that went unanswered)


@contextlib.contextmanager
def remembered() -> Iterator[None]:
    """The block's questions each asked of a child once: x3drbp report's steps, each a command run
    in its process, asked the backends the report had asked, and their declarations, in ten
    children importing every engine (1.2 s of CPU each); an answer that did not come is asked again."""
    global _said, _found
    previous = _said, _found
    _said, _found = ({}, {}) if _said is None else previous
    try:
        yield
    finally:
        _said, _found = previous


class Unprobed(BackendInfo):
    """A backend the probe gave no answer on (it hung, crashed, or left the engine out): whether
    it is installed is unknown, so a command reports it as unavailable rather than leave it out
    as it leaves out an engine that said it is not installed."""


def named_backends(names: Sequence[str], info: dict[str, BackendInfo]) -> list[str]:
    """The backends a command line names, in its order (default: every usable one, and every
    Unprobed one, to be reported); ValueError naming any the registry does not know."""
    unknown = [n for n in names if n not in info]
    if unknown:
        raise ValueError(f"unknown backend(s) {', '.join(unknown)}; known: {', '.join(info)}")
    return list(names) or [n for n, i in info.items() if i.usable or isinstance(i, Unprobed)]


def known(names: Sequence[str]) -> tuple[str, ...]:
    """The registered backends; ValueError naming any of names the registry does not know. No
    engine imported, so a command checks its --backends with the rest of its usage, before it
    loads a scene."""
    from backends import base
    registered = base.engines()
    unknown = [n for n in names if n not in registered]
    if unknown:
        raise ValueError(f"unknown backend(s) {', '.join(unknown)}; known: {', '.join(registered)}")
    return registered


def backend_table(timeout: float = DEFAULT_TIMEOUT, names: Sequence[str] = ()) -> dict[str, BackendInfo]:
    """The backends `names` (default: every one registered, base.engines(): the entry point
    group x3drbp.backends, as the child finds it) as found here, each asked in a child with a
    time limit: importing an engine can crash or hang, and the suite must survive that too.
    The child says what it asks, then answers engine by engine, so one that crashes or hangs it
    is the first unanswered: it is listed Unprobed with why, and a new child asks the rest, each
    such engine costing one child and at most one `timeout`; an engine left out of `names` is
    never imported. ValueError naming any name the registry does not know, before any child."""
    registered = known(names)
    if _found is not None and all(n in _found for n in names or registered):
        return {n: _found[n] for n in dict.fromkeys(names or registered)}
    found: dict[str, dict] = {}
    out: dict[str, BackendInfo] = {}
    asked: list[str] = list(dict.fromkeys(names))
    todo = asked
    while True:
        said, why = answers(_PROBE, todo, timeout, "the backend probe")
        listed = said[0] if said and isinstance(said[0], list) else todo or list(registered)
        asked = asked or listed
        for one in said[1:]:
            found.update(one)
        left = [n for n in listed if n not in found]
        if left:  # the engine it was asking about when it ended
            why = why or "the backend probe ended"
            out[left[0]] = Unprobed(left[0], unavailable=f"{why} (importing it or asking its version)")
        todo = left[1:]
        if not todo:
            break
    for name, d in found.items():
        out[name] = BackendInfo(name, d.get("version"), d.get("unavailable"), d.get("integration"),
                                d.get("accurate_integration"), d.get("scope"))
    cache.learn({n: i.version if i.usable else None for n, i in out.items()})  # the runs' keys need no probe of their own
    if _found is not None:
        _found.update((n, i) for n, i in out.items() if not isinstance(i, Unprobed))
    return {n: out[n] for n in asked}


def chosen(names: Sequence[str], timeout: float = DEFAULT_TIMEOUT) -> tuple[dict[str, BackendInfo], list[str]]:
    """What a command's --backends names (default: every registered backend) is here, probed
    alone (backend_table), and the backends to run or report (named_backends); ValueError
    naming unknown ones."""
    info = backend_table(timeout, names)
    return info, named_backends(names, info)


def _version(backend: str) -> str | None:
    """The backend's engine version for the run cache's keys (None: not usable here)."""
    info = backend_table(names=[backend]).get(backend)
    return info.version if info is not None and info.usable else None


cache.asks_versions(_version)
