"""What the evaluator needs of an engine: a small protocol, so that x3d_core imports none.

backends/ implements it once per engine (see backends/base.py for the declared feature
table and the registry).
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from .collision import ContactPoints
from .world import State, World


class Unsupported(Exception):
    """The engine cannot build something the world needs that no feature name covers
    (a slider closing a loop of joints, say); the message says what."""


class Stopped(RuntimeError):
    """The run ended before its duration; the message says why. `trace`, set by the
    evaluator, holds every frame before: what did run is kept."""

    trace = None


class BlewUp(Stopped):
    """A body's state stopped being finite (or sane, see evaluator.STATE_BOUND), or the
    engine gave up on it; the message says what (the evaluator adds when)."""


class TimedOut(Stopped):
    """The run passed its wall-clock limit (`x3drbp run --timeout`), raised between steps."""


class Simulation(Protocol):
    """One World built in one engine."""

    def step(self, n: int = 1) -> None:
        """Advance n fixed steps, with gravity, forces and torques applied at each."""

    def state(self) -> State:
        """Every body's state, rows as in world.bodies, read in bulk."""

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        """Overwrite every body's velocities (world frame; linear at the centre of mass);
        fixed bodies ignore it."""

    def contacts(self) -> ContactPoints:
        """The contact points of the last step (only asked for where a CollisionSensor or
        the trace needs them; a world without collisions has none)."""

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        """The force (at the centre of mass) and torque every body gets at each step from
        now on, world frame; a build starts with the world's forces and torques fields."""


class Engine(Protocol):
    name: str

    def build(self, world: World, dt: float) -> Simulation:
        """An engine model of exactly what the world needs."""
