"""The X_ITE harness's own logic, without a browser: what a page records and refuses, the step
X_ITE takes, the field probes, the browser's failures as verdicts, and the report's column.
The real browser is driven in tests/test_x_ite.py (opt-in)."""

from __future__ import annotations

import json
import shutil
import textwrap

import pytest

from conformance.browsers.x_ite import harness as x_ite
from x3drbp import main as cli_main
from conformance.cases import CASES
from conformance.browsers.x_ite.judge import probe_fields
from conformance.browsers.x_ite.variants import CONTACT, MASS, needs, ready, without, without_nodes
from conftest import case_scene
from reports.report_page import report_markdown
from reports.x_ite_text import render
from x3d_core.encodings.load import load
from x3d_core.traces.trace import read_trace

CASE = {c.name: c for c in CASES}


def _scene(tmp_path, body: str, name: str = "s.x3d") -> str:
    path = tmp_path / name
    path.write_text(textwrap.dedent(f"""\
        <?xml version="1.0" encoding="UTF-8"?>
        <X3D profile='Full' version='4.0'><Scene>
        {body}
        </Scene></X3D>
        """))
    return str(path)


@pytest.mark.parametrize("name", ["hinge_limits", "sensor_geometry", "universal_joint"])
def test_outputs_are_what_the_evaluator_records(tmp_path, name):
    """The page reads the (node, field) pairs x3drbp's own trace has at time 0."""
    scene = case_scene(name)
    trace = tmp_path / "t.csv"
    assert cli_main(["run", scene, "--backend", "bullet", "--duration", "0.05", "--trace", str(trace)]) == 0
    recorded = {(r.node, r.field) for r in read_trace(str(trace)) if r.time == 0}
    what = x_ite.outputs(load(scene))
    read = {(b, f) for b in what["bodies"] for f in ("position", "orientation", "linearVelocity", "angularVelocity")}
    read |= {(j, f) for j, fields in what["joints"].items() for f in fields}
    read |= {(s, "isActive") for s in what["sensors"]}
    assert read == recorded


def test_a_body_without_def_is_refused_by_name(tmp_path):
    path = _scene(tmp_path, "<RigidBodyCollection><RigidBody/><RigidBody DEF='B'/></RigidBodyCollection>")
    with pytest.raises(x_ite.NotRecordable, match="RigidBody_1"):
        x_ite.outputs(load(path))


def test_step_is_the_frame_in_iterations_substeps(tmp_path):
    path = _scene(tmp_path, "<RigidBodyCollection iterations='4'><RigidBody DEF='B'/></RigidBodyCollection>")
    assert x_ite.step(load(path), 50.0) == pytest.approx(1 / 200, rel=1e-15)
    assert x_ite.step(load(case_scene("free_fall")), 60.0) == pytest.approx(1 / 600, rel=1e-15)


def test_probes_are_the_exercised_fields():
    assert probe_fields(CASE["hinge_limits"]) == [("SingleAxisHingeJoint", "minAngle"),
                                                 ("SingleAxisHingeJoint", "maxAngle")]  # not ".limits"
    assert ("RigidBody", "inertia") in probe_fields(CASE["torque_free"])  # from inertia.offDiagonal
    assert probe_fields(CASE["collision_filtering"]) == []  # node types and geometry only


def test_without_puts_the_field_at_its_default(tmp_path):
    scene = case_scene("hinge_limits")
    out = str(tmp_path / "v.x3d")
    assert without(scene, "SingleAxisHingeJoint", "maxAngle", out)
    hinge = next(iter(load(out).of_type("SingleAxisHingeJoint")))
    original = next(iter(load(scene).of_type("SingleAxisHingeJoint")))
    assert hinge.get("maxAngle") == pytest.approx(3.141592653)  # the default
    assert original.get("maxAngle") != pytest.approx(3.141592653)
    assert hinge.get("minAngle") == original.get("minAngle")
    assert not without(scene, "SingleAxisHingeJoint", "stopBounce", str(tmp_path / "w.x3d"))  # not set there
    assert not (tmp_path / "w.x3d").exists()


