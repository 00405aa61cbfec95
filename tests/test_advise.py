"""x3drbp advise: the rule on synthetic runs (each branch and tie), when two runs part, and
the command end to end on a folder of scenes with one that does not load."""

from __future__ import annotations

import json
import subprocess
import sys
import shutil

import numpy as np
import pytest
from conftest import ROOT, SCENES, case_scene, needs_ode

from conformance.analyses import advice as A
from conformance.analyses import sweep as S
from conformance.analyses.sweep_metrics import Cost, Positions
from x3drbp import main as cli_main

TOL = 1e-3


def _option(backend: str, dt: float, error: float | None, cost: float | tuple[float, float, float] | None,
            parts: dict | None = None) -> A.Option:
    c = None if cost is None else Cost(*cost) if isinstance(cost, tuple) else Cost(cost, cost, cost)
    return A.Option(backend, dt, "measured", "", error, error, c, parts or {})


def _judged(**approximations: int) -> dict[str, A.Judged]:
    return {b: A.Judged(approximated=[f"use{k}: note" for k in range(n)]) for b, n in approximations.items()}


def test_within_the_tolerance_the_fastest_wins_and_coarser_steps_count():
    opts = [_option("ode", 1 / 60, 5e-3, 0.01), _option("ode", 1 / 240, 8e-4, 0.04),
            _option("mujoco", 1 / 240, 1e-4, 0.06), _option("mujoco", 1 / 1000, 1e-6, 0.2)]
    c = A.choose(opts, _judged(ode=0, mujoco=0), 1.0, TOL, 0.0)
    chosen, rule, runners = c.chosen, c.rule, c.runners_up
    assert c.said == "within the tolerance: the fastest"
    # ode at 1/60 is faster but 5 mm off; within 1 mm, ode at 1/240 is the fastest: more
    # accuracy is not asked for
    assert (chosen.backend, chosen.dt, rule) == ("ode", 1 / 240, A.WITHIN)
    assert [(o.backend, o.dt) for o in runners] == [("mujoco", 1 / 240)]
    # the reference's own error widens the tolerance: 5 mm counts when the reference may be 4.5 mm off,
    # and the advice says accuracy cannot be ranked, never "within the tolerance" beside 5 mm
    c = A.choose(opts, _judged(ode=0, mujoco=0), 1.0, TOL, 4.5e-3)
    assert (c.chosen.backend, c.chosen.dt, c.rule) == ("ode", 1 / 60, A.CANNOT_RANK)
    assert c.said.startswith("accuracy cannot be ranked on this scene") and "within the tolerance:" not in c.said


def test_the_budget_excludes_and_nothing_affordable_is_said():
    opts = [_option("ode", 1 / 240, 8e-4, 0.04), _option("mujoco", 1 / 1000, 1e-6, 0.2)]
    c = A.choose(opts, _judged(ode=0, mujoco=0), 0.03, TOL, 0.0)
    assert c.chosen is None and c.rule == A.NONE_AFFORDABLE
    assert A.choose(opts, _judged(ode=0, mujoco=0), 0.1, TOL, 0.0).chosen.backend == "ode"
    failed = [_option("ode", 1 / 240, None, None)]
    c = A.choose(failed, _judged(ode=0), 1.0, TOL, 0.0)
    assert (c.chosen, c.rule) == (None, A.NONE_RAN)


def test_none_within_the_tolerance_the_most_accurate_ties_within_the_reference_error():
    opts = [_option("bullet", 1 / 1000, 2.8e-3, 0.003), _option("dart", 1 / 1000, 2.9e-3, 0.001),
            _option("mujoco", 1 / 1000, 2e-2, 0.0005)]
    c = A.choose(opts, _judged(bullet=0, dart=0, mujoco=0), 1.0, TOL, 0.0)
    assert (c.chosen.backend, c.rule) == ("bullet", A.MOST_ACCURATE)
    assert [o.backend for o in c.runners_up] == ["dart", "mujoco"]  # by error, as the rule ranks them
    # within the reference's own error, 2.8 and 2.9 mm are one error: the faster wins
    assert A.choose(opts, _judged(bullet=0, dart=0, mujoco=0), 1.0, TOL, 2e-4).chosen.backend == "dart"
    # an uncertainty over the tolerance (2 mm here) is said: the ranking is at its resolution alone
    c = A.choose([opts[0], opts[2]], _judged(bullet=0, mujoco=0), 1.0, 1e-4, 2e-3)
    assert (c.chosen.backend, c.rule) == ("bullet", A.MOST_ACCURATE) and c.said == (
        "accuracy cannot be ranked finer than the reference's uncertainty (0.002 m, over the tolerance); "
        "none within the tolerance: the most accurate, errors within it one")


