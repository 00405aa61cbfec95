"""advise's speed ties and its timing (issue 38): a tie needs the speeds close relative to
each other as well (a cheap run 5.7 times another's cost is no tie), a coarser step of one
backend measured costlier than a finer one is a tie (the load's doing: the flaky
tests/test_advise_load.py), the tie-break named is the one that set aside the last rival, only
the runs whose speed could change the advice are timed again, and Drake's fine pair is not run
where its error-controlled run is the reference (that run is its own finer run)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from conftest import SCENES, case_scene

from conformance.analyses import advice as A
from conformance.analyses import sweep as S
from conformance.analyses.sweep_job import JobResult
from conformance.analyses.sweep_metrics import Cost, Positions
from x3drbp import main as cli_main
from conformance.runner import cache

TOL = 1e-3


def _option(backend: str, dt: float, error: float, cost: float | tuple[float, float, float],
            parts: dict | None = None) -> A.Option:
    c = Cost(*cost) if isinstance(cost, tuple) else Cost(cost, cost, cost)
    return A.Option(backend, dt, "measured", "", error, error, c, parts or {})


def _judged(**approximations: int) -> dict[str, A.Judged]:
    return {b: A.Judged(approximated=[f"use{k}: note" for k in range(n)]) for b, n in approximations.items()}


def test_a_cheap_run_several_times_cheaper_is_no_tie():
    """Under 1 ms per simulated s the floor ties runs only within SPEED_NOISE (2x) of each other:
    0.1 ms against 0.57 ms is the faster run, said as the fastest, not a tie settled by a
    tie-break (the old floor made any two runs under 1 ms a tie)."""
    quick = _option("bullet", 1 / 60, 5e-4, 1e-4)
    slower = _option("ode", 1 / 60, 5e-4, 5.7e-4)
    c = A.choose([quick, slower], _judged(bullet=1, ode=0), 1.0, TOL, 0.0)
    assert c.chosen is quick and c.said == "within the tolerance: the fastest" and c.settled == "the fastest"
    assert A.tie(slower, quick) is None
    # within the factor, the floor still ties them: the fewer approximations win, and the line says why
    near = _option("ode", 1 / 60, 5e-4, 1.9e-4)
    c = A.choose([quick, near], _judged(bullet=1, ode=0), 1.0, TOL, 0.0)
    assert c.chosen is near and A.tie(near, quick) == A.FLOOR and A.FLOOR in c.said
    # above the floor, relative closeness alone ties: 30%, not 1 ms
    assert A.tie(_option("ode", 1 / 60, 5e-4, 0.0129), _option("bullet", 1 / 60, 5e-4, 0.01)) == A.RELATIVE
    assert A.tie(_option("ode", 1 / 60, 5e-4, 0.0131), _option("bullet", 1 / 60, 5e-4, 0.01)) is None


def test_a_coarser_step_of_one_backend_measured_costlier_ties_with_the_finer():
    """What flaked in tests/test_advise_load.py: Drake's error-controlled runs at 1/60 and 1/240
    do the same work (its error control sets the step), and one timing under load put 1/60 at
    1.38x the cost of 1/240: no longer 'the fastest' at 1/240, but a tie the coarser step wins."""
    fine = _option("drake", 1 / 240, 3e-10, (0.0292, 0.0290, 0.0295))
    coarse = _option("drake", 1 / 60, 3e-10, (0.0404, 0.0400, 0.0410))
    c = A.choose([fine, coarse], _judged(drake=1), 1.0, TOL, 3e-10)
    assert c.chosen is coarse and c.settled == "tied on speed; tie-break 4: the coarser step"
    assert c.said == ("within the tolerance: tied on speed with drake at dt 1/240 " + A.COARSER
                      + "; chosen by tie-break 4: the coarser step")
    # only the same backend's coarser step: another backend's run 1.38x the cost is slower, and a
    # coarser step beyond SPEED_NOISE is measured as costlier
    other = _option("mujoco", 1 / 60, 3e-10, (0.0404, 0.0400, 0.0410))
    assert A.tie(other, fine) is None and A.tie(_option("drake", 1 / 60, 3e-10, 0.06), fine) is None
    assert A.tie(fine, _option("drake", 1 / 60, 3e-10, 0.02)) is None  # a finer step costlier is no noise


def test_the_tie_break_named_is_the_one_that_set_aside_the_last_rival():
    """Three runs tied on speed: the chosen one has fewer approximations than one rival (tie-break
    1) and agrees with more backends than the other (tie-break 3): 3 is what decided, named so."""
    chosen = _option("mujoco", 1 / 240, 5e-4, 0.010, {"bullet": None, "ode": None})
    approximating = _option("bullet", 1 / 240, 5e-4, 0.011, {"mujoco": None, "ode": None})
    parting = _option("ode", 1 / 240, 5e-4, 0.012, {"mujoco": None, "bullet": 0.5})
    for order in ([chosen, approximating, parting], [parting, approximating, chosen]):
        c = A.choose(order, _judged(mujoco=0, bullet=1, ode=0), 1.0, TOL, 0.0)
        assert c.chosen is chosen and c.settled == "tied on speed; tie-break 3: " + A.TIEBREAKS[2]


def test_only_the_runs_whose_speed_could_change_the_advice_are_timed_again():
    """Issue 38's chain, measured once: ODE at 1/1000 is the most accurate affordable run; Drake's
    runs are within the tolerance at about the budget (they decide the advice if they fit it), the
    others' far from any tie; MuJoCo's 1/1000 run is as accurate as Bullet's, within 30% of its cost."""
    judged = _judged(ode=0, mujoco=0, bullet=0, drake=1)
    ode = _option("ode", 1 / 1000, 1.2198e-3, 0.0099)
    mujoco = _option("mujoco", 1 / 1000, 1.2986e-3, 0.0059)
    bullet = _option("bullet", 1 / 1000, 1.2986e-3, 0.0070)
    coarse = [_option(b, 1 / 60, 0.0219, c) for b, c in (("ode", 0.00046), ("mujoco", 0.0004), ("bullet", 0.0007))]
    drake = [_option("drake", dt, 9e-12, c) for dt, c in ((1 / 60, 1.03), (1 / 240, 1.01), (1 / 1000, 1.07))]
    options = [ode, mujoco, bullet, *coarse, *drake]
    c = A.choose(options, judged, 1.0, TOL, 8.85e-12)
    assert (c.chosen, c.rule) == (ode, A.MOST_ACCURATE)
    picked = A.unsettled(options, judged, 1.0, TOL, 8.85e-12)
    # the chosen run, and Drake's three: any of them 30% cheaper fits the budget and is recommended;
    # MuJoCo's and Bullet's runs are less accurate than ODE's, so their speed decides nothing
    assert [options[k] for k in picked] == [ode, *drake]
    # Drake at three times the budget: 30% either way changes nothing, and it is timed once
    far = [_option("drake", d.dt, 9e-12, 3.0) for d in drake]
    assert [k for k in A.unsettled([ode, mujoco, bullet, *coarse, *far], judged, 1.0, TOL, 8.85e-12)] == [0]
    # within the tolerance, the runs that could tie with the chosen one are timed again, not the others
    within = [_option("ode", 1 / 240, 5e-4, 0.010), _option("mujoco", 1 / 240, 5e-4, 0.0125),
              _option("bullet", 1 / 240, 5e-4, 0.030), _option("dart", 1 / 240, 5e-3, 0.001)]
    assert A.unsettled(within, _judged(ode=0, mujoco=0, bullet=0, dart=0), 1.0, TOL, 0.0) == [0, 1]


