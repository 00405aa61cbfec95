"""The real X_ITE browser in headless Chromium (opt-in: `make test-x-ite`, or pytest -m x_ite;
`make x-ite-install` installs it). Checks that the harness controls X_ITE's time (its frames
fall exactly where the trace says, runs are bit-identical) and that its verdicts come out of
the ordinary checks end to end."""

from __future__ import annotations

import json
import textwrap

import numpy as np
import pytest

from conformance.browsers.x_ite import harness as x_ite
from conformance.cli import main as cli_main
from conftest import case_scene
from x3d_core.trace import read_trace

pytestmark = [pytest.mark.x_ite,
              pytest.mark.skipif(x_ite.unavailable() is not None, reason=f"X_ITE: {x_ite.unavailable()}")]

G = 9.8  # RigidBodyCollection.gravity by default
# X_ITE's frame step: a moving average over this many frames of the frame period, from 0
X_ITE_DELAY = 15


def _record(scene: str, out: str, *args: str) -> list:
    assert cli_main(["x-ite", "record", scene, "--trace", out, *args]) == 0
    return read_trace(out)


def test_runs_are_bit_identical(tmp_path):
    scene = case_scene("pendulum_period")
    _record(scene, str(tmp_path / "a.csv"), "--duration", "1")
    _record(scene, str(tmp_path / "b.csv"), "--duration", "1")
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()


def test_frames_fall_where_the_clock_puts_them(tmp_path):
    """With preferAccuracy X_ITE takes `iterations` equal substeps of its frame step h_k, an
    average over X_ITE_DELAY frames of the frame period; so after frame k a falling ball's
    speed is exactly g * sum(h_i), h_i = (1 - (14/15)^i) / rate. Any frame off the clock
    (a late one, a skipped one, load time leaking in) changes that sum by a whole h_i (>1e-3
    here); ammo.js computes in float32, so the bound is float32 rounding over k*iterations
    additions (1e-6 relative each)."""
    scene = tmp_path / "fall.x3d"
    scene.write_text(textwrap.dedent("""\
        <?xml version="1.0" encoding="UTF-8"?>
        <X3D profile='Full' version='4.0'><Scene>
        <RigidBodyCollection DEF='World' preferAccuracy='true' iterations='4'>
          <RigidBody DEF='Ball' position='0 10 0'>
            <CollidableShape containerField='geometry'><Shape><Sphere radius='0.1'/></Shape></CollidableShape>
          </RigidBody>
        </RigidBodyCollection>
        </Scene></X3D>
        """))
    rate = 50.0
    rows = _record(str(scene), str(tmp_path / "t.csv"), "--frame-rate", str(rate), "--duration", "2")
    v = [(r.time, float(r.value.split()[1])) for r in rows if r.node == "Ball" and r.field == "linearVelocity"]
    t, vy = np.array(v).T
    k = np.arange(t.size)
    assert np.array_equal(t, k / rate)  # frame k written at k / rate exactly
    h = (1 - ((X_ITE_DELAY - 1) / X_ITE_DELAY) ** k[1:]) / rate
    expected = -G * np.concatenate([[0.0], np.cumsum(h)])
    assert np.max(np.abs(vy - expected)) <= 1e-6 * G * t[-1] * 4 * k[-1] ** 0.5 + 1e-6


def test_cases_are_judged_by_the_ordinary_checks(tmp_path):
    """free_fall: X_ITE's ball (no collision geometry) sits at the origin, not at 10 m, and
    its clock starts slow: the case fails on both measures, gravity having its effect;
    hinge_limits: the probe finds the field X_ITE ignores; the divergence is recorded."""
    out = tmp_path / "x"
    assert cli_main(["x-ite", "cases", "--cases", "free_fall,hinge_limits", "--against", "bullet",
                     "--out", str(out)]) == 0
    data = json.loads((out / "x_ite.json").read_text())
    found = {c["case"]: c for c in data["cases"]}
    fall = found["free_fall"]
    assert fall["verdict"] == "wrong" and fall["ignored"] == []
    assert fall["probed"] == ["RigidBodyCollection.gravity"]
    failing = {m["quantity"] for m in fall["validation"]["case"]["measures"] if not m["ok"]}
    assert failing == {"Ball.position", "Ball.linearVelocity"}
    assert fall["dt"] == pytest.approx(1 / 600)
    hinge = found["hinge_limits"]
    assert hinge["verdict"] == "ignores" and "SingleAxisHingeJoint.maxAngle" in hinge["ignored"]
    for c in (fall, hinge):
        assert (out / c["recording"]).stat().st_size > 0
    assert "| free_fall | **wrong** |" in (out / "x_ite.md").read_text()
