"""Warnings that say what a scene will really do (x3d_core/semantics/outcome.py): each from `x3drbp check`
with its file, line and node, repeated once by `x3drbp run` and `x3drbp compare`, and a
counter-scene where it must not appear; a scene with nothing to simulate stops run and compare
with exit 1 and no trace. Every scene is written here."""

from __future__ import annotations

import pytest

from backends import base
from x3drbp import main as cli_main
from x3d_core.encodings.load import load
from x3d_core.semantics.world import STATIC, worlds
from x3d_core.traces.trace import read_trace

USABLE = [n for n in ("ode", "mujoco", "bullet", "dart") if not isinstance(base.available().get(n, "absent"), str)]
pytestmark = pytest.mark.skipif(not USABLE, reason="no backend to run on")
ANYWAY = "(some browsers, X_ITE and Jolt-based ones, collide them anyway)"
SHAPE = "CollidableShape { shape Shape { geometry Sphere { radius 0.1 } } }"


def _scene(tmp_path, text: str, name: str = "s.x3dv") -> str:
    path = tmp_path / name
    path.write_text("#X3D V4.0 utf8\n" + text)
    return str(path)


def _check(path: str, capsys) -> list[str]:
    """`x3drbp check`'s warning lines."""
    assert cli_main(["check", path]) == 0
    return [line for line in capsys.readouterr().out.splitlines() if ": warning: " in line]


def _run(path: str, capsys, *extra: str, duration: str = "0.05") -> tuple[int, str]:
    """`x3drbp run` on the first usable backend: exit status and standard error."""
    code = cli_main(["run", path, "--backend", USABLE[0], "--duration", duration, *extra])
    return code, capsys.readouterr().err


def _said_once(path: str, line: str, capsys) -> None:
    """The line is one of check's warnings, and run prints it exactly once."""
    assert line in _check(path, capsys)
    code, err = _run(path, capsys, "--trace", path + ".csv")
    assert code == 0 and err.splitlines().count(line) == 1, err


# -- 1. collision geometry that nothing lets collide ----------------------------------------
# A ball 0.3 m above a fixed floor body, both with geometry: it rests on the floor at 0.15 m
# where they collide, and is far below it after 0.5 s where they do not. The warning must
# appear exactly where the run shows the ball passing through (collision.py's reading).

BALL_ON_FLOOR = """DEF World RigidBodyCollection {
  bodies [
    DEF Ball RigidBody { position 0 0.3 0 geometry DEF BallShape %s }
    DEF Floor RigidBody { fixed TRUE geometry DEF FloorShape CollidableShape { shape Shape { geometry Box { size 4 0.1 4 } } } }
  ]
  %%s
}
%%s""" % SHAPE
BOTH = "collider CollisionCollection { collidables [ USE BallShape USE FloorShape ] }"
SENSOR = "DEF Sensor CollisionSensor { collider CollisionCollection { collidables [ USE BallShape USE FloorShape ] } }\n"
STATIC_SHAPE = "CollidableShape { translation 5 0 0 shape Shape { geometry Box { size 1 1 1 } } }"
BOTH_BODIES = "RigidBody Ball, RigidBody Floor carry collision geometry that never collides: "
THROUGH = f"; they will pass through each other and the floor {ANYWAY}"


@pytest.mark.parametrize("collider,after,why", [
    ("", "", BOTH_BODIES + "the collection has no collider" + THROUGH),
    ("collider CollisionCollection { collidables USE BallShape }", "",
     BOTH_BODIES + "its collider CollisionCollection holds one collidable (a contact takes two collidables of "
                   "different bodies)" + THROUGH),
    (f"collider CollisionCollection {{ collidables [ {STATIC_SHAPE} {STATIC_SHAPE} ] }}",
     "", BOTH_BODIES + "its collider CollisionCollection holds static collidables only (a contact takes two "
                       "collidables of different bodies)" + THROUGH),
    ("collider CollisionCollection { enabled FALSE collidables [ USE BallShape USE FloorShape ] }", "",
     BOTH_BODIES + "its collider CollisionCollection is disabled" + THROUGH),
    ("", SENSOR, BOTH_BODIES + "the collection has no collider, and the contacts of CollisionSensor Sensor are "
                               "not routed to its set_contacts" + THROUGH),
    (f"collider CollisionCollection {{ collidables [ USE FloorShape {STATIC_SHAPE} ] }}", "",
     "RigidBody Ball carries collision geometry that never collides: the collider CollisionCollection gives it no "
     f"collision shape; it will pass through every other body and the floor {ANYWAY}"),
    (BOTH, "", None),  # a proper collider with the floor and the ball
    ("", SENSOR + "ROUTE Sensor.contacts TO World.set_contacts\n", None),  # the sensor's collider acts as the collection's
], ids=["no-collider", "one-collidable", "static-only", "disabled-collider", "unrouted-sensor", "not-in-collider", "collider",
        "routed-sensor"])
