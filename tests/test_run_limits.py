"""`x3drbp run` refuses settings that cannot run (exit 2, one line, before any work) and
stops at its --timeout with the frames before kept, even when an engine call never returns."""

from __future__ import annotations

import os
import signal
import subprocess
import sys

import pytest

from conftest import ROOT, SCENES
from x3d_core.encodings.load import load
from x3d_core.semantics.evaluator import MAX_SOLVER_ITERATIONS, RunSettings, too_much_solving
from x3d_core.semantics.world import worlds
from x3d_core.traces.trace import read_trace

PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
FAULTY = os.path.join(ROOT, "tests", "faulty_backends.py")
pytest.importorskip("mujoco")


def x3drbp(*args: str, script: tuple[str, ...] = ("-m", "x3drbp")) -> subprocess.CompletedProcess:
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


@pytest.mark.parametrize("fault", ["stuck", "gil"])
def test_timeout_ends_an_engine_call_that_never_returns(tmp_path, fault):
    """An engine call that sleeps an hour with SIGALRM blocked (stuck), or that also holds the
    interpreter lock all the while (gil: no Python thread runs, the old watchdog thread's
    neither, as in pybullet's 90 s step of 100 overlapping boxes), ends 0.5 s + the 5 s grace
    in: x3drbp() gives up after 60 s, so returning at all is the check."""
    out = tmp_path / "t.csv"
    r = x3drbp("run", PENDULUM, "--backend", f"faulty-{fault}", "--timeout", "0.5", "--trace", str(out),
               script=(FAULTY, "-m", "x3drbp"))
    assert r.returncode == 1
    assert last_line(r.stderr).endswith("passed its time limit of 0.5 s inside one engine call (no trace written)")
    assert not out.exists()


def test_a_watched_run_that_crashes_reads_as_a_crash(tmp_path):
    """Under --timeout the command waits for the run it forked: the run's segfault is the
    command's own death by SIGSEGV, as without the watchdog (the runners' `crashed`)."""
    r = x3drbp("run", PENDULUM, "--backend", "faulty-segv", "--timeout", "60", "--trace", str(tmp_path / "t.csv"),
               script=(FAULTY, "-m", "x3drbp"))
    assert r.returncode == -signal.SIGSEGV
    assert not (tmp_path / "t.csv").exists()


def _hinge(tmp_path, iterations: int) -> str:
    path = tmp_path / "hinge.x3d"
    path.write_text("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Immersive' version='4.0'><head>"
                    "<component name='RigidBodyPhysics' level='2'/></head><Scene>\n"
                    f"<RigidBodyCollection DEF='World' iterations='{iterations}'><RigidBody DEF='Anchor' fixed='true'/>"
                    "<RigidBody DEF='Bob' position='0.5 -0.5 0' inertia='0.01 0 0 0 0.01 0 0 0 0.01'/>"
                    "<SingleAxisHingeJoint axis='0 0 1'><RigidBody USE='Anchor' containerField='body1'/>"
                    "<RigidBody USE='Bob' containerField='body2'/></SingleAxisHingeJoint>"
                    "</RigidBodyCollection></Scene></X3D>")
    return str(path)


@pytest.mark.parametrize("backend", ["ode", "mujoco"])
def test_iterations_past_the_solver_bound_are_refused_before_any_run(tmp_path, backend):
    """iterations 10^9 on ODE took a minute a step (58 ns an iteration): the default 240 steps
    make 2.4e11 iterations, past the bound, refused in one line naming the file, line and field
    before the engine is imported (so whatever the backend); x3drbp() gives up after 60 s."""
    path = _hinge(tmp_path, 10**9)
    r = x3drbp("run", path, "--backend", backend, "--trace", str(tmp_path / "t.csv"))
    assert r.returncode == 1
    assert one_line(r.stderr) == (f"{path}:3:34: error: RigidBodyCollection World.iterations: 1000000000 "
                                  "iterations a step for 240 steps (--duration 1 at --dt 0.00416667) make 2.4e+11 "
                                  "solver iterations; a run takes at most 1e+11")
    assert not (tmp_path / "t.csv").exists()


def test_the_solver_bound_is_steps_times_iterations(tmp_path):
    ws = worlds(load(_hinge(tmp_path, 416_666_666)))  # x 240 steps: 9.99999998e10
    assert too_much_solving(ws, RunSettings()) is None
    ws = worlds(load(_hinge(tmp_path, 416_666_667)))  # 1.00000000008e11
    assert too_much_solving(ws, RunSettings())[1] == 240 * 416_666_667 > MAX_SOLVER_ITERATIONS
    assert too_much_solving(ws, RunSettings(duration=0.5)) is None  # half the steps
