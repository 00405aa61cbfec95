"""Advice for a user's scene: which backend, at which step, and why.

Per scene: what each backend makes of the features the scene uses (refused, approximated,
and the verdicts of the conformance cases that exercise them), then a small sweep
(conformance/analyses/sweep.py) of the scene as the file gives it on every backend that can
run it, at a few steps, against one common reference (Drake's error-controlled run where
Drake runs the scene in continuous mode, whether or not it is compared; else one backend's
fine run; sweep.py says which and how its own error is estimated; Drake's fine run is that
error-controlled run where it is the reference), and how long each run stays within 1 mm /
1 mrad of each other backend's run at the same step. Each run is timed once, and the runs whose
speed could change the advice (unsettled()) `repeats` times in all, their speed the median,
until no such run is left: the 3 repeats of a 5 s Drake run far from any tie and from the
budget are not paid for. A run whose first timing is near the budget (near_budget) has its
further timings started as soon as it ends, beside the other runs (sweep.Pool); they count only
where unsettled() picks it, so the advice is the same as where they wait for every first timing.
The recommendation is a rule, stated here and in docs/commands/advise.md, not a score:

1. Out: a backend that refuses a feature the scene uses, and every run that did not end
   well (blew up, crashed, timed out). Set aside: a backend that fails (violates the spec
   in) a conformance case exercising a feature the scene uses while another affordable
   backend passes it; where every affordable backend is set aside so, the rule goes on
   with all of them and the first line of the advice says why.
2. Affordable: a run whose engine steps cost at most `budget` CPU seconds per simulated
   second (median of the repeats; 1 is real time on a quiet machine). Speeds are the
   steps' CPU time in the child, not wall time: other load on the machine does not
   reorder them.
3. Of the affordable runs, those within `tolerance` of the reference (error <= tolerance +
   the reference's uncertainty: its own error, and on a scene with contacts or stops the
   other backends' spread around it where larger, sweep.py): the fastest by median.
   Accuracy beyond the tolerance is not asked for, so a coarser step that is accurate
   enough wins. Where the reference's uncertainty exceeds the tolerance (a bouncing ball,
   whose engines' fine runs lie centimetres apart), accuracy cannot be ranked on the scene,
   and the advice says so: of the runs the reference cannot tell from within the
   tolerance, the fastest.
4. No affordable run within the tolerance: the most accurate affordable run (errors within
   the reference's uncertainty or rounding tie; the fastest of those).
5. Nothing affordable: no recommendation; the fastest run is named with its cost. No
   recommendation either where no run ended well, or where every backend refuses a use
   the scene makes (a routed input, say: each refusal is listed).
A speed ties with the fastest's (tie(): one reason each) where their repeats' spreads overlap,
where it is within SPEED_RELATIVE (30%) of it, or, within a factor SPEED_NOISE (2) of it, where
it is within SPEED_RESOLUTION (1 ms per simulated second) of it or is the same backend's run at
a coarser step (which does no more work); the advice says a tie is one ("tied on speed with
...; chosen by tie-break 1: fewer approximations"), never "the fastest", and names the
tie-break that set aside the last rival. The tie-breaks (TIEBREAKS): 1, fewer approximations
of what the scene uses (one per declared note, however many uses it covers); 2, fewer
conformance cases exercising the scene's features whose accuracy is graded beyond its bound;
3, the run that stays within 1 mm / 1 mrad of more other backends for the whole run; 4, the
coarser step; 5, the backend's name. Each other backend's best run by the same rule is a
runner-up, with what it would cost or lose against the recommendation.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from x3d_core.model.scene import Scene
from x3d_core.semantics.analysis import run_features

from conformance import cases as C
from conformance.results import FAIL, PASS, dt_label
from conformance.runner import children, probe
from conformance.analyses import sweep as S
from conformance.analyses.compare import DEFAULT_THRESHOLDS, pose_gaps
from conformance.analyses.sweep_metrics import Cost, Positions, same_error, shared_frames

DEFAULT_DTS = (1 / 60, 1 / 240, 1 / 1000)
DEFAULT_DURATION = 5.0  # s: how long the runs are watched for parting
DEFAULT_BUDGET = 1.0  # CPU s in the engine's steps per simulated s: real time
DEFAULT_TOLERANCE = 1e-3  # m from the reference over the window: the 1 mm compare holds runs to
JOINTS = ("BallJoint", "SingleAxisHingeJoint", "DoubleAxisHingeJoint", "SliderJoint", "UniversalJoint", "MotorJoint")
WITHIN, CANNOT_RANK, MOST_ACCURATE, NONE_AFFORDABLE, NONE_RAN, NONE_CAN = (
    "within the tolerance", "accuracy cannot be ranked", "none within the tolerance: the most accurate",
    "nothing fits the budget", "no run ended well", "every backend refuses a use the scene makes")
CANNOT_RANK_SAID = ("accuracy cannot be ranked on this scene (the reference's uncertainty exceeds the tolerance); "
                    "ranked by speed among the runs it cannot place beyond the tolerance")
# Speeds within this fraction of each other are ties: single runs' CPU time varies by up to 30%
# on a shared machine (benchmarks/engine_speed.py, load 2), and a load widens some runs' spreads
# and not others'.
SPEED_RELATIVE = 0.3
# The most a load was measured to stretch a run's CPU time: a busy sibling hyperthread doubled a
# 0.3 ms run's. The floor below and tie()'s coarser step hold within this factor only: beyond it
# the measure tells runs apart, so that 0.1 ms against 0.57 ms (5.7x) is no tie, however cheap.
SPEED_NOISE = 2.0
# CPU s per simulated s: speeds closer than this (and within SPEED_NOISE) are ties. Runs this
# cheap (1,000x real time) are resolved by no measure under load finer than that factor, and no
# budget hangs on the difference.
SPEED_RESOLUTION = 1e-3
TIEBREAKS = ("fewer approximations", "fewer cases graded beyond their bound",
             "within 1 mm / 1 mrad of more backends for the whole run", "the coarser step", "the backend's name")


def kind(scene: Scene) -> str:
    """The kind of scene, by what a run of it needs: joints, contacts, both, or neither."""
    used = run_features(scene)
    joints = any(f in JOINTS for f in used)
    contacts = any(f.startswith("CollisionCollection") for f in used)
    return {(True, True): "joints and contacts", (True, False): "joints", (False, True): "contacts",
            (False, False): "free bodies"}[(joints, contacts)]


@dataclass(frozen=True)
class Said:
    """A conformance case's verdict on a backend, and whether its accuracy is graded beyond
    the case's bound (the verdict does not say: conforming is not being accurate)."""
    verdict: str
    beyond_bound: bool = False


