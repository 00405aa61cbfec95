"""advise's runs packed on the cores (issue 38: the 10-link ball-joint chain within 30 s on 2
cores): the longest job waiting starts first whichever batch gave it, Drake's error-controlled
runs (costly at every step) before the fixed-step runs, a run whose first timing is near the
budget timed again as soon as it ends rather than after every other run, and the judgement's
child beside the declarations'; the advice the same as without the speculation."""

from __future__ import annotations

import sys
import threading
from concurrent.futures import Future
from dataclasses import replace

import numpy as np
import pytest
from conftest import SCENES, case_scene

from backends import base
from conformance.analyses import advice as A
from conformance.analyses import sweep as S
from conformance.analyses.sweep_job import Job, JobResult
from conformance.analyses.sweep_metrics import Cost, Positions
from x3drbp import advise as advise_cli
from x3drbp import main as cli_main
from conformance.runner import children
from x3d_core.encodings.load import load

PLANS = {"mujoco": S.BackendPlan("mujoco", "3", True, True), "drake": S.BackendPlan("drake", "1", False, True)}
DTS = (1 / 60, 1 / 240)
# CPU s per simulated s of each point's run: Drake's about the budget (1), MuJoCo's at 1/60 too
COST = {("drake", 1 / 60): 0.9, ("drake", 1 / 240): 0.95, ("mujoco", 1 / 60): 0.95, ("mujoco", 1 / 240): 0.01}


def _poses(job, offset: float) -> Positions:
    times = np.arange(0.0, job.settings.duration + 1e-9, 1 / job.settings.frame_rate)
    values = np.zeros((len(times), 1, 3))
    values[:, :, 0] = offset  # along x: the distance between two runs is the difference of their offsets
    return Positions(times, ("B",), values, np.zeros((len(times), 1, 4)))


def _fake(ran: list):
    """run_job's stand-in: each job recorded as it starts; Drake error-controlled (1e-11 with
    preferAccuracy TRUE, else 1e-6) and within 1e-12 m of its reference, MuJoCo 2 mm off and more;
    each repeat costing COST (the reference runs and fine runs 0.01)."""
    lock = threading.Lock()

    def run_job(job):
        with lock:
            ran.append(job)
        drake = job.backend == S.DRAKE
        cost = COST.get((job.backend, job.settings.dt), 0.01) * job.settings.duration
        cpu = tuple(cost * (1 + 0.01 * k) for k in range(job.repeats))
        offset = 1e-12 * (job.prefer_accuracy is not True) if drake else 2e-3 + job.settings.dt
        return JobResult("measured", step_s=cpu, simulation_s=sum(cpu), cpu_s=cpu, positions=_poses(job, offset),
                         target_accuracy=(1e-11 if job.prefer_accuracy else 1e-6) if drake else None)
    return run_job


def test_the_longest_job_waiting_starts_first_whichever_batch_gave_it(monkeypatch):
    """One worker: a job given late (a further timing) goes before the shorter ones given earlier."""
    started, began, hold = [], threading.Event(), threading.Event()

    def run_job(job):
        started.append(job.backend)
        if job.backend == "first":
            began.set()
            hold.wait(10)
        return JobResult("measured")
    monkeypatch.setattr(S, "run_job", run_job)
    (target,) = S.targets([case_scene("double_pendulum_energy")], DTS)
    job = Job(target.scene, "first", target.settings)
    with S.Pool(1) as pool:
        futures = [pool.submit(job, 0)]
        assert began.wait(10)
        futures += [pool.submit(replace(job, backend=name), priority)
                    for name, priority in (("short", 1), ("shorter", 0.5), ("long", 9))]
        hold.set()
        for f in futures:
            f.result()
    assert started == ["first", "long", "short", "shorter"]


def test_drake_s_error_controlled_runs_start_first(monkeypatch):
    """Ranked by duration over step, Drake's 1/60 run (its error control, not the step, sets its
    cost: 4.3 CPU s on issue 38's chain) started after every other backend's 1/240 run."""
    ran: list = []
    monkeypatch.setattr(S, "run_job", _fake(ran))
    (target,) = S.targets([case_scene("double_pendulum_energy")], DTS, duration=5)
    S.run_sweep([target], PLANS, DTS, [], [], workers=1, repeats=1, controlled=True, reference_as_fine=True)
    drake = [k for k, job in enumerate(ran) if job.backend == S.DRAKE]
    assert drake == list(range(len(drake))) and len(drake) == 4  # its two points and its reference pair


def _advice(monkeypatch, path: str, ran: list) -> dict:
    monkeypatch.setattr(S, "run_job", _fake(ran))
    judged = {path: {b: A.Judged() for b in PLANS}}
    (advice,) = A.advise([path], {path: load(path)}, PLANS, judged, DTS, duration=5, workers=1)
    return advice.to_json()


