"""Whether a world moves in one plane, and the sections of its shapes by that plane.

A planar engine (backends/pymunk.py) can run a world exactly only where nothing can
leave the plane, so this analysis proves it from the start state or refuses, naming
the body or joint, the field and its value. The plane is z = c with its normal +z:
a 2D engine's own plane, into which a scene drawn in the X3D default view (x right,
y up, gravity -y) already falls. c is the z of the first moving body's centre of mass;
every other one must share it. Scenes planar in another plane are refused (turning
them into z = c is a change of frame this module does not make).

A world is planar when every moving body's centre of mass lies on the plane, its
velocity and force lie in it, its angular velocity and torque lie along z, its
orientation turns about z, and its inertia has no product of inertia with z (so that
spin about z makes no torque out of the plane); gravity lies in the plane; hinges turn
about z, sliders slide in the plane, ball joints sit on the plane (their force then
acts at the plane and makes no tipping torque), a universal joint has one axis along z
and the other in the plane (the out-of-plane freedom is never excited: a pivot); motor
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
body's shapes are centred on the plane (symmetric about it, so are their contact
patches), and a static prism is centred on it too or reaches past the plane on both
sides by at least the moving shapes' largest half-extent along z (a floor wider than
what stands on it). Meshes and elevation grids are refused.
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
    z: float  # the plane z = z
    sections: list[Section]  # one per world.collisions.geometries (empty without collisions)


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
    """The plane the world moves in and its shapes' sections; NotPlanar otherwise."""
    b = world.bodies
    moving = np.flatnonzero(~b.fixed)
    com = b.position + R.rotate(b.orientation, b.com)
    z = float(com[moving[0], 2]) if len(moving) else 0.0
    reasons: list[str] = []
    if abs(world.gravity[2]) > TOLERANCE:
        reasons.append(f"RigidBodyCollection {world.name} gravity ({_text(world.gravity)}) leaves the plane")
    for i in moving:
        name = f"RigidBody {b.names[i]}"
        checks = (("centre of mass", com[i], abs(com[i, 2] - z) > TOLERANCE, f"is off the plane z = {z:g}"),
                  ("orientation", R.to_axis_angle(b.orientation[i]), not _along_z(b.orientation[i, 1:]),
                   "does not turn about z"),
                  ("linearVelocity", b.linear_velocity[i], abs(b.linear_velocity[i, 2]) > TOLERANCE,
                   "leaves the plane"),
                  ("angularVelocity", b.angular_velocity[i], not _along_z(b.angular_velocity[i]), "is not along z"),
                  ("forces", b.forces[i], abs(b.forces[i, 2]) > TOLERANCE, "leave the plane"),
                  ("torques", b.torques[i], not _along_z(b.torques[i]), "are not along z"),
                  ("inertia", b.inertia[i], np.abs(b.inertia[i, :2, 2]).max() > TOLERANCE * np.abs(b.inertia[i]).max(),
                   "couples spin about z out of the plane (products of inertia with z)"))
        reasons.extend(f"{name} {field} ({_text(v)}) {why}" for field, v, bad, why in checks if bad)
    reasons.extend(_joints(world, z))
    found: list[Section] = []
    if world.collisions is not None:
        speed = world.collisions.parameters.surface_speed
        if abs(speed[1]) > TOLERANCE:
            reasons.append(f"CollisionCollection surfaceSpeed ({_text(speed)}): SPEED-2 drives along z, ODE's "
                           "second friction direction for normals in the plane")
        found, bad = sections(world, z)
        reasons.extend(bad)
    if reasons:
        raise NotPlanar(reasons)
    return Planar(z, found)


def _joints(world: World, z: float) -> list[str]:
    out = []
    for j in world.joints:
        if j.body1 == j.body2 or j.body1 == j.body2 == STATIC:  # joins nothing that moves
            continue
        name = f"{j.type} {j.name}"
        if j.type == "SingleAxisHingeJoint" and not _along_z(j.axes[0]):
            out.append(f"{name} axis ({_text(j.axes[0])}) is not along z")
        elif j.type == "SliderJoint" and abs(j.axes[0, 2]) > TOLERANCE:
            out.append(f"{name} axis ({_text(j.axes[0])}) leaves the plane")
        elif j.type == "BallJoint" and abs(j.anchor[2] - z) > TOLERANCE:
            out.append(f"{name} anchorPoint ({_text(j.anchor)}) is off the plane z = {z:g}")
        elif j.type == "UniversalJoint" and not universal_pivot(j.axes[:2]):
            out.append(f"{name} axis1 ({_text(j.axes[0])}), axis2 ({_text(j.axes[1])}): neither is along z with "
                       "the other in the plane")
        elif j.type == "UniversalJoint" and abs(j.anchor[2] - z) > TOLERANCE:
            out.append(f"{name} anchorPoint ({_text(j.anchor)}) is off the plane z = {z:g}")
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


def sections(world: World, z: float) -> tuple[list[Section], list[str]]:
    """Each geometry's section by the plane z at the start (world coordinates), and the
    reasons why some are not exact (module docstring)."""
    b = world.bodies
    poses = [_pose(g, world) for g in world.collisions.geometries]
    moving = [g.body != STATIC and not b.fixed[g.body] for g in world.collisions.geometries]
    reach = max((_half_extent(g, m) for g, (_, m), mv in zip(world.collisions.geometries, poses, moving) if mv),
                default=0.0)
    out, reasons = [], []
    for g, (centre, m), mv in zip(world.collisions.geometries, poses, moving):
        s = _section(g, centre, m, z, None if mv else reach)
        if isinstance(s, str):
            reasons.append(f"CollidableShape {g.name} ({g.kind}) {s}")
        else:
            out.append(s)
    return out, reasons


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
