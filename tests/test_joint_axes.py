"""A joint axis of 0 0 0 (X3D 3.3's default for most joint axes) defines no direction, and the
spec gives none in its place: every backend refuses the joint with one message naming the
joint and the field, exit 3, where each once failed its own way (ODE refused, Bullet a
LinAlgError and LAPACK's noise, MuJoCo "axis too small", DART ran with every body frozen).
A MotorJoint's zero axis is the exception: the clause defines it, disabled (tests/test_motor_joint.py)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from backends import base
from conftest import ROOT
from x3d_core.load import load
from x3d_core.world import undirected, worlds

INSTALLED = [n for n, b in base.available().items() if not isinstance(b, str)]
HEAD = ("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Immersive' version='{version}'><head>"
        "<component name='RigidBodyPhysics' level='2'/></head><Scene>"
        "<RigidBodyCollection><RigidBody DEF='Anchor' fixed='true'/>"
        "<RigidBody DEF='Bob' position='0.5 -0.5 0' inertia='0.01 0 0 0 0.01 0 0 0 0.01'/>{joint}"
        "</RigidBodyCollection></Scene></X3D>")
BODIES = "<RigidBody USE='Anchor' containerField='body1'/><RigidBody USE='Bob' containerField='body2'/>"


def scene(tmp_path, joint: str, version: str = "4.0") -> str:
    path = tmp_path / "s.x3d"
    path.write_text(HEAD.format(version=version, joint=joint.replace("BODIES", BODIES)))
    return str(path)


@pytest.mark.parametrize("backend", INSTALLED)
def test_every_backend_refuses_a_zero_hinge_axis_with_one_message(tmp_path, backend):
    path = scene(tmp_path, "<SingleAxisHingeJoint DEF='Pivot' axis='0 0 0'>BODIES</SingleAxisHingeJoint>")
    r = subprocess.run([sys.executable, "-m", "conformance.cli", "run", path, "--backend", backend, "-q",
                        "--trace", str(tmp_path / "t.csv")], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert r.returncode == 3, r.stderr
    lines = [ln for ln in r.stderr.splitlines() if "unsupported by" in ln]
    assert lines == [f"{path}: unsupported by {backend}: SingleAxisHingeJoint Pivot.axis = 0 0 0: a joint axis "
                     "of no direction (the spec gives none in its place)"], r.stderr
    assert "Traceback" not in r.stderr and "Warning" not in r.stderr and "Error" not in r.stderr
    assert not (tmp_path / "t.csv").exists()


@pytest.mark.parametrize("joint, named", [
    ("<SliderJoint DEF='J' axis='0 0 0'>BODIES</SliderJoint>", ["SliderJoint J.axis"]),
    ("<UniversalJoint DEF='J' axis2='0 0 0'>BODIES</UniversalJoint>", ["UniversalJoint J.axis2"]),
    ("<DoubleAxisHingeJoint DEF='J' axis1='0 0 0' axis2='0 0 0'>BODIES</DoubleAxisHingeJoint>",
     ["DoubleAxisHingeJoint J.axis1", "DoubleAxisHingeJoint J.axis2"]),
    ("<MotorJoint DEF='J' enabledAxes='2' motor2Axis='0 0 0' motor3Axis='0 0 0'>BODIES</MotorJoint>",
     []),  # a zero motor axis is disabled (37.4.9), not undirected
    ("<SingleAxisHingeJoint DEF='J' axis='0 0 0'><RigidBody USE='Bob' containerField='body1'/>"
     "<RigidBody USE='Bob' containerField='body2'/></SingleAxisHingeJoint>", []),  # joins nothing: built by none
    ("<BallJoint DEF='J'>BODIES</BallJoint>", []),
])
def test_the_axes_a_joint_needs(tmp_path, joint, named):
    assert undirected(worlds(load(scene(tmp_path, joint)))[0]) == named


def test_a_3_3_file_that_leaves_the_axis_out_has_the_zero_default(tmp_path):
    s = load(scene(tmp_path, "<SingleAxisHingeJoint DEF='J'>BODIES</SingleAxisHingeJoint>", version="3.3"))
    assert undirected(worlds(s)[0]) == ["SingleAxisHingeJoint J.axis"]
    s = load(scene(tmp_path, "<SingleAxisHingeJoint DEF='J'>BODIES</SingleAxisHingeJoint>", version="4.0"))
    assert undirected(worlds(s)[0]) == []  # 4.0's default: 0 1 0
