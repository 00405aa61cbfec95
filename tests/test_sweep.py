"""The sweep: its measures on synthetic data, the scene rewrite, a real tiny sweep through the
command, and the same numbers from a Dask cluster as from the local pool."""

from __future__ import annotations

import json
import socket

import numpy as np
import pytest
from conftest import case_scene

from conformance import results
from conformance.analyses import sweep as S
from x3drbp import main as cli_main
from conformance.analyses.sweep_job import with_collection_fields
from conformance.analyses.sweep_metrics import Cost, Positions, comparison_interval, pareto, window_error
from x3d_core.encodings.load import load

BACKEND = "mujoco"  # a dependency, installed wherever the project is


def _exact(*costs: float | None) -> list[Cost | None]:
    return [None if c is None else Cost(c, c, c) for c in costs]


def test_pareto_front_is_exact_without_spread_or_tolerance():
    costs = _exact(1.0, 2.0, 3.0, 2.0, 4.0, 1.0, None, 0.5, 3.0)
    errors = [5.0, 2.0, 1.0, 3.0, 1.0, 5.0, 0.1, None, float("nan")]
    # 0 and 5 are equal: one front point, 0 standing for both; 3 is as fast as 1 but less
    # accurate; 4 as accurate as 2 but slower; 6, 7, 8 lack a finite cost or error
    assert pareto(costs, errors) == [0, 1, 2, None, None, 0, None, None, None]
    assert pareto([], []) == []
    assert pareto(_exact(1.0, 1.0), [2.0, 1.0]) == [None, 1]  # equal speed: the more accurate one only


def test_fronts_rank_by_cpu_time_which_load_does_not_reorder():
    """Under a busy machine a run's wall time stretches while its CPU time stays: the run whose
    wall time a neighbour stretched is still the faster one on the front."""
    quiet = S.Point("s", "bullet", 1 / 60, None, None, error=0.1, wall_per_sim_s=0.004, wall_low=0.004,
                    wall_high=0.004, cpu_per_sim_s=0.003, cpu_low=0.003, cpu_high=0.003)
    busy = S.Point("s", "mujoco", 1 / 60, None, None, error=0.1, wall_per_sim_s=0.009, wall_low=0.009,
                   wall_high=0.009, cpu_per_sim_s=0.001, cpu_low=0.001, cpu_high=0.001)
    S.mark_pareto([quiet, busy])
    assert busy.pareto_scene and not quiet.pareto_scene and busy.cost.median == 0.001 and busy.wall.median == 0.009


def test_pareto_merges_ties_within_the_spread_and_the_reference_error():
    # pymunk's 10 and 50 iterations of free motion: errors apart by rounding, speeds within
    # each other's spread: one front point, the faster median standing for both
    assert pareto([Cost(1.0, 0.9, 1.2), Cost(1.1, 0.95, 1.3)], [0.25, 0.25 - 1e-17]) == [0, 0]
    # the same errors, the second slower beyond both spreads: it is off the front
    assert pareto([Cost(1.0, 0.9, 1.1), Cost(2.0, 1.9, 2.1)], [0.25, 0.25 - 1e-17]) == [0, None]
    # without the merge the slower would sit on the front by the 17th digit
    assert pareto(_exact(1.0, 2.0), [0.25, 0.25 - 1e-6]) == [0, 1]
    # errors apart by less than the reference's own error tie; by more, they do not
    assert pareto(_exact(1.0, 2.0), [0.25, 0.24], tolerance=0.02) == [0, None]
    assert pareto(_exact(1.0, 2.0), [0.25, 0.2], tolerance=0.02) == [0, 1]
    # more accurate beyond the tolerance and no slower within the spread: both stay (neither
    # is faster by median and as accurate)
    assert pareto([Cost(1.0, 0.5, 1.5), Cost(1.2, 0.9, 1.3)], [1.0, 0.1]) == [0, 1]


def test_cost_is_the_median_and_spread_of_the_repeats():
    c = Cost.of([3.0, 1.0, 2.0])
    assert (c.median, c.low, c.high) == (2.0, 1.0, 3.0)
    assert c.ties(Cost(3.5, 3.0, 4.0)) and not c.ties(Cost(3.5, 3.1, 4.0))


