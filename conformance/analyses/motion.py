"""The bodies of a scene as the engines got them, and their motion read off a trace: what the
energy and momentum checks of `stability` and `energy` compute from."""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from x3d_core.encodings.load import load
from x3d_core.semantics import rotation as R
from x3d_core.semantics.world import worlds
from x3d_core.traces.trace import TraceView


@dataclass
class Model:
    """The bodies as the engines got them (x3d_core's reading of the scene), by trace name."""
    names: list[str]
    mass: np.ndarray  # (n,)
    inertia: np.ndarray  # (n, 3, 3) body axes, about the centre of mass
    com: np.ndarray  # (n, 3) local
    moving: np.ndarray  # (n,) bool: not fixed
    gravity: np.ndarray  # (3,), or (n, 3): the gravity each body feels

    def rows(self, names: Sequence[str] = ()) -> list[int]:
        """Rows of the named bodies (all moving bodies when none are named)."""
        if not names:
            return [int(i) for i in np.flatnonzero(self.moving)]
        return [self.names.index(n) for n in names]


@functools.lru_cache(maxsize=None)
def model(path: str) -> Model:
    w = worlds(load(path))[0]
    b = w.bodies
    return Model(list(b.names), b.mass, b.inertia, b.com, ~b.fixed, w.gravity)


@dataclass
class Motion:
    """Bodies' states over the frames: (frames, bodies, ...) arrays; the centre of mass's
    position and velocity, world inertia and angular velocity."""
    t: np.ndarray
    com: np.ndarray
    v: np.ndarray
    w: np.ndarray
    i_world: np.ndarray
    mass: np.ndarray

    @classmethod
    def read(cls, view: TraceView, m: Model, rows: Sequence[int]) -> Motion:
        def stack(fld: str) -> np.ndarray:
            return np.stack([view.series(m.names[r], fld)[1] for r in rows], axis=1)
        t = view.series(m.names[rows[0]], "position")[0]
        mats = R.matrix(R.from_axis_angle(stack("orientation")))
        com = stack("position") + np.einsum("fbij,bj->fbi", mats, m.com[rows])
        i_world = mats @ m.inertia[rows] @ np.swapaxes(mats, -1, -2)
        return cls(t, com, stack("linearVelocity"), stack("angularVelocity"), i_world, m.mass[rows])

    def kinetic(self) -> np.ndarray:
        """Kinetic energy per frame (J), translation and rotation."""
        linear = 0.5 * np.einsum("b,fbi,fbi->f", self.mass, self.v, self.v)
        return linear + 0.5 * np.einsum("fbi,fbij,fbj->f", self.w, self.i_world, self.w)

    def potential(self, gravity: np.ndarray) -> np.ndarray:
        """Potential energy per frame (J), zero at the origin; gravity (3,) for every body, or
        (bodies, 3) one per body read."""
        return -np.einsum("b,fbi,bi->f", self.mass, self.com, np.broadcast_to(gravity, self.com.shape[1:]))

    def energy(self, gravity: np.ndarray) -> np.ndarray:
        """Kinetic plus potential energy per frame (J), potential zero at the origin."""
        return self.kinetic() + self.potential(gravity)

    def angular_momentum(self) -> np.ndarray:
        """World angular momentum about the origin per frame, (frames, 3)."""
        spin = np.einsum("fbij,fbj->fi", self.i_world, self.w)
        return spin + np.einsum("b,fbi->fi", self.mass, R.cross(self.com, self.v))


def first_past(t: np.ndarray, x: np.ndarray, bound: float) -> float | None:
    """The first time x exceeds bound (a non-finite x counts as past it)."""
    past = np.flatnonzero(~(np.asarray(x) <= bound))
    return float(t[past[0]]) if past.size else None
