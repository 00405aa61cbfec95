"""The warm fork server (conformance/runner/fork_server.py, x3drbp/run_server.py):
a run it forks is the same run a fresh `x3drbp run` is, byte for byte, and as isolated: its
own session, its crash or hang one verdict, nothing left behind; a server that dies or an
environment that changes costs a new server, never a run. Processes are found through /proc."""

from __future__ import annotations

import os
import signal
import threading
import time

import pytest

from conftest import ROOT, case_scene
from backends import base
from conformance import results
from conformance.results import Settings
from conformance.runner import children, fork_server

from procs import table

pytestmark = pytest.mark.skipif(not fork_server.usable(), reason="the fork server needs Linux's pidfd")
INSTALLED = [n for n, b in base.available().items() if not isinstance(b, str)]
PENDULUM = os.path.join(ROOT, "scenes", "examples", "pendulum.x3d")
LONG = Settings(30.0, 1e-6)  # minutes of steps: a run that is still going when the test acts on it


def _in_thread(fn) -> tuple[threading.Thread, list]:
    out: list = []
    t = threading.Thread(target=lambda: out.append(fn()), daemon=True)
    t.start()
    return t, out


def _cmdline(pid: int) -> bytes:
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            return f.read()
    except OSError:
        return b""


def _the_run(within: float = 30.0) -> int:
    """The one run the server is forking now, once it has begun: its command line shows as
    an `x3drbp run`'s (the child sets it in its own session, before it runs; until then it
    shows the server's)."""
    deadline = time.monotonic() + within
    while time.monotonic() < deadline:
        server = fork_server._server
        kids = [p for p, proc in table().items() if server is not None and proc.ppid == server.proc.pid
                and proc.state != "Z" and b"x3drbp run" in _cmdline(p)]
        if kids:
            return kids[0]
        time.sleep(0.02)
    pytest.fail("the server forked no run that shows as one")


@pytest.mark.parametrize("backend", INSTALLED)
def test_a_warm_run_writes_the_very_bytes_a_fresh_one_does(tmp_path, monkeypatch, backend):
    for k, scene in enumerate((PENDULUM, case_scene("sensor_geometry"))):
        warm, cold = tmp_path / f"warm{k}.csv", tmp_path / f"cold{k}.csv"
        assert children.run_child(scene, backend, Settings(1.0, 1 / 240), str(warm)).verdict in (None, results.UNSUPPORTED)
        with monkeypatch.context() as m:
            m.setenv("X3DRBP_FORK_SERVER", "0")
            assert not fork_server.usable()
            out = children.run_child(scene, backend, Settings(1.0, 1 / 240), str(cold))
        if out.verdict == results.UNSUPPORTED:  # pymunk: a scene out of its plane
            assert not warm.exists()
            continue
        assert out.verdict is None, out
        assert warm.read_bytes() == cold.read_bytes()


def test_a_scene_whose_file_name_is_not_utf_8_runs_warm(tmp_path):
    # its name reaches Python as a surrogate, which setproctitle refused: every warm run of
    # it ended with exit 1 and no word (compare's and advise's verdicts: "error: exit status 1")
    scene = os.fsdecode(os.path.join(os.fsencode(str(tmp_path)), b"p\xffq.x3d"))
    with open(PENDULUM, "rb") as src, open(scene, "wb") as dst:
        dst.write(src.read())
    assert fork_server.usable()
    out = children.run_child(scene, INSTALLED[0], Settings(0.1, 1 / 240), str(tmp_path / "t.npz"))
    assert out.verdict is None, out


def test_a_warm_run_has_a_session_of_its_own_and_its_crash_is_a_verdict(tmp_path):
    backend = INSTALLED[0]
    children.run_child(PENDULUM, backend, Settings(0.1, 1 / 240), str(tmp_path / "warmup.npz"))  # the server up
    thread, out = _in_thread(lambda: children.run_child(case_scene("free_fall"), backend, LONG,
                                                        str(tmp_path / "t.npz"), timeout=120))
    pid = _the_run()
    assert (table()[pid].pgrp, table()[pid].session) == (pid, pid)  # its own group and session: the terminal's Ctrl-C never reaches it
    assert b"free_fall.x3d --backend " + backend.encode() in _cmdline(pid)  # what ps shows of it: which run
    os.kill(pid, signal.SIGSEGV)
    thread.join(30)
    assert out and out[0].verdict == results.CRASHED and out[0].reason.startswith("killed by SIGSEGV"), out


