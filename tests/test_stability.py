"""The stability suite: its scenes, its monitors on synthetic traces, its verdicts for children
that crash or hang, and one real run through `x3drbp stability`."""

from __future__ import annotations

import json
import math
import sys

import numpy as np
import pytest

from conformance import results
from conformance.runner import children, probe
from conformance.analyses import stability as S
from x3d_core.traces.trace import TraceView
from x3drbp import main as cli_main
from x3d_core.encodings.load import load
from x3d_core.semantics.analysis import features
from x3d_core.semantics.world import worlds
from x3d_core.traces.trace import Row

from fake_child import fake_python

INFO = probe.backend_table()
INSTALLED = [n for n, i in INFO.items() if i.usable]
REFERENCE = "mujoco" if "mujoco" in INSTALLED else (INSTALLED[0] if INSTALLED else None)
G = 9.8


# -- the scenes ---------------------------------------------------------------------------

@pytest.mark.parametrize("case", S.CASES, ids=lambda c: c.name)
def test_scene_is_clean_and_has_what_its_monitors_read(case):
    scene = load(case.path)
    assert not scene.errors and not scene.warnings, [str(d) for d in scene.diagnostics]
    with open(case.path, encoding="utf-8") as f:
        assert f.read().lstrip().split("\n", 2)[1].startswith("<!-- Stability:"), "a leading comment says why"
    w = worlds(scene)[0]
    joints = {j.name: j for j in w.joints}
    for mon in case.monitors:
        for name in getattr(mon, "joints", ()):
            assert {"body1AnchorPoint", "body2AnchorPoint"} <= set(joints[name].outputs), name
        for name in (*getattr(mon, "bodies", ()), *[b for b in [getattr(mon, "body", None)] if b]):
            assert name in w.bodies.names


def _world(name: str):
    return worlds(load(S.BY_NAME[name].path))[0]


def test_chain_has_fifty_ball_joints_from_a_fixed_body_and_its_exchange():
    w = _world("ball_chain_50")
    balls = [j for j in w.joints if j.type == "BallJoint"]
    assert len(balls) >= 50 and len(S.BY_NAME["ball_chain_50"].monitors[1].joints) == len(balls)
    b = w.bodies
    assert b.fixed[b.names.index("Anchor")] and np.all(b.position[:, 1] == 0)  # released horizontal
    # hanging straight down, each link's centre ends its distance from the anchor below it
    assert S.CHAIN_EXCHANGE == pytest.approx(G * float(b.mass @ np.linalg.norm(b.position, axis=1)), rel=1e-12)


def test_mass_ratios_are_one_to_a_thousand():
    w = _world("mass_ratio_pendulum")
    b = w.bodies
    m = dict(zip(b.names, b.mass))
    wrist = next(j for j in w.joints if j.name == "Wrist")
    assert {b.names[wrist.body1], b.names[wrist.body2]} == {"Bob", "Arm"} and m["Bob"] / m["Arm"] == 1000
    assert S.PENDULUM_EXCHANGE == pytest.approx(G * float(b.mass @ np.linalg.norm(b.position, axis=1)), rel=1e-12)
    b = _world("mass_ratio_stack").bodies
    m = dict(zip(b.names, b.mass))
    assert m["Heavy"] / m["Light"] == 1000 and b.position[b.names.index("Heavy"), 1] > b.position[
        b.names.index("Light"), 1]


def test_box_stack_has_ten_boxes_and_watches_the_top_one():
    b = _world("box_stack_10").bodies
    assert len(b) >= 10
    top = b.names[int(np.argmax(b.position[:, 1]))]
    assert S.BY_NAME["box_stack_10"].monitors[0].body == top


def test_wheels_spin_fast_with_and_without_finite_rotation():
    w = _world("spinning_wheel_finite")
    b = w.bodies
    assert not w.gravity.any()
    for case, finite in (("spinning_wheel_finite", True), ("spinning_wheel_plain", False)):
        (name,) = S.BY_NAME[case].monitors[0].bodies
        i = b.names.index(name)
        spin_axis = np.argmax(np.diag(b.inertia[i]))
        assert abs(b.angular_velocity[i, spin_axis]) >= 100 and b.finite_rotation[i] == finite
        assert 0 < np.linalg.norm(np.delete(b.angular_velocity[i], spin_axis)) < 0.05 * 150  # a slight wobble
    assert "RigidBody.useFiniteRotation" in features(load(S.BY_NAME["spinning_wheel_finite"].path))


def test_tumble_spins_about_the_intermediate_axis_for_30_s():
    case = S.BY_NAME["intermediate_axis_tumble"]
    b = _world(case.name).bodies
    ev = np.diag(b.inertia[0])
    middle = int(np.argsort(ev)[1])
    w = b.angular_velocity[0]
    assert abs(w[middle]) > 100 * np.linalg.norm(np.delete(w, middle)) and case.duration >= 30