def _positions(times, values, bodies=("A", "B")) -> Positions:
    return Positions(np.asarray(times, dtype=float), tuple(bodies), np.asarray(values, dtype=float))


def test_window_error_compares_shared_frames_within_the_window():
    ref_times = np.arange(0, 21) * 0.05
    ref = _positions(ref_times, np.zeros((21, 2, 3)))
    run_values = np.zeros((21, 2, 3))
    run_values[4, 1] = [0.3, 0.4, 0.0]  # body B 0.5 m off at t = 0.2
    run_values[20, 0] = [10.0, 0.0, 0.0]  # beyond a 0.5 s window: not error
    run = _positions(ref_times, run_values)
    assert window_error(run, ref, 0.5) == pytest.approx(0.5)
    assert window_error(run, ref, 1.0) == pytest.approx(10.0)
    # a run sampled every other frame, times off by rounding, meets the reference where both recorded
    sparse = _positions(ref_times[::2] + 1e-12, run_values[::2])
    assert window_error(sparse, ref, 0.5) == pytest.approx(0.5)
    with pytest.raises(ValueError, match="different bodies"):
        window_error(_positions(ref_times, run_values, ("A", "C")), ref, 0.5)
    with pytest.raises(ValueError, match="no frame"):
        window_error(_positions(ref_times + 0.01, run_values), ref, 0.5)


def test_comparison_interval_is_a_whole_number_of_every_step():
    assert comparison_interval([1 / 60, 1 / 240, 1 / 1000, 1 / 4000, 1 / 32000]) == pytest.approx(0.05)
    assert comparison_interval([1 / 240]) == pytest.approx(1 / 60)  # never finer than a display frame
    assert comparison_interval([1 / 7, 1 / 60]) == pytest.approx(1.0)
    with pytest.raises(ValueError, match="window"):
        S.targets(["bounce_apex"], [1 / 7, 1 / 60], window=0.5)


def test_scene_rewrite_sets_every_collection(tmp_path):
    out = tmp_path / "bounce.x3d"
    with_collection_fields(case_scene("bounce_apex"), str(out), 50, True)
    collections = load(str(out)).of_type("RigidBodyCollection")
    assert len(collections) == 3
    assert all(c.get("iterations") == 50 and c.get("preferAccuracy") is True for c in collections)
    with_collection_fields(case_scene("ball_chain"), str(out), None, True)  # iterations='20' kept
    (chain,) = load(str(out)).of_type("RigidBodyCollection")
    assert chain.get("iterations") == 20 and chain.get("preferAccuracy") is True


def test_targets_pick_the_reference():
    dts = [1 / 60, 1 / 240]
    closed, contact, scene = S.targets(["pendulum_period", "bounce_apex",
                                        case_scene("double_pendulum_energy")], dts)
    assert (closed.reference, closed.quantity, closed.settings.duration) == (S.CLOSED_FORM, "Bob.period", 2.0)
    assert (contact.reference, contact.case, contact.settings.frame_rate) == (S.COMMON, None, 60.0)
    assert (scene.name, scene.scene) == ("double_pendulum_energy",
                                         "conformance/cases/double_pendulum_energy/double_pendulum_energy.x3d")
    with pytest.raises(ValueError, match="neither a case"):
        S.targets(["no_such_thing"], dts)
    # two scene files of one stem: their plots (sweep_NAME.png) must not overwrite each other
    twins = S.targets([case_scene("free_fall"), case_scene("free_fall")], dts)
    assert [t.name for t in twins] == ["free_fall", "free_fall-2"]
    with pytest.raises(ValueError, match="several runs"):
        S.targets(["frame_rate"], dts)


def test_the_default_scenes_are_found_from_any_folder(tmp_path, monkeypatch):
    # run from another folder, the default's bundled scene file was "neither a case nor a scene file"
    monkeypatch.chdir(tmp_path)
    chosen = S.targets(list(S.DEFAULT_SCENES), [1 / 60, 1 / 240])
    assert [t.name for t in chosen] == ["pendulum_period", "projectile", "bounce_apex", "double_pendulum_energy"]
    assert chosen[-1].scene == "conformance/cases/double_pendulum_energy/double_pendulum_energy.x3d"