@dataclass
class Judged:
    """What one backend makes of a scene: refused and approximated uses, the verdicts of the
    cases exercising the features it uses (those that do not pass; the count of the rest), and
    those cases whose accuracy is graded beyond their bound."""
    refused: list[str] = field(default_factory=list)  # "use: why"
    approximated: list[str] = field(default_factory=list)  # "uses: note", one per approximation
    failing: dict[str, str] = field(default_factory=dict)  # case -> verdict
    passing: int = 0
    beyond_bound: list[str] = field(default_factory=list)  # cases


_JUDGED = """
import json, sys
from backends import base
from x3d_core.encodings.load import load
scenes = {p: load(p) for p in sys.argv[2:]}
out = {p: {n: [[str(u), u.feature, d.support.value, d.note] for u, d in base.judged(base.load(n), s)]
           for n in sys.argv[1].split(",")} for p, s in scenes.items()}
print("x3drbp-answer " + json.dumps(out))
"""


def judge(paths: Sequence[str], backends: Sequence[str], verdict: Callable[[str, str], Said],
          timeout: float) -> tuple[dict[str, dict[str, Judged]] | None, str]:
    """Per scene and backend, what the backend makes of it, asked in a child (the judgement
    needs each engine's module); verdict(case, backend): a case's verdict and accuracy grade,
    measured or pinned."""
    answer, why = probe.ask(_JUDGED, [",".join(backends), *paths], timeout, "the judgement's child")
    if answer is None:
        return None, why
    exercised = C.exercising()
    out: dict[str, dict[str, Judged]] = {}
    for path, per_backend in answer.items():
        out[path] = {}
        for b, uses in per_backend.items():
            approximated: dict[str, list[str]] = {}  # note -> the uses it covers: one approximation each
            for u, _, support, note in uses:
                if support == "approximate":
                    approximated.setdefault(note, []).append(u)
            j = Judged(refused=[f"{u}: {note}" for u, _, support, note in uses if support == "unsupported"],
                       approximated=[f"{', '.join(us)}: {note}" for note, us in approximated.items()])
            cases = dict.fromkeys(c for _, feature, _, _ in uses for c in exercised.get(feature, ()))
            for case in cases:
                said = verdict(case, b)
                if said.verdict == PASS:
                    j.passing += 1
                else:
                    j.failing[case] = said.verdict
                if said.beyond_bound:
                    j.beyond_bound.append(case)
            out[path][b] = j
    return out, ""