def test_impact_start_puts_no_step_end_in_the_walls_near_half():
    """At 1/60, 1/240 and 1/1000 no step ends with the centre in -0.04 < x < 0, so an engine
    that stops the pellet found the wall between step ends (the scene's comment)."""
    b = _world("thin_wall_impact").bodies
    x0, v = b.position[0, 0], b.linear_velocity[0, 0]
    assert v >= 50
    for dt in (1 / 60, 1 / 240, 1 / 1000):
        x = x0 + v * dt * np.arange(200)
        assert not np.any((x > -0.04) & (x < 0)), dt


def test_four_bar_closes_a_loop_and_its_exchange():
    w = _world("four_bar_linkage")
    assert [w.joints[k].name for k in w.loop_joints] == ["PinC"]
    b = w.bodies
    length = {n: float(m) for n, m in zip(b.names, b.mass)}  # 1 kg per metre
    a, d = np.array([0.0, 0.0]), np.array([0.6, 0.0])
    pe = []
    for th in np.linspace(0, 2 * math.pi, 20001):
        pb = a + length["Crank"] * np.array([math.cos(th), math.sin(th)])
        dist = np.linalg.norm(d - pb)
        along = (length["Coupler"] ** 2 - length["Rocker"] ** 2 + dist ** 2) / (2 * dist)
        u = (d - pb) / dist
        pc = pb + along * u + math.sqrt(length["Coupler"] ** 2 - along ** 2) * np.array([-u[1], u[0]])
        pe.append(G * (length["Crank"] * pb[1] + length["Coupler"] * (pb[1] + pc[1]) + length["Rocker"] * pc[1]) / 2)
    start = G * float(b.mass @ b.position[:, 1])
    assert start == pytest.approx(pe[5000], abs=1e-9)  # the crank upright
    assert S.FOUR_BAR_EXCHANGE == pytest.approx(start - min(pe), abs=1e-3)


# -- the monitors on synthetic traces -----------------------------------------------------

def _pendulum_rows(times: np.ndarray, gain: np.ndarray) -> list[Row]:
    """Mass_ratio_pendulum's bodies at rest where they start, but Bob moving at the speed that
    gives the energy `gain` (J); the joints as written, their gap growing with time."""
    rows = []
    for t, e in zip(times.tolist(), gain.tolist()):
        speed = math.sqrt(2 * e / 100.0)
        rows += [Row(t, "Arm", "position", "0.5 0 0"), Row(t, "Arm", "orientation", "0 0 1 0"),
                 Row(t, "Arm", "linearVelocity", "0 0 0"), Row(t, "Arm", "angularVelocity", "0 0 0"),
                 Row(t, "Bob", "position", "1.1 0 0"), Row(t, "Bob", "orientation", "0 0 1 0"),
                 Row(t, "Bob", "linearVelocity", f"0 {speed!r} 0"), Row(t, "Bob", "angularVelocity", "0 0 0"),
                 Row(t, "Shoulder", "body1AnchorPoint", "0 0 0"), Row(t, "Shoulder", "body2AnchorPoint", "0 0 0"),
                 Row(t, "Wrist", "body1AnchorPoint", "1 0 0"),
                 Row(t, "Wrist", "body2AnchorPoint", f"1 {0.004 * t!r} 0")]
    return rows


def test_energy_growth_and_joint_drift_found_at_their_first_frame():
    case = S.BY_NAME["mass_ratio_pendulum"]
    m = S.model(case.path)
    times = np.arange(0, 601) / 60
    gain = np.where(times > 1.0, 0.2 * S.PENDULUM_EXCHANGE, 0.0)  # 20% from the first frame after 1 s
    verdict, at, reason, figures = S.judge(case, TraceView(_pendulum_rows(times, gain)), m)
    assert verdict == S.ENERGY and at == pytest.approx(61 / 60) and "energy gain" in reason
    by = {f.quantity.split(" over")[0]: f for f in figures}
    assert by["energy gain"].value == pytest.approx(20.0) and by["energy gain"].bound == 10.0
    gap = by["anchor gap"]  # 4 mm/s: past 1 cm after 2.5 s, Wrist the worst joint
    assert gap.value == pytest.approx(0.04) and gap.where == "Wrist" and gap.at == pytest.approx(151 / 60)
    quiet = TraceView([r for r in _pendulum_rows(times[:120], np.zeros(120))])
    assert S.judge(case, quiet, m)[:2] == (S.SURVIVED, None)  # a gap of 4.7 mm holds


