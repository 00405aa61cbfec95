"""ODE backend (the system's libode through backends/ode_lib.py): the engine the spec's parameters come from.

Every body is an ODE body and every joint an ODE joint between two bodies (or a body
and the static environment, ODE's NULL body), so loops need nothing special. ODE puts a
body's frame at its centre of mass: a body starts at its X3D origin plus the turned
centerOfMass, and state() takes that offset back off; its geometries are offset from
the centre of mass by the same amount. A fixed body is no ODE body: its joints attach
to the static environment and its geometries are placed in the world.

ODE facts this relies on (Debian's libode8, ODE 0.16.2, double precision; measured in
tests/test_backend_ode.py and tests/test_collisions_ode.py): dJointAttach(j, 0, b)
swaps the ends and marks the joint reversed, so a hinge's or a slider's angle, rate
and stops still measure body1 relative to body2 (x3d_core's convention, which is ODE's);
hinge2 reads axis 1 in body1 and axis 2 in body2 and ODE aborts the process when one is
attached to a single body, so a kinematic body at rest stands in for the static end; force and torque accumulators are cleared
after each step (loads are written into them before every one); dBodyGet* return
pointers into the body, read in bulk through one numpy view (ode_lib.Window); the
quick-step solver runs dWorldSetQuickStepNumIterations sweeps, dWorldStep is the
direct (Dantzig) solver; both integrate semi-implicit Euler, with the rotation as
ODE's finite rotation mode says.

A SliderJoint's stops are ODE's at StopERP 0 (the row stops the motion, or bounces it at
stopBounce times the impact rate), and their error correction is the backend's (_hold): ODE's
StopERP corrects a stop's depth by a velocity that stays once the depth is gone, so a body
crossing the stop in a step was sent back at up to its impact speed with stopBounce 0, which
the clause's "no bounce at all" forbids (docs/spec-loose-ends.md, 13). Hinge stops are still
ODE's StopERP.

Collisions (where world.collisions is not None): one ODE geom per geometry, in no space.
The broad phase is numpy's: moving geoms as bounding spheres (every allowed pair listed at
build and tested at once where there are few, _ALL_PAIRS; else binned in a grid, see
_near), static ones as their ODE AABBs, pairs kept where x3d_core's may_touch allows; each
step then runs dCollide over the overlapping pairs in index order (the lower index as
ODE's geom 1), so contacts come in the same order every run; it needs no Python
callback from C per candidate pair, as dSpaceCollide would (not measured against it),
and never tests two unmoving geoms unless a sensor reports them. ODE's contact normal points from geom
2 into geom 1: turned round for ContactPoints. Every contact gets one dContact surface,
the collection's parameters as ODE's own mode bits (appliedParameters is ODE's mode
word), with dContactApprox1 so that mu is Coulomb's coefficient (without it ODE reads
mu as a force bound in newtons). A set only sensors watch (world.watched) gets geoms of its own
on the same bodies, tested the same way where the bodies are at each frame's end, and no
contact joint: ODE reports them and nothing feels them.
"""

from __future__ import annotations

import ctypes
import math
import sys
from typing import NamedTuple

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.semantics.collision import Collisions, ContactPoints, ContactParameters, Geometry
from x3d_core.semantics.engine import BlewUp, Unsupported, engine_abort
from x3d_core.semantics.world import STATIC, Joint, State, World

from . import ode_lib as ode
from .base import BODIES, JOINTS, SEMI_IMPLICIT, SMALLEST_NORMAL, Backend, approximate, below, native, unsupported

lib = ode.lib
_FULL_TURN = np.pi - 1e-9  # an angle range this wide is no limit at all
_Z_TO_Y = R.from_axis_angle(np.array([1.0, 0.0, 0.0, -np.pi / 2]))  # ODE's cylinder axis z, turned to X3D's y
_CONE_SIDES = 64  # a cone is the convex hull of a 64-gon and its apex
_PER_PAIR = 16  # the most contacts dCollide returns for one pair of geoms
_SLACK = 1e-9  # m: bounding volumes this close count as overlapping
# Up to this many pairs with a moving side, every allowed pair is listed once at build and
# tested in one vectorised pass a step; past it, _near's grid (linear in the geoms). Measured
# (CPU, dt 1/240, same contacts to the bit): a car's 4 wheels on a floor, 2 s in 0.06 s against
# the grid's 0.18 s; 100 boxes in a pit (5450 pairs) 0.49 s against 0.63 s; 200 bodies in it
# (20900 pairs), 1 s in 0.54 s against 0.30 s
_ALL_PAIRS = 8000


def _fatal(kind: str, number: int, text: str) -> None:
    """ODE's error and debug handler: ODE aborts the process once it returns (an assertion
    such as a quaternion it cannot normalise, after an infinite spin), so the run ends here
    as a blow-up, with the frames before it (x3d_core.semantics.engine.engine_abort)."""
    engine_abort(f"ODE {kind} {number}: {text.strip()}")


def _message(number: int, text: str) -> None:
    """ODE's non-fatal messages, on stderr as ODE prints them."""
    print(f"ODE Message {number}: {text.strip()}", file=sys.stderr)


ode.handlers(_fatal, _message)

# sqrt of the largest double: ODE squares lengths (dot products, norms, bounding boxes), so
# one beyond it overflows and ODE aborts (measured: a box of size 1e154 runs, 1e200 aborts)
_MAX_LENGTH = float(np.sqrt(sys.float_info.max))
_INVERTED = (f"ODE inverts it: a value under {SMALLEST_NORMAL:.4g} (a subnormal) has an infinite inverse, "
             "and ODE aborts (measured: inertia 1e-308 runs, 1e-320 aborts) or the state turns non-finite")


