"""The same scene on the same backend twice gives byte-identical traces, on a contact-rich
scene too: a pile of 24 boxes and spheres dropped on a floor under a CollisionSensor, 2 s.
Each run is its own `x3drbp run` child, as the suite runs them."""

from __future__ import annotations

import pytest

from backends import base
from conformance import results
from conformance.runner import children, verdicts
from conformance.results import Settings

INSTALLED = [n for n, b in base.available().items() if not isinstance(b, str)]
SETTINGS = Settings(2.0, 1 / 240, 60.0)


def pile_x3d(planar: bool = False, layers: int = 3, rows: int = 2, columns: int = 4) -> str:
    """Boxes and spheres of 0.2 m in a jittered grid over a floor, every pair colliding
    (planar: all in the plane z = 0, for a 2D engine)."""
    bodies, shapes = [], []
    for k in range(layers * rows * columns):
        layer, rest = divmod(k, rows * columns)
        i, j = divmod(rest, columns)
        x, y = (j - 1.5) * 0.25 + 0.03 * (layer % 2) + 0.5 * i * planar, 0.15 + 0.25 * (layer + i * planar)
        z = 0.0 if planar else (i - 0.5) * 0.25 + 0.02 * (k % 3)
        geometry = "<Sphere radius='0.1'/>" if k % 2 else "<Box size='0.2 0.2 0.2'/>"
        bodies.append(f"<RigidBody DEF='B{k}' mass='0.5' position='{x!r} {y!r} {z!r}' "
                      f"orientation='0 0 1 {0.1 * k!r}' inertia='0.0033 0 0 0 0.0033 0 0 0 0.0033'>"
                      f"<CollidableShape DEF='S{k}' containerField='geometry'><Shape containerField='shape'>"
                      f"{geometry}</Shape></CollidableShape></RigidBody>")
        shapes.append(f"<CollidableShape USE='S{k}'/>")
    shapes.append("<CollidableShape DEF='Floor' translation='0 -0.1 0'><Shape containerField='shape'>"
                  "<Box size='4 0.2 4'/></Shape></CollidableShape>")
    return ("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='4.0'><Scene>\n"
            "<RigidBodyCollection DEF='World'>\n" + "\n".join(bodies)
            + "\n<CollisionCollection DEF='Contacts' frictionCoefficients='0.5 0.5'>\n" + "\n".join(shapes)
            + "\n</CollisionCollection>\n</RigidBodyCollection>\n<CollisionSensor DEF='Sensor'>"
            "<CollisionCollection USE='Contacts' containerField='collider'/></CollisionSensor>\n</Scene></X3D>\n")


def twice(tmp, backends: list[str], planar: bool) -> dict:
    """(outcome, trace path) of each backend's two runs of the pile, all run in parallel."""
    scene = tmp / f"pile{'-planar' * planar}.x3d"
    scene.write_text(pile_x3d(planar))
    pairs = [(b, k) for b in backends for k in (1, 2)]
    paths = {(b, k): tmp / f"{scene.stem}-{b}-{k}.csv" for b, k in pairs}
    jobs = [(lambda b=b, k=k: children.run_child(str(scene), b, SETTINGS, str(paths[b, k]))) for b, k in pairs]
    return {(b, k): (o, paths[b, k]) for (b, k), o in zip(pairs, verdicts.run_many(jobs))}


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The 3D pile on every installed backend; the planar one where a backend refuses it."""
    tmp = tmp_path_factory.mktemp("pile")
    out = twice(tmp, INSTALLED, planar=False)
    flat = [b for b in INSTALLED if out[b, 1][0].verdict == results.UNSUPPORTED]
    return out | twice(tmp, flat, planar=True) if flat else out


@pytest.mark.parametrize("backend", INSTALLED)
def test_the_same_pile_twice_gives_the_same_bytes(runs, backend):
    (first, a), (second, b) = runs[backend, 1], runs[backend, 2]
    assert first.verdict is None and second.verdict is None, (first.reason, second.reason)
    text = a.read_bytes()
    assert b"contacts[0]" in text  # the pile touches: the sensor's contacts are in the trace
    assert text == b.read_bytes()