def test_sweep_command_writes_json_markdown_and_plot(tmp_path):
    out = tmp_path / "sweep"
    assert cli_main(["sweep", "--scenes", "projectile", "--backends", BACKEND, "--dts", "1/60,1/240",
                     "--iterations", "10", "--accuracy", "false", "--out", str(out), "--workers", "2", "-q"]) == 0
    doc = json.loads((out / "sweep.json").read_text())
    assert doc["scenes"][0]["reference"] == S.CLOSED_FORM and doc["scenes"][0]["unit"] == "m"
    points = doc["points"]
    assert [(p["dt_label"], p["iterations"], p["prefer_accuracy"]) for p in points] == \
        [("1/60", 10, False), ("1/240", 10, False)]
    assert all(p["verdict"] == results.PASS and 0 < p["wall_per_sim_s"] < p["simulation_per_sim_s"] for p in points)
    assert all(p["wall_low"] <= p["wall_per_sim_s"] <= p["wall_high"] for p in points)
    assert all(0 < p["cpu_low"] <= p["cpu_per_sim_s"] <= p["cpu_high"] for p in points)
    assert doc["settings"]["repeats"] == S.REPEATS
    assert [p["timed"] for p in points] == [S.REPEATS] * 2  # both head the front: the table states their speeds
    # semi-implicit Euler's position error is first order: a quarter of the step, a quarter of the error
    assert points[1]["error"] / points[0]["error"] == pytest.approx(0.25, rel=0.05)
    assert points[1]["pareto_scene"] or points[0]["pareto_scene"]
    text = (out / "sweep.md").read_text()
    assert "## projectile" in text and "| mujoco | 1/240 | 10 | FALSE |" in text and "Reference: closed form" in text
    png = (out / "sweep_projectile.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 1000
    assert cli_main(["sweep", "--scenes", "no_such_case", "--out", str(out), "-q"]) == 2
    assert cli_main(["sweep", "--backends", "no_such_engine", "--out", str(out), "-q"]) == 2


def test_dask_cluster_gives_the_local_pool_s_numbers():
    distributed = pytest.importorskip("distributed")
    chosen = S.targets(["projectile", case_scene("double_pendulum_energy")], [1 / 60, 1 / 240])
    plans, _ = S.backend_plans([BACKEND])

    def errors(scheduler: str | None) -> list:
        sweep = S.run_sweep(chosen, plans, [1 / 60, 1 / 240], [10], [False], scheduler=scheduler, workers=2)
        return [(p.scene, p.dt, p.verdict, p.error) for p in sweep.points]

    local = errors(None)
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None,
                                  silence_logs=50) as cluster:
        assert errors(cluster.scheduler_address) == local
    assert all(e is not None and e > 0 for *_, e in local)


def test_common_reference_is_the_first_fine_run_of_the_order_with_its_own_error():
    times = np.array([0.0, 0.5, 1.0])

    def ran(offset: float) -> S.JobResult:
        return S.JobResult("measured", positions=_positions(times, np.full((3, 2, 3), offset)))

    job = S.Job("scene.x3d", "x", results.Settings(1.0, 1 / 8000))
    plans = {b: S.BackendPlan(b, "1", True, True) for b in ("bullet", "mujoco", "ode")}
    fine = {("s", "mujoco"): (job, ran(0.0), ran(0.3)),  # refining moves it 0.3 m: its own error, stated
            ("s", "ode"): (job, ran(1.0), ran(1.01)),
            ("s", "bullet"): (job, ran(2.0), S.JobResult("blew up", "at t=0.1"))}
    ref = S.common_reference("s", plans, fine)
    assert (ref.backend, ref.error) == ("mujoco", pytest.approx(0.3 * np.sqrt(3)))
    fine[("s", "mujoco")] = (job, ran(0.0), S.JobResult("timed out"))  # its check did not end: the next
    assert S.common_reference("s", plans, fine).backend == "ode"
    fine = {k: (job, S.JobResult("crashed", "signal 11"), v[2]) for k, v in fine.items()}
    why = S.common_reference("s", plans, fine)
    assert isinstance(why, str) and "mujoco: crashed (signal 11)" in why and "bullet: crashed" in why


