"""`x3drbp compare`: the divergence metrics on traces with a known answer, and the command
on real backends (one made to crash)."""

from __future__ import annotations

import json
import math
import os
import signal

import numpy as np
import pytest

from conformance.runner import children, probe
from x3d_core.traces.trace import TraceView
from x3drbp import main as cli_main
from conformance.analyses.compare import compare_pair
from conformance.results import Comparison, PairComparison
from conftest import SCENES
from reports.compare_text import render
from x3d_core.traces.trace import Row

PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
TIMES = np.arange(0, 11) * 0.05  # 0 ... 0.5 s


def _view(bodies: dict[str, tuple[np.ndarray, np.ndarray]], joints: dict[tuple[str, str], np.ndarray] = {},
          times: np.ndarray = TIMES) -> TraceView:
    """A trace of bodies (positions (n, 3), rotations (n, 4)) and joint outputs (n, width)."""
    def text(v: np.ndarray) -> str:
        return " ".join(repr(x) for x in np.atleast_1d(v).tolist())
    rows = []
    for k, t in enumerate(times.tolist()):
        for name, (p, r) in bodies.items():
            rows += [Row(t, name, "position", text(p[k])), Row(t, name, "orientation", text(r[k]))]
        rows += [Row(t, node, fld, text(v[k])) for (node, fld), v in joints.items()]
    return TraceView(rows)


def _still(p=(0.0, 0.0, 0.0), r=(0.0, 0.0, 1.0, 0.0), n: int = len(TIMES)) -> tuple[np.ndarray, np.ndarray]:
    return np.tile(np.array(p, dtype=float), (n, 1)), np.tile(np.array(r, dtype=float), (n, 1))


def _drifting(speed: float) -> tuple[np.ndarray, np.ndarray]:
    p, r = _still()
    p[:, 1] = speed * TIMES
    return p, r


# -- metrics ------------------------------------------------------------------------------

