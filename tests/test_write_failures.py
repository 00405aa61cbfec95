"""Outputs that cannot be written are the command's failure, whoever writes them: a rerun
recording on a full disk, a run's trace (kept or not) that its child could not write, a kept
trace's folder removed mid-run; and two conformance commands never share an --out folder.

A full disk is RLIMIT_FSIZE in the command's process (and its children), SIGXFSZ ignored:
a write past the limit fails with EFBIG, as one on a full disk fails with ENOSPC.
"""

from __future__ import annotations

import fcntl
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import termios
import time

import pytest

from conftest import ROOT, SCENES
from x3drbp import main as cli_main
from conformance import cases as C
from conformance.results import ERROR, PASS
from conformance.runner import children, verdicts

PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
RUN = ("--duration", "0.1", "-q")
CASE = ("--cases", "free_fall", "--backends", "pymunk", "-q")  # one pair: an 11 kB kept CSV, a 4 kB matrix.json
GUARD_S = 300  # a hang fails the test instead of stalling the suite; no figure depends on it
pytest.importorskip("pymunk")
pytest.importorskip("mujoco")


def x3drbp(*args: str, fsize: int | None = None, **kw) -> subprocess.CompletedProcess:
    """The command in a child; with `fsize`, no file of it or its children grows past that."""
    def child() -> None:
        if fsize is not None:
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # inherited across exec, as ignored signals are
            resource.setrlimit(resource.RLIMIT_FSIZE, (fsize, fsize))
    return subprocess.run([sys.executable, "-m", "x3drbp", *args], cwd=ROOT, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True, timeout=GUARD_S, preexec_fn=child, **kw)


def _last(p: subprocess.CompletedProcess) -> str:
    assert "Traceback" not in p.stderr, p.stderr
    return p.stderr.strip().splitlines()[-1]


@pytest.mark.parametrize("command", [("run", PENDULUM, "--backend", "pymunk", "--trace", "/dev/null"),
                                     ("compare", PENDULUM, "--backends", "pymunk,mujoco")])
def test_a_recording_on_a_full_disk_is_one_line_exit_1_and_no_file(command, tmp_path):
    # the traces (6.5 kB each) fit in 30 kB, the recording (56 kB and more) does not; rerun's
    # own file writer either never returned (compare: 610 s, deaf to SIGTERM) or left a
    # truncated .rrd under its name with exit 0
    rrd = tmp_path / "r.rrd"
    p = x3drbp(*command, *RUN, "--rerun", str(rrd), fsize=30_000)
    assert p.returncode == 1, p.stderr
    assert _last(p) == f"x3drbp {command[0]}: cannot write {rrd}: File too large"
    assert os.listdir(tmp_path) == []  # neither the recording nor its temporary file


def test_a_signal_stops_compare_while_its_recording_waits_on_a_write(tmp_path):
    # the recording's reader stops reading (a stalled disk or pipe): SIGTERM still stops compare
    fifo = tmp_path / "r.rrd"
    os.mkfifo(fifo)
    reader = os.open(fifo, os.O_RDWR | os.O_NONBLOCK)  # a reader that never reads, so the writer's open passes
    try:
        fcntl.fcntl(reader, fcntl.F_SETPIPE_SZ, 4096)  # the least, so that any recording fills it
        p = subprocess.Popen([sys.executable, "-m", "x3drbp", "compare", PENDULUM, "--backends",
                              "pymunk,mujoco", *RUN, "--rerun", str(fifo)], cwd=ROOT, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
        buffered = bytearray(4)
        while p.poll() is None:  # until the pipe is full: the writer is blocked in its write
            fcntl.ioctl(reader, termios.FIONREAD, buffered)
            if int.from_bytes(buffered, sys.byteorder) >= 4096:
                break
            time.sleep(0.05)  # a poll's pause, not a limit
        assert p.poll() is None, p.stderr.read()
        p.terminate()
        _, err = p.communicate(timeout=GUARD_S)
    finally:
        os.close(reader)
    assert p.returncode == 143 and err.strip().splitlines()[-1] == "x3drbp compare: interrupted", err


@pytest.mark.parametrize("keep", [True, False])
def test_a_trace_a_run_cannot_write_is_the_commands_failure_not_a_verdict(keep, tmp_path):
    # the kept CSV (11 kB) past 8 kB, or the run's temporary .npz (several kB) past 2 kB: before,
    # the pair's verdict was `error` (which expectations would pin) and the command exited 0
    out = tmp_path / "out"
    p = x3drbp("conformance", *CASE, "--out", str(out), *(("--keep-traces",) if keep else ()),
               fsize=8_000 if keep else 2_000)
    assert p.returncode == 1, p.stderr
    trace = f"{out}/traces/free_fall-pymunk.csv: " if keep else "/free_fall-pymunk.npz: "
    assert _last(p).startswith("x3drbp conformance: cannot write ") and trace in _last(p), p.stderr
    assert _last(p).endswith(": File too large")
    assert not (out / "matrix.json").exists()


def test_a_kept_traces_folder_removed_mid_run_is_the_commands_failure(tmp_path, monkeypatch, capsys):
    out = tmp_path / "out"
    real = verdicts.run_child

    def removed_first(scene, backend, settings, trace, *args, **kw):
        shutil.rmtree(out / "traces")
        return real(scene, backend, settings, trace, *args, **kw)

    monkeypatch.setattr(verdicts, "run_child", removed_first)
    assert cli_main(["conformance", *CASE, "--out", str(out), "--keep-traces"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith(f"x3drbp conformance: cannot write {out}/traces/free_fall-pymunk.csv: "), err
    assert not (out / "matrix.json").exists()


def test_no_pair_starts_once_a_trace_could_not_be_written(tmp_path, monkeypatch):
    # a full disk fails every run after it: the matrix stops at the first, not after all of them
    started = []

    def full(scene, backend, settings, trace, *args, **kw):
        started.append(trace)
        return children.Outcome(ERROR, f"x3drbp run: cannot write {trace}: No space left on device")

    monkeypatch.setattr(verdicts, "run_child", full)
    with pytest.raises(OSError, match="No space left on device"):
        verdicts.run_matrix([C.BY_NAME[n] for n in ("free_fall", "constant_force", "damping")],
                            ["pymunk"], workers=1)
    assert len(started) == 1


def test_a_second_conformance_into_the_same_folder_says_it_is_in_use(tmp_path, monkeypatch):
    # the second command removed the first's kept trace: "the run succeeded but wrote no trace"
    out = tmp_path / "out"
    second: list[subprocess.CompletedProcess] = []
    real = verdicts.run_child

    def with_another_command(*args, **kw):  # while this command holds out, another starts into it
        if not second:
            second.append(x3drbp("conformance", *CASE, "--out", str(out), "--keep-traces"))
        return real(*args, **kw)

    monkeypatch.setattr(verdicts, "run_child", with_another_command)
    assert cli_main(["conformance", *CASE, "--out", str(out), "--keep-traces"]) == 0
    assert [r["verdict"] for r in json.loads((out / "matrix.json").read_text())["results"]] == [PASS]
    assert second[0].returncode == 1
    assert _last(second[0]) == f"x3drbp conformance: {out} is in use by another x3drbp command (pid {os.getpid()})"
    assert (out / "traces" / "free_fall-pymunk.csv").stat().st_size > 1000
    monkeypatch.undo()
    assert x3drbp("conformance", *CASE, "--out", str(out), "--keep-traces").returncode == 0  # held no longer
