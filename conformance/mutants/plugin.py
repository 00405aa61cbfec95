"""Each mutant as a backend: the entry points site.py declares name this module's attributes.

`mutant-NAME = conformance.mutants.plugin:NAME` (hyphens made underscores: Mutant.attribute):
each attribute is made on first use (a module __getattr__), so that only the child that runs a
mutant imports its base engine. The backend declares what its base declares (a browser with a bug claims what it
claims anyway), and builds with the mutant's edit and relay around the base's build.
"""

from __future__ import annotations

import functools
from typing import Any

from backends import base
from x3d_core.semantics.engine import Simulation
from x3d_core.semantics.world import World

from conformance.mutants.table import BY_NAME, Mutant


class MutantBackend(base.Backend):
    def __init__(self, mutant: Mutant):
        self.mutant = mutant
        self.name = mutant.backend

    @functools.cached_property
    def real(self) -> base.Backend:
        return base.load(self.mutant.base)

    @property
    def declared(self) -> dict[str, base.Declared]:  # type: ignore[override]
        return self.real.declared

    @property
    def limits(self) -> dict:  # type: ignore[override]
        return getattr(self.real, "limits", {})

    @property
    def integration(self) -> str | None:  # type: ignore[override]
        return self.real.integration

    @property
    def accurate_integration(self) -> str | None:  # type: ignore[override]
        return self.real.accurate_integration

    def version(self) -> str:
        return f"{self.mutant.base} {self.real.version()}, mutated: {self.mutant.bug}"

    def build(self, world: World, dt: float) -> Simulation:
        if self.mutant.world is not None:
            self.mutant.world(world)
        sim = self.real.build(world, dt)
        return self.mutant.relay(sim, world) if self.mutant.relay is not None else sim


_BY_ATTRIBUTE = {m.attribute: m for m in BY_NAME.values()}


@functools.cache
def __getattr__(attr: str) -> Any:
    mutant = _BY_ATTRIBUTE.get(attr)
    if mutant is None:
        raise AttributeError(f"module {__name__!r} has no attribute {attr!r}")
    return MutantBackend(mutant)
