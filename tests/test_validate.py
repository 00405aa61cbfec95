"""`x3drbp validate`: traces written by x3drbp itself conform, a wrong one fails naming the
measure, malformed ones are refused line by line (exit 2, no traceback)."""

from __future__ import annotations

import json
import os

import pytest

from x3drbp import main as cli_main
from conftest import SCENES, case_scene, needs_ode

FREE_FALL = case_scene("free_fall")
FRAME_RATE = case_scene("frame_rate")
PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")


@pytest.fixture(scope="module")
def bullet_fall(tmp_path_factory) -> list[str]:
    """free_fall's trace by Bullet, as lines."""
    path = tmp_path_factory.mktemp("validate") / "bullet.csv"
    assert cli_main(["run", FREE_FALL, "--backend", "bullet", "--trace", str(path)]) == 0
    return path.read_text().splitlines()


def _write(tmp_path, lines: list[str], name: str = "theirs.csv") -> str:
    path = tmp_path / name
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def _edit(lines: list[str], where: str, fn) -> list[str]:
    """lines with fn applied to the value of every row whose node,field is `where`."""
    out = []
    for ln in lines:
        t, node, fld, value = ln.split(",")
        out.append(",".join([t, node, fld, fn(value)]) if f"{node},{fld}" == where else ln)
    return out


def _validate(*args: str) -> int:
    return cli_main(["validate", *args])


def test_own_trace_conforms_against_another_backend(bullet_fall, tmp_path, capsys):
    # times off by 1e-13 s, as a browser summing 1/60 per frame writes them: still the same frames
    lines = [bullet_fall[0]] + [f"{float(ln.split(',', 1)[0]) + 1e-13!r},{ln.split(',', 1)[1]}"
                                for ln in bullet_fall[1:]]
    out_json = tmp_path / "out.json"
    assert _validate(FREE_FALL, "--trace", _write(tmp_path, lines), "--against", "mujoco",
                     "--json", str(out_json)) == 0
    out = capsys.readouterr().out
    assert "Case free_fall: **conforms; accuracy within the bound**" in out and "| mujoco | agrees | 61 |" in out and "**Conforms**" in out
    data = json.loads(out_json.read_text())
    assert data["conforms"] and data["agreeing"] == ["mujoco"] and data["case"]["verdict"] == "pass"


def test_halved_gravity_fails_naming_the_measure(bullet_fall, tmp_path, capsys):
    def half(value: str) -> str:  # y0 - g t^2 / 4 instead of / 2
        x, y, z = (float(v) for v in value.split())
        return f"{x!r} {10.0 - (10.0 - y) / 2.0!r} {z!r}"
    lines = _edit(bullet_fall, "Ball,position", half)
    assert _validate(FREE_FALL, "--trace", _write(tmp_path, lines), "--against", "mujoco") == 1
    out = capsys.readouterr().out
    assert "Case free_fall: **violates the spec: Ball physics clock against the frame clock" in out
    # the positions say the ball fell half as far in the time its velocities say: a clock at half pace (with twice
    # the gravity, which cannot be told from it) is what the trace shows, and the clock's sentence is what it breaks
    assert "| Ball physics clock against the frame clock (largest lag) |" in out and "**fail** |" in out
    assert "| mujoco | differs: position |" in out and "**Does not conform**" in out  # the one kind off


@needs_ode
def test_a_scene_without_case_conforms_by_agreeing_with_one_backend(tmp_path, capsys):
    path = str(tmp_path / "ode.csv")
    assert cli_main(["run", PENDULUM, "--backend", "ode", "--duration", "0.25", "--trace", path]) == 0
    assert _validate(PENDULUM, "--trace", path, "--against", "ode,pymunk") == 0
    out = capsys.readouterr().out
    assert "| ode | agrees |" in out and "| pymunk | differs: position, " in out and "agreement with one backend" in out


@needs_ode
def test_a_trace_no_backend_ran_against_is_not_judged_rather_than_accused(tmp_path, capsys):
    """The car is no case, and pymunk (planar) refuses it: nothing measured their trace, and
    'does not conform' (exit 1) said so of a trace nothing held to anything."""
    car, path = os.path.join(SCENES, "examples", "car.x3d"), str(tmp_path / "ode.csv")
    assert cli_main(["run", car, "--backend", "ode", "--duration", "0.2", "--trace", path]) == 0
    capsys.readouterr()
    out = str(tmp_path / "v.json")
    assert _validate(car, "--trace", path, "--against", "pymunk", "--json", out) == 3
    text = capsys.readouterr().out
    assert "**Not judged**: no backend ran the scene" in text and "Does not conform" not in text
    doc = json.loads(open(out, encoding="utf-8").read())
    assert doc["judged"] is False and doc["conforms"] is False