def _refused(world: World, dt: float) -> str | None:
    """Why ODE cannot take this world at this step, naming the value, or None (checked in bulk
    before anything is handed over: ODE would abort the process on these)."""
    b = world.bodies
    for name, arr in (("position", b.position), ("orientation", b.orientation), ("linearVelocity", b.linear_velocity),
                      ("angularVelocity", b.angular_velocity), ("forces", b.forces), ("torques", b.torques),
                      ("mass", b.mass), ("inertia", b.inertia)):
        bad = ~np.isfinite(arr).reshape(len(arr), math.prod(arr.shape[1:])).all(axis=1)  # per body, none too
        if bad.any():
            return f"RigidBody {b.names[int(np.flatnonzero(bad)[0])]}: a non-finite {name} (ODE would abort)"
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        cfm = {"RigidBodyCollection.constantForceMix": world.constant_force_mix}
        if world.collisions is not None and world.collisions.parameters.softness_cfm is not None:
            cfm["CollisionCollection.softnessConstantForceMix"] = world.collisions.parameters.softness_cfm
        for name, value in cfm.items():
            if not np.isfinite(float(value) / dt):
                return (f"{name} = {float(value):g}: ODE divides it by the step ({dt:g} s) and the quotient "
                        "overflows (ODE would abort)")
        for g in (g for c in (world.collisions, *world.watched) if c is not None for g in c.geometries):
            extent = [np.abs(g.size).max(initial=0.0)]
            if g.vertices is not None and len(g.vertices):
                extent.append(np.abs(g.vertices).max())
            if max(extent) > _MAX_LENGTH:
                return (f"{g.name}: a {g.kind} {max(extent):g} m across: ODE squares lengths and beyond "
                        f"{_MAX_LENGTH:.4g} m they overflow (ODE would abort)")
    return None


def _cone(radius: float, height: float) -> tuple[np.ndarray, np.ndarray, list[list[int]]]:
    """X3D's cone (axis y, apex at +height/2) as ODE's convex: points, planes (n, d with
    n.x = d, outward) and faces (point indices, counter-clockwise seen from outside)."""
    a = 2 * np.pi * np.arange(_CONE_SIDES) / _CONE_SIDES
    rim = np.stack([radius * np.cos(a), np.full(_CONE_SIDES, -height / 2), radius * np.sin(a)], axis=1)
    apex = np.array([0.0, height / 2, 0.0])
    points = np.vstack([rim, apex])
    faces = [list(range(_CONE_SIDES))]  # the base, seen from below: counter-clockwise in x, z
    for k in range(_CONE_SIDES):
        faces.append([_CONE_SIDES, (k + 1) % _CONE_SIDES, k])
    planes = []
    for f in faces:
        p0, p1, p2 = points[f[0]], points[f[1]], points[f[2]]
        n = np.cross(p1 - p0, p2 - p0)
        n /= np.linalg.norm(n)
        planes.append([*n, n @ p0])
    return points, np.array(planes), faces


class _Shape:
    """One geometry's ODE geom and what must outlive it (the arrays ODE reads from)."""

    def __init__(self, g: Geometry):
        self.keep: list[object] = []
        self.data = None  # trimesh or heightfield data to destroy with the geom, and how
        self.free_data = None
        self.shift = np.zeros(3)  # the ODE geom's origin in the X3D geometry's frame
        self.turn = R.IDENTITY.copy()  # the ODE geom's orientation in the X3D geometry's frame
        if g.kind == "box":
            size = np.maximum(np.asarray(g.size, dtype=np.float64), 1e-9)
            self.id = lib.dCreateBox(None, *size)
            self.radius = float(np.linalg.norm(size)) / 2
        elif g.kind == "sphere":
            self.id = lib.dCreateSphere(None, float(g.size[0]))
            self.radius = float(g.size[0])
        elif g.kind == "cylinder":
            r, h = float(g.size[0]), float(g.size[1])
            self.id = lib.dCreateCylinder(None, r, h)
            self.turn = _Z_TO_Y
            self.radius = float(np.hypot(r, h / 2))
        elif g.kind == "cone":
            points, planes, faces = _cone(float(g.size[0]), float(g.size[1]))
            polygons = (ctypes.c_uint * sum(len(f) + 1 for f in faces))(*[x for f in faces for x in (len(f), *f)])
            p, q = ode.array(planes), ode.array(points)
            self.keep = [p, q, polygons]
            self.id = lib.dCreateConvex(None, p, len(planes), q, len(points), polygons)
            self.radius = float(np.linalg.norm(points, axis=1).max())
        elif g.kind == "mesh":
            self._trimesh(np.asarray(g.vertices, dtype=np.float64), np.asarray(g.triangles, dtype=np.int32))
        elif g.kind == "heightfield":
            self._heightfield(g)
        else:
            raise Unsupported(f"{g.name}: no ODE geom for a {g.kind}")

    def _trimesh(self, vertices: np.ndarray, triangles: np.ndarray) -> None:
        """ODE keeps pointers to the vertex and index arrays (they must outlive the geom)."""
        v = np.ascontiguousarray(vertices)
        t = np.ascontiguousarray(triangles, dtype=np.int32)
        self.data, self.free_data = lib.dGeomTriMeshDataCreate(), lib.dGeomTriMeshDataDestroy
        lib.dGeomTriMeshDataBuildDouble(self.data, v.ctypes.data, 3 * 8, len(v), t.ctypes.data, t.size, 3 * 4)
        self.keep = [v, t]
        self.id = lib.dCreateTriMesh(None, self.data, None, None, None)
        self.radius = float(np.linalg.norm(v, axis=1).max()) if len(v) else 0.0

    def _heightfield(self, g: Geometry) -> None:
        """ODE's heightfield is centred on its origin, x across its width and z across its depth,
        heights row by row along x (X3D's order): the grid's corner is shifted to X3D's origin.
        It is solid below, down to its lowest point less its own largest extent."""
        nx, nz = g.grid
        v = g.vertices
        width, depth = float(v[nx - 1, 0] - v[0, 0]), float(v[-1, 2] - v[0, 2])
        heights = v[:, 1]
        self.data, self.free_data = lib.dGeomHeightfieldDataCreate(), lib.dGeomHeightfieldDataDestroy
        lib.dGeomHeightfieldDataBuildDouble(self.data, ode.array(heights), 1, width, depth, nx, nz, 1.0, 0.0,
                                            max(width, depth), 0)
        self.id = lib.dCreateHeightfield(None, self.data, 1)
        self.shift = np.array([width / 2, 0.0, depth / 2])
        self.radius = float(np.linalg.norm(v - [width / 2, 0.0, depth / 2], axis=1).max())

    def destroy(self) -> None:
        lib.dGeomDestroy(self.id)
        if self.data is not None:
            self.free_data(self.data)