def test_speed_ties_go_to_fewer_approximations_then_agreement_then_the_coarser_step():
    a = _option("bullet", 1 / 240, 5e-4, (0.010, 0.008, 0.014), {"mujoco": None, "ode": 0.5})
    b = _option("mujoco", 1 / 240, 5e-4, (0.011, 0.009, 0.013), {"bullet": None, "ode": None})
    c = _option("ode", 1 / 240, 5e-4, (0.012, 0.010, 0.015), {"bullet": 0.5, "mujoco": None})
    assert A.choose([a, b, c], _judged(bullet=1, mujoco=0, ode=0), 1.0, TOL, 0.0).chosen is b  # fewest approximations
    assert A.choose([a, b, c], _judged(bullet=0, mujoco=0, ode=0), 1.0, TOL, 0.0).chosen is b  # agrees with both others
    slow = _option("mujoco", 1 / 240, 5e-4, (0.020, 0.019, 0.021))  # beyond a's spread: not a tie
    assert A.choose([a, slow], _judged(bullet=1, mujoco=0), 1.0, TOL, 0.0).chosen is a
    refused = {"bullet": A.Judged(refused=["X: no"]), "mujoco": A.Judged()}
    assert A.choose([a, slow], refused, 1.0, TOL, 0.0).chosen is slow  # a backend refusing a use is out

    # a tie is said as one, with the tie-break that settled it; never "the fastest"
    said = A.choose([a, b, c], _judged(bullet=1, mujoco=0, ode=1), 1.0, TOL, 0.0).said
    assert said == ("within the tolerance: tied on speed with bullet at dt 1/240 and ode at dt 1/240 within their "
                    "spreads; chosen by tie-break 1: fewer approximations")
    said = A.choose([a, b, c], _judged(bullet=0, mujoco=0, ode=0), 1.0, TOL, 0.0).said
    assert "the fastest" not in said and said.endswith("chosen by tie-break 3: within 1 mm / 1 mrad of more backends "
                                                       "for the whole run")
    # runs cheaper than the speed resolution tie though their spreads lie apart (within SPEED_NOISE of
    # each other): said so, not "within their spreads"
    quick = _option("bullet", 1 / 60, 5e-4, (0.0003, 0.00029, 0.00032))
    slower = _option("ode", 1 / 60, 5e-4, (0.00055, 0.0005, 0.0006))
    c = A.choose([quick, slower], _judged(bullet=1, ode=0), 1.0, TOL, 0.0)
    assert c.chosen is slower and c.said == (
        "within the tolerance: tied on speed with bullet at dt 1/60 within 1 ms of CPU per simulated s and a "
        "factor 2 of each other, finer than runs this cheap are told apart; chosen by tie-break 1: fewer "
        "approximations")


def test_within_the_tolerance_is_never_said_beside_an_error_above_it():
    """1.2 mm passes within 1 mm plus a reference 0.5 mm off: said with the reference's error, not as within."""
    c = A.choose([_option("ode", 1 / 60, 1.2e-3, 0.01)], _judged(ode=0), 1.0, TOL, 5e-4)
    assert c.rule == A.WITHIN and c.said.startswith("within the tolerance and the reference's uncertainty (0.0005 m)")


