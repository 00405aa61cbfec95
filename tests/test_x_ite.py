"""The real X_ITE browser in headless Chromium (opt-in: `make test-x-ite`, or pytest -m x_ite;
`make x-ite-install` installs it). Checks that the harness controls X_ITE's time (its frames
fall exactly where the trace says, runs are bit-identical) and that its verdicts come out of
the ordinary checks end to end."""

from __future__ import annotations

import json
import re
import textwrap

import numpy as np
import pytest

from conformance.browsers.x_ite import harness as x_ite
from conformance.browsers.x_ite.judge import run_cases
from conformance.cases import select
from conformance.cases.case import Case
from conformance.cases.closed_forms import CLOCK, GRAVITY, ballistic
from x3drbp import main as cli_main
from conformance.results import Measure, Settings
from conftest import case_scene, scene_file
from x3d_core.traces.trace import read_trace

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
            <CollidableShape containerField='geometry'><Shape containerField='shape'><Sphere radius='0.1'/></Shape></CollidableShape>
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
    """free_fall: X_ITE's ball (no collision geometry) leaves its file position for the origin at
    the first step: the start's measure fails (37.4.10's initial conditions), not the clock's nor
    gravity's, gravity having its effect; hinge_limits: the probe finds the field X_ITE ignores;
    the divergence is recorded."""
    out = tmp_path / "x"
    assert cli_main(["x-ite", "cases", "--cases", "free_fall,hinge_limits", "--against", "bullet",
                     "--out", str(out)]) == 0
    data = json.loads((out / "x_ite.json").read_text())
    found = {c["case"]: c for c in data["cases"]}
    fall = found["free_fall"]
    assert fall["verdict"] == "wrong" and fall["ignored"] == [] and fall["untold"] == {}
    assert fall["probed"] == ["RigidBodyCollection.gravity"]
    failing = {m["quantity"] for m in fall["validation"]["case"]["measures"] if not m["ok"] and m["basis"] == "spec"}
    assert failing == {"Ball first frame after the start - its file position (the motion starts there)"}
    assert fall["dt"] == pytest.approx(1 / 600)
    hinge = found["hinge_limits"]
    assert hinge["verdict"] == "ignores" and "SingleAxisHingeJoint.maxAngle" in hinge["ignored"]
    for c in (fall, hinge):
        assert (out / c["recording"]).stat().st_size > 0
    # the case cell links its recording: "| free_fall ([recording](...)) | **wrong** |"
    row = r"^\| free_fall( \(\[recording\]\([^)]*\)\))? \| \*\*wrong\*\* \|"
    assert re.search(row, (out / "x_ite.md").read_text(), re.M)


def _scene_file(tmp_path, name: str, body: str) -> str:
    return scene_file(tmp_path, body, name)


def _fails(why: str):
    """An expectation that fails by a spec measure, so that the case's fields are probed."""
    def expect(traces, settings):
        return [Measure(why, 1.0, 0.5, "m", CLOCK)]
    return expect


