"""What the evaluator needs of an engine: a small protocol, so that x3d_core imports none.

backends/ implements it once per engine (see backends/base.py for the declared feature
table and the registry).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from typing import NoReturn, Protocol

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


class Progress:
    """How far the run in progress has come, kept by the evaluator (x3d_core.semantics.evaluator.run) for
    engine_abort: the trace so far, how many of its blocks are whole frames, and the time the
    engine is stepping towards."""

    def __init__(self, trace=None):
        self.trace, self.whole, self.t = trace, 0, 0.0


progress: Progress | None = None  # the run in progress, or None
_on_abort: Callable[[BlewUp], None] | None = None
EXIT_ABORTED = 1  # the exit status after an engine abort, as `x3drbp run` exits on a blow-up


def on_engine_abort(hook: Callable[[BlewUp], None] | None) -> Callable[[BlewUp], None] | None:
    """Install what an engine abort does before the process exits (engine_abort): called with a
    BlewUp whose .trace holds every whole frame so far (None before the first), it does what
    its caller does with a BlewUp raised (`x3drbp run`: writes e.trace, prints one line).
    Returns the hook it replaces."""
    global _on_abort
    previous, _on_abort = _on_abort, hook
    return previous


def engine_abort(message: str) -> NoReturn:
    """An engine is about to end the process from inside a step (ODE's assertions abort()):
    called from the engine's error callback, which cannot raise through C. Makes the blow-up a
    verdict: the BlewUp it would have been (the frames before kept) goes to the on_engine_abort
    hook, then the process exits with EXIT_ABORTED, one line on stderr where no hook wrote one."""
    p = progress
    e = BlewUp(f"blew up by t={p.t:g}: {message}" if p is not None else f"blew up while building: {message}")
    if p is not None and p.trace is not None:
        del p.trace.blocks[p.whole:]
        e.trace = p.trace
    try:
        if _on_abort is not None:
            _on_abort(e)
        else:
            print(f"{e} (no trace written)", file=sys.stderr)
    except BaseException as err:  # a hook that fails still ends in one line and the exit status
        print(f"{e} (and writing what ran failed: {type(err).__name__}: {err})", file=sys.stderr)
    finally:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except Exception:
                pass
        os._exit(EXIT_ABORTED)


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

    def watched_contacts(self, k: int) -> ContactPoints:
        """The contact points of world.watched[k], a set only sensors watch, detected where the
        bodies are now (asked for at frame ends) and never acted on: geometry indices into that
        set's geometries. Only a backend that declares CollisionSensor.collider.watchedOnly
        supported is asked (x3d_core.semantics.analysis refuses the others)."""

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        """The force (at the centre of mass) and torque every body gets at each step from
        now on, world frame; a build starts with the world's forces and torques fields."""


def target_accuracy(sim: Simulation) -> float | None:
    """The target accuracy of the error-controlled integrator a simulation steps by (an
    attribute target_accuracy, which a fixed-step simulation need not have); None where it
    steps by the fixed step. An engine may pick its mode per world (Drake's continuous plant
    only where nothing collides), so only the simulation can say whether a run was
    error-controlled: the sweep's reference must be (conformance/analyses/sweep.py)."""
    return getattr(sim, "target_accuracy", None)


class Engine(Protocol):
    name: str

    def build(self, world: World, dt: float) -> Simulation:
        """An engine model of exactly what the world needs."""
