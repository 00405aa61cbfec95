"""A CollisionSensor watching a CollisionCollection that no RigidBodyCollection collides with
(issue 35 item 7): the world plans the collection once for reporting only (collision.watch), the
engine detects it without responding, and a backend that cannot is refused by name
(analysis.WATCHED_ONLY). The closed-form check of the reports is conformance/cases/sensor_only."""

from __future__ import annotations

import numpy as np
import pytest

from backends import base
from conftest import loaded_scene
from engine_run import run_x3d, scene_worlds, shape
from x3d_core.semantics.analysis import WATCHED_ONLY, features, run_features
from x3d_core.semantics.world import STATIC, State, worlds

BALL = shape("<Sphere radius='0.1'/>", "BallShape")
GATE = shape("<Box size='4 0.5 4'/>", "GateShape", "translation='0 0.75 0'")  # y 0.5 to 1.0
FLOOR = shape("<Box size='4 1 4'/>", "Floor", "translation='0 -0.5 0'")  # top face at y = 0
BODY = ("<RigidBody DEF='Ball' position='0 2 0' inertia='0.004 0 0 0 0.004 0 0 0 0.004'>"
        "<CollidableShape USE='BallShape' containerField='geometry'/></RigidBody>")


def scene(watched: str = "", sensor: str = "", collection: str = "", body: str = BODY) -> str:
    """A sensor on a collection of the ball and the gate, then the ball's RigidBodyCollection."""
    return (f"<CollisionSensor DEF='Sensor' {sensor}><CollisionCollection DEF='Watched' containerField='collider' "
            f"{watched}>{BALL}{GATE}</CollisionCollection></CollisionSensor>"
            f"<RigidBodyCollection DEF='World' gravity='0 -9.81 0'>{collection}{body}</RigidBodyCollection>")


def loaded(tmp_path, body: str):
    return loaded_scene(tmp_path, body)


# -- the plan ---------------------------------------------------------------------------

def test_a_collection_no_body_collection_uses_is_planned_for_its_sensor_alone(tmp_path):
    [w] = scene_worlds(tmp_path, scene())
    assert w.collisions is None  # nothing acts on the bodies
    [c] = w.watched
    assert [(g.name, g.body) for g in c.geometries] == [("BallShape", 0), ("GateShape", STATIC)]
    assert [name for name, _ in c.sensors] == ["Sensor"]


@pytest.mark.parametrize("watched, sensor", [("enabled='false'", ""), ("", "enabled='false'")],
                         ids=["collection disabled", "sensor disabled"])
def test_a_disabled_collection_or_sensor_is_not_run(tmp_path, watched, sensor):
    [w] = scene_worlds(tmp_path, scene(watched, sensor))
    assert w.watched == [] and w.collisions is None


def test_a_collection_a_body_collection_collides_with_is_not_watched(tmp_path):
    [w] = scene_worlds(tmp_path, scene(collection="<CollisionCollection USE='Watched' containerField='collider'/>"))
    assert w.watched == [] and [name for name, _ in w.collisions.sensors] == ["Sensor"]


def test_a_watched_collection_goes_to_the_world_whose_bodies_carry_it(tmp_path):
    other = "<RigidBodyCollection DEF='Other'><RigidBody DEF='Lone'/></RigidBodyCollection>"
    first, second = scene_worlds(tmp_path, other + scene())  # the ball's collection is the second
    assert first.watched == [] and len(second.watched) == 1
    static = ("<CollisionSensor DEF='S2'><CollisionCollection containerField='collider'>"
              f"{shape('<Box/>', 'A')}{shape('<Box/>', 'B')}</CollisionCollection></CollisionSensor>")
    first, second = scene_worlds(tmp_path, other + scene() + static)  # on no body: the first world's
    assert [n for c in first.watched for n, _ in c.sensors] == ["S2"]


INNER = shape("<Sphere/>", "Inner", "translation='1 0 0'", "collidable")  # 1 m along x of its offset