@dataclass
class Option:
    """One backend at one step on the scene, measured."""
    backend: str
    dt: float
    verdict: str
    reason: str
    error: float | None  # m from the common reference over the window
    self_error: float | None  # m from the same backend at the fine step
    cost: Cost | None  # CPU s in the engine's steps per simulated s: what the rule ranks (load does not reorder it)
    parts: dict[str, float | None] = field(default_factory=dict)  # other backend -> when they part (None: never)
    wall: Cost | None = None  # wall s in the engine's steps per simulated s: shown, not ranked
    timed: int = 1  # timed runs its speed is the median of (one where the speed could not change the advice)

    @property
    def ran(self) -> bool:
        return self.error is not None and self.cost is not None and math.isfinite(self.error)


def parting(a: Positions, b: Positions, thresholds: dict[str, float] = DEFAULT_THRESHOLDS) -> float | None:
    """The first frame time at which some body of two runs is further apart than the
    position threshold (m) or turned from itself by more than the orientation one (rad);
    None when they stay within both over every frame they share."""
    times, i, j = shared_frames(a, b)
    if not times.size:
        raise ValueError("the runs share no frame")
    dp, do = pose_gaps(a.values[i], a.orientations[i], b.values[j], b.orientations[j])
    over = np.flatnonzero(((dp > thresholds["position"]) | (do > thresholds["orientation"])).any(axis=1))
    return float(times[over[0]]) if over.size else None


@dataclass
class Advice:
    scene: str
    kind: str
    reference: S.Reference | str
    judged: dict[str, Judged]
    options: list[Option]
    choice: Choice

    def to_json(self) -> dict:
        ref, c = self.reference, self.choice
        return {
            "scene": self.scene, "kind": self.kind, "rule": c.rule, "said": c.said, "settled": c.settled,
            "reference": ref.to_json() if isinstance(ref, S.Reference) else {"backend": None, "method": None,
                                                                             "why_none": ref},
            "judged": {b: vars(j) for b, j in self.judged.items()},
            "options": [_option_json(o) for o in self.options],
            "recommended": None if c.chosen is None else _key(c.chosen),
            "runners_up": [_key(o) for o in c.runners_up],
        }


def _key(o: Option) -> dict:
    return {"backend": o.backend, "dt": o.dt}


def _option_json(o: Option) -> dict:
    d = {"backend": o.backend, "dt": o.dt, "verdict": o.verdict, "reason": o.reason, "error": o.error,
         "self_error": o.self_error, "parts": o.parts}
    if o.cost is not None:
        d.update(cpu_per_sim_s=o.cost.median, cpu_low=o.cost.low, cpu_high=o.cost.high, timed=o.timed)
    if o.wall is not None:
        d.update(wall_per_sim_s=o.wall.median, wall_low=o.wall.low, wall_high=o.wall.high)
    return d


@dataclass
class Choice:
    """What the rule chose: the run (or None), the branch, the first line's honest account of
    why (a tie said as a tie, the tie-break that settled it), each other backend's best run, and
    in a few words how the branch settled it ('the fastest', or the speed tie's tie-break): a
    table's cell, beside a runner-up that may be cheaper."""
    chosen: Option | None
    rule: str
    said: str
    runners_up: list[Option]
    settled: str = ""


def _tiebreak(o: Option, judged: dict[str, Judged]) -> tuple:
    """The tie-breaks, in TIEBREAKS' order (lower is better)."""
    agreeing = sum(1 for t in o.parts.values() if t is None)
    j = judged[o.backend]
    return len(j.approximated), len(j.beyond_bound), -agreeing, -o.dt, o.backend


def _label(o: Option) -> str:
    return f"{o.backend} at dt {dt_label(o.dt)}"


