"""Collisions in the ODE backend against closed forms. ODE finds a step's contacts at its
start and solves them with the step, so an impact is seen up to one step late: a body lands
up to v*dt deep and rebounds with e times its approach speed, which holds up to one step's
gravity g*dt more than the closed form's; contact parameters are ODE's own (the backend
passes appliedParameters as ODE's contact mode bits). The bounce cases run constantForceMix 0:
with X3D's default 1e-4 ODE's contact is a stiff spring-damper that takes 13% off a 1 kg
ball's first apex (measured), which the rigid closed form does not have."""

from __future__ import annotations

import math

import numpy as np
import pytest

try:
    from backends.ode import BACKEND
except ImportError as e:
    pytest.skip(f"ODE is not installed: {e}", allow_module_level=True)

from engine_run import DT, G, last, run_x3d, scene_worlds, values  # noqa: E402
from x3d_core.evaluator import RunSettings, run  # noqa: E402


def simulate(tmp_path, body: str, *args, **kwargs):
    return run_x3d(tmp_path, body, *args, **{"backend": BACKEND, **kwargs})


def shape(geometry: str, name: str = "", extra: str = "", container: str = "") -> str:
    d = f" DEF='{name}'" if name else ""
    c = f" containerField='{container}'" if container else ""
    return f"<CollidableShape{d}{c} {extra}><Shape containerField='shape'>{geometry}</Shape></CollidableShape>"


RIGID = "constantForceMix='0'"
CFM = 1e-4  # X3D's default constantForceMix
FLOOR = shape("<Box size='10 1 10'/>", "Floor", "translation='0 -0.5 0'")  # top face at y = 0


def collection(bodies: str, collidables: str, params: str = "", world: str = "") -> str:
    return (f"<RigidBodyCollection gravity='0 -9.81 0' {world}>{bodies}"
            f"<CollisionCollection containerField='collider' {params}>{collidables}</CollisionCollection>"
            "</RigidBodyCollection>")


def ball(name: str, y: float, r: float, x: float = 0, z: float = 0) -> str:
    return (f"<RigidBody DEF='{name}' position='{x} {y} {z}' inertia='0.004 0 0 0 0.004 0 0 0 0.004'>"
            f"{shape(f'<Sphere radius={chr(39)}{r}{chr(39)}/>', name + 'S', container='geometry')}</RigidBody>")


def crate(name: str, y: float, v: str = "0 0 0") -> str:
    return (f"<RigidBody DEF='{name}' position='0 {y} 0' linearVelocity='{v}' "
            "inertia='0.0166667 0 0 0 0.0266667 0 0 0 0.0166667'>"
            f"{shape('<Box size=' + chr(39) + '0.4 0.2 0.4' + chr(39) + '/>', name + 'S', container='geometry')}"
            "</RigidBody>")


def apexes(y: np.ndarray) -> np.ndarray:
    k = np.flatnonzero((y[1:-1] > y[:-2]) & (y[1:-1] >= y[2:])) + 1
    return y[k]


@pytest.mark.parametrize("e", [0.5, 0.8])
def test_bounce_apex(tmp_path, e):
    h0, r = 1.0, 0.1
    s = simulate(tmp_path, collection(ball("B", h0 + r, r), FLOOR + "<CollidableShape USE='BS'/>",
                                      f"bounce='{e}' minBounceSpeed='0.1'", RIGID), duration=2.5, frame_rate=240)
    apex = apexes(values(s, "B", "position")[:, 1] - r)[0]
    v = math.sqrt(2 * G * h0)
    # rebound speed e (v + g dt) at most, from up to v dt below the surface
    assert abs(apex - e * e * h0) <= e * e * h0 * (2 * G * DT / v) + v * DT