def test_a_run_near_the_budget_is_timed_again_as_it_ends_and_the_advice_is_the_same(monkeypatch):
    """Drake's runs cost about the budget and are within the tolerance, tied: both timed 3 times,
    their further timings started as each ends, before MuJoCo's runs (one of them near the budget
    too, but less accurate: its speed decides nothing, and what was started for it is dropped);
    the advice as where every further timing waits for the last first timing."""
    path = case_scene("double_pendulum_energy")
    ran: list = []
    advice = _advice(monkeypatch, path, ran)
    timed = {(o["backend"], o["dt"]): o["timed"] for o in advice["options"]}
    assert timed == {("drake", 1 / 60): 3, ("drake", 1 / 240): 3, ("mujoco", 1 / 60): 1, ("mujoco", 1 / 240): 1}
    assert advice["recommended"] == {"backend": "drake", "dt": 1 / 60}
    again = [k for k, job in enumerate(ran) if job.repeats == 2]
    first = [k for k, job in enumerate(ran) if job.repeats == 1]
    drake_again = [k for k in again if ran[k].backend == S.DRAKE]
    assert len(drake_again) == 2 and drake_again[-1] < first[-1]
    # the same advice where nothing is timed ahead: the further timings after every first one
    monkeypatch.setattr(A, "near_budget", lambda cost, budget: False)
    ran_after: list = []
    assert _advice(monkeypatch, path, ran_after) == advice
    again = [k for k, job in enumerate(ran_after) if job.repeats == 2]
    assert len(again) == 2 and min(again) > max(k for k, job in enumerate(ran_after) if job.repeats == 1)


def test_near_the_budget_is_a_single_timing_s_reach():
    cost = Cost(0.8, 0.8, 0.8)
    assert A.near_budget(cost, 1.0) and A.near_budget(cost, 0.62) and not A.near_budget(cost, 0.6)
    assert not A.near_budget(cost, 1.05)  # 0.8 * 1.3 = 1.04: no single timing puts it past 1.05
    assert A.near_budget(Cost(4e-4, 4e-4, 4e-4), 7e-4)  # under 1 ms per simulated s, a factor 2


def test_time_again_takes_the_timings_started_ahead_and_drops_those_not_started(monkeypatch):
    ran: list = []
    monkeypatch.setattr(S, "run_job", _fake(ran))
    (target,) = S.targets([case_scene("double_pendulum_energy")], DTS, duration=5)
    sweep = S.run_sweep([target], PLANS, DTS, [], [], workers=1, repeats=1, controlled=True, reference_as_fine=True)
    ahead, waiting = Future(), Future()
    ahead.set_result(JobResult("measured", cpu_s=(7.0, 8.0), step_s=(7.0, 8.0)))
    sweep.ahead = {0: (2, ahead), 1: (2, waiting)}
    ran.clear()
    S.time_again(sweep, [0, 2], 2, workers=1)
    assert sweep.runs[0][1].cpu_s[1:] == (7.0, 8.0)  # taken: no run of its own
    assert [(j.backend, j.settings.dt) for j in ran] == [(sweep.points[2].backend, sweep.points[2].dt)]
    assert waiting.cancelled() and sweep.ahead == {}


INSTALLED = [n for n, b in base.available().items() if not isinstance(b, str)]


@pytest.mark.skipif(not INSTALLED, reason="an installed backend to judge the scene on")
def test_the_judgement_s_child_runs_beside_the_declarations(monkeypatch):
    judging = threading.Event()

    def judge(paths, backends, verdict, timeout):
        judging.set()
        return None, "stopped here"

    def plans(command, names, timeout):
        assert judging.wait(10), "the declarations were read before the judgement started"
        return {n: S.BackendPlan(n, "1", False, False) for n in names}
    monkeypatch.setattr(A, "judge", judge)
    monkeypatch.setattr(advise_cli, "plans", plans)
    assert cli_main(["advise", f"{SCENES}/examples/pendulum.x3d", "--backends", INSTALLED[0], "-q"]) == 3


def test_a_run_dropped_while_it_runs_is_ended(monkeypatch):
    """Started ahead and not wanted (Pool.drop): its child is ended, not waited for (it would
    sleep 30 s and then give a result)."""
    began = threading.Event()

    def run_job(job):
        began.set()
        ended = children.call([sys.executable, "-c", "import time; time.sleep(30)"], 60)
        return JobResult("measured", str(ended.returncode))
    monkeypatch.setattr(S, "run_job", run_job)
    (target,) = S.targets([case_scene("double_pendulum_energy")], DTS)
    with S.Pool(1) as pool:
        future = pool.submit(Job(target.scene, "mujoco", target.settings), 1)
        assert began.wait(10)
        assert pool.drop(future)
        assert isinstance(future.exception(), children.Dropped)
        assert not pool.drop(future)  # ended: nothing left to drop