# why a speed ties with the fastest's, in tie()'s order: the words the first line says (never
# "the fastest", which it says of a run nothing ties with)
SPREADS = "within their spreads"
RELATIVE = f"within {SPEED_RELATIVE:.0%} of each other's cost, as much as single runs vary on a shared machine"
FLOOR = (f"within {SPEED_RESOLUTION * 1e3:g} ms of CPU per simulated s and a factor {SPEED_NOISE:g} of each "
         "other, finer than runs this cheap are told apart")
COARSER = (f"as a coarser step of the same backend within a factor {SPEED_NOISE:g} of its cost (a coarser step "
           "does no more work)")


def tie(o: Option, first: Option) -> str | None:
    """Why run o's speed cannot be told from that of `first`, the fastest (SPREADS, RELATIVE,
    FLOOR or COARSER), or None where it can. COARSER: a coarser step does no more work (fewer
    steps; for an error-controlled integrator, fewer step boundaries to land on), so where it
    measures costlier than a finer one of the same backend, the measure is the load's. On the
    bundled pendulum Drake's runs take 1,971 integrator steps a simulated second at dt 1/60 and
    2,073 at 1/240 (its error control sets the step, not the cap), yet at load average 6 one
    timing each put 1/60 at 1.38x the cost of 1/240: beyond the 30% tie, so that advise chose
    1/240 under load and 1/60 on a quiet machine (tests/test_advise_load.py failed so)."""
    a, b = o.cost, first.cost
    if a.ties(b):
        return SPREADS
    if a.median <= (1 + SPEED_RELATIVE) * b.median:
        return RELATIVE
    if a.median <= SPEED_NOISE * b.median:
        if a.median - b.median <= SPEED_RESOLUTION:
            return FLOOR
        if o.backend == first.backend and o.dt > first.dt:
            return COARSER
    return None


def _decided(chosen: Option, rivals: list[Option], judged: dict[str, Judged]) -> int:
    """The tie-break that chose the run from its tied rivals: the one that set aside the last of
    them (each rival falls at the first tie-break on which the two differ)."""
    mine = _tiebreak(chosen, judged)
    return max(next(i for i, (a, b) in enumerate(zip(mine, _tiebreak(r, judged))) if a != b) for r in rivals)


def _fastest(group: list[Option], judged: dict[str, Judged]) -> tuple[Option, str, str]:
    """The fastest by median, the runs whose speed ties with it (tie()) decided by the
    tie-breaks; what to say of its speed ('the fastest' only where nothing ties with it), and
    that in a few words."""
    first = min(group, key=lambda o: o.cost.median)
    tied = [o for o in group if tie(o, first) is not None]
    chosen = min(tied, key=lambda o: _tiebreak(o, judged))
    others = [o for o in tied if o is not chosen]
    if not others:
        return chosen, "the fastest", "the fastest"
    k = _decided(chosen, others, judged)
    # why they tie, each in the words that hold for it (a runner-up at a quarter of the cost is no
    # tie "within its spread"), in tie()'s order
    why = " or ".join(r for r in (SPREADS, RELATIVE, FLOOR, COARSER)
                      if any(tie(o, first) == r for o in tied if o is not first))
    return chosen, (f"tied on speed with {' and '.join(map(_label, others))} {why}; "
                    f"chosen by tie-break {k + 1}: {TIEBREAKS[k]}"), f"tied on speed; tie-break {k + 1}: {TIEBREAKS[k]}"


def _outdone(backend: str, backends: Sequence[str], judged: dict[str, Judged]) -> list[str]:
    """The cases exercising what the scene uses that the backend fails (violates the spec)
    while another of `backends` passes them."""
    return [c for c, v in judged[backend].failing.items() if v == FAIL
            and any(b != backend and c not in judged[b].failing for b in backends)]


def _passed_over(set_aside: list[Option], chosen: Option, outdone: dict[str, list[str]], able: Sequence[str],
                 judged: dict[str, Judged]) -> str:
    """What the first line adds where a run as good by the rule's measure (within the tolerance,
    or more accurate) and no slower was set aside for failing a case another backend passes:
    "the fastest" or "the most accurate" is then of the rest, and says which run it passed over."""
    rivals = [o for o in set_aside if o.cost.median <= chosen.cost.median or o.error < chosen.error]
    if not rivals:
        return ""
    o = min(rivals, key=lambda o: o.cost.median)
    fails = outdone[o.backend]
    passers = [b for b in able if b != o.backend and not set(fails) & set(judged[b].failing)]
    cost = o.cost.median / chosen.cost.median if chosen.cost.median > 0 else float("inf")
    return (f", of the backends that fail no case another passes: {_label(o)} ({cost:.3g}x the cost, error "
            f"{o.error:.3g} m) fails {', '.join(fails)}, which {', '.join(passers)} pass{'es' if len(passers) == 1 else ''}")