def test_joint_drift_first_wins_and_a_non_finite_value_is_past_its_bound():
    case = S.BY_NAME["mass_ratio_pendulum"]
    m = S.model(case.path)
    times = np.arange(0, 301) / 60
    gain = np.where(times >= 4.5, math.inf, 0.0)
    verdict, at, reason, figures = S.judge(case, TraceView(_pendulum_rows(times, gain)), m)
    assert verdict == S.JOINT and at == pytest.approx(151 / 60) and "Wrist" in reason
    energy = next(f for f in figures if f.quantity.startswith("energy gain"))
    assert math.isinf(energy.value) and energy.at == pytest.approx(4.5)
    assert S.first_past(times, np.where(times > 1, math.nan, 0.0), 1.0) == pytest.approx(61 / 60)


def test_displacement_and_tunnelling():
    times = [0.0, 0.5, 1.0]
    rows = [Row(t, "Box10", "position", f"{x} 1.9 0") for t, x in zip(times, (0.0, 0.012, 0.003))]
    (worst, end) = S.Displacement("Box10").read(TraceView(rows), None)
    assert (worst.value, worst.at, end.value, end.bound) == (pytest.approx(0.012), 0.5, pytest.approx(0.003), None)
    case = S.BY_NAME["thin_wall_impact"]
    m = S.model(case.path)

    def pellet(xs, vs):
        return TraceView([Row(t, "Pellet", f, v) for t, x, u in zip(times, xs, vs) for f, v in (
            ("position", f"{x} 0 0"), ("orientation", "0 0 1 0"), ("linearVelocity", f"{u} 0 0"),
            ("angularVelocity", "0 0 0"))])
    assert S.judge(case, pellet((-1.1, 0.233, 40.0), (80, 80, 80)), m)[:2] == (S.TUNNELLED, 0.5)
    assert S.judge(case, pellet((-1.1, -0.03, -0.03), (80, 0, 0)), m)[:2] == (S.STOPPED, None)
    assert S.judge(case, pellet((-1.1, -0.03, -0.5), (80, -81, -81)), m)[:2] == (S.ENERGY, 0.5)


# -- children that do not finish -------------------------------------------------------------

@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals and shell scripts")
def test_a_crashing_child_is_a_verdict_and_the_rest_still_runs(tmp_path, monkeypatch):
    if REFERENCE is None:
        pytest.skip("no backend is installed")
    monkeypatch.setattr(children.sys, "executable", fake_python(tmp_path, f"""case "$*" in
  *spinning_wheels*) kill -SEGV $$ ;;
  *) exec {sys.executable} "$@" ;;
esac
"""))
    cases = [S.BY_NAME["spinning_wheel_finite"], S.BY_NAME["thin_wall_impact"]]
    crashed, real = S.run_suite(cases, [REFERENCE], [1 / 60])
    assert crashed.verdict == results.CRASHED and "SIGSEGV" in crashed.reason and not crashed.figures
    assert real.verdict in (S.TUNNELLED, S.STOPPED) and real.figures


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals and shell scripts")
def test_cases_of_one_scene_share_its_run_and_the_finer_step_runs_first(tmp_path, monkeypatch):
    """The two spinning-wheel cases watch two wheels of one scene: it runs once a backend and step
    (it ran twice, 44 s of Drake's runs), judged by each case's monitors; the finer step first."""
    if REFERENCE is None:
        pytest.skip("no backend is installed")
    log = tmp_path / "runs.log"
    monkeypatch.setattr(children.sys, "executable", fake_python(tmp_path, f"""echo "$*" >> '{log}'
exec {sys.executable} "$@"
"""))
    finite, plain = S.BY_NAME["spinning_wheel_finite"], S.BY_NAME["spinning_wheel_plain"]
    got = S.run_suite([finite, plain], [REFERENCE], [1 / 60, 1 / 240], workers=1)
    runs = log.read_text().splitlines()
    assert [float(r.split(" --dt ")[1].split()[0]) for r in runs] == [1 / 240, 1 / 60]
    assert all("spinning_wheels.x3d" in r for r in runs)
    assert [(r.case, r.dt) for r in got] == [(c.name, dt) for c in (finite, plain) for dt in (1 / 60, 1 / 240)]
    for f, p in zip(got[:2], got[2:]):  # one run, judged by each case's monitors (its wheel's energy, momentum)
        if f.verdict in (S.SURVIVED, S.ENERGY, S.MOMENTUM):
            assert len(f.figures) == len(p.figures) == 3 and f.figures != p.figures
        else:  # what ended the run ended it for both
            assert (p.verdict, p.reason, p.at) == (f.verdict, f.reason, f.at) and f.reason


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals and shell scripts")
@pytest.mark.parametrize("script,verdict,at", [
    ("sleep 30\n", results.TIMED_OUT, None),
    ("echo 's.x3d: fake: blew up by t=0.35: MuJoCo found a huge acceleration' >&2; exit 1\n", results.BLEW_UP, 0.35),
    ("echo 's.x3d: unsupported by fake: not planar' >&2; exit 3\n", results.UNSUPPORTED, None),
])
def test_children_that_do_not_finish_keep_their_verdict(tmp_path, monkeypatch, script, verdict, at):
    monkeypatch.setattr(children.sys, "executable", fake_python(tmp_path, script))
    r = S.run_one(S.BY_NAME["thin_wall_impact"], "fake", 1 / 60, timeout=0.5)
    assert (r.verdict, r.at) == (verdict, at) and r.reason