def test_the_warning_appears_exactly_where_the_ball_passes_through_the_floor(tmp_path, capsys, collider, after, why):
    path = _scene(tmp_path, BALL_ON_FLOOR % (collider, after))
    warned = [w for w in _check(path, capsys) if "never collides" in w]
    code, err = _run(path, capsys, "--trace", path + ".csv", duration="0.5")
    assert code == 0, err
    ball = [r.value for r in read_trace(path + ".csv") if r.node == "Ball" and r.field == "position"]
    height = float(ball[-1].split()[1])
    if why is None:
        assert warned == [] and "never collides" not in err and height > 0.1
        return
    at = "7:12" if collider else "2:11"  # the collider field's value, else the collection
    line = f"{path}:{at}: warning: RigidBodyCollection World.collider: {why}"
    assert warned == [line] and err.splitlines().count(line) == 1, (warned, err)
    assert height < -0.5  # through the floor


# -- 2. structure a run reads otherwise than the file suggests ------------------------------
# Each scene: its warning (the line after the file name), and what the run does, as it says.

LOOSE = "DEF World RigidBodyCollection { bodies DEF Kept RigidBody { } }\nDEF Loose RigidBody { position 0 1 0 }\n"
TRANSFORMED = "DEF Lift Transform { %s children DEF World RigidBodyCollection { bodies DEF Ball RigidBody { } } }\n"
SHARED = f"""DEF World RigidBodyCollection {{
  bodies [
    DEF A RigidBody {{ geometry DEF S {SHAPE} }}
    DEF B RigidBody {{ position 1 0 0
      geometry %s }}
  ]
  collider CollisionCollection {{ collidables [ USE S {STATIC_SHAPE} ] }}
}}
"""
JOINED = """DEF One RigidBodyCollection { bodies DEF A RigidBody { } }
DEF Two RigidBodyCollection { bodies [ DEF B RigidBody { position 0 -1 0 } %s ]
  joints DEF J BallJoint { anchorPoint 0 0 0
    body1 USE A body2 USE B } }
"""


PLACED = """DEF World RigidBodyCollection {
  bodies DEF Ball RigidBody { position 0 1 0
    geometry DEF S CollidableShape { %s shape Shape { geometry Sphere { radius 0.1 } } } }
  collider CollisionCollection { collidables [ USE S
    DEF Floor CollidableShape { shape Shape { geometry Box { size 4 0.1 4 } } } ] }
}
"""


def _shape_pose_in_body(path: str) -> tuple[list[float], list[float]]:
    (w,) = worlds(load(path))
    (g,) = [g for g in w.collisions.geometries if g.name == "S"]
    return g.position.tolist(), g.orientation.tolist()


def _traced_bodies(path: str) -> set[str]:
    return {r.node for r in read_trace(path + ".csv")}


def _ball_start(path: str) -> str:
    return [r.value for r in read_trace(path + ".csv") if r.node == "Ball" and r.field == "position"][0]


def _owners_of_s(path: str) -> list[int]:
    (w,) = worlds(load(path))
    return [g.body for g in w.collisions.geometries if g.name == "S"]


def _joint_rows(path: str) -> tuple[int, int]:
    (j,) = [w for w in worlds(load(path)) if w.name == "Two"][0].joints
    return j.body1, j.body2


@pytest.mark.parametrize("text,line,does,result", [
    (LOOSE, "3:11: warning: RigidBody Loose: in no RigidBodyCollection: it is not simulated and not in the trace "
            "(it stays where the file puts it)", _traced_bodies, {"Kept"}),
    (TRANSFORMED % "translation 0 1 0", "2:10: warning: Transform Lift: its transform is ignored for "
     "RigidBodyCollection World: bodies are in world coordinates, so a run places them by their own fields alone",
     _ball_start, "0 0 0"),  # not 0 1 0
    (SHARED % "USE S", "6:16: warning: RigidBody B.geometry: CollidableShape S is also in RigidBody A's geometry, "
     "earlier in RigidBodyCollection World's bodies: it moves and collides with RigidBody A only, and RigidBody B "
     "gets no collision shape from it", _owners_of_s, [0]),  # one shape, on A's row
    (JOINED % "", "5:11: warning: BallJoint J.body1: RigidBody A is not in the joint's collection RigidBodyCollection "
     "Two; the spec leaves such a joint undefined: a run ties this end to the static world, as if body1 were NULL, "
     "and the joint does not act on RigidBody A", _joint_rows, (STATIC, 0)),
    (PLACED % "translation 0 1 0", "4:38: warning: CollidableShape S.translation: the clause reads it two ways: "
     "x3drbp takes 37.4.10's (collidables \"have their location set to the same location as the body instance in "
     "which they are located\", so a run ignores its translation), another browser may take 37.3.1's (\"an offset "
     "from, and rotation about, the body's center\") and place the geometry elsewhere",
     _shape_pose_in_body, ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0])),  # at the body's frame, not 1 m above it
], ids=["in-no-collection", "transform", "shared-collidable", "joint-across-collections", "collidable-on-a-body"])
def test_each_warning_is_said_once_by_run_and_says_what_it_does(tmp_path, capsys, text, line, does, result):
    path = _scene(tmp_path, text)
    _said_once(path, f"{path}:{line}", capsys)
    assert does(path) == result