def _surface(p: ContactParameters) -> np.ndarray:
    """One dContact with the collection's surface: appliedParameters as ODE's mode bits."""
    c = np.zeros(1, dtype=ode.CONTACT)
    on = p.applied
    mode = ode.CONTACT_APPROX1
    c["mu"] = p.friction[0]
    if "FRICTION_COEFFICIENT-2" in on:
        mode |= ode.CONTACT_MU2
        c["mu2"] = p.friction[1]
    if "BOUNCE" in on:
        mode |= ode.CONTACT_BOUNCE
        c["bounce"], c["bounce_vel"] = p.bounce, p.min_bounce_speed
    if p.softness_erp is not None:
        mode |= ode.CONTACT_SOFT_ERP
        c["soft_erp"] = p.softness_erp
    if p.softness_cfm is not None:
        mode |= ode.CONTACT_SOFT_CFM
        c["soft_cfm"] = p.softness_cfm
    for k, bit in enumerate((ode.CONTACT_MOTION1, ode.CONTACT_MOTION2)):
        if f"SPEED-{k + 1}" in on:
            mode |= bit
            c[f"motion{k + 1}"] = p.surface_speed[k]
    for k, bit in enumerate((ode.CONTACT_SLIP1, ode.CONTACT_SLIP2)):
        if f"SLIP-{k + 1}" in on:
            mode |= bit
            c[f"slip{k + 1}"] = p.slip[k]
    c["mode"] = mode
    return c


# A moving geom's cell and the 13 neighbouring cells "after" it (the other 13 see it from theirs)
_AFTER = np.array([o for o in np.ndindex(3, 3, 3) if o > (1, 1, 1)], dtype=np.int64) - 1
_CELLS = 1 << 20  # cells per axis at most: far-apart cells merge, so keys fit 63 bits