def _on(line: int, old: str, new: str):
    """An edit of one line (1: the header) of the trace."""
    def edit(lines: list[str]) -> list[str]:
        assert old in lines[line - 1]
        return lines[:line - 1] + [lines[line - 1].replace(old, new, 1)] + lines[line:]
    return edit


# (an edit of the trace, the line reported, a phrase of the message); rows 2-5 are Ball's
# position, orientation, linearVelocity, angularVelocity at time 0, row 7 its orientation at 1/60 s
MALFORMED = {
    "bad header": (_on(1, "time,node,field,value", "time,node,field"), 1, "header is 'time,node,field'"),
    "non-monotonic time": (_on(7, "0.016666666666666666", "0.01"), 7, "before the previous row's"),
    "unknown node": (_on(4, "Ball", "Balll"), 4, "node 'Balll' is not in the scene"),
    "unknown field": (_on(3, "orientation", "orientaton"), 3, "RigidBody has no output field 'orientaton'"),
    "unparsable value": (_on(2, "0 10 0", "0 ten 0"), 2, "is not 3 numbers"),
    "non-unit axis": (_on(3, "0 0 1 0", "0 0 2 0"), 3, "axis has length 2"),
    "wrong column count": (_on(5, "0 0 0", "0 0 0,1"), 5, "5 columns, expected 4"),
}


@pytest.mark.parametrize("kind", list(MALFORMED))
def test_malformed_trace_names_the_line(kind, bullet_fall, tmp_path, capsys):
    edit, line, phrase = MALFORMED[kind]
    path = _write(tmp_path, edit(bullet_fall))
    assert _validate(FREE_FALL, "--trace", path, "--against", "mujoco") == 2
    err = capsys.readouterr().err
    assert f"{path}:{line}: " in err and phrase in err, err
    assert "Traceback" not in err


def test_missing_body_field_and_wrong_trace_count_are_refused(bullet_fall, tmp_path, capsys):
    lines = [ln for ln in bullet_fall if ",angularVelocity," not in ln]
    path = _write(tmp_path, lines)
    assert _validate(FREE_FALL, "--trace", path) == 2
    assert f"{path}: no rows for Ball.angularVelocity" in capsys.readouterr().err
    assert _validate(FRAME_RATE, "--trace", path) == 2
    assert "takes 2 trace(s) (--trace, in this order: 30 frames/s, 144 frames/s), got 1" in capsys.readouterr().err


def test_a_step_no_backend_can_take_is_bad_usage_before_any_run(bullet_fall, tmp_path, capsys, monkeypatch):
    """--dt 1e-12 (2e11 steps for free_fall's 2 s) was handed to every backend, each refused it in
    its row, and the trace was judged 'does not conform', exit 1, for a setting of the command line."""
    from conformance.analyses import validation

    def ran(*args, **kwargs):
        raise AssertionError("a backend ran")
    monkeypatch.setattr(validation, "run_backends", ran)
    path = _write(tmp_path, bullet_fall)
    assert _validate(FREE_FALL, "--trace", path, "--against", "bullet", "--dt", "1e-12") == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and err[0].startswith(f"x3drbp validate: {path} reads as ") and "steps; a run takes at most" in err[0]


# -- a scene of an implementer's own: every output compared, the step hinted, steps typed as fractions --------

ARM = """<?xml version="1.0" encoding="UTF-8"?>
<X3D profile='Immersive' version='4.0'>
  <head><component name='RigidBodyPhysics' level='2'/></head>
  <Scene>
    <RigidBodyCollection DEF='World' gravity='0 -9.81 0'>
      <RigidBody DEF='Anchor' fixed='true'/>
      <RigidBody DEF='Arm' mass='2' position='0.6 0 0' inertia='0.01 0 0 0 0.01 0 0 0 0.01'/>
      <SingleAxisHingeJoint DEF='Hinge' anchorPoint='0 0 0' axis='0 0 1' forceOutput='"ALL"'>
        <RigidBody USE='Anchor' containerField='body1'/>
        <RigidBody USE='Arm' containerField='body2'/>
      </SingleAxisHingeJoint>
    </RigidBodyCollection>
  </Scene>
</X3D>
"""  # an arm released level, no conformance case: judged by agreement with a backend


@pytest.fixture(scope="module")
def arm(tmp_path_factory) -> tuple[str, list[str]]:
    """The arm's scene, and MuJoCo's trace of it (0.5 s at 1/240 s, 60 frames/s) as lines."""
    folder = tmp_path_factory.mktemp("arm")
    scene, trace = folder / "arm.x3d", folder / "mujoco.csv"
    scene.write_text(ARM)
    assert cli_main(["run", str(scene), "--backend", "mujoco", "--duration", "0.5", "--trace", str(trace)]) == 0
    return str(scene), trace.read_text().splitlines()


def _negated(value: str) -> str:
    return " ".join(repr(-float(x)) for x in value.split())


