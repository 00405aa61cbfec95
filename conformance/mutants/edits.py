"""The two ways a mutant injects its bug: an edit of the World, and a relay of the Simulation.

A World edit is made in place, on the World the run holds, before the engine builds it: what
x3d_core computes for every engine from the same World (damping, MotorJoint torques, joint
outputs, auto-disable) then reads the bug too, as a browser that misreads a field misreads it
for its own outputs. A relay stands between the evaluator and the built simulation and
distorts what one call reports or receives; the plain Relay changes nothing (the identity
mutant: the wrapping itself is faithful).
"""

from __future__ import annotations

import dataclasses
from collections import defaultdict
from collections.abc import Callable
from typing import Any

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.semantics import world as W
from x3d_core.semantics.collision import ContactPoints, Geometry, _shapes
from x3d_core.semantics.engine import Simulation
from x3d_core.semantics.world import Joint, State, World

WorldEdit = Callable[[World], None]


def reset(path: str, how: Callable[[Any], Any]) -> WorldEdit:
    """The value at a dotted path of the World (bodies.mass, collisions.parameters.bounce)
    replaced by how(value); nothing where the path meets None (a world where nothing collides)."""
    *parents, last = path.split(".")

    def edit(world: World) -> None:
        owner: Any = world
        for name in parents:
            owner = getattr(owner, name)
            if owner is None:
                return
        value = getattr(owner, last)
        if value is not None:
            setattr(owner, last, how(value))
    return edit


def joints(types: tuple[str, ...], how: Callable[[Joint], None]) -> WorldEdit:
    """how(joint) for each joint of those types."""
    def edit(world: World) -> None:
        for j in world.joints:
            if j.type in types:
                how(j)
    return edit


def params(types: tuple[str, ...], **how: Callable[[float], float]) -> WorldEdit:
    """Numeric joint fields replaced by how[field](value), where the joint has the field."""
    def edit(j: Joint) -> None:
        j.params.update({f: h(j.params[f]) for f, h in how.items() if f in j.params})
    return joints(types, edit)


def geometries(how: Callable[[Geometry], Geometry]) -> WorldEdit:
    """Each collision geometry replaced by how(geometry)."""
    return reset("collisions", lambda c: dataclasses.replace(c, geometries=[how(g) for g in c.geometries]))


def hold(rows: Callable[[World], np.ndarray]) -> WorldEdit:
    """The bodies held out of the physics made rows(world) (a bool per body): joints rejoined
    to the bodies now free (a fixed body is the static environment to a joint) and the joint
    forest grown again, as world.py builds them."""
    def edit(world: World) -> None:
        b = world.bodies
        b.fixed = rows(world)
        at = {id(n): i for i, n in enumerate(b.nodes)}
        world.joints = [W._joint(j.node, at, b.fixed, {id(j.node): j.name}) for j in world.joints]
        W._forest(world)
    return edit


def every_body_collides(world: World) -> None:
    """Every body's collidables collide: a body the collider leaves out collides with its own."""
    c = world.collisions
    if c is None:
        return
    listed = {g.body for g in c.geometries}
    extra: list[Geometry] = []
    for row, body in enumerate(world.bodies.nodes):
        for node in body.get("geometry"):
            if row not in listed and node.get("enabled") and world.bodies.enabled[row]:
                names = defaultdict(lambda: node.def_name or node.type_name)
                _shapes(node, row, (np.zeros(3), R.IDENTITY.copy()), names, extra)
    world.collisions = dataclasses.replace(c, geometries=[*c.geometries, *extra])


class Relay:
    """A Simulation that passes every call on to the engine's; a mutant's relay overrides the
    call its bug distorts."""

    def __init__(self, inner: Simulation, world: World):
        self.inner, self.world = inner, world

    def __getattr__(self, name: str) -> Any:  # step, state, set_velocities, set_loads, contacts
        return getattr(self.inner, name)


class LateState(Relay):
    """Reports the state from before the last step call (a frame late where the evaluator
    steps a whole frame at once)."""

    before: State | None = None

    def step(self, n: int = 1) -> None:
        if n > 1:
            self.inner.step(n - 1)
        self.before = self.inner.state()
        self.inner.step(1)

    def state(self) -> State:
        return self.before if self.before is not None else self.inner.state()


class BodyFrameSpin(Relay):
    """Reports angular velocity in each body's own frame, not the world's."""

    def state(self) -> State:
        s = self.inner.state()
        return dataclasses.replace(s, angular_velocity=R.rotate(R.conjugate(s.orientation), s.angular_velocity))


class BodyFrameLoads(Relay):
    """Applies the forces (with `forces`) or torques (with `torques`) it is given, world frame,
    as if they were in each body's frame: turned by the body's orientation at every step."""

    def __init__(self, inner: Simulation, world: World, forces: bool = False, torques: bool = False):
        super().__init__(inner, world)
        self.turned = (forces, torques)
        self.loads = (world.bodies.forces.copy(), world.bodies.torques.copy())

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        self.loads = (np.array(forces), np.array(torques))
        self.inner.set_loads(forces, torques)

    def step(self, n: int = 1) -> None:
        if not any(t and np.any(v) for v, t in zip(self.loads, self.turned)):
            self.inner.step(n)
            return
        for _ in range(n):
            q = self.inner.state().orientation
            self.inner.set_loads(*(R.rotate(q, v) if t else v for v, t in zip(self.loads, self.turned)))
            self.inner.step(1)


class FlippedNormals(Relay):
    """Reports each contact's normal pointing from geometry2 towards geometry1."""

    def contacts(self) -> ContactPoints:
        p = self.inner.contacts()
        return dataclasses.replace(p, normal=-p.normal)