def choose(options: Sequence[Option], judged: dict[str, Judged], budget: float, tolerance: float,
           reference_error: float) -> Choice:
    """The rule of the module docstring."""
    ok = [o for o in options if o.ran and not judged[o.backend].refused]
    affordable = [o for o in ok if o.cost.median <= budget]
    if not affordable:
        rule = NONE_AFFORDABLE if ok else NONE_RAN
        return Choice(None, rule, rule, [])
    able = list(dict.fromkeys(o.backend for o in affordable))
    outdone = {b: _outdone(b, able, judged) for b in able}
    clean = [o for o in affordable if not outdone[o.backend]]

    def best(group: list[Option]) -> tuple[Option, str, str, str]:
        accurate = [o for o in group if o.error <= tolerance + reference_error]
        if accurate:
            o, speed, settled = _fastest(accurate, judged)
            rule = WITHIN if reference_error <= tolerance else CANNOT_RANK
            within = ("within the tolerance" if o.error <= tolerance else
                      f"within the tolerance and the reference's uncertainty ({reference_error:.3g} m)")
            return o, rule, f"{within if rule == WITHIN else CANNOT_RANK_SAID}: {speed}", settled
        least = min(o.error for o in group)
        o, speed, settled = _fastest([o for o in group if same_error(o.error, least, reference_error)], judged)
        said = MOST_ACCURATE + ("" if speed == "the fastest" else f"; {speed}")
        if reference_error > tolerance:  # what the reference cannot tell apart is said, not ranked
            said = (f"accuracy cannot be ranked finer than the reference's uncertainty ({reference_error:.3g} m, "
                    f"over the tolerance); {said}, errors within it one")
        return o, MOST_ACCURATE, said, "" if settled == "the fastest" else settled

    chosen, rule, said, settled = best(clean or affordable)
    if not clean:
        said = ("every backend that fits fails a case another passes ("
                + "; ".join(f"{b}: {', '.join(cs)}" for b, cs in outdone.items()) + "), so one is chosen regardless; "
                + said)
    else:
        better = (lambda o: o.error <= tolerance + reference_error) if rule != MOST_ACCURATE else (
            lambda o: o.error < chosen.error - reference_error)
        said += _passed_over([o for o in affordable if outdone[o.backend] and better(o)], chosen, outdone, able, judged)
    others = [best([o for o in affordable if o.backend == b]) for b in able if b != chosen.backend]
    # runners-up in the rule's own order: those within the tolerance by speed, then the rest by error
    others.sort(key=lambda t: (t[1] == MOST_ACCURATE, t[0].cost.median if t[1] != MOST_ACCURATE else t[0].error))
    return Choice(chosen, rule, said, [o for o, _, _, _ in others], settled)


def _outcome(c: Choice) -> tuple:
    """What a choice says: the run, the branch, the first line (its ties, its tie-break, a run it
    passed over) and how the branch settled it."""
    return None if c.chosen is None else _key(c.chosen), c.rule, c.said, c.settled


def unsettled(options: Sequence[Option], judged: dict[str, Judged], budget: float, tolerance: float,
              reference_error: float) -> list[int]:
    """The runs (indices into options) whose speed could change the advice: the chosen one (the
    advice states its speed), and each that, its speed anywhere a single timing may put it (a
    factor 1 + SPEED_RELATIVE either way; SPEED_NOISE under SPEED_RESOLUTION), would change what
    the choice says (_outcome): a run that could tie with the chosen one or outrun it, or cross
    the budget where that decides. Each run alone, the others as measured: advise asks again once
    these are timed again, until none is left."""
    said = choose(options, judged, budget, tolerance, reference_error)
    out = []
    for k, o in enumerate(options):
        if not o.ran or judged[o.backend].refused:
            continue
        if o is said.chosen:
            out.append(k)
            continue
        f = margin(o.cost)
        for g in (1 / f, f):
            moved = replace(o, cost=o.cost.scaled(g))
            if _outcome(choose([moved if p is o else p for p in options], judged, budget, tolerance,
                               reference_error)) != _outcome(said):
                out.append(k)
                break
    return out


