"""A joint axis of 0 0 0 (X3D 3.3's default for most joint axes) defines no direction, and the
spec gives none in its place: every backend refuses the joint with one message naming the
joint and the field, exit 3, where each once failed its own way (ODE refused, Bullet a
LinAlgError and LAPACK's noise, MuJoCo "axis too small", DART ran with every body frozen).
A MotorJoint's zero axis is the exception: the clause defines it, disabled (tests/test_motor_joint.py)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from backends import base
from conftest import ROOT
from x3d_core.encodings.load import load
from x3d_core.semantics import rotation as R
from x3d_core.semantics.world import undirected, worlds

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
    r = subprocess.run([sys.executable, "-m", "x3drbp", "run", path, "--backend", backend, "-q",
                        "--trace", str(tmp_path / "t.csv")], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert r.returncode == 3, r.stderr
    lines = [ln for ln in r.stderr.splitlines() if "unsupported by" in ln]
    assert lines == [f"{path}: unsupported by {backend}: SingleAxisHingeJoint Pivot.axis = 0 0 0: a joint axis "
                     "of no direction (the spec gives none in its place)"], r.stderr
    assert "Traceback" not in r.stderr and "Warning" not in r.stderr and "Error" not in r.stderr
    assert not (tmp_path / "t.csv").exists()


@pytest.mark.parametrize("joint, named", [
    ("<SliderJoint DEF='J' axis='0 0 0'>BODIES</SliderJoint>", ["SliderJoint J.axis = 0 0 0"]),
    ("<UniversalJoint DEF='J' axis2='0 0 0'>BODIES</UniversalJoint>", ["UniversalJoint J.axis2 = 0 0 0"]),
    ("<DoubleAxisHingeJoint DEF='J' axis1='0 0 0' axis2='0 0 0'>BODIES</DoubleAxisHingeJoint>",
     ["DoubleAxisHingeJoint J.axis1 = 0 0 0", "DoubleAxisHingeJoint J.axis2 = 0 0 0"]),
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
    assert undirected(worlds(s)[0]) == ["SingleAxisHingeJoint J.axis = 0 0 0"]
    s = load(scene(tmp_path, "<SingleAxisHingeJoint DEF='J'>BODIES</SingleAxisHingeJoint>", version="4.0"))
    assert undirected(worlds(s)[0]) == []  # 4.0's default: 0 1 0


# Axes of extreme length: |1e200 0 0| overflows to inf and |1e-170 0 0| underflows to 0, so the
# plain norm made both 0 0 0 (refused, with numpy's overflow warning) though each points along +x
EXTREME = {"1e200 0 0": [1, 0, 0], "1e-170 0 0": [1, 0, 0], "5e-324 0 0": [1, 0, 0],
           "-1e308 1e308 0": [-0.5 ** 0.5, 0.5 ** 0.5, 0]}


@pytest.mark.parametrize("axis", EXTREME)
@pytest.mark.parametrize("joint", [
    "<SingleAxisHingeJoint DEF='J' axis='A'>BODIES</SingleAxisHingeJoint>",
    "<SliderJoint DEF='J' axis='A'>BODIES</SliderJoint>",
    "<DoubleAxisHingeJoint DEF='J' axis1='A' axis2='0 0 1'>BODIES</DoubleAxisHingeJoint>",
    "<MotorJoint DEF='J' enabledAxes='1' motor1Axis='A'>BODIES</MotorJoint>",
])
def test_an_axis_of_extreme_length_is_its_direction(tmp_path, axis, joint, recwarn):
    w = worlds(load(scene(tmp_path, joint.replace("'A'", f"'{axis}'"))))[0]
    assert w.joints[0].axes[0].tolist() == pytest.approx(EXTREME[axis], rel=1e-15, abs=0)
    assert undirected(w) == []
    assert not [str(x.message) for x in recwarn.list]  # no numpy overflow warning


def test_an_extreme_axis_is_exactly_the_unit_axis():
    assert R.unit(np.array([[1e200, 0, 0], [1e-170, 0, 0], [5e-324, 0, 0], [0, -1e-300, 0]])).tolist() == \
        [[1, 0, 0], [1, 0, 0], [1, 0, 0], [0, -1, 0]]
    assert R.unit(np.array([-0.0, 0, 0])).tolist() == [0, 0, 0]


@pytest.mark.parametrize("backend", INSTALLED)
def test_every_backend_runs_an_axis_of_extreme_length_as_the_unit_axis(tmp_path, backend):
    """0 0 1e-170 scales to exactly 0 0 1 (along z: pymunk's plane too), so the run is the
    unit axis's to the bit."""
    traces = []
    for k, axis in enumerate(("0 0 1e-170", "0 0 1")):
        (tmp_path / str(k)).mkdir()
        hinge = f"<SingleAxisHingeJoint DEF='Pivot' axis='{axis}'>BODIES</SingleAxisHingeJoint>"
        path = scene(tmp_path / str(k), hinge)
        trace = tmp_path / str(k) / "t.csv"
        r = subprocess.run([sys.executable, "-m", "x3drbp", "run", path, "--backend", backend, "-q",
                            "--duration", "0.05", "--trace", str(trace)], cwd=ROOT, capture_output=True, text=True,
                           timeout=120)
        assert r.returncode == 0, r.stderr
        assert "Warning" not in r.stderr and "overflow" not in r.stderr
        traces.append(trace.read_text())
    assert traces[0] == traces[1]


def test_a_refusal_quotes_the_axis_given(tmp_path):
    path = scene(tmp_path, "<SingleAxisHingeJoint DEF='Pivot' axis='-0 0 0'>BODIES</SingleAxisHingeJoint>")
    assert undirected(worlds(load(path))[0]) == ["SingleAxisHingeJoint Pivot.axis = -0 0 0"]


def _check(path: str) -> str:
    r = subprocess.run([sys.executable, "-m", "x3drbp", "check", path], cwd=ROOT, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0 and "Traceback" not in r.stderr, r.stderr
    return r.stdout + r.stderr


@pytest.mark.parametrize("joint, said", [
    ("<SliderJoint DEF='J' axis='0 0 0'>BODIES</SliderJoint>",  # refused by every run, and check said nothing
     "SliderJoint J.axis: axis is 0 0 0 and defines no direction"),
    ("<DoubleAxisHingeJoint DEF='J' axis1='0 1e200 0' axis2='0 1 0'>BODIES</DoubleAxisHingeJoint>",
     "DoubleAxisHingeJoint J.axis2: axis1 and axis2 are parallel: one line, not the two independent axes"),
    ("<UniversalJoint DEF='J' axis1='1e200 0 0' axis2='1e-170 1e-170 0'>BODIES</UniversalJoint>",
     "UniversalJoint J.axis2: axis1 and axis2 are 45 degrees apart, not perpendicular"),
])
def test_check_warns_of_the_axes_a_run_refuses_or_leaves_undefined(tmp_path, joint, said):
    """A zero slider axis and a hinge2's parallel axes every run refuses; a universal joint's
    axes 45 degrees apart the spec leaves undefined (measured in unit axes: no overflow)."""
    out = _check(scene(tmp_path, joint))
    assert said in out and "overflow" not in out and "RuntimeWarning" not in out, out


@pytest.mark.parametrize("axes", ["axis1='1e200 0 0' axis2='0 1e-170 0'", "axis1='1e-170 0 0' axis2='0 0 1e300'"])
def test_check_takes_extreme_perpendicular_axes_as_perpendicular(tmp_path, axes):
    out = _check(scene(tmp_path, f"<UniversalJoint DEF='J' {axes}>BODIES</UniversalJoint>"))
    assert "0 warnings" in out and "overflow" not in out, out