@pytest.mark.skipif(shutil.which("node") is None, reason="node is not installed: the fake browser is a node script")
def test_a_browser_that_dies_is_each_unfinished_run_s_verdict(tmp_path, monkeypatch):
    """The first run finishes, then the browser exits: the second gets that as its error."""
    (tmp_path / "record.mjs").write_text(textwrap.dedent("""\
        import { readFileSync, writeFileSync } from "node:fs";
        const job = JSON.parse(readFileSync(process.argv[2], "utf8"));
        writeFileSync(job.runs[0].out, "time,node,field,value\\n");
        console.log(JSON.stringify({run: 0, ok: true, frames: 1, wallSeconds: 0.5,
                                    messages: ["GL Driver Message: noise", "X_ITE: a real warning"]}));
        console.error("renderer crashed");
        process.exit(3);
        """))
    monkeypatch.setattr(x_ite, "HERE", str(tmp_path))
    runs = [x_ite.Recording("a.x3d", str(tmp_path / f"{k}.csv"), 60.0, 1.0, {}) for k in range(2)]
    x_ite.record(runs, timeout=60)
    assert runs[0].ok and runs[0].frames == 1 and runs[0].messages == ["X_ITE: a real warning"]
    assert not runs[1].ok and runs[1].error == "the browser exited with status 3: renderer crashed"


@pytest.mark.skipif(shutil.which("node") is None, reason="node is not installed: the fake browser is a node script")
def test_a_browser_that_hangs_is_a_timeout(tmp_path, monkeypatch):
    (tmp_path / "record.mjs").write_text("setInterval(() => {}, 1000);\n")
    monkeypatch.setattr(x_ite, "HERE", str(tmp_path))
    runs = [x_ite.Recording("a.x3d", str(tmp_path / "0.csv"), 60.0, 1.0, {})]
    x_ite.record(runs, timeout=1.0)
    assert not runs[0].ok and runs[0].error.startswith("timeout")


def _results() -> dict:
    base = {"dt": 1 / 600, "ignored": [], "probed": [], "agreeing": [], "recording": None, "wall_s": 1.0,
            "messages": [], "validation": None}
    return {"versions": {"x_ite": "15.0.1", "chromium": "Chromium 156"}, "backends": ["bullet", "ode"],
            "thresholds": {}, "wall_s": 12.0, "cases": [
                {**base, "case": "free_fall", "verdict": "right", "detail": "", "agreeing": ["bullet"]},
                {**base, "case": "hinge_limits", "verdict": "ignores", "detail": "Hinge.angle 0.6 > 0.001 rad",
                 "ignored": ["SingleAxisHingeJoint.maxAngle"], "probed": ["SingleAxisHingeJoint.minAngle",
                                                                          "SingleAxisHingeJoint.maxAngle"],
                 "recording": "recordings/hinge_limits.rrd"},
                {**base, "case": "incline", "verdict": "wrong", "detail": "Box.position 1 > 0.01 m",
                 "probed": ["CollisionCollection.frictionCoefficients"], "messages": ["Ammo: warning"]},
                {**base, "case": "bounce_apex", "verdict": "error", "detail": "timeout", "dt": None}]}


def test_the_column_says_right_ignores_wrong_and_error_with_evidence():
    matrix = {"backends": {"bullet": {"run": True}, "ode": {"run": True}, "dart": {"run": False}},
              "results": [{"case": "free_fall", "backend": "bullet", "verdict": "pass"},
                          {"case": "hinge_limits", "backend": "ode", "verdict": "fail"}]}
    text = render(_results(), matrix)
    rows = {ln.split(" | ")[0][2:].split(" ")[0]: ln for ln in text.splitlines() if ln.startswith("| ") and " | " in ln}
    assert rows["case"].startswith("| case | X_ITE | the engines |")  # the engines' verdicts in one column
    assert rows["free_fall"].startswith("| free_fall | right | pass: bullet |")
    assert "| **ignores** | fail: ode |" in rows["hinge_limits"] and "dart" not in text
    assert "**ignores**" in rows["hinge_limits"] and "no effect: SingleAxisHingeJoint.maxAngle" in rows["hinge_limits"]
    assert "(recordings/hinge_limits.rrd)" in rows["hinge_limits"]
    assert "**wrong**" in rows["incline"] and "every field its probes could tell has an effect" in rows["incline"]
    assert "**error**" in rows["bounce_apex"] and "timeout" in rows["bounce_apex"]
    assert "1 right, 0 right with other conventions, 1 ignores, 1 wrong, 1 error" in text and "- Ammo: warning" in text