def test_a_warm_run_past_its_time_limit_is_timed_out_and_gone(tmp_path):
    backend = INSTALLED[0]
    children.run_child(PENDULUM, backend, Settings(0.1, 1 / 240), str(tmp_path / "warmup.npz"))
    thread, out = _in_thread(lambda: children.run_child(case_scene("free_fall"), backend, LONG,
                                                        str(tmp_path / "t.npz"), timeout=1.0))
    pid = _the_run()
    thread.join(30)
    assert out and out[0].verdict == results.TIMED_OUT and out[0].reason == "no result within 1 s", out
    with pytest.raises(ProcessLookupError):
        os.killpg(pid, 0)


def test_a_server_that_dies_is_replaced_and_no_run_is_lost(tmp_path):
    backend = INSTALLED[0]
    assert children.run_child(PENDULUM, backend, Settings(0.1, 1 / 240), str(tmp_path / "a.npz")).verdict is None
    first = fork_server._server
    os.kill(first.proc.pid, signal.SIGKILL)
    first.proc.wait()
    assert children.run_child(PENDULUM, backend, Settings(0.1, 1 / 240), str(tmp_path / "b.npz")).verdict is None
    assert fork_server._server is not first and fork_server._server.alive()


def test_a_changed_environment_gets_a_server_started_in_it(tmp_path, monkeypatch):
    backend = INSTALLED[0]
    monkeypatch.setenv("X3DRBP_TEST_MARK", "one")
    assert children.run_child(PENDULUM, backend, Settings(0.1, 1 / 240), str(tmp_path / "a.npz")).verdict is None
    monkeypatch.setenv("X3DRBP_TEST_MARK", "two")
    assert children.run_child(PENDULUM, backend, Settings(0.1, 1 / 240), str(tmp_path / "b.npz")).verdict is None
    with open(f"/proc/{fork_server._server.proc.pid}/environ", "rb") as f:
        assert b"X3DRBP_TEST_MARK=two\0" in f.read()


@pytest.fixture
def quick_to_give_up(monkeypatch):
    """A server given up on within a second (a stuck one costs that), a fresh failure count,
    and whatever server a test stopped killed after it."""
    monkeypatch.setattr(fork_server, "ANSWER_WAIT", 1.0)
    monkeypatch.setattr(fork_server, "STATUS_WAIT", 1.0)
    monkeypatch.setattr(fork_server, "_failures", 0)
    stopped: list[int] = []
    yield stopped
    for pid in stopped:
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


def _stop_server(tmp_path, stopped: list[int]) -> fork_server.Server:
    backend = INSTALLED[0]
    assert children.run_child(PENDULUM, backend, Settings(0.1, 1 / 240), str(tmp_path / "warmup.npz")).verdict is None
    server = fork_server._server
    stopped.append(server.proc.pid)
    return server


def test_a_stopped_server_is_given_up_and_the_run_is_done_afresh(tmp_path, quick_to_give_up):
    server = _stop_server(tmp_path, quick_to_give_up)
    os.kill(server.proc.pid, signal.SIGSTOP)
    thread, out = _in_thread(lambda: children.run_child(PENDULUM, INSTALLED[0], Settings(0.1, 1 / 240),
                                                        str(tmp_path / "t.npz"), timeout=60))
    thread.join(60)  # a bound for a test that fails: it hung without one
    assert out and out[0].verdict is None, out
    assert (tmp_path / "t.npz").exists()
    assert server.proc.wait(10) == -signal.SIGKILL  # killed, not left stopped
    assert children.run_child(PENDULUM, INSTALLED[0], Settings(0.1, 1 / 240), str(tmp_path / "u.npz")).verdict is None
    assert fork_server._server is not server and fork_server._server.alive()  # a new one serves


def test_a_run_that_ends_while_its_server_is_stopped_is_redone_not_timed_out(tmp_path, quick_to_give_up):
    server = _stop_server(tmp_path, quick_to_give_up)
    trace = tmp_path / "t.npz"
    # 30,000 steps: the run is still going when found, whatever the machine
    thread, out = _in_thread(lambda: children.run_child(PENDULUM, INSTALLED[0], Settings(3.0, 1e-4), str(trace),
                                                        timeout=20))
    run = _the_run()
    os.kill(run, signal.SIGSTOP)  # held while its server is stopped, then let end: its end goes unreported
    os.kill(server.proc.pid, signal.SIGSTOP)
    os.kill(run, signal.SIGCONT)
    thread.join(120)
    assert out and out[0].verdict is None, out  # not "timed out": the server's silence is no verdict
    assert trace.exists()
    assert server.proc.wait(10) == -signal.SIGKILL