def _poses(job, offset: float) -> Positions:
    times = np.arange(0.0, job.settings.duration + 1e-9, 1 / job.settings.frame_rate)
    values = np.zeros((len(times), 1, 3))
    values[:, :, 0] = offset  # along x: the distance between two runs is the difference of their offsets
    return Positions(times, ("B",), values, np.zeros((len(times), 1, 4)))


def _fake_runs(discrete: bool, ran: list):
    """An executor of sweep jobs that records them and returns made-up runs: Drake error-controlled
    (its target 1e-11 with preferAccuracy TRUE, else 1e-6) unless `discrete`."""
    def execute(jobs, scheduler, workers, progress, expected=None, *_):
        ran.append(list(jobs))
        out = []
        for job in jobs:
            accuracy = None if discrete or job.backend != S.DRAKE else 1e-11 if job.prefer_accuracy else 1e-6
            offset = 1e-12 * (job.prefer_accuracy is not True) + 1e-3 * (job.backend != S.DRAKE) + job.settings.dt
            out.append(JobResult("measured", step_s=(0.01,), simulation_s=0.02, cpu_s=(0.01,),
                                 positions=_poses(job, offset), target_accuracy=accuracy))
        return out
    return execute


PLANS = {"mujoco": S.BackendPlan("mujoco", "3", True, True), "drake": S.BackendPlan("drake", "1", False, True)}


def test_drake_s_fine_pair_is_not_run_where_its_error_controlled_run_is_the_reference(monkeypatch):
    dts = [1 / 60, 1 / 240]
    (target,) = S.targets([case_scene("double_pendulum_energy")], dts)
    fine_dt = min(dts) / S.REFINEMENT
    for as_fine in (False, True):
        ran: list = []
        monkeypatch.setattr(S, "execute", _fake_runs(False, ran))
        sweep = S.run_sweep([target], PLANS, dts, [], [], repeats=1, controlled=True, reference_as_fine=as_fine)
        drake_fine = [j for batch in ran for j in batch if j.backend == S.DRAKE and j.settings.dt < min(dts)]
        assert sweep.references[target.name].method == S.ERROR_CONTROLLED and len(ran) == 1
        if not as_fine:  # the sweep's own: Drake's fine pair runs, as every backend's
            assert sorted(j.settings.dt for j in drake_fine) == [fine_dt, 2 * fine_dt]
            continue
        assert not drake_fine  # advise's: its reference run stands for it
        assert sweep.fine[(target.name, S.DRAKE)] is sweep.controlled[target.name]
        assert sweep.fine[(target.name, "mujoco")][0].settings.dt == fine_dt
        for p in sweep.points:  # self-consistency against Drake's own finer run: its reference
            assert p.self_error == (p.error if p.backend == S.DRAKE else pytest.approx(p.dt - fine_dt))


