"""Running a small scene on one backend and reading its trace back, for the backend tests."""

from __future__ import annotations

import math

import numpy as np

from x3d_core.encodings.load import load
from x3d_core.semantics import rotation as R
from x3d_core.semantics.evaluator import RunSettings, run
from x3d_core.semantics.world import worlds

DT = 1 / 240
G = 9.81

Series = dict[tuple[str, str], list[tuple[float, np.ndarray]]]

# A body with every pose and mass field off its default (an off-centre centre of mass, a full
# inertia tensor), and the scene that starts it moving: for the backends' read-back tests
ODD_BODY = ("position='1 2 3' orientation='0.2 1 0.3 0.9' centerOfMass='0.3 -0.1 0.2' mass='2' "
            "inertia='0.3 0.02 -0.01 0.02 0.4 0.03 -0.01 0.03 0.5'")
ODD_SCENE = (f"<RigidBodyCollection gravity='0 -9.81 0'><RigidBody DEF='B' {ODD_BODY} "
             "linearVelocity='0.5 0 -1' angularVelocity='0 2 1'/></RigidBodyCollection>")

# A turned body, its centre of mass off its origin and a full inertia tensor (an engine's inertial
# frame both offset and turned against the body frame), falling: the backends' inertial-frame tests
TURNED_ORIENTATION = np.array([0.3, 1, 0.2, 0.7])
TURNED_BODY = ("<RigidBodyCollection gravity='0 -9.81 0'><RigidBody DEF='B' position='1 2 3' "
               f"orientation='{' '.join(map(repr, TURNED_ORIENTATION.tolist()))}' centerOfMass='0.3 -0.1 0.2' mass='2' "
               "inertia='0.2 0.03 0.01 0.03 0.15 -0.02 0.01 -0.02 0.1'/></RigidBodyCollection>")


# A bob on a massless rod of 1 m, hinged about z to a fixed anchor: the backends' hinge tests
PENDULUM = """<RigidBodyCollection gravity='0 -9.81 0'>
  <RigidBody DEF='Anchor' fixed='true'/>
  <RigidBody DEF='Bob' position='{x} {y} 0' inertia='1e-6 0 0 0 1e-6 0 0 0 1e-6'/>
  <SingleAxisHingeJoint DEF='H' axis='0 0 1' forceOutput='"ALL"' {limits}>
    <RigidBody USE='{first}' containerField='body1'/><RigidBody USE='{second}' containerField='body2'/>
  </SingleAxisHingeJoint></RigidBodyCollection>"""


def pendulum(theta0: float, limits: str = "", bob_is_body1: bool = False) -> str:
    """The PENDULUM released theta0 from the downward vertical, with the hinge's limit fields."""
    first, second = ("Bob", "Anchor") if bob_is_body1 else ("Anchor", "Bob")
    return PENDULUM.format(x=math.sin(theta0), y=-math.cos(theta0), limits=limits, first=first, second=second)


def scene_worlds(tmp_path, body: str, version: str = "4.0") -> list:
    """The worlds of a scene given as the X3D XML text of its Scene's content (which must
    load without errors), in a file of that X3D version."""
    p = tmp_path / "s.x3d"
    p.write_text(f"<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='{version}'><Scene>\n"
                 f"{body}\n</Scene></X3D>\n")
    scene = load(str(p))
    assert not scene.errors, [str(e) for e in scene.errors]
    return worlds(scene)


def run_x3d(tmp_path, body: str, duration: float = 1.0, frame_rate: float = 60, dt: float = DT,
            times: np.ndarray | None = None, *, backend, version: str = "4.0") -> Series:
    """Run the scene (X3D XML text of the Scene's content, in a file of that X3D version) and
    return its trace as (node, field) -> [(time, value)], values parsed with float()."""
    trace = run(scene_worlds(tmp_path, body, version), backend, RunSettings(duration, dt, frame_rate), times)
    series: Series = {}
    for r in trace.rows:
        series.setdefault((r.node, r.field), []).append((r.time, _value(r.value)))
    return series


def shape(geometry: str, name: str = "", extra: str = "", container: str = "") -> str:
    """A CollidableShape around one geometry (X3D XML text)."""
    d = f" DEF='{name}'" if name else ""
    c = f" containerField='{container}'" if container else ""
    return f"<CollidableShape{d}{c} {extra}><Shape containerField='shape'>{geometry}</Shape></CollidableShape>"


def _value(text: str):
    """Numbers as an array; anything else (true, a node's name) as the text itself."""
    try:
        return np.array([float(x) for x in text.split()])
    except ValueError:
        return text


def values(series: Series, node: str, field: str) -> np.ndarray:
    return np.array([v for _, v in series[(node, field)]])


def times(series: Series, node: str, field: str) -> np.ndarray:
    return np.array([t for t, _ in series[(node, field)]])


def first(series: Series, node: str, field: str) -> np.ndarray:
    return series[(node, field)][0][1]


def last(series: Series, node: str, field: str) -> np.ndarray:
    return series[(node, field)][-1][1]


def same_rotation(axis_angle: np.ndarray, expected: np.ndarray, tol: float) -> bool:
    q, e = R.from_axis_angle(axis_angle), R.from_axis_angle(expected)
    return min(np.abs(q - e).max(), np.abs(q + e).max()) < tol


def assert_odd_body_reads_back(s: Series) -> None:
    """ODD_SCENE's first record is the scene's own pose and velocities, to rounding."""
    assert np.abs(first(s, "B", "position") - [1, 2, 3]).max() <= 1e-12
    assert same_rotation(first(s, "B", "orientation"), np.array([0.2, 1, 0.3, 0.9]), 1e-12)
    assert np.abs(first(s, "B", "linearVelocity") - [0.5, 0, -1]).max() <= 1e-12
    assert np.abs(first(s, "B", "angularVelocity") - [0, 2, 1]).max() <= 1e-12
