"""One `x3drbp run` in a child process with a time limit, and the verdict of how it ended.

An engine's segfault or endless loop is then a verdict, not a lost suite: a child that
died by a signal is crashed, one past its time limit is timed out (its whole process
group killed), exit 3 is unsupported with the backend's own reason.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Sequence
from dataclasses import dataclass

from conformance.results import BLEW_UP, CRASHED, ERROR, TIMED_OUT, UNSUPPORTED, Settings

DEFAULT_TIMEOUT = 60.0
EXIT_UNSUPPORTED = 3  # conformance.cli.run
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


@dataclass
class Outcome:
    """What one child run came to: None verdict when it wrote its trace."""
    verdict: str | None
    reason: str = ""


def _tail(text: str, lines: int = 3) -> str:
    kept = [ln.strip() for ln in text.strip().splitlines() if ln.strip()]
    return " | ".join(kept[-lines:])


def classify(returncode: int | None, stderr: str, timed_out: bool = False, timeout: float = DEFAULT_TIMEOUT,
             backend: str = "") -> Outcome:
    """The verdict of one child `x3drbp run` from how it ended (None: it succeeded)."""
    if timed_out:
        return Outcome(TIMED_OUT, f"no result within {timeout:g} s")
    if returncode is None:
        return Outcome(ERROR, "the run did not start")
    if returncode < 0:
        try:
            name = signal.Signals(-returncode).name
        except ValueError:
            name = f"signal {-returncode}"
        return Outcome(CRASHED, f"killed by {name}" + (f": {_tail(stderr)}" if stderr.strip() else ""))
    if returncode == 0:
        return Outcome(None)
    if returncode == EXIT_UNSUPPORTED:
        marker = f"unsupported by {backend}: " if backend else "unsupported by "
        reasons = []
        for line in stderr.splitlines():
            if marker in line:
                reasons.append(line.split(marker, 1)[1].strip())
        return Outcome(UNSUPPORTED, "; ".join(reasons) or _tail(stderr) or "the backend refused the scene")
    if "blew up" in stderr:
        line = next(ln for ln in stderr.splitlines() if "blew up" in ln)
        return Outcome(BLEW_UP, line.strip())
    if "Traceback (most recent call last)" in stderr:
        return Outcome(CRASHED, f"uncaught exception: {_tail(stderr, 1)}")
    return Outcome(ERROR, _tail(stderr) or f"exit status {returncode}")


def run_child(scene: str, backend: str, settings: Settings, trace: str,
              timeout: float = DEFAULT_TIMEOUT, extra: Sequence[str] = ()) -> Outcome:
    """`x3drbp run` (with the `extra` options) in its own process (and process group),
    killed after `timeout` seconds."""
    cmd = [sys.executable, "-m", "conformance.cli", "run", scene, "--backend", backend, *settings.args(),
           "--trace", trace, *extra]
    try:
        proc = subprocess.Popen(cmd, cwd=ROOT, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                stderr=subprocess.PIPE, text=True, start_new_session=True)
    except OSError as e:
        return Outcome(ERROR, f"could not start {sys.executable}: {e}")
    try:
        _, err = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        try:
            os.killpg(proc.pid, signal.SIGKILL)  # the child's own group: it and anything it started
        except ProcessLookupError:
            pass
        proc.communicate()
        return classify(None, "", timed_out=True, timeout=timeout)
    out = classify(proc.returncode, err, backend=backend)
    if out.verdict is None and not os.path.exists(trace):
        return Outcome(ERROR, "the run succeeded but wrote no trace")
    return out
