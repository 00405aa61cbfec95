"""Whether a world moves in one plane, and the sections of its shapes by that plane.

A planar engine (backends/pymunk.py) can run a world exactly only where nothing can
leave its plane, so this analysis proves it from the start state or refuses, naming
the body or joint, the field and its value. The planes are z = c with normal +z: a 2D
engine's own plane, into which a scene drawn in the X3D default view (x right, y up,
gravity -y) already falls. Each moving body keeps to the plane through its centre of
mass; bodies may sit in parallel planes (a row of balls side by side in z, each
bouncing on one floor), and the 2D engine then keeps apart any two shapes that can
never touch in 3D. Scenes planar in another plane are refused (turning them into z = c
is a change of frame this module does not make).

A world is planar when every moving body's velocity and force lie in its plane, its angular velocity and torque lie along z, its
orientation turns about z, and its inertia has no product of inertia with z (so that
spin about z makes no torque out of the plane); gravity lies in the plane; hinges turn
about z, sliders slide in the plane (both hold every tipping torque, so they may join
bodies in different planes), ball joints sit on the plane of each body they join
(their force then acts at the plane and makes no tipping torque), a universal joint
has one axis along z and the other in the plane (the out-of-plane freedom is never
excited: a pivot) and sits on the planes as a ball joint does; motor
torques act about z; surface speed acts only along the first friction direction (for
a normal in the plane ODE's second direction is z). A DoubleAxisHingeJoint is refused
by the backend's table (its suspension and second hinge act out of the plane).

Shapes: the contact between two shapes happens in the plane, so their 2D sections give
the 3D contacts exactly, when each is a prism along z across the plane (a box with an
axis along z, a cylinder along z: a rectangle, a circle) or convex and symmetric about
the plane (a sphere: a circle; a cylinder or a cone whose axis lies in the plane: a
rectangle, a triangle). For two convex shapes symmetric about the plane the closest
points lie in it (the midpoints of a closest pair and its mirror image are as close),
and such a shape's section is its widest, so against a prism the plane's section is
where they are closest too. And the contact forces must not tip a body: a moving
body's shapes are centred on its plane (symmetric about it, so are their contact
patches), and a static prism is centred on each plane too or reaches past it on both
sides by at least the largest half-extent along z of the moving shapes in that plane
(a floor wider than what stands on it). Two shapes whose extents along z can never
meet (moving shapes in planes farther apart than their half-extents, a static shape
clear of a plane's moving shapes) are kept apart; any other pair across planes could
touch out of the plane and is refused. Meshes and elevation grids are refused.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import rotation as R
from .collision import Geometry
from .engine import Unsupported
from .world import STATIC, World

TOLERANCE = 1e-9  # SI: a field this close to the plane's value is on it (files hold decimals)
Z = np.array([0.0, 0.0, 1.0])


@dataclass
class Section:
    """A shape's section by the plane at the start, world coordinates: a circle (radius
    > 0, vertices None) about centre, or a convex polygon."""
    centre: np.ndarray  # (2,)
    radius: float
    vertices: np.ndarray | None  # (k, 2)


@dataclass
class Planar:
    planes: np.ndarray  # (n,) each body's plane z = c (NaN for a fixed body)
    sections: list[Section | None]  # per world.collisions.geometries; None: touches nothing
    apart: set[tuple[int, int]]  # geometry pairs (low, high) that can never touch in 3D
    contact_z: np.ndarray  # per geometry, the plane its contacts lie in (NaN for a static one)


class NotPlanar(Unsupported):
    """The world can leave the plane; reasons name what, one each."""

    def __init__(self, reasons: list[str]):
        self.reasons = reasons
        more = f" (and {len(reasons) - 3} more)" if len(reasons) > 3 else ""
        super().__init__("not planar: " + "; ".join(reasons[:3]) + more)


def _text(v: np.ndarray) -> str:
    return " ".join(f"{x:g}" for x in np.ravel(v))


def _along_z(v: np.ndarray) -> bool:
    return bool(np.all(np.abs(v[..., :2]) <= TOLERANCE))


def analyse(world: World) -> Planar:
    """The plane each body moves in and its shapes' sections; NotPlanar otherwise."""
    b = world.bodies
    moving = np.flatnonzero(~b.fixed)
    com = b.position + R.rotate(b.orientation, b.com)
    planes = np.where(b.fixed, np.nan, com[:, 2])
    reasons: list[str] = []
    if abs(world.gravity[2]) > TOLERANCE:
        reasons.append(f"RigidBodyCollection {world.name} gravity ({_text(world.gravity)}) leaves the plane")
    for i in moving:
        name = f"RigidBody {b.names[i]}"
        checks = (("orientation", R.to_axis_angle(b.orientation[i]), not _along_z(b.orientation[i, 1:]),
                   "does not turn about z"),
                  ("linearVelocity", b.linear_velocity[i], abs(b.linear_velocity[i, 2]) > TOLERANCE,
                   "leaves the plane"),
                  ("angularVelocity", b.angular_velocity[i], not _along_z(b.angular_velocity[i]), "is not along z"),
                  ("forces", b.forces[i], abs(b.forces[i, 2]) > TOLERANCE, "leave the plane"),
                  ("torques", b.torques[i], not _along_z(b.torques[i]), "are not along z"),
                  ("inertia", b.inertia[i], np.abs(b.inertia[i, :2, 2]).max() > TOLERANCE * np.abs(b.inertia[i]).max(),
                   "couples spin about z out of the plane (products of inertia with z)"))
        reasons.extend(f"{name} {field} ({_text(v)}) {why}" for field, v, bad, why in checks if bad)
    reasons.extend(_joints(world, planes))
    found: list[Section | None] = []
    apart: set[tuple[int, int]] = set()
    contact_z = np.zeros(0)
    if world.collisions is not None:
        speed = world.collisions.parameters.surface_speed
        if abs(speed[1]) > TOLERANCE:
            reasons.append(f"CollisionCollection surfaceSpeed ({_text(speed)}): SPEED-2 drives along z, ODE's "
                           "second friction direction for normals in the plane")
        found, apart, contact_z, bad = sections(world, planes)
        reasons.extend(bad)
    if reasons:
        raise NotPlanar(reasons)
    return Planar(planes, found, apart, contact_z)