def test_position_divergence_statistics_and_first_crossing():
    a = _view({"Alpha": _still(), "Bravo": _still(), "Still": _still()})
    # Alpha 0.011 t, Bravo 0.012 t apart: both pass 1 mm first at t = 0.1 s, Bravo the worse
    b = _view({"Alpha": _drifting(0.011), "Bravo": _drifting(0.012), "Still": _still()})
    p = compare_pair("a", a, "b", b)
    d = np.column_stack([0.011 * TIMES, 0.012 * TIMES, 0 * TIMES])
    assert p.bodies == ["Alpha", "Bravo", "Still"] and np.array_equal(p.times, TIMES)
    pos = p.position
    assert pos.rms == pytest.approx(math.sqrt(np.mean(d ** 2)), rel=1e-12)
    assert pos.max == pytest.approx(0.012 * 0.5, rel=1e-12) and pos.max_body == "Bravo" and pos.max_time == 0.5
    np.testing.assert_allclose(pos.frame_rms, np.sqrt(np.mean(d ** 2, axis=1)), rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(pos.frame_max, 0.012 * TIMES, rtol=1e-12)
    np.testing.assert_allclose(pos.body_max, [0.011 * 0.5, 0.012 * 0.5, 0], rtol=1e-12)
    assert pos.first_over.time == pytest.approx(0.1) and pos.first_over.bodies == ["Bravo", "Alpha"]
    np.testing.assert_allclose(pos.first_over.values, [0.0012, 0.0011], rtol=1e-12)
    assert p.orientation.max == 0 and p.orientation.first_over is None


def test_orientation_divergence_is_the_angle_between_whatever_sign_or_axis_the_trace_writes():
    n = len(TIMES)
    a = _view({"Same": _still(r=(0, 0, 1, 0.5)), "Flip": _still(r=(0, 0, 1, 0.5)),
               "Tilted": _still(r=(0, 0, 1, 0.5)), "Round": _still(r=(0, 0, 1, 3.1))})
    b = _view({"Same": _still(r=(0, 0, -1, -0.5)),  # the same rotation
               "Flip": _still(r=(0, 0, 1, 0.5 + 2 * math.pi)),  # the same rotation as -q
               "Tilted": _still(r=(0, 0, 1, 0.6)),  # 0.1 rad further
               "Round": _still(r=(0, 0, -1, 3.1))})  # 2 pi - 6.2 rad away, the short way round
    o = compare_pair("a", a, "b", b).orientation
    np.testing.assert_allclose(o.body_max, [0, 0, 0.1, 2 * math.pi - 6.2], atol=1e-12)
    assert o.max_body == "Tilted" and o.first_over.time == 0 and o.first_over.bodies == ["Tilted", "Round"]
    assert o.frame_max.shape == (n,)


def test_bodies_and_joint_outputs_in_one_trace_only_are_listed_and_the_rest_compared():
    angle = np.full(len(TIMES), 3.1)
    anchor = np.tile([0.0, 1.0, 0.0], (len(TIMES), 1))
    a = _view({"Bob": _drifting(0.01), "Extra": _still()},
              {("Pivot", "angle"): angle, ("Pivot", "body1AnchorPoint"): anchor, ("Pivot", "angleRate"): angle})
    b = _view({"Other": _still(), "Bob": _still()},
              {("Pivot", "angle"): -angle, ("Pivot", "body1AnchorPoint"): anchor + [0.003, 0.004, 0.0]})
    p = compare_pair("a", a, "b", b)
    assert p.bodies == ["Bob"] and p.only_in_a == ["Extra"] and p.only_in_b == ["Other"]
    assert p.position.max == pytest.approx(0.005)
    assert p.joints_only_in_a == ["Pivot.angleRate"] and p.joints_only_in_b == []
    by = {j.field: j for j in p.joints}
    assert by["angle"].unit == "rad" and by["angle"].max == pytest.approx(2 * math.pi - 6.2, abs=1e-12)
    assert by["body1AnchorPoint"].unit == "m" and by["body1AnchorPoint"].rms == pytest.approx(0.005)
    assert p.worst_joint() is by["angle"]  # 0.083 rad / 1 mrad beats 0.005 m / 1 mm


def test_velocities_are_compared_as_positions_are_and_joint_rates_held_to_them():
    n = len(TIMES)
    w = np.tile([0.0, 0.0, 2.0], (n, 1))
    outputs = {("Bob", "linearVelocity"): np.zeros((n, 3)), ("Bob", "angularVelocity"): w,
               ("Pivot", "angleRate"): w[:, 2]}
    a = _view({"Bob": _still()}, outputs)
    # v 5 mm/s off (3, 4, 0) from 0.2 s on, w as it is, angleRate 4 mrad/s off
    v = np.where(TIMES[:, None] >= 0.2, [0.003, 0.004, 0.0], 0.0)
    b = _view({"Bob": _still()}, {**outputs, ("Bob", "linearVelocity"): v, ("Pivot", "angleRate"): w[:, 2] + 0.004})
    p = compare_pair("a", a, "b", b)
    lin, ang = p.velocities
    assert (lin.quantity, lin.unit, ang.quantity, ang.unit) == ("linearVelocity", "m/s", "angularVelocity", "rad/s")
    assert lin.max == pytest.approx(0.005) and lin.first_over.time == pytest.approx(0.2) and ang.max == 0
    assert p.position.max == 0 and p.diverged() == ["linearVelocity", "Pivot.angleRate"]
    data = json.loads(json.dumps(p.to_json()))
    assert PairComparison.from_json(data).to_json() == data
    loose = compare_pair("a", a, "b", b, {"linearVelocity": 0.01, "angularVelocity": 0.005})
    assert loose.diverged() == [] and {j.field: j.threshold for j in loose.joints} == {"angleRate": 0.005}
    assert compare_pair("a", _view({"Bob": _still()}), "b", _view({"Bob": _still()})).velocities == []  # none held


def test_a_trace_against_itself_diverges_nowhere_and_the_json_round_trips():
    a = _view({"Bob": _drifting(0.3), "Anchor": _still(r=(1, 2, 3, 2.0))}, {("Pivot", "angle"): TIMES})
    p = compare_pair("x", a, "y", a)
    for d in (p.position, p.orientation):
        assert d.rms == 0 and d.max == 0 and d.first_over is None
    assert [j.max for j in p.joints] == [0]
    c = Comparison("s.x3d", 0.5, 0.01, 20, {"position": 1e-3, "orientation": 1e-3}, [], [p])
    data = json.loads(json.dumps(c.to_json()))
    assert Comparison.from_json(data).to_json() == data


def test_runs_without_a_body_in_common_compare_to_nothing_without_failing():
    p = compare_pair("a", _view({"One": _still()}), "b", _view({"Two": _still()}))
    assert p.bodies == [] and p.position.rms is None and p.orientation.first_over is None
    c = Comparison("s.x3d", 0.5, 0.01, 20, {"position": 1e-3, "orientation": 1e-3}, [], [p])
    assert "bodies only in a: One" in render(c)


# -- the command --------------------------------------------------------------------------

INSTALLED = [n for n, i in probe.backend_table().items() if i.usable]
needs_two = pytest.mark.skipif(len(INSTALLED) < 2, reason=f"two backends needed, installed: {INSTALLED}")


@needs_two
def test_compare_two_backends_on_the_pendulum_writes_table_and_json(tmp_path, capsys):
    out = tmp_path / "c.json"
    pair = INSTALLED[:2]
    code = cli_main(["compare", PENDULUM, "--backends", ",".join(pair), "--duration", "0.5", "--json", str(out)])
    text = capsys.readouterr().out
    assert code == 0
    assert f"| {pair[0]} / {pair[1]} | 2 | 31 |" in text
    data = json.loads(out.read_text())
    assert set(data) == {"scene", "duration", "dt", "frame_rate", "thresholds", "runs", "pairs"}
    assert [r["backend"] for r in data["runs"]] == pair
    for r in data["runs"]:
        assert r["verdict"] == "ran" and r["realtime_basis"] == "simulation"
        assert 0 < r["simulation_wall_s"] < r["child_wall_s"]
        assert r["realtime_factor"] == pytest.approx(0.5 / r["simulation_wall_s"])
    (p,) = data["pairs"]
    assert (p["a"], p["b"], p["bodies"]) == (*pair, ["Anchor", "Bob"])
    assert len(p["times"]) == 31 and p["times"][-1] == 0.5
    for q in ("position", "orientation"):
        assert len(p[q]["frame_rms"]) == len(p[q]["frame_max"]) == 31 and len(p[q]["body_max"]) == 2
        assert p[q]["body_max"][0] == 0  # the fixed anchor
    assert {(j["node"], j["field"]) for j in p["joints"]} == {("Pivot", "angle"), ("Pivot", "angleRate")}
    assert Comparison.from_json(data).to_json() == data


@needs_two
def test_a_crashed_backend_is_its_verdict_and_the_others_still_compare(tmp_path, capsys, monkeypatch):
    victim = INSTALLED[0]
    real = children.run_child

    def crashing(scene, backend, *args, **kwargs):
        if backend == victim:  # as a child killed by a segfault ends
            return children.classify(-signal.SIGSEGV, "Fatal Python error: Segmentation fault")
        return real(scene, backend, *args, **kwargs)

    monkeypatch.setattr(children, "run_child", crashing)
    others = INSTALLED[1:3]
    out = tmp_path / "c.json"
    code = cli_main(["compare", PENDULUM, "--backends", ",".join([victim, *others]), "--duration", "0.1",
                     "--json", str(out), "--jobs", "2"])
    text = capsys.readouterr().out
    data = json.loads(out.read_text())
    assert data["runs"][0]["verdict"] == "crashed" and "SIGSEGV" in data["runs"][0]["reason"]
    assert f"{victim}: **crashed**" in text
    if len(others) == 2:
        assert code == 0 and [(p["a"], p["b"]) for p in data["pairs"]] == [tuple(others)]
    else:  # one backend left: nothing to compare
        assert code == 1 and data["pairs"] == []


@pytest.mark.parametrize("command", [["compare", PENDULUM], ["advise", PENDULUM], ["sweep", "--scenes", PENDULUM]])
def test_an_unknown_backend_is_said_alone_before_the_scene_loads(command, capsys):
    """Bad usage is one line: the pendulum's warning (its bob's geometry collides with nothing)
    was printed first, as the scene loaded before the backends were looked up."""
    assert cli_main([*command, "--backends", "ode,nosuch"]) == 2
    (line,) = capsys.readouterr().err.splitlines()
    assert line.startswith(f"x3drbp {command[0]}: unknown backend(s) nosuch; known: ")


def test_compare_exit_statuses_on_bad_usage_and_broken_scenes(tmp_path, capsys):
    assert cli_main(["compare", PENDULUM, "--backends", "nosuchengine,mujoco"]) == 2
    assert cli_main(["compare", PENDULUM, "--backends", "mujoco,mujoco"]) == 2  # one backend twice is one
    assert cli_main(["compare", PENDULUM, "--threshold", "position=-1"]) == 2
    assert cli_main(["compare", PENDULUM, "--threshold", "speed=1"]) == 2
    assert cli_main(["compare", PENDULUM, "--dt", "0"]) == 2
    capsys.readouterr()
    scene = tmp_path / "bad.x3dv"
    scene.write_text("#X3D V4.0 utf8\nRigidBody { mass 0 }\n")
    assert cli_main(["compare", str(scene)]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{scene}:2:" in err and "mass" in err and "Traceback" not in err