@pytest.mark.parametrize("field", ["linearVelocity", "angularVelocity"])
def test_a_wrong_velocity_does_not_conform_and_is_named(arm, tmp_path, capsys, field):
    """Their poses right, one velocity negated (the arm swings at up to 5.7 rad/s, 3.4 m/s): only
    positions and orientations were compared, and such a trace 'Conforms'."""
    scene, lines = arm
    capsys.readouterr()
    assert _validate(scene, "--trace", _write(tmp_path, lines), "--against", "mujoco") == 0
    assert "| mujoco | agrees | 31 |" in capsys.readouterr().out
    assert _validate(scene, "--trace", _write(tmp_path, _edit(lines, f"Arm,{field}", _negated)), "--against",
                     "mujoco") == 1
    out = capsys.readouterr().out
    assert f"| mujoco | differs: {field} | 31 |" in out and "**Does not conform**" in out
    assert f"{field} RMS / max ({'m/s' if field == 'linearVelocity' else 'rad/s'})" in out


def test_a_joint_rate_is_held_to_the_velocity_threshold_of_its_unit(arm, tmp_path, capsys):
    """Hinge.angleRate 0.01 rad/s off: past the default 1 mrad/s, within --threshold angularVelocity=0.02
    (a kind --threshold refused before velocities were compared)."""
    scene, lines = arm
    path = _write(tmp_path, _edit(lines, "Hinge,angleRate", lambda v: repr(float(v) + 0.01)))
    capsys.readouterr()
    assert _validate(scene, "--trace", path, "--against", "mujoco") == 1
    assert "| mujoco | differs: Hinge.angleRate | 31 |" in capsys.readouterr().out
    assert _validate(scene, "--trace", path, "--against", "mujoco", "--threshold", "angularVelocity=0.02") == 0
    out = capsys.readouterr().out
    assert "| mujoco | agrees | 31 |" in out and "angularVelocity 0.02 rad/s" in out


def test_a_trace_stepped_once_per_frame_is_told_to_try_that_step(arm, tmp_path, capsys):
    """An implementation that steps once per frame (1/60 s) did not conform at the default 1/240 s,
    with no word of --dt; now the line says what to try and what that step gives."""
    scene, _ = arm
    path, out_json = str(tmp_path / "per_frame.csv"), str(tmp_path / "v.json")
    assert cli_main(["run", scene, "--backend", "mujoco", "--duration", "0.5", "--dt", "1/60", "--trace", path]) == 0
    capsys.readouterr()
    assert _validate(scene, "--trace", path, "--against", "mujoco", "--json", out_json) == 1
    out = capsys.readouterr().out
    assert "**Does not conform**" in out and out.endswith(
        "Their frames are 1/60 s apart: if the implementation steps once per frame, try --dt 1/60: at that step it "
        "conforms (agrees with mujoco).\n")
    step = json.loads(open(out_json, encoding="utf-8").read())["frame_step"]
    assert step == {"dt": pytest.approx(1 / 60, rel=1e-12), "conforms": True, "agreeing": ["mujoco"]}
    assert _validate(scene, "--trace", path, "--against", "mujoco", "--dt", "1/60") == 0
    out = capsys.readouterr().out
    assert "| mujoco | agrees | 31 |" in out and "Their frames are" not in out


@pytest.mark.parametrize("command", [
    ["validate", FREE_FALL, "--trace", "nosuch.csv"],
    ["run", FREE_FALL, "--backend", "mujoco"],
    ["compare", FREE_FALL, "--backends", "mujoco,bullet"],
])
@pytest.mark.parametrize("value", ["1/0", "0", "-0.5", "1/-240", "abc", "nan", "inf"])
def test_every_dt_refuses_what_is_no_step_in_one_and_the_same_line(command, value, capsys):
    assert cli_main([*command, f"--dt={value}"]) == 2
    err = capsys.readouterr().err
    assert err == (f"x3drbp {command[0]}: --dt must be a positive step in seconds, as 1/240 or 0.004, "
                   f"not {value!r}\n")


def test_measures_quoting_less_than_read_as_typed_in_the_terminal(tmp_path, capsys):
    """motor_speed's measures say `(t < t*)`; the terminal showed `(t &lt; t*)`, and names' `_` as `\\_`."""
    scene, path = case_scene("motor_speed"), str(tmp_path / "bullet_motor.csv")
    assert cli_main(["run", scene, "--backend", "bullet", "--duration", "1.5", "--trace", path]) == 0
    capsys.readouterr()
    _validate(scene, "--trace", path, "--against", "bullet")
    out = capsys.readouterr().out
    assert "| Wheel.angularVelocity, torque-limited ramp (t < t*) |" in out
    assert f"Traces: {path};" in out and "&lt;" not in out and "&gt;" not in out and "\\_" not in out
