"""Advice for a user's scene: which backend, at which step, and why.

Per scene: what each backend makes of the features the scene uses (refused, approximated,
and the verdicts of the conformance cases that exercise them), then a small sweep
(conformance/analyses/sweep.py) of the scene as the file gives it on every backend that can
run it, at a few steps, against one common reference, with each run's speed the median of
repeats; and how long each run stays within 1 mm / 1 mrad of each other backend's run at
the same step. The recommendation is a rule, stated here and in README, not a score:

1. Out: a backend that refuses a feature the scene uses, and every run that did not end
   well (blew up, crashed, timed out).
2. Affordable: a run whose engine steps cost at most `budget` wall seconds per simulated
   second (median of the repeats; 1 is real time).
3. Of the affordable runs, those within `tolerance` of the reference (error <= tolerance +
   the reference's own error): the fastest by median. Accuracy beyond the tolerance is
   not asked for, so a coarser step that is accurate enough wins.
4. No affordable run within the tolerance: the most accurate affordable run (errors within
   the reference's own error or rounding tie; the fastest of those).
5. Nothing affordable: no recommendation; the fastest run is named with its cost. No
   recommendation either where no run ended well, or where every backend refuses a use
   the scene makes (a routed input, say: each refusal is listed).
Speeds whose repeats' spreads overlap the fastest's are ties; ties go to the backend with
fewer approximations of what the scene uses (one per declared note, however many uses it
covers), then to fewer conformance cases exercising the scene's features whose accuracy is
graded beyond its bound, then to the run that stays within 1 mm /
1 mrad of more other backends for the whole run, then to the coarser step, then to the
backend's name. Each other backend's best run by the same rule is a runner-up, with what it
would cost or lose against the recommendation.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from x3d_core.analysis import run_features
from x3d_core.model import Scene

from conformance import cases as C
from conformance.results import PASS
from conformance.runner import children, probe
from conformance.analyses import sweep as S
from conformance.analyses.compare import DEFAULT_THRESHOLDS, pose_gaps
from conformance.analyses.sweep_metrics import Cost, Positions, same_error, shared_frames

DEFAULT_DTS = (1 / 60, 1 / 240, 1 / 1000)
DEFAULT_DURATION = 5.0  # s: how long the runs are watched for parting
DEFAULT_BUDGET = 1.0  # wall s in the engine's steps per simulated s: real time
DEFAULT_TOLERANCE = 1e-3  # m from the reference over the window: the 1 mm compare holds runs to
JOINTS = ("BallJoint", "SingleAxisHingeJoint", "DoubleAxisHingeJoint", "SliderJoint", "UniversalJoint", "MotorJoint")
WITHIN, MOST_ACCURATE, NONE_AFFORDABLE, NONE_RAN, NONE_CAN = (
    "within the tolerance: the fastest", "none within the tolerance: the most accurate",
    "nothing fits the budget", "no run ended well", "every backend refuses a use the scene makes")


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
    cost: Cost | None  # wall s in the engine's steps per simulated s
    parts: dict[str, float | None] = field(default_factory=dict)  # other backend -> when they part (None: never)

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
    recommended: Option | None
    rule: str  # which branch of the rule chose it
    runners_up: list[Option]

    def to_json(self) -> dict:
        ref = self.reference
        return {
            "scene": self.scene, "kind": self.kind, "rule": self.rule,
            "reference": ({"backend": ref.backend, "dt": ref.dt, "error": ref.error} if isinstance(ref, S.Reference)
                          else {"backend": None, "why_none": ref}),
            "judged": {b: vars(j) for b, j in self.judged.items()},
            "options": [_option_json(o) for o in self.options],
            "recommended": None if self.recommended is None else _key(self.recommended),
            "runners_up": [_key(o) for o in self.runners_up],
        }


def _key(o: Option) -> dict:
    return {"backend": o.backend, "dt": o.dt}


def _option_json(o: Option) -> dict:
    d = {"backend": o.backend, "dt": o.dt, "verdict": o.verdict, "reason": o.reason, "error": o.error,
         "self_error": o.self_error, "parts": o.parts}
    if o.cost is not None:
        d.update(wall_per_sim_s=o.cost.median, wall_low=o.cost.low, wall_high=o.cost.high)
    return d


def choose(options: Sequence[Option], judged: dict[str, Judged], budget: float, tolerance: float,
           reference_error: float) -> tuple[Option | None, str, list[Option]]:
    """The rule of the module docstring: (the recommended run or None, the branch that
    chose it, each other backend's best run, best first)."""
    ok = [o for o in options if o.ran and not judged[o.backend].refused]
    affordable = [o for o in ok if o.cost.median <= budget]
    if not affordable:
        return None, NONE_AFFORDABLE if ok else NONE_RAN, []

    def tiebreak(o: Option) -> tuple:
        agreeing = sum(1 for t in o.parts.values() if t is None)
        j = judged[o.backend]
        return len(j.approximated), len(j.beyond_bound), -agreeing, -o.dt, o.backend

    def fastest(group: list[Option]) -> Option:
        """The fastest by median, ties (spreads overlapping its own) broken by tiebreak."""
        first = min(group, key=lambda o: o.cost.median)
        return min((o for o in group if o.cost.ties(first.cost)), key=tiebreak)

    def best(group: list[Option]) -> tuple[Option, str]:
        accurate = [o for o in group if o.error <= tolerance + reference_error]
        if accurate:
            return fastest(accurate), WITHIN
        least = min(o.error for o in group)
        return fastest([o for o in group if same_error(o.error, least, reference_error)]), MOST_ACCURATE

    chosen, rule = best(affordable)
    others = [best([o for o in affordable if o.backend == b]) for b in dict.fromkeys(o.backend for o in affordable)
              if b != chosen.backend]
    # runners-up in the rule's own order: those within the tolerance by speed, then the rest by error
    others.sort(key=lambda pair: (pair[1] != WITHIN, pair[0].cost.median if pair[1] == WITHIN else pair[0].error))
    return chosen, rule, [o for o, _ in others]


def advise(paths: Sequence[str], scenes: dict[str, Scene], plans: dict[str, S.BackendPlan],
           judged: dict[str, dict[str, Judged]], dts: Sequence[float] = DEFAULT_DTS,
           duration: float = DEFAULT_DURATION, window: float = S.DEFAULT_WINDOW, budget: float = DEFAULT_BUDGET,
           tolerance: float = DEFAULT_TOLERANCE, timeout: float = children.DEFAULT_TIMEOUT,
           workers: int | None = None, progress: bool = False, repeats: int = S.REPEATS) -> list[Advice]:
    """Advice for each scene (loaded, with something to simulate), in the order given."""
    out = []
    for path in paths:
        able = {b: p for b, p in plans.items() if not judged[path][b].refused}  # a refusal needs no run
        (target,) = S.targets([path], dts, window, duration)
        swept = S.run_sweep([target], able, dts, (), (), timeout, None, workers, progress, repeats) if able else None
        options = [] if swept is None else [
            Option(p.backend, p.dt, p.verdict, p.reason, p.error, p.self_error, p.cost) for p in swept.points]
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
        ref_error = reference.error if isinstance(reference, S.Reference) else 0.0
        chosen, rule, runners_up = choose(options, judged[path], budget, tolerance, ref_error)
        if not able:
            rule = NONE_CAN
        out.append(Advice(path, kind(scenes[path]), reference, judged[path], options, chosen, rule, runners_up))
    return out