def test_placed_puts_each_geometry_where_its_body_is(tmp_path):
    offset = ("<RigidBody DEF='Ball' position='1 2 3' orientation='0 1 0 1.5707963267948966' "
              "inertia='0.004 0 0 0 0.004 0 0 0 0.004'><CollidableOffset DEF='Off' containerField='geometry'>"
              f"{INNER}</CollidableOffset></RigidBody>")
    body = (f"<RigidBodyCollection>{offset}</RigidBodyCollection><CollisionSensor>"
            f"<CollisionCollection containerField='collider'><CollidableOffset USE='Off'/>{GATE}</CollisionCollection>"
            "</CollisionSensor>")
    [w] = scene_worlds(tmp_path, body)
    [c] = w.watched
    s = State.initial(w.bodies)
    position, orientation = c.placed(s)
    assert position == pytest.approx(np.array([[1, 2, 2], [0, 0.75, 0]]), abs=1e-12)  # (1, 0, 0) turned to -z
    assert orientation[0] == pytest.approx(s.orientation[0], abs=1e-12)
    s.position[0], s.orientation[0] = 0.0, [1.0, 0.0, 0.0, 0.0]
    assert c.placed(s)[0][0] == pytest.approx([1, 0, 0], abs=1e-12)


# -- what a run needs -------------------------------------------------------------------

def test_a_run_needs_the_feature_where_a_watched_set_is_planned(tmp_path):
    needed = run_features(loaded(tmp_path, scene()))
    assert WATCHED_ONLY in needed and "CollidableShape.geometry.Sphere" in needed  # its shapes count, unused as they are
    off = loaded(tmp_path, scene("enabled='false'"))
    assert WATCHED_ONLY in features(off) and WATCHED_ONLY not in run_features(off)  # in the file, not run
    acting = loaded(tmp_path, scene(collection="<CollisionCollection USE='Watched' containerField='collider'/>"))
    assert WATCHED_ONLY not in features(acting)


@pytest.mark.parametrize("name", ["physx", "pymunk"])
def test_a_backend_that_cannot_detect_without_responding_refuses_it_by_name(tmp_path, name):
    try:
        backend = base.load(name)
    except ImportError as e:
        pytest.skip(f"{name} is not installed: {e}")
    refused = [u.feature for u, d in base.judged(backend, loaded(tmp_path, scene()))
               if d.support is base.Support.UNSUPPORTED]
    assert refused == [WATCHED_ONLY]


# -- the engines that detect it ---------------------------------------------------------

NATIVE = ["ode", "bullet", "mujoco", "dart", "drake"]


def engine(name: str):
    try:
        return base.load(name)
    except ImportError as e:
        pytest.skip(f"{name} is not installed: {e}")


def at(series, key, t: float):
    return next(v for time, v in series[key] if abs(time - t) < 1e-9)


@pytest.mark.parametrize("name", NATIVE)
def test_a_watched_collection_is_reported_and_pushes_nothing(tmp_path, name):
    b = engine(name)
    assert b.support(WATCHED_ONLY).support is base.Support.NATIVE
    watched = run_x3d(tmp_path, scene(), backend=b)
    unwatched = run_x3d(tmp_path, scene(sensor="enabled='false'"), backend=b)
    assert ("Sensor", "isActive") not in unwatched
    # the ball overlaps the gate from 0.428 s to 0.571 s of its fall from y = 2
    assert [at(watched, ("Sensor", "isActive"), t) for t in (0.3, 0.5, 0.7)] == ["false", "true", "false"]
    assert {at(watched, ("Sensor", f"intersections[{k}]"), 0.5) for k in (0, 1)} == {"BallShape", "GateShape"}
    assert {at(watched, ("Sensor", "contacts[0].body1"), 0.5), at(watched, ("Sensor", "contacts[0].body2"), 0.5)} \
        == {"Ball", "NULL"}
    for field in ("position", "linearVelocity"):  # to the bit: the watched shapes take no part in the physics
        assert [v.tolist() for _, v in watched[("Ball", field)]] == [v.tolist() for _, v in unwatched[("Ball", field)]]


@pytest.mark.parametrize("name", NATIVE)
def test_a_watched_set_and_the_collider_act_apart(tmp_path, name):
    """The ball falls through the watched gate onto the collider's floor and rests there: each
    sensor reports its own collection."""
    collider = (f"<CollisionCollection containerField='collider'><CollidableShape USE='BallShape'/>{FLOOR}"
                "</CollisionCollection>")
    second = "<CollisionSensor DEF='FloorSensor'><CollisionCollection USE='FloorSet' containerField='collider'/>" \
             "</CollisionSensor>"
    body = scene(collection=collider.replace("<CollisionCollection ", "<CollisionCollection DEF='FloorSet' ")) + second
    series = run_x3d(tmp_path, body, backend=engine(name))
    assert [at(series, ("Sensor", "isActive"), t) for t in (0.5, 1.0)] == ["true", "false"]
    assert [at(series, ("FloorSensor", "isActive"), t) for t in (0.5, 1.0)] == ["false", "true"]
    assert at(series, ("Ball", "position"), 1.0)[1] == pytest.approx(0.1, abs=0.01)  # on the floor