@pytest.mark.parametrize("text,fragment", [
    ("DEF World RigidBodyCollection { bodies DEF Kept RigidBody { } }\n", "in no RigidBodyCollection"),
    (SHARED % f"DEF T {SHAPE}", "is also in"),  # each body its own collidable
    (JOINED.replace("bodies DEF A RigidBody { }", "bodies [ ]") % "DEF A RigidBody { }", "joint"),
    # ignoring a transform that moves nothing changes nothing: no warning to give
    (TRANSFORMED % "", "Transform"),
    (TRANSFORMED % "translation 0 0 0 rotation 0 1 0 0 scale 1 1 1 center 3 3 3", "Transform"),
    (TRANSFORMED % "rotation 1 0 0 6.283185307179586", "Transform"),
    # a body's collidable placed at the identity: both readings put it at the body's frame
    (PLACED % "translation 0 0 0 rotation 0 1 0 0", "the clause reads it two ways"),
], ids=["collected", "own-collidables", "joint-within", "identity", "identity-given", "full-turn",
        "collidable-at-identity"])
def test_the_counter_scenes_are_not_warned(tmp_path, capsys, text, fragment):
    path = _scene(tmp_path, text)
    assert not [w for w in _check(path, capsys) if fragment in w]


def test_a_body_held_by_another_transforming_group_is_warned(tmp_path, capsys):
    path = _scene(tmp_path, "DEF Geo GeoTransform { translation 0 1 0 children DEF Ball RigidBody { } }\n"
                            "DEF World RigidBodyCollection { bodies USE Ball }\n")
    warned = [w for w in _check(path, capsys) if "its transform is ignored" in w]
    assert warned == [f"{path}:2:9: warning: GeoTransform Geo: its transform is ignored for RigidBody Ball: bodies "
                      "are in world coordinates, so a run places them by their own fields alone"]


# -- 3. nothing to simulate ---------------------------------------------------------------

@pytest.mark.parametrize("text,where", [
    ("DEF World RigidBodyCollection { bodies DEF Off RigidBody { enabled FALSE } }\n",
     "2:11: warning: RigidBodyCollection World: "),
    ("DEF World RigidBodyCollection { enabled FALSE bodies DEF Ball RigidBody { } }\n",
     "2:11: warning: RigidBodyCollection World: "),
    ("Transform { }\n", "1:1: warning: "),
], ids=["disabled-body", "disabled-collection", "no-physics"])
def test_nothing_to_simulate_is_warned_and_stops_run_and_compare_with_no_trace(tmp_path, capsys, text, where):
    path = _scene(tmp_path, text)
    assert _check(path, capsys) == [f"{path}:{where}nothing to simulate: no enabled RigidBody in an enabled "
                                    "RigidBodyCollection; `x3drbp run` and `x3drbp compare` exit 1 and write no trace"]
    stop = f"{path}: nothing to simulate: no enabled RigidBody in an enabled RigidBodyCollection (no trace written)"
    out = tmp_path / "t.csv"
    code, err = _run(path, capsys, "--trace", str(out))
    assert (code, err.splitlines()) == (1, [stop]) and not out.exists() and not list(tmp_path.glob("*.csv*"))
    assert cli_main(["compare", path, "--backends", "ode,mujoco"]) == 1
    assert capsys.readouterr().err.splitlines() == [stop]


def test_one_enabled_body_is_something_to_simulate(tmp_path, capsys):
    path = _scene(tmp_path, "DEF World RigidBodyCollection { bodies [ DEF Off RigidBody { enabled FALSE } "
                            "DEF On RigidBody { } ] }\n")
    assert _check(path, capsys) == []
    code, err = _run(path, capsys, "--trace", path + ".csv")
    assert code == 0 and err == "" and {r.node for r in read_trace(path + ".csv")} == {"On"}


@pytest.mark.skipif(len(USABLE) < 2, reason="two backends needed")
def test_compare_says_each_warning_once_however_many_backends_run(tmp_path, capsys):
    path = _scene(tmp_path, BALL_ON_FLOOR % ("", ""))
    assert cli_main(["compare", path, "--backends", ",".join(USABLE[:2]), "--duration", "0.1"]) == 0
    err = capsys.readouterr().err
    assert err.count("never collides") == 1 and err.startswith(f"{path}:2:11: warning: "), err