def test_a_backend_failing_a_case_another_passes_is_not_recommended():
    """The pendulum with hinge limits: pymunk, the fastest, fails hinge_limits, which bullet passes."""
    fast, slow = _option("pymunk", 1 / 60, 5e-4, 0.001), _option("bullet", 1 / 60, 5e-4, 0.01)
    judged = {"pymunk": A.Judged(failing={"hinge_limits": "fail"}), "bullet": A.Judged(passing=1)}
    c = A.choose([fast, slow], judged, 1.0, TOL, 0.0)
    assert c.chosen is slow and c.runners_up == [fast]
    # "the fastest" is of the rest, and the line names the faster run it passed over and why
    assert c.said == ("within the tolerance: the fastest, of the backends that fail no case another passes: "
                      "pymunk at dt 1/60 (0.1x the cost, error 0.0005 m) fails hinge_limits, which bullet passes")
    # one set aside but slower: nothing to say
    judged_slow = {"pymunk": A.Judged(passing=1), "bullet": A.Judged(failing={"hinge_limits": "fail"})}
    assert A.choose([fast, slow], judged_slow, 1.0, TOL, 0.0).said == "within the tolerance: the fastest"
    # every backend fails a case another passes: one is still chosen, and the first line says why
    judged["bullet"] = A.Judged(failing={"hinge_max_limit": "fail"})
    judged["pymunk"].passing = 1
    c = A.choose([fast, slow], judged, 1.0, TOL, 0.0)
    assert c.chosen is fast and c.said.startswith("every backend that fits fails a case another passes "
                                                  "(pymunk: hinge_limits; bullet: hinge_max_limit)")
    # a case that differs only in conventions sets nothing aside
    judged = {"pymunk": A.Judged(failing={"hinge_limits": "conventions"}), "bullet": A.Judged(passing=1)}
    assert A.choose([fast, slow], judged, 1.0, TOL, 0.0).chosen is fast


def test_parting_is_the_first_frame_past_either_threshold():
    times = np.arange(5) * 0.1
    pos = np.zeros((5, 2, 3))
    ori = np.tile([0.0, 0.0, 1.0, 0.0], (5, 2, 1))
    a = Positions(times, ("A", "B"), pos, ori)
    moved = pos.copy()
    moved[3:, 1, 0] = 2e-3  # body B 2 mm off from the fourth frame
    assert A.parting(a, Positions(times, ("A", "B"), moved, ori)) == pytest.approx(0.3)
    turned = ori.copy()
    turned[2:, 0, 3] = 2e-3  # body A turned 2 mrad from the third frame
    assert A.parting(a, Positions(times, ("A", "B"), pos, turned)) == pytest.approx(0.2)
    within = pos + 5e-4
    assert A.parting(a, Positions(times, ("A", "B"), within, ori)) is None
    with pytest.raises(ValueError, match="share no body"):
        A.parting(a, Positions(times, ("A", "C"), pos, ori))


USER_SCENES = ("limited_pendulum.x3d", "bouncing_ball.x3dj", "car.x3d")  # the pendulum, ball and car


