"""What a conformance case is: a scene, how to run it, what must come out, and the scene
edits it must catch."""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from x3d_core.traces.trace import TraceView

from conformance.results import Measure, Settings

HERE = os.path.dirname(os.path.abspath(__file__))

# the traces of the case's runs, in order, and the runs' settings -> the measures
Expectation = Callable[[Sequence[TraceView], Sequence[Settings]], list[Measure]]


@dataclass(frozen=True)
class Mutation:
    """A scene edit that stands for a backend ignoring what the case checks (usually its key
    field reset to the default): the case must FAIL on the mutated scene. `old` is text the
    scene holds exactly once, replaced by `new`; a case about its runs rather than a field
    (frame_rate) replaces the runs instead (old = new = "": the scene as it is). `spec` is False
    where what the edit stands for is itself a reading of a point the clause leaves open (a
    frame-period step, friction directions that follow the motion): the edit must then make a
    measure fail, a convention at least, and the case may still conform. `grades` is True where
    the edit stands for a looser solve, which the clause allows (a loop of joints held softly):
    it must then push an accuracy grade past its bound, and the verdict may stay. `on` names the
    backend the edit is judged on where the reference cannot show it (it honours the field whatever
    the scene says: MuJoCo turns every body by the exponential map): the case must pass there as it
    is, and the edit is judged there alone."""
    old: str
    new: str
    runs: tuple[Settings, ...] | None = None
    spec: bool = True
    grades: bool = False
    on: str | None = None

    def apply(self, text: str) -> str:
        """The scene's text with the edit made (ValueError unless `old` is there exactly once)."""
        if not self.old:
            return text
        found = text.count(self.old)
        if found != 1:
            raise ValueError(f"the mutation's text is in the scene {found} times, not once: {self.old!r}")
        return text.replace(self.old, self.new)


@dataclass(frozen=True)
class Case:
    name: str
    scene: str  # file name in the case's folder (or an absolute path)
    checks: str  # one line: the field(s) exercised and the closed form or invariant
    runs: tuple[Settings, ...]
    expect: Expectation
    # the Measure whose error is against a continuous closed form, so that its decrease with
    # dt (the fitted order) shows convergence; None where the check is exact or an invariant
    convergence: str | None = None
    expected_order: float | None = None  # what semi-implicit Euler gives, for the reader
    # the feature names (x3d_core.semantics.analysis) the case exercises with non-default values: the
    # case would fail if a backend ignored them
    exercises: tuple[str, ...] = field(default_factory=tuple)
    # Mutations, or (old, new) pairs for scene edits: at least one per case
    mutations: tuple[Mutation, ...] = field(default_factory=tuple)
    folder: str = ""  # the case's folder (discover() sets it; "": conformance/cases/NAME)
    # the subjects ("TYPE DEF.field") of the loader's warnings the scene provokes on purpose: a case
    # about what the clause makes of a value authors are warned of (forceOutput's names beside NONE)
    warned: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "mutations", tuple(m if isinstance(m, Mutation) else Mutation(*m)
                                                    for m in self.mutations))

    @property
    def path(self) -> str:
        if os.path.isabs(self.scene):
            return self.scene
        return os.path.join(self.folder or os.path.join(HERE, self.name), self.scene)

    def at_dt(self, dt: float) -> tuple[Settings, ...]:
        return tuple(s.with_dt(dt) for s in self.runs)