def _near(centres: np.ndarray, radius: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The pairs of bounding spheres within _SLACK of each other: spheres binned in a grid of
    cells as wide as the largest sphere (so a pair that can touch is in one cell or two
    neighbouring ones), the exact test on those pairs. Linear in the geoms for spheres of
    like size, where testing every pair costs n^2 each step (3e4 geoms: 4.5e8 pairs)."""
    n = len(radius)
    with np.errstate(invalid="ignore"):  # a state gone non-finite: the evaluator reports it at the frame
        cell = np.clip(np.floor((centres - centres.min(axis=0)) / (2 * radius.max() + _SLACK)), 0, _CELLS) + 1
        cell = np.nan_to_num(cell).astype(np.int64)
    dims = cell.max(axis=0) + 2  # +-1 around every cell stays inside
    key = (cell * np.array([dims[1] * dims[2], dims[2], 1])).sum(axis=1)
    order = np.argsort(key, kind="stable")
    key = key[order]
    ends = [(np.arange(1, n + 1), np.searchsorted(key, key, side="right"))]  # same cell, later in order
    for dx, dy, dz in _AFTER:
        target = key + (dx * dims[1] + dy) * dims[2] + dz
        ends.append((np.searchsorted(key, target, side="left"), np.searchsorted(key, target, side="right")))
    start = np.concatenate([lo for lo, _ in ends])
    count = np.concatenate([hi - lo for lo, hi in ends])
    first = np.repeat(np.tile(np.arange(n), len(ends)), count)
    second = np.repeat(start, count) + np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    i, j = order[first], order[second]
    d = centres[i] - centres[j]
    near = np.einsum("ij,ij->i", d, d) <= (radius[i] + radius[j] + _SLACK) ** 2
    return i[near], j[near]


class _Slide(NamedTuple):
    """A SliderJoint's stops as _hold corrects them: ODE's stop row stops and bounces, the move corrects."""
    joint: int
    lo: float
    hi: float
    erp: float  # stopErrorCorrection: the fraction of the depth one step corrects
    moves: tuple[tuple[int, float], ...]  # (ODE body, its share of the correction: + on ODE's body1 side, - body2's)


class _Candidates(NamedTuple):
    """The pairs a small scene's contacts are tested on, with what their tests compare that no
    step changes (worked out once at build: computed every step, they cost a car's step more
    than its bounding-volume tests)."""
    pairs_moving: int  # how many moving pairs
    rows: np.ndarray  # rows into _Contacts.moving: the moving pairs' first sides, their second, the moving-static
    # pairs' moving sides
    low: np.ndarray  # the static side's box, widened by _SLACK
    high: np.ndarray
    # the largest squared gap of a pair that may touch, moving pairs first: (r_a + r_b + _SLACK)^2 between
    # two spheres, the moving side's squared radius between its sphere and a static box
    reach: np.ndarray
    order: np.ndarray  # the order that puts the pairs (moving pairs first) in index order
    pairs: np.ndarray  # (lower, higher) geom indices, in that order


class _Contacts:
    """The world's geoms and, each step, their contact joints (see the module's docstring); for a
    set only sensors watch (respond False), its geoms and contacts alone: no joint is made."""

    def __init__(self, sim: OdeSimulation, c: Collisions, respond: bool = True):
        self.sim, self.respond = sim, respond
        b = sim.world.bodies
        self.shapes = [_Shape(g) for g in c.geometries]
        n = len(self.shapes)
        self.ids = [s.id for s in self.shapes]
        moving = np.array([g.body != STATIC and not b.fixed[g.body] for g in c.geometries], dtype=bool)
        self.body_handle = [sim.handles[g.body] if m else None for g, m in zip(c.geometries, moving)]
        offsets = np.zeros((n, 3))
        for k, (g, s) in enumerate(zip(c.geometries, self.shapes)):
            q = R.multiply(g.orientation, s.turn)
            origin = g.position + R.rotate(g.orientation, s.shift)  # in the body frame (the world for STATIC)
            if moving[k]:
                lib.dGeomSetBody(s.id, sim.handles[g.body])
                offsets[k] = origin - b.com[g.body]  # ODE's body frame is at the centre of mass
                lib.dGeomSetOffsetPosition(s.id, *offsets[k])
                lib.dGeomSetOffsetQuaternion(s.id, ode.array(q))
            else:
                if g.body != STATIC:  # a fixed body's geometry, placed where the body is
                    origin = b.position[g.body] + R.rotate(b.orientation[g.body], origin)
                    q = R.multiply(b.orientation[g.body], q)
                lib.dGeomSetPosition(s.id, *origin)
                lib.dGeomSetQuaternion(s.id, ode.array(q))
        # broad phase: moving geoms' bounding spheres, static ones' AABBs (min, max)
        self.moving = np.flatnonzero(moving)
        self.fixed = np.flatnonzero(~moving)
        self.radius = np.array([s.radius for s in self.shapes])[self.moving]
        self.offset = offsets[self.moving]
        self.offset_any = bool(np.any(self.offset))
        self.row = sim.slot[[c.geometries[k].body for k in self.moving]]  # each moving geom's ODE body
        box = (ctypes.c_double * 6)()
        aabb = np.zeros((len(self.fixed), 6))
        for n_, k in enumerate(self.fixed):
            lib.dGeomGetAABB(self.ids[k], box)
            aabb[n_] = box[:]
        self.low, self.high = aabb[:, 0::2] - _SLACK, aabb[:, 1::2] + _SLACK
        self.may_touch = c.may_touch
        # pairs of two unmoving geoms touch nothing, but a sensor reports their contacts
        i, j = self.fixed[np.array(np.triu_indices(len(self.fixed), 1), dtype=np.int64)] if c.sensors \
            else np.zeros((2, 0), dtype=np.int64)
        kept = self.may_touch(i, j)
        self.static_pairs = list(zip(i[kept].tolist(), j[kept].tolist()))
        m, f = len(self.moving), len(self.fixed)
        self.candidates = self._candidates() if m * (m - 1) // 2 + m * f <= _ALL_PAIRS else None
        self.gap = np.zeros((len(self.candidates.reach) if self.candidates is not None else 0, 3))  # _listed_pairs'
        self.template = _surface(c.parameters)
        self.buffer = np.zeros(0, dtype=ode.CONTACT)
        self._grow(256)
        self.group = lib.dJointGroupCreate(0)
        self.count = 0
        self.touching: tuple[list[int], list[int], list[int]] = ([], [], [])  # each pair's geoms, its count

    def _grow(self, capacity: int) -> None:
        """A contact buffer with room for capacity contacts, the surface already in every slot."""
        old = self.buffer
        self.buffer = np.repeat(self.template, capacity)
        self.buffer[:len(old)] = old
        self.address = self.buffer.ctypes.data

    def _candidates(self) -> _Candidates:
        """Every allowed pair with a moving side, once: moving pairs (rows a, b into self.moving),
        moving-static pairs (rows m into self.moving, each with its static geom's box), and the
        order that puts both lists' (lower, higher) geom indices, kept by may_touch, in index order."""
        a, b = np.triu_indices(len(self.moving), 1)
        m, f = (x.ravel() for x in np.meshgrid(np.arange(len(self.moving)), np.arange(len(self.fixed)),
                                                indexing="ij"))
        both = np.concatenate([np.stack([self.moving[a], self.moving[b]], axis=1),
                               np.stack([self.moving[m], self.fixed[f]], axis=1)]).astype(np.int64)
        both.sort(axis=1)
        kept = self.may_touch(both[:, 0], both[:, 1])
        kept_mm, kept_mf = kept[:len(a)], kept[len(a):]
        both = both[kept]
        order = np.lexsort((both[:, 1], both[:, 0]))
        a, b, m, f = a[kept_mm], b[kept_mm], m[kept_mf], f[kept_mf]
        r = self.radius
        return _Candidates(len(a), np.concatenate([a, b, m]), self.low[f], self.high[f],
                           np.concatenate([(r[a] + r[b] + _SLACK) ** 2, r[m] ** 2]), order, both[order])

    def pairs(self, centres: np.ndarray) -> list[tuple[int, int]]:
        """The allowed pairs whose bounding volumes overlap, lower index first, in index order."""
        if self.candidates is not None:
            return self._listed_pairs(centres)
        out = []
        m, r = self.moving, self.radius
        if len(m) > 1:
            i, j = _near(centres, r)
            out.append(np.stack([m[i], m[j]], axis=1))
        if len(m) and len(self.fixed):
            gap = np.maximum(self.low[None] - centres[:, None], 0) + np.maximum(centres[:, None] - self.high[None], 0)
            i, j = np.nonzero(np.einsum("ijk,ijk->ij", gap, gap) <= r[:, None] ** 2)
            out.append(np.stack([m[i], self.fixed[j]], axis=1))
        if not out:
            return list(self.static_pairs)
        both = np.concatenate(out)
        both.sort(axis=1)
        both = both[self.may_touch(both[:, 0], both[:, 1])]
        both = both[np.lexsort((both[:, 1], both[:, 0]))]
        return self.static_pairs + [tuple(p) for p in both.tolist()]

    def _listed_pairs(self, centres: np.ndarray) -> list[tuple[int, int]]:
        """pairs() over the candidates listed at build: the same tests as _near's and the
        grid's AABB test, on every listed pair at once. A car's ten pairs cost a numpy call's
        overhead each, not arithmetic, so both kinds' gaps go into one array, squared and compared
        in one go; a sphere's gap to a box is c - clip(c, low, high), the same squares as the grid
        test's max(low - c, 0) + max(c - high, 0) in two calls fewer."""
        k, n = self.candidates, self.candidates.pairs_moving
        gap = self.gap
        with np.errstate(invalid="ignore"):  # a state gone non-finite: the evaluator reports it at the frame
            x = centres[k.rows]
            np.subtract(x[:n], x[n:2 * n], out=gap[:n])
            c = x[2 * n:]
            np.subtract(c, np.minimum(np.maximum(c, k.low), k.high), out=gap[n:])
            hit = (np.einsum("ij,ij->i", gap, gap) <= k.reach)[k.order]
        return self.static_pairs + [tuple(p) for p in k.pairs[hit].tolist()]

    def collide(self, position: np.ndarray, orientation: np.ndarray) -> None:
        """This step's contacts as contact joints (last step's joints go first)."""
        lib.dJointGroupEmpty(self.group)
        centres = position[self.row]
        if self.offset_any:  # a geometry off its body's centre of mass (its rotation costs a car's step a fifth)
            centres = centres + R.rotate(orientation[self.row], self.offset)
        ids, found = self.ids, 0
        first, second, counts = [], [], []
        for i, j in self.pairs(centres):
            if len(self.buffer) - found < _PER_PAIR:
                self._grow(2 * len(self.buffer))
            k = lib.dCollide(ids[i], ids[j], _PER_PAIR, self.address + found * 248 + ode.GEOM_OFFSET, 248)
            if k:
                found += k
                first.append(i)
                second.append(j)
                counts.append(k)
        self.count = found
        self.touching = (first, second, counts)  # as arrays only for points(): a step needs none
        if not self.respond:
            return
        world, group, handle = self.sim.ode_world, self.group, self.body_handle
        at = self.address
        for i, j, k in zip(first, second, counts):
            b1, b2 = handle[i], handle[j]
            if b1 is not None or b2 is not None:  # two unmoving geoms: reported, nothing to push
                for contact in range(at, at + k * 248, 248):
                    lib.dJointAttach(lib.dJointCreateContact(world, group, contact), b1, b2)
            at += k * 248

    def points(self) -> ContactPoints:
        c = self.buffer[:self.count]
        first, second, counts = (np.array(x, dtype=int) for x in self.touching)
        return ContactPoints(c["pos"][:, :3].copy(), -c["normal"][:, :3], c["depth"].copy(), np.repeat(first, counts),
                             np.repeat(second, counts))

    def destroy(self) -> None:
        lib.dJointGroupDestroy(self.group)
        for s in self.shapes:
            s.destroy()


class OdeSimulation:
    def __init__(self, world: World, dt: float):
        self.contacts_: _Contacts | None = None
        self.watched: list[_Contacts] = []  # world.watched's, in order
        lib.dAllocateODEDataForThread(ode.ALLOCATE_ALL)  # per thread that steps or collides
        lib.dRandSetSeed(0)  # quick-step reorders its rows with ODE's one global generator: same seed, same run
        self.world, self.dt = world, dt
        b = world.bodies
        w = self.ode_world = lib.dWorldCreate()
        lib.dWorldSetGravity(w, *world.gravity)
        lib.dWorldSetERP(w, world.error_correction)
        lib.dWorldSetCFM(w, world.constant_force_mix)
        lib.dWorldSetQuickStepNumIterations(w, max(0, world.iterations))
        if world.max_correction_speed >= 0:  # -1: no cap (ODE's default, dInfinity)
            lib.dWorldSetContactMaxCorrectingVel(w, world.max_correction_speed)
        lib.dWorldSetContactSurfaceLayer(w, world.contact_surface_thickness)
        self.stepper = lib.dWorldStep if world.prefer_accuracy else lib.dWorldQuickStep
        self.rows = np.flatnonzero(~b.fixed)  # the bodies ODE moves, in world.bodies order
        self.slot = np.full(len(b) + 1, -1, dtype=int)  # body row -> index in self.rows (row -1: none)
        self.slot[self.rows] = np.arange(len(self.rows))
        self.handles: dict[int, int | None] = {STATIC: None}
        self.kinematic: int | None = None
        self.slides: list[_Slide] = []
        self.axis = (ctypes.c_double * 4)()  # dJointGetSliderAxis's dVector3
        try:
            for i in range(len(b)):
                self.handles[i] = self._body(i) if not b.fixed[i] else None
            for j in world.joints:
                self._joint(j)
            if world.collisions is not None:
                self.contacts_ = _Contacts(self, world.collisions)
            for c in world.watched:  # geoms on the bodies, never given a contact joint
                self.watched.append(_Contacts(self, c, respond=False))
        except Unsupported:
            self.close()
            raise
        self._windows()
        self.com = b.com[self.rows]
        self.shifted = bool(np.any(self.com))
        self.start = State.initial(b)
        self.start.linear_velocity[b.fixed] = 0.0
        self.start.angular_velocity[b.fixed] = 0.0
        self.set_loads(b.forces, b.torques)

    # -- building -----------------------------------------------------------
    def _body(self, i: int) -> int:
        b = self.world.bodies
        m, inertia = float(b.mass[i]), b.inertia[i]
        if not m > 0 or not np.all(np.linalg.eigvalsh(inertia) > 0):
            raise Unsupported(f"RigidBody {b.names[i]}: ODE needs a positive mass and a positive definite inertia "
                              f"(mass {m:g}, inertia {inertia.ravel().tolist()})")
        body = lib.dBodyCreate(self.ode_world)
        mass = (ctypes.c_double * ode.MASS_REALS)()
        lib.dMassSetParameters(mass, m, 0.0, 0.0, 0.0, inertia[0, 0], inertia[1, 1], inertia[2, 2],
                               inertia[0, 1], inertia[0, 2], inertia[1, 2])
        lib.dBodySetMass(body, mass)
        q = b.orientation[i]
        lib.dBodySetPosition(body, *(b.position[i] + R.rotate(q, b.com[i])))
        lib.dBodySetQuaternion(body, ode.array(q))
        lib.dBodySetLinearVel(body, *b.linear_velocity[i])
        lib.dBodySetAngularVel(body, *b.angular_velocity[i])
        lib.dBodySetGravityMode(body, int(b.use_gravity[i]))
        if b.finite_rotation[i]:
            lib.dBodySetFiniteRotationMode(body, 1)
            lib.dBodySetFiniteRotationAxis(body, *b.finite_rotation_axis[i])
        return body

    def _joint(self, j: Joint) -> None:
        if j.type == "MotorJoint" or j.body1 == j.body2:
            return  # a motor is loads (the evaluator's); a body joined to itself moves freely
        w, p = self.ode_world, j.params
        b1, b2 = self.handles[j.body1], self.handles[j.body2]
        create = {"BallJoint": lib.dJointCreateBall, "SingleAxisHingeJoint": lib.dJointCreateHinge,
                  "SliderJoint": lib.dJointCreateSlider, "UniversalJoint": lib.dJointCreateUniversal,
                  "DoubleAxisHingeJoint": lib.dJointCreateHinge2}.get(j.type)
        if create is None:
            raise Unsupported(f"{j.type} {j.name}: not built by the ode backend")
        used = {"SingleAxisHingeJoint": 1, "SliderJoint": 1, "UniversalJoint": 2, "DoubleAxisHingeJoint": 2}
        given = j.axes[:used.get(j.type, 0)]
        if np.any(np.linalg.norm(given, axis=1) == 0):
            raise Unsupported(f"{j.type} {j.name}: a zero axis (ODE cannot normalise it)")
        if len(given) == 2 and np.linalg.norm(np.cross(given[0], given[1])) < 1e-9:
            raise Unsupported(f"{j.type} {j.name}: axis1 and axis2 are parallel (ODE needs them apart)")
        if j.type == "DoubleAxisHingeJoint":  # ODE aborts on a hinge2 with one body: a kinematic one stands in
            b1, b2 = (self._anchor() if b is None else b for b in (b1, b2))
        axes, first = j.axes.copy(), j.body1  # first: the body row ODE attaches as its body1
        if b1 is None and j.type in ("SingleAxisHingeJoint", "SliderJoint"):
            # ODE's reversed attach measures the moving body against the static one: attach it as
            # body1 about the opposite axis, whose angle and separation are X3D's body1-relative ones
            b1, b2, axes, first = b2, None, -axes, j.body2
        joint = create(w, None)
        lib.dJointAttach(joint, b1, b2)
        a = j.anchor
        if j.type == "BallJoint":
            lib.dJointSetBallAnchor(joint, *a)
        elif j.type == "SingleAxisHingeJoint":
            lib.dJointSetHingeAnchor(joint, *a)
            lib.dJointSetHingeAxis(joint, *axes[0])
            self._stops(lib.dJointSetHingeParam, joint, 0, p["minAngle"], p["maxAngle"], p["stopBounce"],
                        p["stopErrorCorrection"], angular=True)
        elif j.type == "SliderJoint":
            lib.dJointSetSliderAxis(joint, *axes[0])
            if j.stops is not None:  # else ODE's own: no stops
                # the stop's row at StopERP 0: ODE's ERP would correct the depth by a velocity that stays on
                # once the depth is gone, a rebound at stopBounce 0; _hold moves the bodies back instead
                self._stops(lib.dJointSetSliderParam, joint, 0, *j.stops, p["stopBounce"], 0.0, angular=False)
                if p["stopErrorCorrection"] > 0:
                    self.slides.append(self._slide(joint, j, first))
        elif j.type == "UniversalJoint":
            lib.dJointSetUniversalAnchor(joint, *a)
            lib.dJointSetUniversalAxis1(joint, *axes[0])
            lib.dJointSetUniversalAxis2(joint, *axes[1])
        else:
            self._hinge2(joint, j, axes)

    def _slide(self, joint: int, j: Joint, first: int) -> _Slide:
        """Slider j's stops for _hold, `first` the body row ODE attached as its body1. Each end moves
        with the bodies joined to it other than through j (rigidly: their other joints stay as
        they are), the two sides by the other's share of their mass (their centre of mass stays), a
        side that reaches the static environment not at all; where the sides meet in a loop, or
        both reach it, each end moves alone."""
        ends = (first, j.body2 if first == j.body1 else j.body1)
        sides = [self._side(j, end) for end in ends]
        if set(sides[0][0]) & set(sides[1][0]) or math.isinf(sides[0][1]) and math.isinf(sides[1][1]):
            b = self.world.bodies
            sides = [([e], math.inf if e == STATIC or b.fixed[e] else float(b.mass[e])) for e in ends]
        (rows1, m1), (rows2, m2) = sides
        share = 1.0 if math.isinf(m2) else 0.0 if math.isinf(m1) else m2 / (m1 + m2)
        moves = [(self.handles[r], share) for r in rows1] + [(self.handles[r], share - 1.0) for r in rows2]
        return _Slide(joint, *j.stops, j.params["stopErrorCorrection"],
                      tuple((h, k) for h, k in moves if k and h is not None))

    def _side(self, j: Joint, end: int) -> tuple[list[int], float]:
        """The moving bodies joined to `end` other than through joint j, and their mass (inf where they
        reach the static environment, or `end` is static)."""
        b = self.world.bodies
        if end == STATIC or b.fixed[end]:
            return [], math.inf
        seen, todo, anchored = {end}, [end], False
        while todo:
            r = todo.pop()
            for k in self.world.joints:
                if k is j or k.type == "MotorJoint" or k.body1 == k.body2 or r not in (k.body1, k.body2):
                    continue
                other = k.body2 if r == k.body1 else k.body1
                if other == STATIC or b.fixed[other]:
                    anchored = True
                elif other not in seen:
                    seen.add(other)
                    todo.append(other)
        return sorted(seen), math.inf if anchored else float(sum(b.mass[r] for r in seen))

    def _hold(self, s: _Slide) -> None:
        """stopErrorCorrection of a stop's depth, corrected by moving the bodies back along the axis
        and leaving their velocities as ODE's stop row made them (stopped, or bounced by stopBounce):
        so the clause's two sentences both hold, "all error ... corrected in a single step" at 1 and
        "no bounce at all" at 0. Called after a step through which ODE's row held the stop (it had
        been reached at the step's start): a step that only crosses it has not stopped the motion
        yet, and a body moved back onto the stop then would go on through it."""
        x = lib.dJointGetSliderPosition(s.joint)
        depth = x - s.hi if x > s.hi else x - s.lo if x < s.lo else 0.0
        if depth == 0.0:
            return
        lib.dJointGetSliderAxis(s.joint, self.axis)
        move = -s.erp * depth * np.array(self.axis[:3])
        for body, share in s.moves:
            p = lib.dBodyGetPosition(body)
            lib.dBodySetPosition(body, *(np.array(p[:3]) + share * move))

    def _anchor(self) -> int:
        """A kinematic ODE body at the origin, at rest: the static environment for joints that need a body."""
        if self.kinematic is None:
            self.kinematic = lib.dBodyCreate(self.ode_world)
            lib.dBodySetKinematic(self.kinematic)
        return self.kinematic

    @staticmethod
    def _stops(setter, joint: int, group: int, lo: float, hi: float, bounce: float, erp: float,
               angular: bool) -> bool:
        """A joint's stops with their bounce and ERP (none for a hinge free all round)."""
        if angular and lo <= -_FULL_TURN and hi >= _FULL_TURN:
            return False
        if angular:
            lo, hi = max(lo, -np.pi), min(hi, np.pi)
        setter(joint, group + ode.LO_STOP, lo)
        setter(joint, group + ode.HI_STOP, hi)
        setter(joint, group + ode.BOUNCE, bounce)
        setter(joint, group + ode.STOP_ERP, erp)
        return True

    def _hinge2(self, joint: int, j: Joint, axes: np.ndarray) -> None:
        """ODE's hinge2 as X3D's DoubleAxisHingeJoint: stops on axis 1, suspension along it, two motors."""
        p, put = j.params, lib.dJointSetHinge2Param
        lib.dJointSetHinge2Anchor(joint, *j.anchor)
        lib.dJointSetHinge2Axes(joint, ode.array(axes[0]), ode.array(axes[1]))
        if self._stops(put, joint, 0, p["minAngle1"], p["maxAngle1"], p["stop1Bounce"], p["stop1ErrorCorrection"],
                       angular=True):
            put(joint, ode.STOP_CFM, p["stop1ConstantForceMix"])
        put(joint, ode.SUSPENSION_ERP, p["suspensionErrorCorrection"])
        put(joint, ode.SUSPENSION_CFM, p["suspensionForce"])
        for k in (1, 2):
            group = (k - 1) * ode.PARAM_GROUP
            put(joint, group + ode.VEL, p[f"desiredAngularVelocity{k}"])
            put(joint, group + ode.FMAX, p[f"maxTorque{k}"])

    def _windows(self) -> None:
        """Index arrays into one view of ODE's memory for every moving body's fields."""
        fields = {"position": (lib.dBodyGetPosition, 3), "orientation": (lib.dBodyGetQuaternion, 4),
                  "linear": (lib.dBodyGetLinearVel, 3), "angular": (lib.dBodyGetAngularVel, 3),
                  "force": (lib.dBodyGetForce, 3), "torque": (lib.dBodyGetTorque, 3)}
        handles = [self.handles[int(i)] for i in self.rows]
        where = {name: [ode.address(get(h)) for h in handles] for name, (get, _) in fields.items()}
        if not handles:
            self.window, self.at = None, {}
            return
        self.window = ode.Window([a for v in where.values() for a in v], 4)
        self.at = {name: self.window.index(where[name], width) for name, (_, width) in fields.items()}

    # -- running ------------------------------------------------------------
    def step(self, n: int = 1) -> None:
        w, dt, stepper, c = self.ode_world, self.dt, self.stepper, self.contacts_
        memory = self.window.memory if self.window is not None else None
        for _ in range(n):
            if self.loaded:  # ODE clears its accumulators after every step
                memory[self.at["force"]] = self.forces
                memory[self.at["torque"]] = self.torques
            if c is not None:
                c.collide(*self._poses())
            # the stops ODE's rows hold through this step: reached at its start (ODE's own test, inclusive)
            held = [s for s in self.slides if not s.lo < lib.dJointGetSliderPosition(s.joint) < s.hi]
            if not stepper(w, dt):
                raise BlewUp("ODE's step failed (out of memory for its solver)")
            for s in held:
                self._hold(s)

    def _poses(self) -> tuple[np.ndarray, np.ndarray]:
        """Every moving body's centre of mass and orientation, as ODE holds them."""
        if self.window is None:
            return np.zeros((0, 3)), np.zeros((0, 4))
        memory = self.window.memory
        return memory[self.at["position"]], memory[self.at["orientation"]]

    def state(self) -> State:
        s = self.start
        out = State(s.position.copy(), s.orientation.copy(), s.linear_velocity.copy(), s.angular_velocity.copy())
        if self.window is None:
            return out
        memory, rows = self.window.memory, self.rows
        com, q = self._poses()
        out.position[rows] = com - R.rotate(q, self.com) if self.shifted else com
        out.orientation[rows] = q
        out.linear_velocity[rows] = memory[self.at["linear"]]
        out.angular_velocity[rows] = memory[self.at["angular"]]
        return out

    def set_velocities(self, linear: np.ndarray, angular: np.ndarray) -> None:
        """Written where dBodySetLinearVel and dBodySetAngularVel write (the centre of mass's, world frame)."""
        if self.window is not None:
            self.window.memory[self.at["linear"]] = linear[self.rows]
            self.window.memory[self.at["angular"]] = angular[self.rows]

    def set_loads(self, forces: np.ndarray, torques: np.ndarray) -> None:
        self.forces = np.array(forces, dtype=np.float64)[self.rows]
        self.torques = np.array(torques, dtype=np.float64)[self.rows]
        self.loaded = bool(self.forces.any() or self.torques.any())

    def contacts(self) -> ContactPoints:
        return self.contacts_.points() if self.contacts_ is not None else ContactPoints.none()

    def watched_contacts(self, k: int) -> ContactPoints:
        """dCollide over the watched set's pairs where ODE's bodies are now, no joint made."""
        c = self.watched[k]
        c.collide(*self._poses())
        return c.points()

    def close(self) -> None:
        """Free ODE's world, its bodies and joints, and the geoms."""
        if self.ode_world:
            for c in [self.contacts_, *self.watched]:
                if c is not None:
                    c.destroy()
            lib.dWorldDestroy(self.ode_world)
            self.ode_world = None

    def __del__(self) -> None:
        self.close()


class OdeBackend(Backend):
    name = "ode"
    integration = SEMI_IMPLICIT
    limits = {"RigidBody.mass": below(SMALLEST_NORMAL, _INVERTED), "RigidBody.inertia": below(SMALLEST_NORMAL, _INVERTED)}
    declared = {
        **native(*BODIES, *JOINTS, "RigidBody.useGlobalGravity", "RigidBody.finiteRotationAxis", "RigidBodyCollection.errorCorrection",
                 "RigidBodyCollection.constantForceMix", "RigidBodyCollection.iterations",
                 "RigidBodyCollection.preferAccuracy", "RigidBodyCollection.maxCorrectionSpeed",
                 "RigidBodyCollection.contactSurfaceThickness",
                 "SingleAxisHingeJoint.stopBounce", "SingleAxisHingeJoint.stopErrorCorrection",
                 "SliderJoint.stopBounce", "SliderJoint.stopErrorCorrection",
                 "DoubleAxisHingeJoint", "DoubleAxisHingeJoint.anchorPoint", "DoubleAxisHingeJoint.axis1",
                 "DoubleAxisHingeJoint.axis2", "DoubleAxisHingeJoint.limits", "DoubleAxisHingeJoint.minAngle1",
                 "DoubleAxisHingeJoint.maxAngle1", "DoubleAxisHingeJoint.stop1Bounce",
                 "DoubleAxisHingeJoint.stop1ErrorCorrection", "DoubleAxisHingeJoint.stop1ConstantForceMix",
                 "DoubleAxisHingeJoint.suspensionForce", "DoubleAxisHingeJoint.suspensionErrorCorrection",
                 "DoubleAxisHingeJoint.desiredAngularVelocity1", "DoubleAxisHingeJoint.desiredAngularVelocity2",
                 "DoubleAxisHingeJoint.maxTorque1", "DoubleAxisHingeJoint.maxTorque2",
                 # collisions: ODE's own geoms, colliders and contact joints
                 "CollisionCollection", "CollisionCollection.appliedParameters", "CollisionSensor",
                 # a set only sensors watch: its own geoms on the bodies, dCollide'd, no contact joint
                 "CollisionSensor.collider.watchedOnly", "CollidableShape.geometry.Box", "CollidableShape.geometry.Sphere",
                 "CollidableShape.geometry.Cylinder", "CollisionCollection.bounce",
                 "CollisionCollection.minBounceSpeed", "CollisionCollection.frictionCoefficients",
                 "CollisionCollection.slipFactors", "CollisionCollection.surfaceSpeed",
                 "CollisionCollection.softnessErrorCorrection", "CollisionCollection.softnessConstantForceMix",
                 *(f"CollisionCollection.appliedParameters.{p}" for p in (
                     "BOUNCE", "FRICTION_COEFFICIENT-2", "ERROR_REDUCTION", "CONSTANT_FORCE", "SPEED-1", "SPEED-2",
                     "SLIP-1", "SLIP-2"))),
        **approximate(f"ODE 0.16 has no cone: the convex hull of a {_CONE_SIDES}-gon and the apex (radius 0.12% "
                      "short between its corners)", "CollidableShape.geometry.Cone"),
        **approximate("ODE's trimesh, static or moving (ODE collides moving trimeshes with every shape): a surface "
                      "without volume, so a body moving more than its own thickness in a step passes through",
                      "CollidableShape.geometry.IndexedFaceSet", "CollidableShape.geometry.IndexedTriangleSet",
                      "CollidableShape.geometry.TriangleSet"),
        **approximate("ODE's heightfield: each cell split along ODE's own diagonal (X3D leaves it open), solid "
                      "below down to its lowest point less its largest extent",
                      "CollidableShape.geometry.ElevationGrid"),
        **unsupported("a CollisionCollection has no frictionDirection field (only a Contact node, which only "
                      "set_contacts could feed, has one): there is no direction to give ODE's dContactFDir1",
                      "CollisionCollection.appliedParameters.USER_FRICTION"),
    }

    def version(self) -> str:
        return ode.version()

    def build(self, world: World, dt: float) -> OdeSimulation:
        why = _refused(world, dt)
        if why:
            raise Unsupported(why)
        return OdeSimulation(world, dt)


BACKEND = OdeBackend()