def test_the_labels_hold_on_the_scenes_users_brought(tmp_path, capsys):
    """Whatever one repeat's timings: "the fastest" stands only where nothing as accurate and
    cheaper was passed over unsaid; no backend breaking the clause on a feature the scene uses
    is recommended over one that keeps it (pymunk past its hinge stops); "within the
    tolerance" stands only beside an error within it; a ball whose engines' fine runs lie
    centimetres apart is said not to rank accuracy."""
    out = tmp_path / "advice.json"
    backends = "mujoco,bullet,pymunk,ode"
    assert cli_main(["advise", *(str(SCENES) + "/examples/" + s for s in USER_SCENES), "--backends", backends,
                     "--dts", "1/60,1/240", "--duration", "1", "--repeats", "1", "--json", str(out), "-q"]) == 0
    text = capsys.readouterr().out
    doc = json.loads(out.read_text())
    by_name = {s["scene"].rsplit("/", 1)[1]: s for s in doc["scenes"]}
    assert list(by_name) == list(USER_SCENES)
    for name, scene in by_name.items():
        best = next(o for o in scene["options"] if (o["backend"], o["dt"]) == tuple(scene["recommended"].values()))
        tied = scene["reference"]["error"]
        failing = {b: [c for c, v in j["failing"].items() if v == "fail"] for b, j in scene["judged"].items()}
        keeps = {b for b, cs in failing.items() if not cs and not scene["judged"][b]["refused"]}
        assert not failing[best["backend"]] or not keeps, (name, best["backend"], failing)
        if "within the tolerance:" in scene["said"]:
            assert best["error"] <= TOL
        if "the fastest" in scene["said"] and "of the backends that fail no case" not in scene["said"]:
            rivals = [o for o in scene["options"] if o["error"] is not None and o["error"] <= TOL + tied
                      and not scene["judged"][o["backend"]]["refused"]]
            assert all(o["cpu_per_sim_s"] >= best["cpu_per_sim_s"] for o in rivals), (name, scene["said"])
        assert scene["said"] in text
    assert by_name["limited_pendulum.x3d"]["recommended"]["backend"] != "pymunk"
    assert "left out: pymunk's fine run, which fails hinge_limits" in by_name["limited_pendulum.x3d"]["reference"]["said"]
    assert by_name["bouncing_ball.x3dj"]["said"].startswith("accuracy cannot be ranked")
    assert by_name["car.x3d"]["judged"]["pymunk"]["refused"]  # planar only: the car is refused, said


@needs_ode
def test_advise_a_folder_each_scene_gets_its_answer(tmp_path, capsys):
    folder = tmp_path / "mine"
    folder.mkdir()
    shutil.copy(case_scene("free_fall"), folder / "drop.x3d")
    shutil.copy(case_scene("pendulum_period"), folder / "swing.x3d")
    (folder / "broken.x3d").write_text("<X3D><Scene><RigidBody mass='-1'/></Scene></X3D>")
    (folder / "routed.x3d").write_text(  # an input x3drbp does not run: every backend refuses it
        "<X3D><Scene><RigidBodyCollection><RigidBody DEF='B' containerField='bodies'/></RigidBodyCollection>"
        "<PositionInterpolator DEF='P' key='0 1' keyValue='0 0 0 1 0 0'/>"
        "<ROUTE fromNode='P' fromField='value_changed' toNode='B' toField='set_position'/></Scene></X3D>")
    out = tmp_path / "advice.json"
    code = cli_main(["advise", str(folder), "--backends", "mujoco,ode", "--dts", "1/60,1/240", "--duration", "1",
                     "--repeats", "2", "--json", str(out), "-q"])
    captured = capsys.readouterr()
    assert code == 1  # broken.x3d does not load; the others are still advised
    assert "broken.x3d:1:" in captured.err and "mass" in captured.err
    doc = json.loads(out.read_text())
    assert [s["scene"].rsplit("/", 1)[1] for s in doc["scenes"]] == ["drop.x3d", "routed.x3d", "swing.x3d"]
    routed = doc["scenes"].pop(1)
    assert routed["recommended"] is None and routed["rule"] == A.NONE_CAN and not routed["options"]
    assert all("set_position.routed" in j["refused"][0] for j in routed["judged"].values())
    assert "routed.x3d (free bodies): no recommendation: every backend refuses a use the scene makes" in captured.out
    for scene in doc["scenes"]:
        # a free fall and a pendulum: Drake's error-controlled run is the reference, though drake is not compared
        assert (scene["reference"]["backend"], scene["reference"]["method"]) == ("drake", S.ERROR_CONTROLLED)
        assert scene["reference"]["said"] in captured.out
        best = next(o for o in scene["options"] if o["backend"] == scene["recommended"]["backend"]
                    and o["dt"] == scene["recommended"]["dt"])
        ok = [o for o in scene["options"] if o["error"] is not None]
        assert len(ok) == 4 and best["cpu_per_sim_s"] <= doc["settings"]["budget"] and best["wall_per_sim_s"] > 0
        if scene["rule"] == A.WITHIN:  # nothing within the tolerance is faster beyond the spreads
            within = [o for o in ok if o["error"] <= TOL + scene["reference"]["error"]]
            assert all(o["cpu_high"] >= best["cpu_low"] for o in within)
        else:
            assert best["error"] <= min(o["error"] for o in ok) + scene["reference"]["error"] + 1e-12
        assert scene["scene"] in captured.out
    drop = doc["scenes"][0]
    assert drop["kind"] == "free bodies" and doc["scenes"][1]["kind"] == "joints"
    # a free fall: both integrate semi-implicit Euler, so they agree for the whole run at each step
    assert all(t is None for o in drop["options"] for t in o["parts"].values())
    assert cli_main(["advise", str(folder), "--dts", "0"]) == 2
    (tmp_path / "empty").mkdir()
    assert cli_main(["advise", str(tmp_path / "empty")]) == 2  # no scene at all: bad usage
    capsys.readouterr()
    assert cli_main(["check", str(tmp_path / "empty")]) == 2
    assert capsys.readouterr().err == f"x3drbp check: no X3D files (.x3d, .x3dv, .x3dj) under {tmp_path / 'empty'}\n"
    assert cli_main(["advise", str(tmp_path / "missing.x3d")]) == 1  # a scene that cannot be read, as check says


