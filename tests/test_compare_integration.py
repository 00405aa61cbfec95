"""Integration order (backends.base.Backend.integration): each backend's free fall lands where
its declared scheme puts it, pymunk's position-first steps part from the semi-implicit
engines' by g h^2 n, and `x3drbp compare`'s text says so for such a pair and only there."""

from __future__ import annotations

import json

import numpy as np
import pytest

from backends import base
from conformance.analyses.compare import compare_all
from x3drbp import main as cli_main
from conformance.results import RAN, BackendRun, Comparison
from conftest import case_scene
from reports.compare_text import render
from x3d_core.encodings.load import load
from x3d_core.semantics.evaluator import RunSettings, run
from x3d_core.semantics.world import worlds
from x3d_core.traces.trace import TraceView

H, G, Y0 = 1 / 240, 9.81, 10.0  # free_fall's step (the default), gravity and start height
THRESHOLDS = {"position": 1e-3, "orientation": 1e-3}


def _backend(name: str) -> base.Backend:
    try:
        return base.load(name)
    except ImportError as e:
        pytest.skip(f"{name}: {e}")


def _fall(backend: base.Backend, frame_rate: float, duration: float = 0.5) -> TraceView:
    """The free_fall case's trace on the backend, as its CSV's text reads back."""
    return TraceView(run(worlds(load(case_scene("free_fall"))), backend, RunSettings(duration, H, frame_rate)).rows)


SINGLE_PRECISION = ("physx",)
# error-controlled integration (drake: RK3 to a 1e-6 accuracy target where nothing collides):
# the parabola itself, which a third-order method integrates exactly whatever its target: rounding,
# and the trace's printed digits
ERROR_CONTROLLED = {"drake": 1e-8}


@pytest.mark.parametrize("name", base.IN_TREE)
def test_free_fall_lands_where_the_declared_integration_order_puts_it(name):
    """Semi-implicit Euler (v += h a, then x += h v): y_n = y0 - g h^2 n(n+1)/2; position first
    (x += h v, then v += h a): y_n = y0 - g h^2 n(n-1)/2. A frame a step, so n is the frame."""
    backend = _backend(name)
    view = _fall(backend, 1 / H)
    t, p = view.series("Ball", "position")
    n = np.rint(t / H)
    if name in ERROR_CONTROLLED:
        later, atol = 0, ERROR_CONTROLLED[name]
    else:
        later = {base.SEMI_IMPLICIT: 1, base.POSITION_FIRST: -1}[backend.integration]
        # PhysX holds its state in single precision: a second of fall rounds to ~1e-5 m
        atol = 3e-5 if name in SINGLE_PRECISION else 1e-12
    np.testing.assert_allclose(p[:, 1], Y0 - G * H * H * n * (n + later) / 2, rtol=0, atol=atol)


@pytest.fixture(scope="module")
def comparison() -> Comparison:
    """free_fall on pymunk, MuJoCo and Bullet at 60 frames/s, compared as `x3drbp compare` does."""
    ran = []
    for name in ("pymunk", "mujoco", "bullet"):
        b = _backend(name)
        ran.append((BackendRun(name, RAN, integration=b.integration), _fall(b, 60)))
    return Comparison("free_fall.x3d", 0.5, H, 60, THRESHOLDS, [r for r, _ in ran], compare_all(ran, THRESHOLDS))


def test_pymunk_parts_from_the_semi_implicit_engines_by_g_h2_per_step_and_they_agree_to_rounding(comparison):
    pymunk_mujoco, pymunk_bullet, mujoco_bullet = comparison.pairs
    for p in (pymunk_mujoco, pymunk_bullet):
        steps = np.rint(p.times / H)
        np.testing.assert_allclose(p.position.frame_max, G * H * H * steps, rtol=0, atol=1e-13)
        # 4 steps a frame: 0.68 mm at the first frame, 1.36 mm at the second
        assert p.position.first_over.time == pytest.approx(2 / 60)
        assert p.orientation.max == 0
    assert mujoco_bullet.position.max <= 1e-13 and mujoco_bullet.position.first_over is None


def test_pymunk_turns_dt_w_behind_under_a_constant_torque():
    """The same order for the turn: constant_torque's body spun up from rest is h |w - w0| behind
    (the note's figure for orientation), w as MuJoCo reads it."""
    views = {name: TraceView(run(worlds(load(case_scene("constant_torque"))), _backend(name),
                                 RunSettings(0.5, H, 60)).rows) for name in ("pymunk", "mujoco")}
    (p,) = compare_all([(BackendRun(n, RAN), v) for n, v in views.items()], THRESHOLDS)
    _, w = views["mujoco"].series("Spun", "angularVelocity")
    assert p.bodies == ["Spun"] and p.orientation.max > 1e-3
    np.testing.assert_allclose(p.orientation.frame_max, H * np.linalg.norm(w - w[0], axis=1), rtol=0, atol=1e-14)


