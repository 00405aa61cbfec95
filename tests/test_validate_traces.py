"""`x3drbp validate` takes a trace in either form every trace reader takes (docs/commands/run.md): the CSV,
and x3drbp's own .npz, which it once refused as a CSV that did not parse. And a trace starts
at t = 0, the initial state: one whose first rows were at t = -1e308 "conformed", its
initial state never checked; now that is one line naming the file (and line), exit 2.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from backends import base
from x3d_core.traces.trace import Trace
from x3d_core.traces.trace_npz import arrays, write_npz

from conftest import case_scene
from limited import one_line, x3drbp

SCENE = case_scene("free_fall")


def _trace(times: list[float]) -> Trace:
    """The free_fall case's Ball at each time, falling as the case says it must."""
    trace = Trace()
    for t in times:
        y = 10 - 4.903325 * max(t, 0.0) ** 2
        for field, ftype, value in (("position", "SFVec3f", [0, y, 0]), ("orientation", "SFRotation", [0, 0, 1, 0]),
                                    ("linearVelocity", "SFVec3f", [0, -9.80665 * max(t, 0.0), 0]),
                                    ("angularVelocity", "SFVec3f", [0, 0, 0])):
            trace.add(t, "Ball", field, ftype, value)
    return trace


def test_validate_takes_its_own_npz(tmp_path):
    installed = [b for b in base.IN_TREE if not isinstance(base.available().get(b), str)]
    if not installed:
        pytest.skip("no engine is installed")
    npz = tmp_path / "ours.npz"
    assert x3drbp("run", SCENE, "--backend", installed[0], "--trace", str(npz)).returncode == 0
    p = x3drbp("validate", SCENE, "--trace", str(npz), "--against", installed[0])
    assert p.returncode == 0, p.stdout + p.stderr
    assert "**Conforms**" in p.stdout and "Traceback" not in p.stderr


@pytest.mark.parametrize("form", ["csv", "npz"])
def test_a_trace_must_start_at_zero(tmp_path, form):
    path = tmp_path / f"theirs.{form}"
    trace = _trace([-1e308, 0.5, 1.0])
    if form == "csv":
        trace.write(str(path))
    else:
        write_npz(trace.view(), str(path))
    line = ":2" if form == "csv" else ""  # the first row after the header; the .npz has no lines
    one_line(x3drbp("validate", SCENE, "--trace", str(path)), 2,
             rf"{re.escape(str(path))}{line}: the first row is at t = -1e\+308 s; a trace starts at t = 0, "
             r"the initial state \(within 1e-06 s\)$")


def _npz_with(tmp_path, change) -> str:
    a = arrays(_trace([0.0, 0.5, 1.0]).view())
    change(a)
    path = tmp_path / "theirs.npz"
    np.savez(path, **a)
    return str(path)


@pytest.mark.parametrize("change, said", [
    (lambda a: a["keys"].__setitem__((0, 0), "Nope"),
     "Nope.position: node 'Nope' is not in the scene"),
    (lambda a: a["keys"].__setitem__((0, 1), "spin"),
     "Ball.spin: field 'spin' of Ball: RigidBody has no output field 'spin'"),
    (lambda a: a["t"].__setitem__(slice(0, 3), [0.0, 1.0, 0.5]),
     r"Ball.position: its times decrease \(times never decrease\)"),
    (lambda a: a["v"].__setitem__(slice(9, 12), 2.0),  # the first orientation's axis (after 3 positions)
     "Ball.orientation: rotation at t = 0: the axis has length 3.4641, not 1"),
    (lambda a: a["v"].__setitem__(0, np.inf),
     "Ball.position: a value that is not a finite number"),
])
def test_an_npz_trace_is_checked_as_a_csv_is(tmp_path, change, said):
    path = _npz_with(tmp_path, change)
    one_line(x3drbp("validate", SCENE, "--trace", path), 2, rf"{re.escape(path)}: {said}")