# -- the command ------------------------------------------------------------------------------

def test_command_writes_json_and_markdown(tmp_path, capsys):
    if REFERENCE is None:
        pytest.skip("no backend is installed")
    out = tmp_path / "stab"
    assert cli_main(["stability", "--cases", "thin_wall_impact,intermediate_axis_tumble", "--backends", REFERENCE,
                     "--dts", "1/240", "--out", str(out)]) == 0
    data = json.loads((out / "stability.json").read_text())
    assert data["dts"] == [{"dt": 1 / 240, "label": "1/240"}] and data["backends"][REFERENCE]["run"]
    assert [(r["case"], r["backend"]) for r in data["results"]] == [("thin_wall_impact", REFERENCE),
                                                                    ("intermediate_axis_tumble", REFERENCE)]
    for r in data["results"]:
        assert r["verdict"] in (S.SURVIVED, S.STOPPED, S.TUNNELLED, S.ENERGY, S.MOMENTUM), r
        assert r["figures"] and all(isinstance(f["value"], float) for f in r["figures"])
    text = (out / "stability.md").read_text()
    assert text in capsys.readouterr().out
    assert f"| case | dt | {REFERENCE} |" in text and "| thin_wall_impact | 1/240 |" in text
    assert "### intermediate_axis_tumble" in text and "angular momentum drift" in text


@pytest.mark.parametrize("dts, says", [
    ("1/0", "--dts must be positive steps in seconds, as 1/240 or 0.004, not '1/0'"),  # was "Fraction(1, 0)"
    ("abc", "--dts must be positive steps in seconds, as 1/240 or 0.004, not 'abc'"),
    (",", "--dts names no step: ','"),  # ran the default steps
    # ran every case to be refused in its child, then stopped on a trace name 300 digits long
    ("1e-300", "mass_ratio_pendulum: 10 s at a step of 1e-300 s makes 1e+301 steps; a run takes at most 1e+09"),
])
def test_a_bad_step_is_bad_usage_before_any_run(dts, says, tmp_path, capsys):
    if REFERENCE is None:
        pytest.skip("no backend is installed")
    out = tmp_path / "stab"
    assert cli_main(["stability", "--cases", "mass_ratio_pendulum", "--backends", REFERENCE, "--dts", dts,
                     "--out", str(out), "-q"]) == 2
    assert capsys.readouterr().err == f"x3drbp stability: {says}\n"
    assert not out.exists()


@pytest.mark.parametrize("backend", ["physx", "drake"])
def test_the_newer_engines_get_verdicts_with_their_reasons(tmp_path, backend):
    """PhysX and Drake run the hard cases as every engine does: the free tumble's angular momentum
    has a closed form (conserved), and Drake, integrating to its default 1e-6 accuracy target where nothing
    collides, holds it to far under the 1% bound; a loop of joints is refused by name on Drake's tree."""
    if backend not in INSTALLED:
        pytest.skip(f"{backend} is not installed: {INFO[backend].unavailable}")
    out = tmp_path / "stab"
    assert cli_main(["stability", "--cases", "intermediate_axis_tumble,four_bar_linkage", "--backends", backend,
                     "--dts", "1/60", "--out", str(out), "-q"]) == 0
    got = {r["case"]: r for r in json.loads((out / "stability.json").read_text())["results"]}
    tumble, loop = got["intermediate_axis_tumble"], got["four_bar_linkage"]
    assert tumble["verdict"] in (S.SURVIVED, S.MOMENTUM, S.ENERGY) and tumble["figures"], tumble
    if backend == "drake":
        drift = next(f["value"] for f in tumble["figures"] if "angular momentum" in f["quantity"])
        # % of |L0|: a 1e-6 relative accuracy a step, added up over 30 s of 1/60 s steps, is 1.8e-3 of |L0|
        assert tumble["verdict"] == S.SURVIVED and drift < 0.18, tumble
        assert loop["verdict"] == results.UNSUPPORTED and "closes a loop" in loop["reason"], loop
    else:
        assert loop["verdict"] in (S.SURVIVED, S.ENERGY, S.JOINT), loop  # PhysX's D6 joints close loops


def test_command_usage_errors():
    assert cli_main(["stability", "--cases", "no_such_case"]) == 2
    assert cli_main(["stability", "--dts", "1/0"]) == 2
    assert cli_main(["stability", "--backends", "no_such_engine", "--cases", "thin_wall_impact"]) == 2