def _joints(world: World, planes: np.ndarray) -> list[str]:
    out = []
    for j in world.joints:
        if j.body1 == j.body2 or j.body1 == j.body2 == STATIC:  # joins nothing that moves
            continue
        name = f"{j.type} {j.name}"
        off = [float(planes[r]) for r in (j.body1, j.body2) if r != STATIC and abs(j.anchor[2] - planes[r]) > TOLERANCE]
        where = f"anchorPoint ({_text(j.anchor)}) is off the plane z = {off[0]:g}" if off else ""
        if j.type == "SingleAxisHingeJoint" and not _along_z(j.axes[0]):
            out.append(f"{name} axis ({_text(j.axes[0])}) is not along z")
        elif j.type == "SliderJoint" and abs(j.axes[0, 2]) > TOLERANCE:
            out.append(f"{name} axis ({_text(j.axes[0])}) leaves the plane")
        elif j.type == "BallJoint" and off:
            out.append(f"{name} {where}")
        elif j.type == "UniversalJoint" and not universal_pivot(j.axes[:2]):
            out.append(f"{name} axis1 ({_text(j.axes[0])}), axis2 ({_text(j.axes[1])}): neither is along z with "
                       "the other in the plane")
        elif j.type == "UniversalJoint" and off:
            out.append(f"{name} {where}")
        elif j.type == "MotorJoint":
            n = int(j.params.get("enabledAxes", 0))
            for k in range(n):
                if j.params[f"axis{k + 1}Torque"] and not _along_z(j.axes[k]):
                    out.append(f"{name} motor{k + 1}Axis ({_text(j.axes[k])}) with axis{k + 1}Torque "
                               f"{j.params[f'axis{k + 1}Torque']:g} turns out of the plane")
    return out


def universal_pivot(axes: np.ndarray) -> bool:
    """Whether a universal joint's two axes are one along z and the other in the plane."""
    return any(_along_z(axes[k]) and abs(axes[1 - k, 2]) <= TOLERANCE for k in (0, 1))


def _half_extent(g: Geometry, m: np.ndarray) -> float:
    """How far a shape reaches from its centre along z (m: its axes in the world)."""
    if g.kind == "box":
        return float(np.abs(m[2]) @ g.size / 2)
    if g.kind in ("cylinder", "cone"):
        return float(abs(m[2, 1]) * g.size[1] / 2 + np.hypot(m[2, 0], m[2, 2]) * g.size[0])
    return float(g.size[0]) if g.kind == "sphere" else 0.0


def _pose(g: Geometry, world: World) -> tuple[np.ndarray, np.ndarray]:
    """The geometry's centre and axes (matrix columns) in the world at the start."""
    if g.body == STATIC:
        return g.position, R.matrix(g.orientation)
    b = world.bodies
    q = b.orientation[g.body]
    return b.position[g.body] + R.rotate(q, g.position), R.matrix(R.multiply(q, g.orientation))


