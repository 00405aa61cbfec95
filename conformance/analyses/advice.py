"""Advice for a user's scene: which backend, at which step, and why.

Per scene: what each backend makes of the features the scene uses (refused, approximated,
and the verdicts of the conformance cases that exercise them), then a small sweep
(conformance/analyses/sweep.py) of the scene as the file gives it on every backend that can
run it, at a few steps, against one common reference (Drake's error-controlled run where
Drake runs the scene in continuous mode, whether or not it is compared; else one backend's
fine run; sweep.py says which and how its own error is estimated), with each run's speed
the median of repeats; and how long each run stays within 1 mm / 1 mrad of each other backend's run at
the same step. The recommendation is a rule, stated here and in docs/commands/advise.md, not a score:

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
Speeds whose repeats' spreads overlap the fastest's, or that differ from it by less than
SPEED_RESOLUTION (1 ms per simulated second) or SPEED_RELATIVE (30% of it), are ties, and
the advice says a tie is
one ("tied on speed with ...; chosen by tie-break 1: fewer approximations"), never "the
fastest". The tie-breaks (TIEBREAKS): 1, fewer approximations of what the scene uses (one
per declared note, however many uses it covers); 2, fewer conformance cases exercising the
scene's features whose accuracy is graded beyond its bound; 3, the run that stays within
1 mm / 1 mrad of more other backends for the whole run; 4, the coarser step; 5, the
backend's name. Each other backend's best run by the same rule is a runner-up, with what
it would cost or lose against the recommendation.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from x3d_core.analysis import run_features
from x3d_core.model import Scene

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
# CPU s per simulated s: speeds closer than this are ties. Runs this cheap (1,000x real time)
# are resolved by no measure under load (a busy sibling hyperthread doubled a 0.3 ms run's CPU
# time), and no budget hangs on the difference.
SPEED_RESOLUTION = 1e-3
# and speeds within this fraction of each other: single runs' CPU time varies by up to 30% on a
# shared machine (benchmarks/engine_speed.py, load 2), and a load widens some runs' spreads and
# not others' (an error-controlled integrator's cost barely depends on the step: Drake's runs at
# 1/60 and 1/240 swapped places under a CPU hog)
SPEED_RELATIVE = 0.3
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
from x3d_core.load import load
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
        d.update(cpu_per_sim_s=o.cost.median, cpu_low=o.cost.low, cpu_high=o.cost.high)
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


def _fastest(group: list[Option], judged: dict[str, Judged]) -> tuple[Option, str, str]:
    """The fastest by median, ties (spreads overlapping its own) broken by the tie-breaks; what
    to say of its speed ('the fastest' only where nothing ties with it), and that in a few words."""
    first = min(group, key=lambda o: o.cost.median)
    margin = max(SPEED_RESOLUTION, SPEED_RELATIVE * first.cost.median)
    tied = [o for o in group if o.cost.ties(first.cost) or o.cost.median - first.cost.median <= margin]
    chosen = min(tied, key=lambda o: _tiebreak(o, judged))
    others = [o for o in tied if o is not chosen]
    if not others:
        return chosen, "the fastest", "the fastest"
    rival = min(others, key=lambda o: _tiebreak(o, judged))
    k = next(i for i, (a, b) in enumerate(zip(_tiebreak(chosen, judged), _tiebreak(rival, judged))) if a != b)
    # why they tie, in the words that hold: a runner-up at a quarter of the cost is no tie "within
    # its spread", but it is one within the resolution no measure on a shared machine beats
    why = ("within their spreads" if all(o.cost.ties(first.cost) for o in tied) else
           f"within {margin * 1e3:.2g} ms of CPU per simulated s of each other, finer than runs this cheap are "
           "told apart")
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


def advise(paths: Sequence[str], scenes: dict[str, Scene], plans: dict[str, S.BackendPlan],
           judged: dict[str, dict[str, Judged]], dts: Sequence[float] = DEFAULT_DTS,
           duration: float = DEFAULT_DURATION, window: float = S.DEFAULT_WINDOW, budget: float = DEFAULT_BUDGET,
           tolerance: float = DEFAULT_TOLERANCE, timeout: float = children.DEFAULT_TIMEOUT,
           workers: int | None = None, progress: bool = False, repeats: int = S.REPEATS) -> list[Advice]:
    """Advice for each scene (loaded, with something to simulate), in the order given."""
    out = []
    controlled = S.drake_usable(plans, timeout)  # Drake's error-controlled reference wherever it can run
    for path in paths:
        able = {b: p for b, p in plans.items() if not judged[path][b].refused}  # a refusal needs no run
        (target,) = S.targets([path], dts, window, duration, scenes)
        swept = (S.run_sweep([target], able, dts, (), (), timeout, None, workers, progress, repeats, controlled)
                 if able else None)
        options = [] if swept is None else [
            Option(p.backend, p.dt, p.verdict, p.reason, p.error, p.self_error, p.cost, wall=p.wall) for p in swept.points]
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
        choice = choose(options, judged[path], budget, tolerance, ref_error)
        if not able:
            choice.rule = choice.said = NONE_CAN
        out.append(Advice(path, kind(scenes[path]), reference, judged[path], options, choice))
    return out