def test_the_report_gains_the_x_ite_section_only_when_it_ran(tmp_path):
    meta = {"generated": "now", "cpus": 2, "timings_s": {"conformance": 1.0, "total": 1.0}, "failed": [],
            "backends": {"bullet": "3"}, "quick": True}
    (tmp_path / "report.json").write_text(json.dumps(meta))
    text = report_markdown(str(tmp_path))
    assert "## X_ITE" not in text and "How X_ITE conforms" not in text
    assert "**How to judge your own browser**" in text and "    x3drbp validate SCENE --trace THEIRS.csv" in text
    (tmp_path / "x_ite").mkdir()
    data = {**_results(), "clock": [{"frame_rate": 60.0, "iterations": 10, "prefer_accuracy": False, "lag_s": 0.23, "tolerance_s": 0.0183, "ok": False,
                                     "error": None, "physics_times": [], "basis": "37.2.2.1 ..."}]}
    (tmp_path / "x_ite" / "x_ite.json").write_text(json.dumps(data))
    text = report_markdown(str(tmp_path))
    assert "## X_ITE" in text and "(x_ite/recordings/hinge_limits.rrd)" in text
    assert "**How X_ITE conforms** ([details](#x_ite)): X\\_ITE 15.0.1" in text
    assert ("conforms in 1 of 4 cases (0 of them "
            "differing in conventions); it ignores a field in 1, is wrong in 1, and could not run 1; its physics "
            "clock lags the frames by up to 0.23 s (37.2.2.1); fields without effect: "
            "SingleAxisHingeJoint.maxAngle.") in text
    assert "**The physics clock**, read once for every case" in text and "**violates the spec**" in text


