"""An engine that segfaults, hangs, raises or blows up costs its own run one verdict
(crashed, timed out, error, blew up) and the runs beside it go on; a blown-up run keeps
every frame before the blow-up, as a valid trace."""

from __future__ import annotations

import os
import sys

import pytest

from conftest import ROOT, SCENES
from conformance import results
from conformance.runner import children, probe, verdicts
from conformance.results import Settings
from x3d_core.traces.trace import read_trace

from fake_child import fake_python
from faulty_backends import FAULT_AT

PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
SETTINGS = Settings(0.5, 1 / 240, 20.0)
INSTALLED = [n for n, i in probe.backend_table().items() if i.usable]
pytestmark = pytest.mark.skipif(not INSTALLED, reason="no backend installed")


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory):
    """Every faulty backend and one sound one, run together as the suite runs pairs."""
    tmp = tmp_path_factory.mktemp("faults")
    script = f'exec "{sys.executable}" "{os.path.join(ROOT, "tests", "faulty_backends.py")}" "$@"\n'
    mp = pytest.MonkeyPatch()
    mp.setattr(children.sys, "executable", fake_python(tmp, script))
    names = ["faulty-segv", "faulty-hang", "faulty-gil", "faulty-raise", "faulty-nan", "faulty-huge", INSTALLED[0]]
    jobs = [(lambda n=n: children.run_child(PENDULUM, n, SETTINGS, str(tmp / f"{n}.csv"),
                                          timeout=6 if n in ("faulty-hang", "faulty-gil") else 120)) for n in names]
    try:
        results = verdicts.run_many(jobs, workers=len(jobs))
    finally:
        mp.undo()
    return {n: (o, tmp / f"{n}.csv") for n, o in zip(names, results)}


@pytest.mark.parametrize("backend,verdict,reason", [
    ("faulty-segv", results.CRASHED, "killed by SIGSEGV"),
    ("faulty-hang", results.TIMED_OUT, "no result within 6 s"),
    ("faulty-gil", results.TIMED_OUT, "no result within 6 s"),  # the command, another process, ends its group
    ("faulty-raise", results.ERROR, "RuntimeError: the engine refused to step"),
    ("faulty-nan", results.BLEW_UP, f"blew up at t={FAULT_AT:g}: Bob has a non-finite state"),
    ("faulty-huge", results.BLEW_UP, f"blew up at t={FAULT_AT:g}: Bob's angular velocity is beyond 1e+12"),
])
def test_a_faulty_engine_gets_its_verdict(outcomes, backend, verdict, reason):
    outcome, _ = outcomes[backend]
    assert outcome.verdict == verdict
    assert reason in outcome.reason


def test_the_sound_run_beside_them_succeeds(outcomes):
    outcome, trace = outcomes[INSTALLED[0]]
    assert outcome.verdict is None and trace.exists()


@pytest.mark.parametrize("backend", ["faulty-nan", "faulty-huge"])
def test_a_blown_up_run_keeps_every_frame_before_it(outcomes, backend):
    outcome, trace = outcomes[backend]
    assert "the frames before it written to" in outcome.reason
    rows = read_trace(str(trace))
    times = sorted({r.time for r in rows})
    assert times == pytest.approx([0.0, 0.05])
    per_frame = [sum(r.time == t for r in rows) for t in times]
    assert per_frame[0] == per_frame[1] > 0  # whole frames only
    assert not list(trace.parent.glob(f".{trace.name}-*"))  # no temporary left behind
