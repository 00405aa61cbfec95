"""Ctrl-C or SIGTERM to a command that runs children (conformance, stability, sweep, compare)
stops every child and everything it started, and the command exits 130 or 143 with one line;
a sweep where no run gives a result still writes its files; a backend probe that gives no
answer lists every backend as unavailable, with why, rather than dropping it.

The interrupt tests start the command in a session of its own, as a shell starts a foreground
job: a signal to that group is a terminal's Ctrl-C (the command gets it, the children and
the fork server, in sessions of their own, do not); a signal to the command's pid alone is a
SIGTERM from outside. Processes are found through /proc (Linux)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time

import pytest

from conftest import ROOT, case_scene
from conformance import results
from conformance.analyses import sweep as S
from conformance.analyses.sweep_job import JobResult
from x3drbp import main as cli_main
from conformance.runner import children, probe

from fake_child import fake_python
from procs import table

pytestmark = pytest.mark.skipif(not os.path.isdir("/proc/self"), reason="finds processes through /proc")
# how long an interrupted command may take to end: children.GRACE (SIGTERM, then SIGKILL) and
# start-up, with room for a loaded machine; far under the runs' own 300 s limit, which a
# command that waited for its runs would take
STOPPED_S = 120
BACKEND = "mujoco"  # a dependency, installed wherever the project is
# the command with sys.executable (what children start) replaced by the script argv[1] names
DRIVER = "import sys; sys.executable = sys.argv.pop(1); from x3drbp import main; sys.exit(main(sys.argv[1:]))"
# an `x3drbp run` that ignores SIGTERM and has started a process of its own: only SIGKILL to its group ends both
STUBBORN = f"""case "$*" in
  *"x3drbp run"*) trap '' TERM; sleep 300 & sleep 300; wait ;;
  *) exec "{sys.executable}" "$@" ;;
esac
"""
# runs that take minutes: 10^6 steps and more of a real engine
LONG = {"stability": ["--cases", "thin_wall_impact", "--dts", "1e-7"],
        "sweep": ["--scenes", "projectile", "--dts", "1e-7", "--iterations", "10,50", "--accuracy", "false", "-q"],
        "compare": [case_scene("free_fall"), "--dt", "1e-6", "--duration", "20"],
        "advise": [case_scene("free_fall"), "--dts", "1e-6", "--duration", "20", "-q"]}


# -- processes, from /proc --------------------------------------------------------------------

def _descendants(pid: int) -> dict[int, int]:
    """pid's living descendants -> their process group."""
    procs = table()
    found, todo = {}, [pid]
    while todo:
        parent = todo.pop()
        for p, proc in procs.items():
            if proc.ppid == parent and p not in found and proc.state != "Z":
                found[p] = proc.pgrp
                todo.append(p)
    return found


def _argv(pid: int) -> list[str]:
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            return [a.decode(errors="replace") for a in f.read().split(b"\0")]
    except OSError:
        return []


def _is_run(pid: int) -> bool:
    argv = " ".join(_argv(pid)).split()  # a fork server's run has its command line as one title
    return any(a == "x3drbp" and b == "run" for a, b in zip(argv, argv[1:]))


def _wait_for_runs(parent: subprocess.Popen, count: int = 1, within: float = 60) -> dict[int, int]:
    """Once `count` `x3drbp run` children of the command (or of its fork server) have run a
    moment: every descendant of the command -> its process group."""
    deadline = time.monotonic() + within
    while time.monotonic() < deadline:
        assert parent.poll() is None, parent.communicate()
        procs = _descendants(parent.pid)
        if sum(map(_is_run, procs)) >= count:
            time.sleep(0.5)  # past its start-up: the run has begun
            procs = _descendants(parent.pid)
            _started.extend(set(procs.values()))
            return procs
        time.sleep(0.05)
    parent.kill()
    pytest.fail(f"no `x3drbp run` child within {within} s: {parent.communicate()}")


_started: list[int] = []  # the process groups a test started, ended after it whatever it found


@pytest.fixture(autouse=True)
def _leave_nothing():
    yield
    while _started:
        try:
            os.killpg(_started.pop(), signal.SIGKILL)
        except ProcessLookupError:
            pass


def _alive(pgid: int) -> list[int]:
    """The group's members that are not zombies (an orphan's zombie waits on whoever reaps here)."""
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return []
    return [p for p, proc in table().items() if proc.pgrp == pgid and proc.state != "Z"]


