"""`x3drbp run` and `x3drbp backends` as a user runs them: exit codes, the trace file."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from conftest import ROOT, SCENES
from x3d_core.traces.trace import read_trace

PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
pytest.importorskip("mujoco")


def x3drbp(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "x3drbp", *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)


def test_run_writes_a_row_at_zero_and_at_every_frame_end(tmp_path):
    out = tmp_path / "p.csv"
    r = x3drbp("run", PENDULUM, "--backend", "mujoco", "--duration", "0.5", "--frame-rate", "10",
               "--trace", str(out))
    assert r.returncode == 0, r.stderr
    rows = read_trace(str(out))
    assert sorted({row.time for row in rows}) == pytest.approx([0, 0.1, 0.2, 0.3, 0.4, 0.5])
    at_zero = {(row.node, row.field) for row in rows if row.time == 0}
    assert at_zero == {(b, f) for b in ("Anchor", "Bob") for f in
                       ("position", "orientation", "linearVelocity", "angularVelocity")} | {
                          ("Pivot", "angle"), ("Pivot", "angleRate")}


def test_the_same_run_twice_gives_the_same_bytes(tmp_path):
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    for out in (a, b):
        assert x3drbp("run", PENDULUM, "--backend", "mujoco", "--trace", str(out)).returncode == 0
    assert a.read_bytes() == b.read_bytes()


def test_unsupported_features_exit_3_naming_each_and_write_nothing(tmp_path):
    scene = tmp_path / "s.x3dv"
    scene.write_text("#X3D V4.0 utf8\nRigidBodyCollection { bodies [ DEF A RigidBody { } DEF B RigidBody { } ]\n"
                     "joints SingleAxisHingeJoint { body1 USE A body2 USE B stopBounce 0.5 maxAngle 1 } }\n")
    out = tmp_path / "t.csv"
    r = x3drbp("run", str(scene), "--backend", "mujoco", "--trace", str(out))
    assert r.returncode == 3
    assert "SingleAxisHingeJoint.stopBounce" in r.stderr and not out.exists()


@pytest.mark.parametrize("args", [["--backend", "nope"], ["--backend", "mujoco", "--duration", "x"]])
def test_bad_backend_or_usage_is_not_a_run(args):
    r = x3drbp("run", PENDULUM, *args)
    assert r.returncode in (1, 2) and "Traceback" not in r.stderr


def test_a_scene_with_errors_exits_1(tmp_path):
    scene = tmp_path / "bad.x3dv"
    scene.write_text("#X3D V4.0 utf8\nRigidBody { mass 0 }\n")
    r = x3drbp("run", str(scene), "--backend", "mujoco")
    assert r.returncode == 1 and "mass" in r.stderr


def test_backends_lists_engines_with_versions_and_features():
    r = x3drbp("backends", "--features")
    assert r.returncode == 0
    import mujoco
    assert f"mujoco {mujoco.__version__}" in r.stdout
    assert "  SingleAxisHingeJoint.stopBounce: unsupported (" in r.stdout


@pytest.mark.parametrize("backend", ["ode", "bullet", "mujoco", "dart", "physx", "drake", "pymunk"])
def test_a_collection_of_no_bodies_beside_one_that_has_some_runs(tmp_path, backend):
    """An empty RigidBodyCollection is a world of no bodies: it simulates nothing and breaks nothing
    (ode and physx stopped at their bulk checks of the bodies, 'cannot reshape array of size 0')."""
    from backends import base
    if isinstance(base.available().get(backend, "absent"), str):
        pytest.skip(f"{backend} is not available here")
    scene = tmp_path / "s.x3dv"
    scene.write_text("#X3D V4.0 utf8\nDEF Empty RigidBodyCollection { }\n"
                     "DEF World RigidBodyCollection { bodies DEF Ball RigidBody { } }\n")
    out = tmp_path / "t.csv"
    r = x3drbp("run", str(scene), "--backend", backend, "--duration", "0.05", "--trace", str(out))
    assert r.returncode == 0, r.stderr
    assert {row.node for row in read_trace(str(out))} == {"Ball"}