def test_without_drake_every_backend_is_measured_against_one_fine_run(tmp_path):
    chosen = S.targets([case_scene("double_pendulum_energy")], [1 / 60, 1 / 240])
    plans, _ = S.backend_plans([BACKEND, "bullet"])
    sweep = S.run_sweep(chosen, plans, [1 / 60, 1 / 240], [], [], workers=2, repeats=2, controlled=False)
    ref = sweep.references["double_pendulum_energy"]
    assert ref.backend in plans and ref.error >= 0 and ref.dt == pytest.approx(1 / 1920)
    assert ref.method == S.FINE_RUN and ref.instead == "the drake backend is not available" and not sweep.controlled
    for p in sweep.points:
        assert p.verdict == "measured" and p.iterations is None and p.prefer_accuracy is None
        # the reference backend's points: its own fine run is the common reference
        assert (p.error == p.self_error) == (p.backend == ref.backend)
        assert p.wall_low <= p.wall_per_sim_s <= p.wall_high and p.cost.low <= p.cost.median <= p.cost.high
    assert any(p.pareto_scene for p in sweep.points)
    assert set(sweep.positions) == {("double_pendulum_energy", b, dt) for b in plans for dt in (1 / 60, 1 / 240)}


@pytest.mark.parametrize("text, said", [
    ("<X3D><Scene><RigidBodyCollection><RigidBody mass='abc'/></RigidBodyCollection></Scene></X3D>",
     ":1:45: error: RigidBody.mass: 'abc' is not a number"),
    ("<X3D><Scene><RigidBodyCollection><RigidBody mass=", ":1:"),  # malformed XML: was a traceback
])
def test_a_scene_file_that_does_not_load_is_said_before_any_run(text, said, tmp_path, capsys):
    # a bad field value ran every point to fail alike, then "no results" and exit 0
    scene = tmp_path / "bad scene.x3d"
    scene.write_text(text)
    out = tmp_path / "sweep"
    assert cli_main(["sweep", "--scenes", f"projectile,{scene}", "--backends", BACKEND, "--dts", "1/60,1/240",
                     "--out", str(out), "-q"]) == 1
    err = capsys.readouterr().err
    assert err.startswith(f"{scene}{said}") and err.count("\n") == 1 and "Traceback" not in err, err
    assert not out.exists()