def test_the_text_names_the_integration_order_for_a_pymunk_pair_only(comparison):
    text = render(comparison)
    order = ("steps by explicit Euler in position, {} by semi-implicit Euler: from that alone free "
             "motion parts from the first step, by dt |v - v0|")
    for other in ("mujoco", "bullet"):
        assert f"- pymunk / {other}: pymunk " + order.format(other) in text
    assert "g dt^2 = 0.00017 m more each step, 0.0408 m after 1 s" in text  # 9.8 / 240^2, 9.8 / 240
    assert "- mujoco / bullet" not in text
    assert text.count("from that alone") == 2


def test_no_note_where_a_backend_declares_no_integration(comparison):
    runs = [BackendRun(r.backend, r.verdict, integration=None if r.backend == "pymunk" else r.integration)
            for r in comparison.runs]
    c = Comparison(comparison.scene, comparison.duration, comparison.dt, comparison.frame_rate,
                   comparison.thresholds, runs, comparison.pairs)
    assert "from that alone" not in render(c)


def test_integration_round_trips_through_json_and_older_json_reads_as_undeclared(comparison):
    data = json.loads(json.dumps(comparison.to_json()))
    assert [r["integration"] for r in data["runs"]] == [base.POSITION_FIRST, base.SEMI_IMPLICIT, base.SEMI_IMPLICIT]
    assert Comparison.from_json(data).to_json() == data
    for r in data["runs"]:
        del r["integration"]
    assert [r.integration for r in Comparison.from_json(data).runs] == [None, None, None]


def test_x3drbp_compare_takes_each_backends_integration_from_the_probe(tmp_path, capsys):
    """End to end: the probe asks each backend its order, each run carries it into the JSON, and
    the text's note follows."""
    for name in ("pymunk", "mujoco"):
        _backend(name)
    out = tmp_path / "c.json"
    code = cli_main(["compare", case_scene("free_fall"), "--backends", "pymunk,mujoco", "--duration", "0.1",
                     "--json", str(out)])
    assert code == 0
    runs = json.loads(out.read_text())["runs"]
    assert [r["integration"] for r in runs] == [base.POSITION_FIRST, base.SEMI_IMPLICIT]
    assert "- pymunk / mujoco: pymunk steps by explicit Euler in position" in capsys.readouterr().out


def test_preferring_accuracy_changes_the_schemes_and_the_note_follows(tmp_path, capsys):
    """preferAccuracy TRUE: MuJoCo integrates by RK4, exact on a fall, and Bullet by semi-implicit
    Euler in 4 substeps, (h / 4) |v - v0| / 2 ahead of it: the runs say so and so does the note."""
    from conformance.analyses.sweep_job import with_collection_fields
    for name in ("mujoco", "bullet"):
        _backend(name)
    scene, out = tmp_path / "fall.x3d", tmp_path / "c.json"
    with_collection_fields(case_scene("free_fall"), str(scene), None, True)
    assert cli_main(["compare", str(scene), "--backends", "mujoco,bullet", "--duration", "0.5", "--frame-rate",
                     "240", "--json", str(out)]) == 0
    data = json.loads(out.read_text())
    assert [r["integration"] for r in data["runs"]] == [base.RK4, "semi-implicit Euler in 4 substeps"]
    assert ("mujoco steps by fourth-order Runge-Kutta, bullet by semi-implicit Euler in 4 substeps: from that alone "
            "free motion parts from the first step, by 0.125 dt |v - v0|") in capsys.readouterr().out
    pair = Comparison.from_json(data).pairs[0]
    np.testing.assert_allclose(pair.position.frame_max, 0.125 * H * G * pair.times, rtol=0, atol=1e-12)


def test_a_scheme_s_lead_counts_its_substeps():
    from x3d_core.semantics.integration import in_substeps, lead
    assert lead(base.SEMI_IMPLICIT) == 0.5 and lead(base.POSITION_FIRST) == -0.5 and lead(base.RK4) == 0.0
    assert lead(in_substeps(base.SEMI_IMPLICIT, 4)) == 0.125 and lead(in_substeps(base.RK4, 2)) == 0.0
    assert lead("velocity Verlet") is None and lead("velocity Verlet in 4 substeps") is None