def test_drake_s_fine_pair_runs_after_all_where_it_stepped_the_scene_at_the_fixed_step(monkeypatch):
    dts = [1 / 60, 1 / 240]
    (target,) = S.targets([case_scene("double_pendulum_energy")], dts)
    ran: list = []
    monkeypatch.setattr(S, "execute", _fake_runs(True, ran))
    sweep = S.run_sweep([target], PLANS, dts, [], [], repeats=1, controlled=True, reference_as_fine=True)
    assert sweep.references[target.name].method == S.FINE_RUN  # mujoco's fine run, Drake's not error-controlled
    assert [(j.backend, j.settings.dt) for j in ran[1]] == [(S.DRAKE, min(dts) / S.REFINEMENT),
                                                            (S.DRAKE, 2 * min(dts) / S.REFINEMENT)]
    assert sweep.fine[(target.name, S.DRAKE)][0].settings.dt == min(dts) / S.REFINEMENT


def test_time_again_adds_timings_of_another_run(monkeypatch, tmp_path):
    """The further timings come from one child per point asked for EXTRA repeats, the longest
    measured first; the point's speed is then the median of all. A run of EXTRA repeats is another
    run than the point's own for the run cache; one of a single repeat is the same run, and is not
    read back from it (its timing would count twice)."""
    dts = [1 / 60, 1 / 240]
    (target,) = S.targets([case_scene("double_pendulum_energy")], dts)
    ran: list = []
    monkeypatch.setattr(S, "execute", _fake_runs(False, ran))
    sweep = S.run_sweep([target], PLANS, dts, [], [], repeats=1, controlled=True, reference_as_fine=True)
    seen: list = []

    def again(jobs, scheduler, workers, progress, expected=None, *_):
        seen.append((list(jobs), list(expected), cache.folder()))
        return [JobResult("measured", step_s=(0.03, 0.05)[:jobs[0].repeats], simulation_s=0.1,
                          cpu_s=(0.02, 0.05)[:jobs[0].repeats]) for _ in jobs]
    monkeypatch.setattr(S, "execute", again)
    monkeypatch.setenv("X3DRBP_CACHE", str(tmp_path))
    S.time_again(sweep, [0, 3], 2)
    ((jobs, expected, kept),) = seen
    assert [j.repeats for j in jobs] == [2, 2] and expected == [0.01, 0.01] and kept == str(tmp_path)
    p = sweep.points[0]
    duration = target.settings.duration
    assert (p.cpu_per_sim_s, p.cpu_low, p.cpu_high) == pytest.approx((0.02 / duration, 0.01 / duration,
                                                                      0.05 / duration))
    assert sweep.runs[0][1].cpu_s == (0.01, 0.02, 0.05) and sweep.points[1].cpu_low == sweep.points[1].cpu_high
    S.time_again(sweep, [1], 1)
    assert seen[-1][2] is None and sweep.runs[1][1].cpu_s == (0.01, 0.02)  # the cache off for that one


def test_advise_times_again_only_what_could_change_its_advice(tmp_path, capsys):
    """The pendulum at 1/60 and 1/120 on MuJoCo and Drake: only Drake's runs are within the 1 mm
    tolerance, and they tie with each other, so both are timed --repeats times; MuJoCo's, millimetres
    off, once. Drake's error control takes some 440 steps a simulated second at its default 1e-6, so
    neither cap binds and the two cost about the same (measured 1.15x apart), far inside the 30%
    either way a single timing may move; at 1/240 the cap binds and the two were 1.29x apart, on
    the margin. Drake's self-consistency is against its reference run, its own finer run (no fine
    pair): the same number as its error."""
    pytest.importorskip("pydrake")
    out = tmp_path / "advice.json"
    assert cli_main(["advise", f"{SCENES}/examples/pendulum.x3d", "--backends", "mujoco,drake", "--dts",
                     "1/60,1/120", "--duration", "1", "--repeats", "2", "--json", str(out), "-q"]) == 0
    text = capsys.readouterr().out
    (scene,) = json.loads(out.read_text())["scenes"]
    timed = {(o["backend"], o["dt"]): o["timed"] for o in scene["options"]}
    assert scene["recommended"]["backend"] == "drake"
    assert timed == {("mujoco", 1 / 60): 1, ("mujoco", 1 / 120): 1, ("drake", 1 / 60): 2, ("drake", 1 / 120): 2}
    assert all(o["self_error"] == o["error"] for o in scene["options"] if o["backend"] == "drake")
    assert "the median of 2 repeats for each run whose speed could change the advice, one timed run for the others" in text