def _assert_none_left(procs: dict[int, int], within: float = 3.0) -> None:
    deadline = time.monotonic() + within
    groups = set(procs.values())
    while time.monotonic() < deadline:
        left = {g: _alive(g) for g in groups}
        if not any(left.values()):
            return
        time.sleep(0.05)
    pytest.fail(f"processes left behind: {left} of {procs}")


def _start(command: str, *args: str, script: str | None = None, tmp_path=None) -> subprocess.Popen:
    prefix = ["-c", DRIVER, fake_python(tmp_path, script)] if script else ["-m", "x3drbp"]
    parent = subprocess.Popen([sys.executable, *prefix, command, *args], cwd=ROOT, stdin=subprocess.DEVNULL,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    _started.append(parent.pid)
    return parent


def _interrupt(parent: subprocess.Popen, signals: list[int], whole_group: bool) -> tuple[int, str, float]:
    if signal.SIGINT in signals and signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        pytest.skip("SIGINT is ignored here (a shell's background job), and so by the command")
    started = time.monotonic()
    for k, s in enumerate(signals):
        if k:
            time.sleep(0.1)
        if whole_group:
            os.killpg(parent.pid, s)  # the terminal's Ctrl-C
        else:
            os.kill(parent.pid, s)  # kill(1)
    try:
        _, err = parent.communicate(timeout=STOPPED_S)
    except subprocess.TimeoutExpired:
        parent.kill()
        parent.communicate()
        pytest.fail(f"the command did not end within {STOPPED_S} s of the signal")
    return parent.returncode, err, time.monotonic() - started


def _exited(code: int, status: int, signals: list[int]) -> bool:
    """The status, or, when the last signal came after the command had returned (the interpreter
    exiting, its handlers the default again), death by that signal: a shell says 128 + it both ways."""
    return code == status or (len(signals) > 1 and code == -signals[-1])


def _one_line(stderr: str) -> str:
    lines = stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in stderr, stderr
    return lines[0]


# -- interrupts -------------------------------------------------------------------------------

# (signals sent, to the whole group as a terminal's Ctrl-C does or to the parent alone, exit status)
_SENT = [([signal.SIGINT], True, 130), ([signal.SIGTERM], False, 143), ([signal.SIGINT, signal.SIGINT], True, 130)]
_IDS = ["ctrl-c", "sigterm", "ctrl-c-twice"]
INTERRUPTS = pytest.mark.parametrize("signals,whole_group,status", _SENT, ids=_IDS)
ONE_INTERRUPT = pytest.mark.parametrize("signals,whole_group,status", _SENT[:2], ids=_IDS[:2])

@INTERRUPTS
def test_conformance_interrupted_ends_a_run_that_ignores_sigterm(tmp_path, signals, whole_group, status):
    """Each run is a group of two processes ignoring SIGTERM: the command's SIGTERM, then its
    SIGKILL after children.GRACE, ends both, in both runs at once."""
    pytest.importorskip(BACKEND)
    parent = _start("conformance", "--cases", "free_fall,projectile", "--backends", BACKEND, "--jobs", "2",
                    "--timeout", "300", "--out", str(tmp_path / "out"), script=STUBBORN, tmp_path=tmp_path)
    procs = _wait_for_runs(parent, count=2)
    code, err, took = _interrupt(parent, signals, whole_group)
    assert _exited(code, status, signals) and _one_line(err) == "x3drbp conformance: interrupted"
    assert took < STOPPED_S  # not the runs' 300 s: the command did not wait for them
    _assert_none_left(procs)
    assert os.listdir(tmp_path / "out") == [".x3drbp.lock"]  # no matrix of runs that were stopped (out held)


@pytest.mark.parametrize("command", ["stability", "compare"])
@ONE_INTERRUPT
def test_a_real_run_is_stopped(tmp_path, command, signals, whole_group, status):
    pytest.importorskip(BACKEND)
    backends = f"{BACKEND},bullet" if command == "compare" else BACKEND
    out = ["--json", str(tmp_path / "c.json")] if command == "compare" else ["--out", str(tmp_path / "out")]
    parent = _start(command, *LONG[command], "--backends", backends, "--timeout", "300", *out)
    procs = _wait_for_runs(parent)
    code, err, took = _interrupt(parent, signals, whole_group)
    assert _exited(code, status, signals) and _one_line(err) == f"x3drbp {command}: interrupted"
    assert took < STOPPED_S  # not the runs' 300 s: the command did not wait for them
    _assert_none_left(procs)


# the commands whose runs a pool of threads waits on: sweep on every interrupt, advise
# (the sweep's threads again) on one each of Ctrl-C and SIGTERM; each with the output it must not write
_POOLED = [pytest.param(command, *sent, id=f"{command}-{name}")
           for command, count in (("sweep", len(_SENT)), ("advise", 2))
           for sent, name in zip(_SENT[:count], _IDS[:count])]
_POOLED_OUTPUT = {"sweep": ("--out", "out"), "advise": ("--json", "advice.json")}


@pytest.mark.parametrize("command,signals,whole_group,status", _POOLED)
def test_a_pooled_command_interrupted_stops_its_runs(tmp_path, command, signals, whole_group, status):
    """Two runs at once, each waited on by a thread of the command's pool: the command stops
    both, and writes none of its output."""
    pytest.importorskip(BACKEND)
    option, name = _POOLED_OUTPUT[command]
    parent = _start(command, *LONG[command], "--backends", BACKEND, "--workers", "2", "--timeout", "300",
                    option, str(tmp_path / name))
    procs = _wait_for_runs(parent, count=2)
    code, err, took = _interrupt(parent, signals, whole_group)
    assert _exited(code, status, signals) and _one_line(err) == f"x3drbp {command}: interrupted"
    assert took < STOPPED_S  # not the runs' 300 s: the command did not wait for them
    _assert_none_left(procs)
    assert not (tmp_path / name).exists()


# -- a sweep without results, a probe without an answer ---------------------------------------

def test_sweep_where_every_run_is_refused_still_writes_its_files(tmp_path, monkeypatch, capsys):
    pytest.importorskip(BACKEND)
    monkeypatch.setattr(S, "execute", lambda jobs, *a: [JobResult(results.UNSUPPORTED, "refused here") for _ in jobs])
    out = tmp_path / "sweep"
    assert cli_main(["sweep", "--scenes", f"projectile,{case_scene('double_pendulum_energy')}", "--backends",
                     BACKEND, "--dts", "1/60", "--iterations", "10", "--accuracy", "false", "--out", str(out),
                     "-q"]) == 0
    err = capsys.readouterr().err
    assert _one_line(err).startswith("x3drbp sweep: no results: ")
    doc = json.loads((out / "sweep.json").read_text())
    assert doc["points"] and all(p["error"] is None and p["verdict"] == results.UNSUPPORTED for p in doc["points"])
    text = (out / "sweep.md").read_text()
    assert text.count("No results: ") == 2 and "refused here" in text
    for name in ("projectile", "double_pendulum_energy"):
        png = (out / f"sweep_{name}.png").read_bytes()
        assert png[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.fixture
def silent_probe(tmp_path, monkeypatch):
    """A backend probe that never answers (every child sleeps past its time limit)."""
    monkeypatch.setattr(children.sys, "executable", fake_python(tmp_path, "exec sleep 30\n"))


def test_a_probe_without_an_answer_lists_every_backend_as_unavailable(silent_probe):
    from backends import base
    info = probe.backend_table(timeout=0.3)
    assert list(info) == list(base.engines())
    for name, i in info.items():
        assert not i.usable and "gave no answer within 0.3 s" in i.unavailable, (name, i)
    assert probe.named_backends([], info) == list(base.engines())  # listed, not dropped


def test_compare_says_which_backends_the_probe_did_not_answer_for(silent_probe, tmp_path, capsys):
    scene = os.path.join(ROOT, "scenes", "examples", "pendulum.x3d")
    code = cli_main(["compare", scene, "--timeout", "0.3", "--json", str(tmp_path / "c.json")])
    out = capsys.readouterr().out
    assert code == 1  # nothing compared
    doc = json.loads((tmp_path / "c.json").read_text())
    from backends import base
    assert [r["backend"] for r in doc["runs"]] == list(base.engines())
    for r in doc["runs"]:
        assert r["verdict"] == results.ERROR and "gave no answer within 0.3 s" in r["reason"], r
    assert "gave no answer" in out
