"""What only the ODE backend does with collisions: its heightfield placed as X3D places an
ElevationGrid, and byte-identical runs of a pile of contacts. The contact physics (bounce apex and
threshold, friction, anisotropic friction, conveyor, surface layer, sensor contacts), which ODE
passes with its contact parameters as its own mode bits, is in the conformance cases
(conformance/cases/)."""

from __future__ import annotations

import math

import numpy as np
import pytest

try:
    from backends import ode as ode_backend
    from backends.ode import BACKEND
except ImportError as e:
    pytest.skip(f"ODE is not installed: {e}", allow_module_level=True)

from engine_run import DT, scene_worlds, shape  # noqa: E402
from x3d_core.semantics.evaluator import RunSettings, run  # noqa: E402

FLOOR = shape("<Box size='10 1 10'/>", "Floor", "translation='0 -0.5 0'")  # top face at y = 0


def collection(bodies: str, collidables: str, params: str = "") -> str:
    return (f"<RigidBodyCollection gravity='0 -9.81 0'>{bodies}"
            f"<CollisionCollection containerField='collider' {params}>{collidables}</CollisionCollection>"
            "</RigidBodyCollection>")


def ball(name: str, y: float, r: float, x: float = 0, z: float = 0) -> str:
    return (f"<RigidBody DEF='{name}' position='{x} {y} {z}' inertia='0.004 0 0 0 0.004 0 0 0 0.004'>"
            f"{shape(f'<Sphere radius={chr(39)}{r}{chr(39)}/>', name + 'S', container='geometry')}</RigidBody>")


def crate(name: str, y: float) -> str:
    return (f"<RigidBody DEF='{name}' position='0 {y} 0' "
            "inertia='0.0166667 0 0 0 0.0266667 0 0 0 0.0166667'>"
            f"{shape('<Box size=' + chr(39) + '0.4 0.2 0.4' + chr(39) + '/>', name + 'S', container='geometry')}"
            "</RigidBody>")


def test_heightfield_lies_as_x3d_places_it(tmp_path):
    # a 3 x 3 grid, 1 m spacing, rising 0.2 per row along z: its corner at the origin, heights
    # row by row along x; a ball resting on it at (1, z) touches along the normal (0, 1, -0.2)
    grid = ("<ElevationGrid xDimension='3' zDimension='3' xSpacing='1' zSpacing='1' "
            "height='0 0 0 0.2 0.2 0.2 0.4 0.4 0.4'/>")
    r = 0.1
    n = np.array([0, 1, -0.2]) / math.hypot(1, 0.2)
    centre = np.array([1, 0.2, 1]) + r * n
    body = collection(ball("B", centre[1], r, x=centre[0], z=centre[2]), shape(grid, "Ground") +
                      "<CollidableShape USE='BS'/>", "frictionCoefficients='1 1'").replace(
        "<CollisionCollection ", "<CollisionCollection DEF='C' ")
    world = scene_worlds(tmp_path, body)[0]
    sim = BACKEND.build(world, DT)
    sim.step()
    c = sim.contacts()
    assert len(c.depth) == 1 and c.normal[0] == pytest.approx(n, abs=1e-9)
    off = scene_worlds(tmp_path, body.replace(f"position='{centre[0]}", "position='-1"))[0]  # beside the grid
    sim = BACKEND.build(off, DT)
    sim.step()
    assert len(sim.contacts().depth) == 0


PILE = collection("".join(ball(f"S{k}", 0.3 + 0.25 * k, 0.1, x=0.05 * (k % 3), z=0.03 * k) for k in range(6)) +
                  crate("Box", 2.0), FLOOR + "".join(f"<CollidableShape USE='S{k}S'/>" for k in range(6)) +
                  "<CollidableShape USE='BoxS'/>", "bounce='0.3' frictionCoefficients='0.4 0.4'")


def test_runs_are_byte_identical(tmp_path):
    worlds = scene_worlds(tmp_path, PILE)
    first = run(worlds, BACKEND, RunSettings(2.0, DT, 60)).rows
    again = run(scene_worlds(tmp_path, PILE), BACKEND, RunSettings(2.0, DT, 60)).rows
    assert first == again


def test_listed_pairs_and_the_grid_find_the_same_contacts(tmp_path, monkeypatch):
    # a few geoms have every allowed pair listed at build, many go through _near's grid: both
    # must give the same pairs in the same order, so the same run to the last bit
    listed = run(scene_worlds(tmp_path, PILE), BACKEND, RunSettings(1.0, DT, 60)).rows
    monkeypatch.setattr(ode_backend, "_ALL_PAIRS", 0)
    assert run(scene_worlds(tmp_path, PILE), BACKEND, RunSettings(1.0, DT, 60)).rows == listed