def test_bounce_threshold(tmp_path):
    # a 5 cm drop lands at 0.99 m/s: above minBounceSpeed 1.5 nothing bounces, below 0.5 it does
    r, h0 = 0.1, 0.05
    bodies = ball("Slow", h0 + r, r, x=-1) + ball("Fast", h0 + r, r, x=1)
    for threshold, bounces in ((1.5, False), (0.5, True)):
        s = simulate(tmp_path, collection(bodies, FLOOR + "<CollidableShape USE='SlowS'/><CollidableShape USE='FastS'/>",
                                          f"bounce='0.8' minBounceSpeed='{threshold}'", RIGID), duration=0.6,
                     frame_rate=240)
        y = values(s, "Slow", "position")[:, 1] - r
        landed = int(np.argmax(y <= 0))
        rise = y[landed:].max()
        v = math.sqrt(2 * G * h0)
        if bounces:  # e^2 h0 = 0.032 m, as in test_bounce_apex
            assert abs(rise - 0.64 * h0) <= 0.64 * h0 * 2 * G * DT / v + v * DT
        else:  # no rebound: at most ERP's push out of one step's depth
            assert rise <= v * DT


def test_anisotropic_friction_and_conveyor(tmp_path):
    # for the upward normal ODE's first friction direction is -x, its second +z (either way
    # the pair is ordered, the directions are +-x and z): mu1 0.2 along x, mu2 0.6 along z
    s = simulate(tmp_path, collection(crate("X", 0.1, "-2 0 0") + crate("Z", 0.1, "0 0 2").replace(
        "position='0 0.1 0'", "position='0 0.1 3'"),
        FLOOR + "<CollidableShape USE='XS'/><CollidableShape USE='ZS'/>",
        "frictionCoefficients='0.2 0.6' appliedParameters='\"FRICTION_COEFFICIENT-2\"'"), duration=0.3)
    # sliding friction decelerates at mu g; the step's Euler velocity is exact for constant force
    t = 0.3
    assert last(s, "X", "linearVelocity")[0] == pytest.approx(-2 + 0.2 * G * t, abs=2 * 0.2 * G * DT)
    assert last(s, "Z", "linearVelocity")[2] == pytest.approx(2 - 0.6 * G * t, abs=2 * 0.6 * G * DT)
    belt = simulate(tmp_path, collection(crate("P", 0.1), FLOOR + "<CollidableShape USE='PS'/>",
                                         "frictionCoefficients='0.5 0.5' surfaceSpeed='1.5 0' "
                                         "appliedParameters='\"SPEED-1\"'"), duration=1.0)
    # on the belt at its speed: ODE's soft rows (CFM) miss their velocity targets by up to CFM times
    # their force, here the 1 kg crate's weight: CFM m g
    assert last(belt, "P", "linearVelocity") == pytest.approx([-1.5, 0, 0], abs=CFM * G)


def test_surface_layer_keeps_a_resting_depth(tmp_path):
    # contactSurfaceThickness 0.01: ODE corrects only depth beyond the layer, so a box put 5 mm
    # into the floor is not pushed out; its four contacts' CFM lets it creep down at CFM m g / 4
    # (each row misses its zero speed by CFM times its share of the weight), within g dt^2
    s = simulate(tmp_path, collection(crate("C", 0.095), FLOOR + "<CollidableShape USE='CS'/>",
                                      world="contactSurfaceThickness='0.01'"), duration=1.0)
    assert last(s, "C", "position")[1] == pytest.approx(0.095 - CFM * G / 4 * 1.0, abs=G * DT * DT)


def test_sensor_contacts_of_a_sphere_on_a_box(tmp_path):
    r = 0.1
    s = simulate(tmp_path, collection(ball("B", r, r, x=0.3, z=-0.2), FLOOR + "<CollidableShape USE='BS'/>")
                 .replace("<CollisionCollection ", "<CollisionCollection DEF='C' ") +
                 "<CollisionSensor DEF='Sensor'><CollisionCollection USE='C' containerField='collider'/>"
                 "</CollisionSensor>", duration=0.5)
    assert last(s, "Sensor", "contacts[0].geometry1") == "Floor"
    assert last(s, "Sensor", "contacts[0].geometry2") == "BS"
    assert last(s, "Sensor", "contacts[0].contactNormal") == pytest.approx([0, 1, 0], abs=1e-12)  # floor to ball
    # resting: at most a step's fall under gravity deep (ERP takes the rest out each step)
    assert 0 <= last(s, "Sensor", "contacts[0].depth")[0] <= G * DT * DT
    assert last(s, "Sensor", "contacts[0].position") == pytest.approx([0.3, 0, -0.2], abs=G * DT * DT)
    assert ("Sensor", "contacts[1].position") not in s  # one point for a sphere on a face


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