def test_every_verdict_class_on_small_scenes(tmp_path):
    """One browser session, a case of each class: right with other conventions (a ball with a
    collidable falls at g, judged at the physics time X_ITE's state shows: its lagging clock fails
    37.2.2.1 once, in the clock reading, and never gravity's sentence; its steps, of varying
    length, differ from a fixed step's state only in the physics clock's convention; and damping:
    X_ITE's per-second damping), ignores (constant_torque: X_ITE takes inertia from the collidables, and
    the probe's sphere is the same in both runs), wrong (free_fall), could not tell (a bounce
    probe whose ball meets nothing: no contact, so no verdict on the field), error (a body the page
    cannot name)."""
    g = 5.0  # far from X3D's default 9.8, so that the misread gravity's tolerance is wide (2.4 m/s^2)
    falling = _scene_file(tmp_path, "falling", f"""
        <RigidBodyCollection DEF='World' gravity='0 -{g} 0'>
          <RigidBody DEF='Ball' position='0 10 0'>
            <CollidableShape containerField='geometry'><Shape containerField='shape'><Sphere radius='0.1'/></Shape></CollidableShape>
          </RigidBody>
        </RigidBodyCollection>""")
    untouched = _scene_file(tmp_path, "untouched", """
        <RigidBodyCollection DEF='World'>
          <RigidBody DEF='Ball' position='0 10 0'>
            <CollidableShape DEF='BallShape' containerField='geometry'><Shape containerField='shape'><Sphere radius='0.1'/></Shape></CollidableShape>
          </RigidBody>
          <CollisionCollection DEF='Contacts' containerField='collider' bounce='0.7'>
            <CollidableShape USE='BallShape' containerField='collidables'/>
            <CollidableShape DEF='Floor' containerField='collidables' translation='0 -100 0'>
              <Shape containerField='shape'><Box size='2 0.2 2'/></Shape>
            </CollidableShape>
          </CollisionCollection>
        </RigidBodyCollection>""")
    unnamed = _scene_file(tmp_path, "unnamed", "<RigidBodyCollection DEF='World'><RigidBody/></RigidBodyCollection>")
    mine = [Case("falling", falling, "gravity", (Settings(1.0, 1 / 240),),
                 ballistic("Ball", (0, 10, 0), (0, 0, 0), (0, -g, 0), GRAVITY), exercises=("RigidBodyCollection.gravity",)),
            Case("untouched", untouched, "bounce, never met", (Settings(0.5, 1 / 240),), _fails("made to fail"),
                 exercises=("CollisionCollection.bounce",)),
            Case("unnamed", unnamed, "a body without DEF", (Settings(0.5, 1 / 240),), _fails("never judged"))]
    cases = [*mine, *select(["damping", "constant_torque", "free_fall"])]
    verdicts, clocks = run_cases(cases, str(tmp_path), [], {}, {}, 300.0, None)
    got = {v.case: v for v in verdicts}
    assert {n: v.verdict for n, v in got.items()} == {
        "falling": "conventions", "damping": "conventions", "constant_torque": "ignores", "free_fall": "wrong",
        "untouched": "wrong", "unnamed": "error"}
    measures = got["falling"].validation["case"]["measures"]
    failing = [m for m in measures if not m["ok"] and m["basis"] in ("spec", "convention")]
    assert failing and all(m["basis"] == "convention" and "the physics clock" in m["basis_text"] for m in failing)
    assert got["constant_torque"].ignored == ["RigidBody.inertia"]
    assert got["untouched"].untold == {"CollisionCollection.bounce": "no contact happened in its run (the "
                                       "CollisionSensor watching every collision collection never active)"}
    assert got["untouched"].ignored == [] and "BallShape" not in str(got["untouched"].variants)
    assert "RigidBody_1" in got["unnamed"].detail
    # the clock, read once: X_ITE's frame step is a moving average from 0 (X_ITE_DELAY frames), so its physics
    # lags the frames by up to (X_ITE_DELAY - 1) frames, far beyond one frame and a step:
    # by frame k, sum_i (14/15)^i / rate = 14 (1 - (14/15)^k) / rate (test_frames_fall_where_the_clock_puts_them);
    # without preferAccuracy Bullet's fixed-substep accumulator carries less than one substep (1 / (rate
    # iterations)) of a frame's time on to the next
    (clock,) = clocks
    assert (clock.frame_rate, clock.iterations, clock.prefer_accuracy) == (60.0, 10, False) and not clock.ok
    k = len(clock.physics_times) - 1
    settle = (X_ITE_DELAY - 1) / X_ITE_DELAY
    assert clock.lag_s == pytest.approx((X_ITE_DELAY - 1) * (1 - settle ** k) / 60.0, abs=1 / 600)


def test_a_scene_that_blows_up_is_said_and_exit_1(tmp_path, capsys):
    """A ball given a speed beyond float32 (X_ITE's ammo.js) blows up at once: record says so,
    names the output, and keeps the frames before it."""
    scene = _scene_file(tmp_path, "blow", """
        <RigidBodyCollection DEF='World'>
          <RigidBody DEF='Ball' mass='1e-6' forces='3e38 0 0'>
            <CollidableShape containerField='geometry'><Shape containerField='shape'><Sphere radius='0.1'/></Shape></CollidableShape>
          </RigidBody>
        </RigidBodyCollection>""")
    out = tmp_path / "t.csv"
    assert cli_main(["x-ite", "record", scene, "--trace", str(out), "--duration", "0.5"]) == 1
    err = capsys.readouterr().err
    assert "X_ITE blew up: Ball." in err and "frames before it" in err
    assert read_trace(str(out))
