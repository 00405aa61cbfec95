"""`x3drbp run` refuses settings that cannot run (exit 2, one line, before any work) and
stops at its --timeout with the frames before kept, even when an engine call never returns."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest

from conftest import ROOT, SCENES
from x3d_core.trace import read_trace

PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
FAULTY = os.path.join(ROOT, "tests", "faulty_backends.py")
pytest.importorskip("mujoco")


def x3drbp(*args: str, script: tuple[str, ...] = ("-m", "conformance.cli")) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, *script, *args], cwd=ROOT, capture_output=True, text=True, timeout=60)


def one_line(stderr: str) -> str:
    lines = stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in stderr, stderr
    return lines[0]


def last_line(stderr: str) -> str:
    """What the run said of how it ended (the scene's warnings, an engine's banner come before)."""
    assert "Traceback" not in stderr, stderr
    return stderr.strip().splitlines()[-1]


@pytest.mark.parametrize("settings, said", [
    (["--dt", "0"], "--dt must be a positive step in seconds, as 1/240 or 0.004, not '0'"),
    (["--dt", "nan"], "--dt must be a positive step in seconds, as 1/240 or 0.004, not 'nan'"),
    (["--duration", "-1"], "--duration must be a positive number, not -1"),
    (["--frame-rate", "inf"], "--frame-rate must be a positive number, not inf"),
    (["--timeout", "0"], "--timeout must be a positive number, not 0"),
    (["--frame-rate", "1e9"], "makes 1e+09 frames; a run records at most 1e+06"),
    (["--duration", "10", "--dt", "1e-12"], "makes 1e+13 steps; a run takes at most 1e+09"),
])
def test_settings_that_cannot_run_are_bad_usage(tmp_path, settings, said):
    out = tmp_path / "t.csv"
    r = x3drbp("run", PENDULUM, "--backend", "mujoco", *settings, "--trace", str(out))
    assert r.returncode == 2
    line = one_line(r.stderr)
    assert line.startswith("x3drbp run: ") and said in line
    assert not out.exists()


def test_an_unknown_backend_is_bad_usage():
    r = x3drbp("run", PENDULUM, "--backend", "nosuch")
    assert r.returncode == 2
    assert one_line(r.stderr).startswith("x3drbp run: no backend 'nosuch'; known: ")


def test_timeout_stops_between_steps_and_keeps_whole_frames(tmp_path):
    out = tmp_path / "t.csv"
    # 10 s at a microsecond step is 10^7 steps: minutes of work, stopped after 1 s
    r = x3drbp("run", PENDULUM, "--backend", "mujoco", "--duration", "10", "--dt", "1e-6",
               "--frame-rate", "1000", "--timeout", "1", "--trace", str(out))
    assert r.returncode == 1
    assert "passed its time limit of 1 s (the frames before it written to" in last_line(r.stderr)
    rows = read_trace(str(out))
    times = sorted({row.time for row in rows})
    assert 0 < times[-1] < 10  # it ran, and it stopped early
    per_frame = {t: sum(row.time == t for row in rows) for t in (times[0], times[-1])}
    assert per_frame[times[0]] == per_frame[times[-1]] == 10  # 2 bodies x 4 fields + the hinge's 2


def test_timeout_ends_an_engine_call_that_never_returns(tmp_path):
    out = tmp_path / "t.csv"
    started = time.monotonic()
    r = x3drbp("run", PENDULUM, "--backend", "faulty-stuck", "--timeout", "0.5", "--trace", str(out),
               script=(FAULTY, "-m", "conformance.cli"))
    assert r.returncode == 1
    assert last_line(r.stderr).endswith("passed its time limit of 0.5 s inside one engine call (no trace written)")
    assert not out.exists()
    assert time.monotonic() - started < 30  # 0.5 s + the 5 s grace + start-up, not the hour it sleeps
