"""A run that blows up at t = 0 (its initial state already beyond the evaluator's bound) has
no frame to keep: the .npz writer once crashed on the empty trace (IndexError), and the
child's traceback then made `compare` show a line of Python source, `raise BlewUp(f"...")`,
as the verdict's reason. Now the trace without rows is written whole (either form), the run
says one line and exits 1, and a child's reason is its last line that says something, never
a traceback's source line.
"""

from __future__ import annotations

import re

import pytest

from backends import base
from conformance.results import BLEW_UP, CRASHED
from conformance.runner.children import classify
from x3d_core.traces.trace import read_view

from conftest import case_scene
from limited import leftovers, one_line, x3drbp

# pybullet prints its build time on import: the engines that print nothing of their own
INSTALLED = [b for b in base.IN_TREE if b != "bullet" and not isinstance(base.available().get(b), str)]
SAID = "blew up at t=0: Ball's position is beyond 1e+12 (SI units)"


@pytest.fixture
def boom(tmp_path) -> str:
    """free_fall with its Ball at 1e200 m: beyond the bound before any step."""
    with open(case_scene("free_fall"), encoding="utf-8") as f:
        text = f.read()
    path = tmp_path / "boom.x3d"
    path.write_text(text.replace("position='0 10 0'", "position='0 1e200 0'"))
    return str(path)


@pytest.mark.skipif(not INSTALLED, reason="no engine is installed")
@pytest.mark.parametrize("form", ["npz", "csv"])
def test_a_blow_up_at_t0_writes_a_trace_without_rows(tmp_path, boom, form):
    trace = tmp_path / f"t.{form}"
    p = x3drbp("run", boom, "--backend", INSTALLED[0], "--trace", str(trace))
    one_line(p, 1, re.escape(f"{boom}: {INSTALLED[0]}: {SAID} (the frames before it written to {trace})") + "$")
    view = read_view(str(trace))
    assert len(view) == 0 and view.keys() == [] and view.times().size == 0
    assert not leftovers(str(tmp_path))


@pytest.mark.skipif(len(INSTALLED) < 2, reason="compare needs two engines")
def test_compare_gives_the_blow_up_as_its_reason(boom):
    p = x3drbp("compare", boom, "--backends", ",".join(INSTALLED[:2]))
    assert "Traceback" not in p.stderr and "raise " not in p.stdout, p.stdout + p.stderr
    for b in INSTALLED[:2]:
        assert f"- {b}: **blew up**: {boom}: {b}: {SAID}" in p.stdout.replace("\\", ""), p.stdout


TRACEBACK = """Traceback (most recent call last):
  File "/x3drbp/x3d_core/semantics/evaluator.py", line 362, in _blew_up
    raise BlewUp(f"blew up at t={t:g}: {self.world.bodies.names[row]}'s {what} is beyond "
x3d_core.semantics.engine.BlewUp: blew up at t=0: Ball's position is beyond 1e+12 (SI units)

During handling of the above exception, another exception occurred:

Traceback (most recent call last):
  File "/x3drbp/x3d_core/traces/trace.py", line 177, in view
    every[np.concatenate(([True], every[1:] != every[:-1]))], count)
    ~~~~~^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^
IndexError: boolean index did not match indexed array along axis 0
"""
FAULT = """Fatal Python error: Segmentation fault

Current thread 0x00007f (most recent call first):
  File "/x3drbp/backends/ode.py", line 530 in step
    raise BlewUp("blew up in the step")
  File "/x3drbp/x3d_core/semantics/evaluator.py", line 250 in run
"""


def test_a_childs_reason_is_never_a_line_of_source():
    """The error lines, not the frames and their source lines beneath a traceback's header."""
    out = classify(1, TRACEBACK)
    assert (out.verdict, out.reason) == (BLEW_UP, f"x3d_core.semantics.engine.BlewUp: {SAID}")
    assert classify(1, TRACEBACK.replace("blew up", "went")).reason == (
        "uncaught exception: IndexError: boolean index did not match indexed array along axis 0")
    crashed = classify(-11, FAULT)
    assert (crashed.verdict, crashed.reason) == (CRASHED, "killed by SIGSEGV: Fatal Python error: Segmentation fault")