def test_the_text_says_where_the_reference_favours_the_choice_or_cannot_resolve_the_tolerance():
    from reports.advice_text import scene_lines
    option = {"backend": "mujoco", "dt": 1 / 240, "verdict": "measured", "reason": "", "error": 2e-3,
              "self_error": 2e-3, "parts": {"ode": None}, "cpu_per_sim_s": 0.01, "cpu_low": 0.009, "cpu_high": 0.011}
    scene = {"scene": "s.x3d", "kind": "contacts", "rule": A.CANNOT_RANK, "said": A.CANNOT_RANK_SAID + ": the fastest",
             "options": [option],
             "reference": {"backend": "mujoco", "method": S.FINE_RUN, "dt": 1 / 8000, "error": 3.5e-3,
                           "said": "mujoco's run at dt 1/8000 s, own error 0.0035 m"},
             "judged": {"mujoco": {"refused": [], "approximated": [], "failing": {}, "passing": 2}},
             "recommended": {"backend": "mujoco", "dt": 1 / 240}, "runners_up": []}
    settings = {"budget": 1.0, "tolerance": 1e-3, "window": 1.0, "duration": 5.0}
    text = "\n".join(scene_lines(scene, settings))
    assert "the reference is this backend's own run (fine run), which favours it" in text
    assert "the reference's uncertainty (0.0035 m) exceeds the tolerance" in text
    assert text.startswith("s.x3d (contacts): mujoco at dt 1/240 (accuracy cannot be ranked on this scene")
    scene.update(reference={"backend": "drake", "method": S.ERROR_CONTROLLED, "dt": 1 / 240, "error": 1e-9,
                            "said": "drake's error-controlled RK3"}, rule=A.MOST_ACCURATE, said=A.MOST_ACCURATE)
    text = "\n".join(scene_lines(scene, settings))
    assert "favours" not in text and "exceeds" not in text
    assert "within 1 mm / 1 mrad of ode for all 5 s" in text and "100x real time" in text
    # a runner-up's broken cases are said beside its cost, not left to be found in the matrix
    runner = dict(option, backend="pymunk", cpu_per_sim_s=0.005)
    scene["options"].append(runner)
    scene["runners_up"] = [{"backend": "pymunk", "dt": 1 / 240}]
    scene["judged"]["pymunk"] = {"refused": [], "approximated": ["a: b"], "failing": {
        "hinge_limits": "fail", "contact_slip": "unsupported"}, "passing": 1}
    text = "\n".join(scene_lines(scene, settings))
    assert "    pymunk at dt 1/240: 0.5x the cost" in text and "; fails hinge_limits; 1 approximation(s)" in text
    # the summary table says how the rule settled it and why the cheaper runner-up is not first
    from reports.advice_text import markdown
    scene.update(rule=A.WITHIN, settled="tied on speed; tie-break 1: fewer approximations")
    row = markdown({"settings": {**settings, "dts": [1 / 240], "repeats": 3}, "scenes": [scene]}, details=False)
    assert ("| within 1 mm of the reference, tied on speed; tie-break 1: fewer approximations | pymunk at dt 1/240: "
            "0.5x the cost, error 0.002 m (+0 m); fails hinge\\_limits; 1 approximation(s) |") in row  # markdown-escaped


