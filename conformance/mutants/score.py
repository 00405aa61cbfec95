"""Which mutants the conformance suite kills, and by which cases.

A mutant is killed by a case where its verdict is worse than its base's: pass < conventions <
fail, and a run that gives no judged verdict (crashed, timed out, blew up, error, or refused
as unsupported) is worse than any judged one. How it is killed matters as much (Fate.turned):
a kill to "fail" turns a spec measure, a sentence of the clause the bug breaks; a kill to
"conventions" alone turns only a reading where the clause is silent, which an implementer
would be told is a difference in conventions, not a bug. Only a case its base passes or conforms to in
all but conventions can kill: where the base fails already, or never ran, a bug changes
nothing the verdict could show. So each mutant runs on those cases of its base alone.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, field

from conformance.cases.case import Case
from conformance.results import CONVENTION, CONVENTIONS, FAIL, PASS, SPEC, Result
from conformance.runner import verdicts
from conformance.runner.children import DEFAULT_TIMEOUT

from conformance.mutants.table import Mutant

RANK = {PASS: 0, CONVENTIONS: 1, FAIL: 2}
UNJUDGED = 3  # crashed, timed out, blew up, error, unsupported
KILLABLE = (PASS, CONVENTIONS)
REFUSED = "refused"  # killed only by runs with no judged verdict (a crash, a refusal, a blow-up)


def worse(mutated: str, base: str) -> bool:
    """Whether the verdict on a mutant kills it, against its base's on the same case."""
    return base in KILLABLE and RANK.get(mutated, UNJUDGED) > RANK[base]


@dataclass
class Fate:
    """One mutant's runs, each beside its base's verdict on the case."""
    mutant: Mutant
    runs: list[tuple[Result, str]] = field(default_factory=list)  # (the mutant's result, the base's verdict)

    @property
    def kills(self) -> list[tuple[Result, str]]:
        return [(r, b) for r, b in self.runs if worse(r.verdict, b)]

    @property
    def killed(self) -> bool:
        return bool(self.kills)

    @property
    def turned(self) -> str | None:
        """What the kills turned: SPEC where one of them is a fail (a spec measure), else REFUSED where
        one is a run with no judged verdict, else CONVENTION (conventions only); None if not killed."""
        verdicts = {r.verdict for r, _ in self.kills}
        if not verdicts:
            return None
        if FAIL in verdicts:
            return SPEC
        return CONVENTION if verdicts == {CONVENTIONS} else REFUSED


@dataclass
class Score:
    fates: list[Fate]  # the mutants'
    controls: list[Fate]  # the identity mutants': none may be killed
    bases: dict[str, list[Result]]  # each base's results on every case
    wall_s: float

    @property
    def killed(self) -> int:
        return sum(f.killed for f in self.fates)

    def turning(self, how: str) -> list[Fate]:
        """The killed mutants whose kills turned `how` (SPEC, CONVENTION or REFUSED)."""
        return [f for f in self.fates if f.turned == how]

    @property
    def percent(self) -> float:
        return 100.0 * self.killed / len(self.fates) if self.fates else 0.0


def measure(mutants: Sequence[Mutant], controls: Sequence[Mutant], cases: Sequence[Case],
            timeout: float = DEFAULT_TIMEOUT, workers: int | None = None, progress: bool = False) -> Score:
    """Every base on every case, then every mutant (controls too) on its base's killable cases.
    The mutants must be installed (site.py) where the runner's children look."""
    started = time.perf_counter()
    names = list(dict.fromkeys(m.base for m in (*mutants, *controls)))
    ran = verdicts.run_matrix(cases, names, timeout, workers, progress=progress)
    bases = {b: [r for r in ran if r.backend == b] for b in names}
    verdict = {(r.case, r.backend): r.verdict for r in ran}
    fates = [Fate(m) for m in (*mutants, *controls)]
    jobs = [(f, c) for f in fates for c in cases if verdict[(c.name, f.mutant.base)] in KILLABLE]
    results = verdicts.run_many([(lambda m=f.mutant, c=c: verdicts.run_pair(c, m.backend, timeout))
                                 for f, c in jobs], workers, progress)
    for (f, c), r in zip(jobs, results):
        f.runs.append((r, verdict[(c.name, f.mutant.base)]))
    return Score(fates[:len(mutants)], fates[len(mutants):], bases, time.perf_counter() - started)