def advise(paths: Sequence[str], scenes: dict[str, Scene], plans: dict[str, S.BackendPlan],
           judged: dict[str, dict[str, Judged]], dts: Sequence[float] = DEFAULT_DTS,
           duration: float = DEFAULT_DURATION, window: float = S.DEFAULT_WINDOW, budget: float = DEFAULT_BUDGET,
           tolerance: float = DEFAULT_TOLERANCE, timeout: float = children.DEFAULT_TIMEOUT,
           workers: int | None = None, progress: bool = False, repeats: int = S.REPEATS) -> list[Advice]:
    """Advice for each scene (loaded, with something to simulate), in the order given: each run
    timed once, then those whose speed could change the advice (unsettled) `repeats` times in all.
    The runs go to one pool. Where its first timing is near the budget (near_budget) a run's
    further timings start as it ends, beside the other runs, rather than once they have all
    ended (a speculation: they count only where unsettled() picks the run, as though started
    then, and are dropped where it does not and they have not ended)."""
    out = []
    controlled = S.drake_usable(plans, timeout)  # Drake's error-controlled reference wherever it can run
    with S.Pool(workers) as pool:
        for path in paths:
            able = {b: p for b, p in plans.items() if not judged[path][b].refused}  # a refusal needs no run
            (target,) = S.targets([path], dts, window, duration, scenes)
            ahead = (repeats - 1, lambda cost: near_budget(cost, budget)) if repeats > 1 else None
            swept = (S.run_sweep([target], able, dts, (), (), timeout, None, workers, progress, 1, controlled,
                                 reference_as_fine=True, pool=pool, again=ahead) if able else None)
            options = [] if swept is None else [
                Option(p.backend, p.dt, p.verdict, p.reason, p.error, p.self_error, p.cost, wall=p.wall,
                       timed=len(res.cpu_s)) for p, (_, res) in zip(swept.points, swept.runs)]
            if swept is not None:
                for o in options:
                    mine = swept.positions.get((target.name, o.backend, o.dt))
                    for other in able:
                        theirs = swept.positions.get((target.name, other, o.dt))
                        if other != o.backend and mine is not None and theirs is not None:
                            try:
                                o.parts[other] = parting(mine, theirs)
                            except ValueError:  # no body or frame in common: nothing to say of when they part
                                continue
            reference = swept.references[target.name] if swept is not None else "no backend can run the scene"
            if isinstance(reference, S.Reference):
                reference = reference.without({b: f"which fails {', '.join(cs)}" for b in able
                                               if (cs := _outdone(b, list(able), judged[path]))})
            ref_error = reference.error if isinstance(reference, S.Reference) else 0.0
            again: set[int] = set()
            while swept is not None and repeats > 1:
                picked = [k for k in unsettled(options, judged[path], budget, tolerance, ref_error) if k not in again]
                if not picked:
                    break
                S.time_again(swept, picked, repeats - 1, None, workers, progress, pool)
                again.update(picked)
                for k in picked:
                    p, (_, res) = swept.points[k], swept.runs[k]
                    options[k].cost, options[k].wall, options[k].timed = p.cost, p.wall, len(res.cpu_s)
            for _, future in swept.ahead.values() if swept is not None else ():
                pool.drop(future)  # started ahead and not picked: not waited for
            choice = choose(options, judged[path], budget, tolerance, ref_error)
            if not able:
                choice.rule = choice.said = NONE_CAN
            out.append(Advice(path, kind(scenes[path]), reference, judged[path], options, choice))
    return out


def near_budget(cost: Cost, budget: float) -> bool:
    """Whether a run's first timing lies where one timing more may put it across the budget
    (unsettled()'s factor either way): a run likely to be timed again (where it is accurate
    enough, whether it fits decides the advice), so advise starts its further timings at once."""
    f = margin(cost)
    return budget / f <= cost.median <= budget * f


def margin(cost: Cost) -> float:
    """The factor either way a single timing of this cost may be off by: SPEED_RELATIVE, and
    SPEED_NOISE under SPEED_RESOLUTION (unsettled(), and the sweep's: sweep_timing.py)."""
    return SPEED_NOISE if cost.median < SPEED_RESOLUTION else 1 + SPEED_RELATIVE