@pytest.mark.parametrize("value", ["-1", "abc", "1.5", "2147483648", ","])
def test_iterations_out_of_range_are_a_usage_error(value, tmp_path, capsys):
    # -1 ran every point to fail alike and exited 0; 'abc' said int()'s own words
    assert cli_main(["sweep", "--scenes", "projectile", "--backends", BACKEND, "--iterations", value,
                     "--out", str(tmp_path / "sweep"), "-q"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("x3drbp sweep: --iterations ") and repr(value) in err, err
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("value, says", [
    ("1/0", "--dts must be positive steps in seconds, as 1/240 or 0.004, not '1/0'"),  # "a step divides by zero"
    ("abc", "--dts must be positive steps in seconds, as 1/240 or 0.004, not 'abc'"),  # Fraction's own words
    ("1/60,-1", "--dts must be positive steps in seconds, as 1/240 or 0.004, not '-1'"),  # named no value
    ("1e400", "--dts must be positive steps in seconds, as 1/240 or 0.004, not '1e400'"),  # OverflowError
    ("1e-300,1/60", "a step of 1e-300 s is finer than 1e-9 s, the resolution at which steps are compared"),  # "no steps"
])
def test_a_bad_step_is_a_usage_error_naming_it(value, says, tmp_path, capsys):
    assert cli_main(["sweep", "--scenes", "projectile", "--backends", BACKEND, "--dts", value,
                     "--out", str(tmp_path / "sweep"), "-q"]) == 2
    assert capsys.readouterr().err == f"x3drbp sweep: {says}\n"
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("address", ["garbage", "tcp://host", "tcp://host:http", "ftp://host:21", "tcp://:8786",
                                     "tcp://host:70000"])
def test_a_scheduler_address_that_is_none_is_a_usage_error(address, tmp_path, capsys):
    assert cli_main(["sweep", "--scheduler", address, "--out", str(tmp_path), "-q"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"x3drbp sweep: --scheduler {address!r} is not") and \
        "SCHEME://HOST:PORT" in err, err
    assert not list(tmp_path.iterdir())


def test_an_unreachable_scheduler_fails_within_the_connect_timeout(tmp_path, monkeypatch, capsys):
    pytest.importorskip("distributed")
    from conformance.analyses import distribute
    monkeypatch.setattr(distribute, "CONNECT_TIMEOUT", 1.0)
    with socket.socket() as s:  # bound, never listening: every connection is refused
        s.bind(("127.0.0.1", 0))
        address = f"tcp://127.0.0.1:{s.getsockname()[1]}"
        code = cli_main(["sweep", "--scheduler", address, "--scenes", "projectile", "--backends", BACKEND,
                         "--dts", "1/60", "--iterations", "10", "--accuracy", "false", "--out", str(tmp_path), "-q"])
    assert code == 1
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert last.startswith(f"x3drbp sweep: cannot reach the Dask scheduler at {address} within 1 s"), last


DROP = """<X3D profile='Full' version='4.0'><Scene>
<RigidBodyCollection DEF='World' gravity='0 -9.81 0'>
  <RigidBody DEF='Box' mass='1' position='0 0.4 0' inertia='0.00667 0 0 0 0.00667 0 0 0 0.00667'>
    <CollidableShape DEF='BoxShape' containerField='geometry'>
      <Shape containerField='shape'><Box size='0.2 0.2 0.2'/></Shape>
    </CollidableShape>
  </RigidBody>
  <CollisionCollection containerField='collider'>
    <CollidableShape containerField='collidables' USE='BoxShape'/>
    <CollidableShape containerField='collidables' DEF='Floor' translation='0 -0.1 0'>
      <Shape containerField='shape'><Box size='2 0.2 2'/></Shape>
    </CollidableShape>
  </CollisionCollection>
</RigidBodyCollection></Scene></X3D>
"""  # a box dropped 0.3 m onto a floor, no bounce: Drake runs it, in its discrete (fixed-step) mode


def _drake() -> None:
    pytest.importorskip("pydrake")


def test_a_joint_scene_is_measured_against_drake_s_error_controlled_reference():
    _drake()
    dts = [1 / 60, 1 / 240]
    chosen = S.targets([case_scene("double_pendulum_energy")], dts)
    plans, _ = S.backend_plans([BACKEND])  # drake is not compared: its reference is run all the same
    sweep = S.run_sweep(chosen, plans, dts, [], [], workers=2, repeats=1)
    ref = sweep.references["double_pendulum_energy"]
    assert (ref.method, ref.backend, ref.dt) == (S.ERROR_CONTROLLED, "drake", pytest.approx(1 / 240))
    assert ref.accuracy == pytest.approx(1e-11)  # the child's word: preferAccuracy TRUE, every world continuous
    # its own error: the distance from the run at the 1e5x looser target 1e-6, which error control holds
    # near that target (relative, on positions of order 1 m): within 10x of it over the 1 s window, and
    # not nothing (two targets 1e5x apart give two runs)
    assert 0 < ref.own_error < 1e-5
    assert "error-controlled RK3 at target accuracy 1e-11" in ref.said and "1e-06" in ref.said
    # two independent engines converge to one motion: MuJoCo's fine run (RK4 at 1/1920) lies within the
    # sum of the two runs' stated own errors of Drake's reference
    _, fine, check = sweep.fine[("double_pendulum_energy", BACKEND)]
    mujoco_own = window_error(check.positions, fine.positions, 1.0)
    assert window_error(fine.positions, ref.runs, 1.0) <= mujoco_own + ref.own_error
    coarse, finer = sorted(sweep.points, key=lambda p: -p.dt)
    for p in (coarse, finer):  # each point measured against Drake's run, not its own engine's
        assert p.error == window_error(sweep.positions[("double_pendulum_energy", BACKEND, p.dt)], ref.runs, 1.0)
    # MuJoCo's default semi-implicit Euler is first order: a quarter of the step, a quarter of the error,
    # against a reference whose stated own error is some 1e5 times under either's error
    assert finer.error / coarse.error == pytest.approx(0.25, rel=0.05)
    assert ref.own_error < 1e-4 * finer.error


def test_a_contact_scene_keeps_the_fine_run_reference_and_says_why(tmp_path):
    _drake()
    scene = tmp_path / "drop.x3d"
    scene.write_text(DROP)
    dts = [1 / 60, 1 / 240]
    chosen = S.targets([str(scene), "bounce_apex"], dts, window=0.5)
    plans, _ = S.backend_plans([BACKEND])
    sweep = S.run_sweep(chosen, plans, dts, [], [], workers=2, repeats=1)
    drop, bounce = sweep.references["drop"], sweep.references["bounce_apex"]
    # drake ran the drop but, by its own child's word, at the fixed step: no error-controlled reference
    job, run, _ = sweep.controlled["drop"]
    assert run.verdict == "measured" and run.target_accuracy is None
    assert (drop.method, drop.backend, drop.accuracy) == (S.FINE_RUN, BACKEND, None)
    assert "discrete mode" in drop.instead and "not Drake's error-controlled run" in drop.said
    # drake refuses a bounce: said as its refusal
    assert bounce.method == S.FINE_RUN and bounce.instead.startswith("drake: unsupported")


def test_the_error_controlled_reference_needs_both_runs_error_controlled():
    times = np.array([0.0, 0.5, 1.0])
    job = S.Job("scene.x3d", "drake", results.Settings(1.0, 1 / 240))

    def ran(offset: float, accuracy: float | None) -> S.JobResult:
        return S.JobResult("measured", positions=_positions(times, np.full((3, 2, 3), offset)),
                           target_accuracy=accuracy)

    ref = S.error_controlled(job, ran(0.0, 1e-11), ran(1e-9, 1e-9))
    assert (ref.method, ref.own_error, ref.accuracy) == (S.ERROR_CONTROLLED, pytest.approx(1e-9 * np.sqrt(3)), 1e-11)
    assert "discrete mode" in S.error_controlled(job, ran(0.0, 1e-11), ran(0.0, None))
    assert "did not tighten" in S.error_controlled(job, ran(0.0, 1e-9), ran(0.0, 1e-9))
    assert S.error_controlled(job, ran(0.0, 1e-11), S.JobResult("crashed", "signal 11")) == "drake: crashed (signal 11)"


def test_sweep_json_and_markdown_say_which_reference(tmp_path):
    _drake()
    out = tmp_path / "sweep"
    assert cli_main(["sweep", "--scenes", case_scene("double_pendulum_energy"), "--backends", f"{BACKEND},physx,drake",
                     "--dts", "1/60,1/240", "--iterations", "10", "--accuracy", "false", "--repeats", "1", "--out",
                     str(out), "--workers", "2", "-q"]) == 0
    doc = json.loads((out / "sweep.json").read_text())
    # the two newest backends are swept and on their own fronts like the others
    assert {p["backend"] for p in doc["points"] if p["pareto_backend"] and p["error"] is not None} == \
        {BACKEND, "physx", "drake"}
    (scene,) = doc["scenes"]
    assert (scene["reference_method"], scene["reference_backend"], scene["reference_accuracy"]) == \
        (S.ERROR_CONTROLLED, "drake", 1e-11)
    assert scene["reference_error"] == scene["reference_own_error"] > 0
    (drake,) = doc["error_controlled_runs"]
    assert (drake["target_accuracy"], drake["check_target_accuracy"]) == (1e-11, 1e-6)
    assert "Reference: drake's error-controlled RK3 at target accuracy 1e-11" in (out / "sweep.md").read_text()


def test_events_are_contacts_and_stops(tmp_path):
    drop = tmp_path / "drop.x3d"
    drop.write_text(DROP)
    assert S.has_events(load(str(drop))) and S.has_events(load(case_scene("hinge_limits")))
    assert not S.has_events(load(case_scene("double_pendulum_energy")))
    assert not S.has_events(load(case_scene("free_fall")))
    (target,) = S.targets([str(drop)], [1 / 60])
    assert target.events


def test_a_contact_scene_s_uncertainty_holds_the_backends_spread(tmp_path):
    """The box drop: MuJoCo's fine run is the reference; DART's lies 5.5 mm from it, beyond
    MuJoCo's own error (3.4 mm): differences below the spread are no measured error."""
    scene = tmp_path / "drop.x3d"
    scene.write_text(DROP)
    dts = [1 / 60, 1 / 240]
    chosen = S.targets([str(scene)], dts)
    plans, _ = S.backend_plans([BACKEND, "dart"])
    sweep = S.run_sweep(chosen, plans, dts, [], [], workers=2, repeats=1, controlled=False)
    ref = sweep.references["drop"]
    assert (ref.method, ref.backend, ref.events) == (S.FINE_RUN, BACKEND, True)
    _, dart, _ = sweep.fine[("drop", "dart")]
    gap = window_error(dart.positions, ref.runs, 1.0)
    assert (ref.spread, ref.spread_backend) == (gap, "dart")
    assert ref.error == max(ref.own_error, gap) >= gap > 0  # the stated uncertainty holds the disagreement
    assert f"lie up to {gap:.3g} m from it (dart)" in ref.said


def test_the_spread_is_the_farthest_comparable_fine_run():
    times = np.array([0.0, 0.5, 1.0])
    ref = S.Reference("mujoco", 1 / 1920, 1e-3, _positions(times, np.zeros((3, 2, 3))), check="twice the step")
    near, far = _positions(times, np.full((3, 2, 3), 0.01)), _positions(times, np.full((3, 2, 3), 0.02))
    other = _positions(times, np.zeros((3, 2, 3)), ("A", "C"))  # other bodies: says nothing of the spread
    spread = S.with_spread(ref, {"ode": (1.0, near), "bullet": (1.0, far), "dart": (1.0, other)})
    assert (spread.spread_backend, spread.spread) == ("bullet", pytest.approx(0.02 * np.sqrt(3)))
    assert spread.error == spread.spread and spread.to_json()["spread_backend"] == "bullet"
    alone = S.with_spread(ref, {})
    assert (alone.events, alone.spread_backend, alone.error) == (True, None, 1e-3)
    assert "no other backend's fine run to measure it by" in alone.said
    # a backend that breaks the clause on the scene's feature is no reading of it: its run is left out, said
    kept = spread.without({"bullet": "which fails hinge_limits"})
    assert (kept.spread_backend, kept.spread) == ("ode", pytest.approx(0.01 * np.sqrt(3)))
    assert "left out: bullet's fine run, which fails hinge_limits" in kept.said
    assert kept.to_json()["spread_left_out"] == "bullet's fine run, which fails hinge_limits"
    assert spread.without({"pymunk": "which fails x"}) is spread  # nothing of it in the spread: unchanged
    assert spread.without({"ode": "a", "bullet": "b"}).error == 1e-3  # no spread left: its own error


def test_the_plot_draws_the_reference_s_uncertainty_below_which_errors_tie():
    import matplotlib.pyplot as plt
    from reports.plots import _draw
    point = {"backend": BACKEND, "dt": 1 / 60, "dt_label": "1/60", "iterations": None, "prefer_accuracy": None,
             "error": 0.05, "cpu_per_sim_s": 1e-3, "cpu_low": 1e-3, "cpu_high": 1e-3, "pareto_scene": True,
             "tie_scene": None}
    fig, ax = plt.subplots()
    _draw(ax, {"backends": {BACKEND: {}}}, [point], "m", 0.0268)
    (line,) = [ln for ln in ax.get_lines() if "uncertainty" in ln.get_label()]
    assert list(line.get_ydata()) == [0.0268, 0.0268] and "errors below it tie" in line.get_label()
    ax.clear()
    _draw(ax, {"backends": {BACKEND: {}}}, [point], "m", None)  # a closed form: no line
    assert not [ln for ln in ax.get_lines() if "uncertainty" in ln.get_label()]
    plt.close(fig)