def sections(world: World, planes: np.ndarray) -> tuple[list[Section | None], set[tuple[int, int]], np.ndarray,
                                                        list[str]]:
    """Each geometry's section (world coordinates, at the start), the pairs kept apart, the
    plane of each geometry's contacts, and the reasons why some section or pair is not
    exact (module docstring)."""
    c = world.collisions
    geoms = c.geometries
    poses = [_pose(g, world) for g in geoms]
    moving = np.array([g.body != STATIC and not world.bodies.fixed[g.body] for g in geoms], dtype=bool)
    half = np.array([_half_extent(g, m) for g, (_, m) in zip(geoms, poses)])
    centre_z = np.array([centre[2] for centre, _ in poses])
    contact_z = np.array([planes[g.body] if mv else np.nan for g, mv in zip(geoms, moving)])
    levels = np.unique(planes[~np.isnan(planes)])
    reach = {float(p): float(half[moving & (contact_z == p)].max(initial=0.0)) for p in levels}
    out: list[Section | None] = []
    apart: set[tuple[int, int]] = set()
    reasons: list[str] = []
    for k, (g, (centre, m)) in enumerate(zip(geoms, poses)):
        if moving[k] or g.kind in ("mesh", "heightfield"):
            s = _section(g, centre, m, contact_z[k], None)
        else:  # a static shape: exact in every plane it can reach, apart from the others
            s = None
            for p, r in reach.items():
                if centre_z[k] - half[k] >= p + r - TOLERANCE or centre_z[k] + half[k] <= p - r + TOLERANCE:
                    apart.update((min(k, i), max(k, i)) for i in np.flatnonzero(moving & (contact_z == p)))
                    continue
                s = _section(g, centre, m, p, r)
                if isinstance(s, str):
                    break
        if isinstance(s, str):
            reasons.append(f"CollidableShape {g.name} ({g.kind}) {s}")
        out.append(s)
    first, second = np.nonzero(np.triu(moving[:, None] & moving[None, :], 1))
    kept = (contact_z[first] != contact_z[second]) & c.may_touch(first, second)
    for a, b in zip(first[kept], second[kept]):
        if abs(contact_z[a] - contact_z[b]) >= half[a] + half[b] - TOLERANCE:
            apart.add((int(a), int(b)))
        else:
            reasons.append(f"CollidableShape {geoms[a].name} (plane z = {contact_z[a]:g}) and {geoms[b].name} "
                           f"(plane z = {contact_z[b]:g}) can touch out of the plane")
    return out, apart, contact_z, reasons


def _section(g: Geometry, centre: np.ndarray, m: np.ndarray, z: float, reach: float | None) -> Section | str:
    """The section, or why it is not exact; reach: None for a moving shape (centred on the
    plane), else how far a static prism must reach past the plane on both sides."""
    offset = centre[2] - z
    on_plane = abs(offset) <= TOLERANCE
    along = np.abs(np.abs(m[2]) - 1) <= TOLERANCE  # the shape's axes along z
    across = np.abs(m[2]) <= TOLERANCE  # the shape's axes in the plane
    c2 = centre[:2].copy()
    centred = f"is not centred on the plane z = {z:g} ({offset:g} off)"

    def prism_spans(half: float) -> bool:
        return on_plane or (reach is not None and abs(offset) + reach <= half + TOLERANCE)

    if g.kind == "sphere":
        return Section(c2, float(g.size[0]), None) if on_plane else centred
    if g.kind == "box":
        k = np.flatnonzero(along)
        if not len(k):
            return "has no axis along z"
        if not prism_spans(g.size[k[0]] / 2):
            return centred + ("" if reach is None else f" nor reaches {reach:g} past it on both sides")
        i, j = (a for a in range(3) if a != k[0])
        return _polygon(c2, [(s * g.size[i] / 2) * m[:2, i] + (t * g.size[j] / 2) * m[:2, j]
                             for s, t in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
    if g.kind in ("cylinder", "cone"):
        r, h = float(g.size[0]), float(g.size[1])
        if g.kind == "cylinder" and along[1]:
            if not prism_spans(h / 2):
                return centred + ("" if reach is None else f" nor reaches {reach:g} past it on both sides")
            return Section(c2, r, None)
        if not across[1]:
            return "axis is neither along z (a cylinder) nor in the plane"
        if not on_plane:
            return centred
        axis = m[:2, 1]
        side = np.array([-axis[1], axis[0]]) * r
        top = axis * h / 2
        if g.kind == "cone":  # X3D's cone: base at -h/2, apex at +h/2
            return _polygon(c2, [-top - side, -top + side, top])
        return _polygon(c2, [-top - side, -top + side, top + side, top - side])
    return "has no section known exact (meshes and elevation grids are refused)"


def _polygon(centre: np.ndarray, offsets: list[np.ndarray]) -> Section:
    return Section(centre, 0.0, centre + np.array(offsets))
