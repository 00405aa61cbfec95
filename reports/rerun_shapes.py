"""Collision geometry as rerun archetypes: what a recording draws for each collidable.

The shapes are x3d_core's collision plan (the very shapes the engines collide), so a
recording shows what was simulated, not what the scene renders. X3D's cylinders and
cones stand along y, rerun's cylinders along z: they are turned a quarter about x. Rerun
has no cone, so a cone is tessellated; a heightfield is its grid as triangles.
"""

from __future__ import annotations

import math

import numpy as np
import rerun as rr

from x3d_core.semantics.collision import Geometry

CONE_SEGMENTS = 24
MARKER_RADIUS = 0.02  # m: a body with no collidable is drawn as a point this big
Y_UP = np.array([-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)])  # xyzw: z turned onto y


def xyzw(q: np.ndarray) -> np.ndarray:
    """x3d_core's quaternions (w x y z) in rerun's order (x y z w)."""
    return np.asarray(q)[..., [1, 2, 3, 0]]


def cone_mesh(radius: float, height: float, segments: int = CONE_SEGMENTS) -> tuple[np.ndarray, np.ndarray]:
    """(vertices, triangles) of an X3D cone: apex at y = h/2, base at y = -h/2, base capped."""
    a = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    rim = np.column_stack([radius * np.cos(a), np.full(segments, -height / 2), radius * np.sin(a)])
    vertices = np.vstack([rim, [[0.0, height / 2, 0.0], [0.0, -height / 2, 0.0]]])
    k = np.arange(segments)
    nxt = (k + 1) % segments
    side = np.column_stack([k, np.full(segments, segments), nxt])
    cap = np.column_stack([nxt, np.full(segments, segments + 1), k])
    return vertices, np.vstack([side, cap])


def grid_triangles(nx: int, nz: int) -> np.ndarray:
    """Two triangles per cell of an ElevationGrid's points (x fastest)."""
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(nz - 1))
    a = (j * nx + i).ravel()
    b, c, d = a + 1, a + nx, a + nx + 1
    return np.vstack([np.column_stack([a, c, b]), np.column_stack([b, c, d])])


def shape(g: Geometry, color: tuple[int, int, int]) -> rr.AsComponents:
    """The archetype drawing g in its own frame (the caller places that frame)."""
    if g.kind == "box":
        return rr.Boxes3D(half_sizes=[g.size / 2], colors=[color])
    if g.kind == "sphere":
        return rr.Ellipsoids3D(half_sizes=[np.full(3, g.size[0])], colors=[color])
    if g.kind == "cylinder":
        return rr.Cylinders3D(radii=[g.size[0]], lengths=[g.size[1]], quaternions=[Y_UP], colors=[color])
    if g.kind == "cone":
        vertices, triangles = cone_mesh(float(g.size[0]), float(g.size[1]))
    elif g.kind == "heightfield":
        vertices, triangles = g.vertices, grid_triangles(*g.grid)
    else:
        vertices, triangles = g.vertices, g.triangles
    return rr.Mesh3D(vertex_positions=vertices, triangle_indices=triangles, albedo_factor=color)


def marker(color: tuple[int, int, int]) -> rr.Points3D:
    """What a body without a collidable is drawn as: a point at its origin."""
    return rr.Points3D([[0.0, 0.0, 0.0]], radii=[MARKER_RADIUS], colors=[color])
