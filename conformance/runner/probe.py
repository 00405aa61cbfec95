"""Which backends are here: the registry asked in a child process.

Importing an engine can crash the interpreter; the suite must survive that too.
"""

from __future__ import annotations

import json
import sys
from collections.abc import Sequence
from typing import Any

from conformance.results import BackendInfo
from conformance.runner import children
from conformance.runner.children import DEFAULT_TIMEOUT

_PROBE = """
import json, sys
from backends import base
only = sys.argv[1:]
if only:  # one engine alone (after a probe of all of them died)
    found = {}
    for name in only:
        try:
            found[name] = base.load(name)
        except Exception as e:
            found[name] = f"{type(e).__name__}: {e}"
else:
    try:
        found = base.available()
    except Exception:  # base.available() catches ImportError only: go engine by engine
        found = {}
        for name in base.engines():
            try:
                found[name] = base.load(name)
            except Exception as e:
                found[name] = f"{type(e).__name__}: {e}"
out = {}
for name, b in found.items():
    if isinstance(b, str):
        out[name] = {"unavailable": b}
    else:
        try:
            out[name] = {"version": str(b.version()), "integration": getattr(b, "integration", None),
                         "accurate_integration": getattr(b, "accurate_integration", None)}
        except Exception as e:  # a backend whose engine imports but cannot say its version
            out[name] = {"unavailable": f"version() failed: {type(e).__name__}: {e}"}
print("\\nx3drbp-answer " + json.dumps(out))
"""


ANSWER = "x3drbp-answer "  # the line an asking script prints its JSON answer on


def ask(script: str, args: Sequence[str], timeout: float, what: str) -> tuple[Any, str]:
    """Run a Python script that imports engines in a child (importing one can crash) and read
    the JSON it prints after ANSWER (engines may print on import: pybullet does): (the answer,
    or None and why there is none, naming `what` was asked)."""
    try:
        done = children.call([sys.executable, "-c", script, *args], timeout)
    except OSError as e:
        return None, f"{what} could not start: {e}"
    if done.returncode is None:
        return None, f"{what} gave no answer within {timeout:g} s"
    found = [ln for ln in done.stdout.splitlines() if ln.startswith(ANSWER)]
    if done.returncode == 0 and found:
        try:
            return json.loads(found[-1][len(ANSWER):]), ""
        except json.JSONDecodeError:
            pass
    return None, children.classify(done.returncode, done.stderr).reason or f"{what} printed nothing"


def _probe(names: Sequence[str], timeout: float) -> tuple[dict, str]:
    """Run the probe in a child: (what it reported, why it reported nothing)."""
    found, why = ask(_PROBE, names, timeout, "the backend probe")
    return found or {}, why


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


def backend_table(timeout: float = DEFAULT_TIMEOUT) -> dict[str, BackendInfo]:
    """backends.base.available(), asked in a child process: importing an engine can crash,
    and the suite must survive that too. Should the probe of all engines die, each engine
    is probed alone, so that one broken engine does not hide the others. Every registered
    name (base.engines(): the entry point group x3drbp.backends) gets an entry."""
    from backends import base  # the registry itself imports no engine
    data, why = _probe([], timeout)
    if not data:
        whys = {}
        for name in base.engines():
            one, whys[name] = _probe([name], timeout)
            data.update(one)
    else:
        whys = {}
    out = {}
    for name in dict.fromkeys([*base.engines(), *data]):
        d = data.get(name)
        if d is None:
            out[name] = Unprobed(name, unavailable=whys.get(name) or why or "not reported by base.available()")
        else:
            why_not = d.get("unavailable")
            if why_not and why_not.startswith("unavailable: "):  # base.available()'s own wording
                why_not = why_not[len("unavailable: "):]
            out[name] = BackendInfo(name, d.get("version"), why_not, d.get("integration"),
                                    d.get("accurate_integration"))
    return out