@pytest.mark.parametrize("args, says", [
    (["--duration", "1e12"], "free_fall: its reference run: 1e+12 s at a step of 0.00208333 s (the finest of the "
                             "steps / 8) and 60 frames/s makes 6e+13 frames; a run records at most 1e+06"),
    (["--duration", "1000", "--dts", "1e-6"], "makes 8e+09 steps; a run takes at most 1e+09"),
    (["--dts", ","], "--dts names no step"),
    (["--dts", "1/60", "--dts", " , "], "--dts names no step"),
    (["--repeats", "1000000000"], "argument --repeats: must be a whole number from 1 to 100, not '1000000000'"),
])
def test_settings_past_a_run_s_bounds_are_bad_usage(args, says):
    # --timeout 1, one backend and one step: code that took the settings stops soon all the same
    r = subprocess.run([sys.executable, "-m", "x3drbp", "advise", case_scene("free_fall"), "--backends",
                        "pymunk", "--timeout", "1", "--dts", "1/60", *args, "-q"], cwd=ROOT, capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 2 and says in r.stderr and "Traceback" not in r.stderr, r.stderr
    assert r.stdout == ""


def test_a_bouncing_ball_s_accuracy_cannot_be_ranked_and_is_ranked_by_speed(tmp_path, capsys):
    """bounce_apex: Drake refuses its bounce, so MuJoCo's fine run is the reference, and the other
    fine runs lie centimetres from it (Bullet's 16 mm; PhysX's, 19 mm, is left out: PhysX fails
    error_correction, which a contact scene relies on): the reference's uncertainty holds that
    spread, exceeds the 1 mm tolerance, and the advice says so and takes the fastest run it cannot
    place beyond it."""
    out = tmp_path / "advice.json"
    assert cli_main(["advise", case_scene("bounce_apex"), "--backends", "mujoco,bullet,physx,drake", "--dts",
                     "1/60,1/240", "--duration", "1", "--repeats", "1", "--json", str(out), "-q"]) == 0
    text = capsys.readouterr().out
    (scene,) = json.loads(out.read_text())["scenes"]
    ref = scene["reference"]
    assert (ref["method"], ref["backend"], ref["events"], ref["spread_backend"]) == (S.FINE_RUN, "mujoco", True,
                                                                                    "bullet")
    assert ref["spread_left_out"] == "physx's fine run, which fails error_correction"
    assert ref["instead"].startswith("drake: unsupported")
    assert {o["backend"] for o in scene["options"] if o["error"] is not None} == {"mujoco", "bullet", "physx"}
    assert "bounce" in scene["judged"]["drake"]["refused"][0]  # drake refuses it, and says so
    assert ref["error"] == max(ref["own_error"], ref["spread"]) > TOL
    assert scene["said"].startswith("accuracy cannot be ranked") and scene["said"] in text
    assert ref["said"] in text
    best = next(o for o in scene["options"] if (o["backend"], o["dt"]) == tuple(scene["recommended"].values()))
    ran = [o for o in scene["options"] if o["error"] is not None]
    within = [o for o in ran if o["error"] <= TOL + ref["error"]]
    if scene["rule"] == A.CANNOT_RANK:  # some run the reference cannot place beyond the tolerance: the fastest
        fastest = min(within, key=lambda o: o["cpu_per_sim_s"])  # one repeat: no spread, a tie is the margins alone
        assert best in within and A.tie(_option(best["backend"], best["dt"], best["error"], best["cpu_per_sim_s"]),
                                        _option(fastest["backend"], fastest["dt"], fastest["error"],
                                                fastest["cpu_per_sim_s"])) is not None
    else:  # none: the most accurate, at the reference's resolution
        assert scene["rule"] == A.MOST_ACCURATE and not within
        assert best["error"] <= min(o["error"] for o in ran) + ref["error"]