@pytest.mark.parametrize("argv, says", [
    (["--cases", "nope"], "unknown case(s) nope"),
    (["--against", "nope"], "nope"),
    (["--threshold", "position=-1"], "threshold position must be a positive number"),
])
def test_bad_usage_is_one_line_and_exit_2(tmp_path, capsys, argv, says):
    assert cli_main(["x-ite", "cases", *argv, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("x3drbp x-ite: ") and says in err[0]


@pytest.mark.parametrize("rate,reached", [(60.0, 60.0), (30.0, 30.0), (240.0, 60.0), (144.0, 72.0), (80.0, 40.0),
                                          (500.0, 500.0 / 7), (1000.0, 1000.0 / 13)])
def test_cases_faster_than_x_ite_draws_are_recorded_at_a_rate_it_reaches(rate, reached):
    """X_ITE draws a frame only after more than 1/80 s (MaximumFrameRate): a case's rate
    beyond that is divided down, so every recorded frame is one of the case's."""
    got = x_ite.reachable_rate(rate)
    assert got == pytest.approx(reached, rel=1e-15) and got < x_ite.MAXIMUM_FRAME_RATE
    assert (rate / got) == pytest.approx(round(rate / got), rel=1e-12)


def test_probes_need_what_lets_x_ite_show_their_field():
    assert needs("RigidBody", "torques") == (MASS,)
    assert needs("CollisionCollection", "bounce") == (CONTACT,)
    assert needs("RigidBodyCollection", "contactSurfaceThickness") == (CONTACT,)
    assert needs("SingleAxisHingeJoint", "minAngle") == ()


def test_ready_gives_a_body_its_inertia_and_a_static_floor_a_fixed_body(tmp_path):
    scene = tmp_path / "s.x3d"
    scene.write_text(textwrap.dedent("""\
        <X3D profile='Full' version='4.0'><Scene>
          <RigidBodyCollection DEF='Other'/>
          <CollisionCollection DEF='Coll'>
            <CollidableShape DEF='Floor' containerField='collidables' translation='0 -0.5 0' rotation='1 0 0 0.1'><Shape containerField='shape'><Box size='4 0.1 4'/></Shape></CollidableShape>
          </CollisionCollection>
          <RigidBodyCollection DEF='World'>
            <RigidBody DEF='Spun' mass='2' inertia='0.5 0 0 0 0.8 0 0 0 0.5'/>
            <RigidBody DEF='Anchor' fixed='true'/>
            <CollisionCollection USE='Coll' containerField='collider'/>
          </RigidBodyCollection>
        </Scene></X3D>"""))
    out = str(tmp_path / "ready.x3d")
    assert ready(str(scene), out, (MASS,)) == ["Spun given a collidable sphere of radius 0.866 m"]
    spun = next(b for b in load(out).of_type("RigidBody") if b.def_name == "Spun")
    sphere = spun.get("geometry")[0].get("shape").get("geometry")
    assert sphere.get("radius") == pytest.approx((2.5 * 0.6 / 2) ** 0.5, rel=1e-12)  # 2/5 m r^2 = mean I
    changes = ready(str(scene), out, (CONTACT,))
    assert changes == ["Floor (a collidable on no body) held where it lies by the fixed RigidBody XITE_STATIC_1",
                       "Coll watched by the CollisionSensor XITE_SENSOR_1, so that the run shows its contacts"]
    ready_scene = load(out)
    assert not ready_scene.errors, [str(d) for d in ready_scene.errors]
    held = next(b for b in ready_scene.of_type("RigidBody") if b.def_name == "XITE_STATIC_1")
    assert held.get("fixed") and held.get("geometry")[0].def_name == "Floor"
    # where the floor lies: the body at its translation and rotation, the collidable with none of its own, so
    # both readings of a body's collidable (docs/spec-loose-ends.md section 22) put it there
    assert held.get("position") == pytest.approx((0, -0.5, 0)) and held.get("orientation") == pytest.approx((1, 0, 0, 0.1))
    assert held.get("geometry")[0].get("translation") == pytest.approx((0, 0, 0))
    sensor = next(s for s in ready_scene.of_type("CollisionSensor"))
    assert sensor.def_name == "XITE_SENSOR_1" and sensor.get("collider").def_name == "Coll"
    # the floor goes in the collection whose collider holds it, not the first
    assert held in next(c for c in ready_scene.of_type("RigidBodyCollection") if c.def_name == "World").get("bodies")
    assert ready(str(scene), str(tmp_path / "none.x3d"), ()) == [] and not (tmp_path / "none.x3d").exists()


def test_without_nodes_takes_a_joint_type_out(tmp_path):
    out = str(tmp_path / "v.x3d")
    assert without_nodes(case_scene("slider_stops"), "SliderJoint", out)
    assert not load(out).of_type("SliderJoint") and not load(out).errors
    assert not without_nodes(case_scene("free_fall"), "SliderJoint", out + "2")


@pytest.mark.parametrize("body, says", [
    ("<RigidBodyCollection><RigidBody DEF='Ball' mass='-1'/></RigidBodyCollection>",
     "'s\\x1b[31m\\n.x3d':3:"),  # then ': error: RigidBody Ball.mass: -1 is out of range'
    ("<RigidBodyCollection DEF='W'><RigidBody mass='1'/></RigidBodyCollection>",
     "x3drbp x-ite: 's\\x1b[31m\\n.x3d': RigidBody_1: a page reads nodes by DEF name, and these have none"),
])
def test_record_refuses_a_scene_with_errors_or_unnamed_outputs_in_one_line(tmp_path, monkeypatch, capsys, body, says):
    """A scene with errors went on to be recorded (or to 'X_ITE cannot run here', exit 1); the
    name of one that did not load was said twice, raw, and cut at its first newline."""
    monkeypatch.chdir(tmp_path)
    _scene(tmp_path, body, name="s\x1b[31m\n.x3d")
    assert cli_main(["x-ite", "record", "s\x1b[31m\n.x3d", "--trace", "o.csv"]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith(says), err
    assert "mass='-1'" not in body or err[0].endswith("error: RigidBody Ball.mass: -1 is out of range; allowed (0,inf)")
    assert not (tmp_path / "o.csv").exists()
