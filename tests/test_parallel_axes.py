"""A DoubleAxisHingeJoint whose axis1 and axis2 are parallel has one line where the joint "has two
independent axes" (37.4.8 DoubleAxisHingeJoint): every backend refuses it with one message
naming the joint and both axes, exit 3 (x3d_core.semantics.world.parallel, evaluator.run), where ODE
refused it, MuJoCo's and DART's models were singular (MuJoCo non-finite in the first frame of a
driven hinge2, DART warning at every step) and Bullet ran it."""

from __future__ import annotations

import subprocess
import sys

import pytest

from backends import base
from conftest import ROOT
from test_joint_axes import INSTALLED, scene
from x3d_core.encodings.load import load
from x3d_core.semantics.world import parallel, worlds

HINGE2 = "<DoubleAxisHingeJoint DEF='H' axis1='0 1 0'>BODIES</DoubleAxisHingeJoint>"  # axis2: 4.0's default 0 1 0
NAMED = "DoubleAxisHingeJoint H: axis1 = 0 1 0 and axis2 = 0 1 0 are parallel"


@pytest.mark.parametrize("backend", INSTALLED)
def test_every_backend_refuses_a_hinge2_of_parallel_axes_with_one_message(tmp_path, backend):
    path = scene(tmp_path, HINGE2)
    r = subprocess.run([sys.executable, "-m", "x3drbp", "run", path, "--backend", backend, "-q",
                        "--trace", str(tmp_path / "t.csv")], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert r.returncode == 3, r.stderr
    lines = [ln for ln in r.stderr.splitlines() if "unsupported by" in ln]
    if base.load(backend).support("DoubleAxisHingeJoint").support is base.Support.UNSUPPORTED:  # pymunk: by name
        assert lines and all(f"unsupported by {backend}: DoubleAxisHingeJoint" in ln for ln in lines), r.stderr
    else:
        assert lines == [f"{path}: unsupported by {backend}: {NAMED}: one line, not the two independent axes the "
                         "joint turns about"], r.stderr
    assert "Traceback" not in r.stderr and not (tmp_path / "t.csv").exists()


@pytest.mark.parametrize("joint, named", [
    (HINGE2, [NAMED]),
    ("<DoubleAxisHingeJoint DEF='H' axis1='0 0 1' axis2='0 0 -2'>BODIES</DoubleAxisHingeJoint>",
     ["DoubleAxisHingeJoint H: axis1 = 0 0 1 and axis2 = 0 0 -2 are parallel"]),  # opposite senses: one line
    ("<DoubleAxisHingeJoint DEF='H' axis1='0 1 0' axis2='1 0 0'>BODIES</DoubleAxisHingeJoint>", []),
    ("<DoubleAxisHingeJoint DEF='H' axis1='1 0 0' axis2='1 1e-6 0'>BODIES</DoubleAxisHingeJoint>", []),  # near
    ("<DoubleAxisHingeJoint DEF='H' axis1='0 0 0' axis2='0 0 0'>BODIES</DoubleAxisHingeJoint>", []),  # undirected's
    ("<DoubleAxisHingeJoint DEF='H' axis1='0 1 0'><RigidBody USE='Bob' containerField='body1'/>"
     "<RigidBody USE='Bob' containerField='body2'/></DoubleAxisHingeJoint>", []),  # joins nothing: built by none
    ("<UniversalJoint DEF='U' axis1='1 0 0' axis2='1 0 0'>BODIES</UniversalJoint>", []),  # undefined: ODE's refusal
])
def test_the_hinge2_joints_whose_axes_are_one_line(tmp_path, joint, named):
    assert parallel(worlds(load(scene(tmp_path, joint)))[0]) == named
