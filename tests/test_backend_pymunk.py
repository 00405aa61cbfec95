"""pymunk backend against closed forms, with tolerances argued from the step.

Chipmunk moves positions with the step's starting velocity, then adds gravity to it
(backends/pymunk.py): x_n = x0 - g dt^2 n(n-1)/2 and v_n = -g n dt, to rounding.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

pytest.importorskip("pymunk")

from backends import base  # noqa: E402
from backends.pymunk import BACKEND  # noqa: E402
from engine_run import DT, G, run_x3d, scene_worlds, shape, times, values  # noqa: E402
from x3d_core.engine import Unsupported  # noqa: E402
from x3d_core.evaluator import RunSettings, run  # noqa: E402


simulate = functools.partial(run_x3d, backend=BACKEND)

FLOOR = shape("<Box size='10 1 2'/>", "Floor", "translation='0 -0.5 0'")  # top face at y = 0


def collection(bodies: str, collidables: str, params: str = "", extra: str = "") -> str:
    return (f"<RigidBodyCollection gravity='0 -9.81 0' {extra}>{bodies}"
            f"<CollisionCollection DEF='C' containerField='collider' {params}>{collidables}</CollisionCollection>"
            "</RigidBodyCollection>")


def body(name: str, geometry: str, position: str, extra: str = "") -> str:
    return (f"<RigidBody DEF='{name}' position='{position}' {extra}>"
            f"{shape(geometry, name + 'S', container='geometry')}</RigidBody>")


def test_free_fall_is_explicit_euler_in_position(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'><RigidBody DEF='B' position='1 2 0'/>"
                 "</RigidBodyCollection>", duration=1.0)
    t = times(s, "B", "position")
    n = np.round(t / DT)
    assert np.allclose(values(s, "B", "position")[:, 1], 2 - G * DT * DT * n * (n - 1) / 2, atol=1e-12)
    assert np.allclose(values(s, "B", "linearVelocity")[:, 1], -G * n * DT, atol=1e-12)
    assert np.all(values(s, "B", "position")[:, [0, 2]] == [1, 0])


def _pendulum(limits: str = "", inertia: str = "0.001 0 0 0 0.001 0 0 0 0.001") -> str:
    return ("<RigidBodyCollection gravity='0 -9.81 0'>"
            f"<RigidBody DEF='Bob' mass='1' position='0 -1 0' linearVelocity='0.3 0 0' inertia='{inertia}'/>"
            f"<SingleAxisHingeJoint DEF='H' axis='0 0 1' {limits} forceOutput='\"angle\"'>"
            "<RigidBody USE='Bob' containerField='body1'/></SingleAxisHingeJoint></RigidBodyCollection>")


def test_pendulum_period(tmp_path):
    """Small swing (0.096 rad): T = 2 pi sqrt(I_p / (m g L)) (1 + a^2/16); the upward zero
    crossings are read to a step each, so 2 dt covers both ends of a period."""
    s = simulate(tmp_path, _pendulum(), duration=5.0, frame_rate=240)
    angle, t = values(s, "H", "angle")[:, 0], times(s, "H", "angle")
    up = t[1:][(angle[:-1] < 0) & (angle[1:] >= 0)]
    amplitude = 0.3 / math.sqrt(G)  # v0 / sqrt(g L)
    expected = 2 * math.pi * math.sqrt(1.001 / G) * (1 + amplitude ** 2 / 16)
    assert np.diff(up) == pytest.approx(expected, abs=2 * DT)


def test_hinge_limit_holds_a_rod(tmp_path):
    """A uniform rod (m L^2 / 12 about its centre, comparable to m r^2 about the pivot, so that
    10 sweeps converge) falls onto minAngle: it may pass the stop by one step's travel
    (w dt, w <= sqrt(3 g / L) ~ 5.4 rad/s: 0.023 rad) before the stop's ERP takes it back."""
    s = simulate(tmp_path, _pendulum("minAngle='-0.6' maxAngle='0.4'", "0.0833 0 0 0 0.0833 0 0 0 0.0833")
                 .replace("position='0 -1 0' linearVelocity='0.3 0 0'", "position='1 0 0'"), duration=3.0)
    angle = values(s, "H", "angle")[:, 0]
    assert angle.min() >= -0.6 - 0.023
    assert angle[-1] == pytest.approx(-0.6, abs=1e-3)


def test_slider_slides_with_gravity_to_its_stop(tmp_path):
    """Axis (1 -1 0)/sqrt 2: the acceleration along it is g/sqrt 2 until maxSeparation 0.5;
    separation exact before the stop (x_n as in free fall, along the axis)."""
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'><RigidBody DEF='Car' position='0 0 0'/>"
                 "<SliderJoint DEF='S' axis='1 -1 0' minSeparation='0' maxSeparation='0.5' "
                 "forceOutput='\"separation\"'><RigidBody USE='Car' containerField='body1'/></SliderJoint>"
                 "</RigidBodyCollection>", duration=1.0)
    sep, t = values(s, "S", "separation")[:, 0], times(s, "S", "separation")
    n = np.round(t / DT)
    free = G / math.sqrt(2) * DT * DT * n * (n - 1) / 2
    early = free < 0.4
    assert np.allclose(sep[early], free[early], atol=1e-9)
    assert sep[-1] == pytest.approx(0.5, abs=1e-6)
    assert np.allclose(values(s, "Car", "orientation")[:, 3], 0)


def test_bounce_apex_is_e_squared_h0(tmp_path):
    """A ball from 1 m (bottom) with bounce 0.5: the rebound is e times the approach speed
    before the contact step's gravity, landing up to one step deep: the apex is e^2 h0 within
    about 2 v dt (v = 4.43 m/s: 0.037 m)."""
    ball = body("Ball", "<Sphere radius='0.1'/>", "0 1.1 0", "inertia='0.004 0 0 0 0.004 0 0 0 0.004'")
    s = simulate(tmp_path, collection(ball, "<CollidableShape USE='BallS'/>" + FLOOR,
                                      "bounce='0.5' appliedParameters='\"BOUNCE\"'"), duration=1.5, frame_rate=240)
    y = values(s, "Ball", "position")[:, 1] - 0.1
    t = times(s, "Ball", "position")
    after = t > math.sqrt(2 / G) + 0.05
    assert y[after].max() == pytest.approx(0.25, abs=0.037)


@pytest.mark.parametrize("degrees,mu,sticks", [(20, 0.5, True), (40, 0.5, False)])
def test_incline_sticks_or_slides(tmp_path, degrees, mu, sticks):
    """A box on a plank tilted about z: it sticks where tan <= mu, else slides at
    g (sin - mu cos) (speed exact to the step's quantisation of the start: g dt)."""
    a = math.radians(degrees)
    n = np.array([-math.sin(a), math.cos(a)])
    centre = 0.1 * n  # the box's centre, half its height above the plank's top through the origin
    plank = shape("<Box size='6 0.2 2'/>", "Plank", f"translation='{-0.1 * n[0]} {-0.1 * n[1]} 0' "
                  f"rotation='0 0 1 {a}'")
    box = body("Box", "<Box size='0.2 0.2 0.2'/>", f"{centre[0]} {centre[1]} 0",
               f"orientation='0 0 1 {a}' inertia='0.0067 0 0 0 0.0067 0 0 0 0.0067'")
    s = simulate(tmp_path, collection(box, "<CollidableShape USE='BoxS'/>" + plank,
                                      f"frictionCoefficients='{mu} {mu}'"), duration=1.0)
    speed = np.linalg.norm(values(s, "Box", "linearVelocity")[-1])
    expected = 0.0 if sticks else G * (math.sin(a) - mu * math.cos(a)) * 1.0
    assert speed == pytest.approx(expected, abs=2 * G * DT)


def test_conveyor_drives_along_odes_first_friction_direction(tmp_path):
    """surfaceSpeed 1.5 under an upward normal drives the box along -x (x3d_core.collision)."""
    box = body("Box", "<Box size='0.4 0.2 0.4'/>", "0 0.1 0", "inertia='0.0167 0 0 0 0.0267 0 0 0 0.0167'")
    s = simulate(tmp_path, collection(box, "<CollidableShape USE='BoxS'/>" + FLOOR,
                                      "frictionCoefficients='0.5 0.5' surfaceSpeed='1.5 0' "
                                      "appliedParameters='\"SPEED-1\"'"), duration=1.0)
    assert values(s, "Box", "linearVelocity")[-1] == pytest.approx([-1.5, 0, 0], abs=1e-9)


def test_sensor_contact_normal_and_depth(tmp_path):
    """A ball dropped 0.1 m lands deeper than the slop (v dt = 5.8 mm) and is pushed back to it:
    one contact, normal from geometry1 to geometry2 along y, at the floor's top under the
    ball, depth the collision slop (contactSurfaceThickness) to rounding."""
    ball = body("Ball", "<Sphere radius='0.1'/>", "0.5 0.2 0", "inertia='0.004 0 0 0 0.004 0 0 0 0.004'")
    s = simulate(tmp_path, collection(ball, "<CollidableShape USE='BallS'/>" + FLOOR,
                                      extra="contactSurfaceThickness='0.001'")
                 + "<CollisionSensor DEF='Sensor'><CollisionCollection USE='C' containerField='collider'/>"
                   "</CollisionSensor>", duration=1.0)
    first = s[("Sensor", "contacts[0].geometry1")][-1][1]
    normal = s[("Sensor", "contacts[0].contactNormal")][-1][1]
    assert normal == pytest.approx([0, -1, 0] if first == "BallS" else [0, 1, 0], abs=1e-12)
    assert s[("Sensor", "contacts[0].depth")][-1][1][0] == pytest.approx(0.001, abs=1e-9)
    assert s[("Sensor", "contacts[0].position")][-1][1] == pytest.approx([0.5, 0, 0], abs=1e-3)
    assert ("Sensor", "contacts[1].depth") not in s


def test_same_run_twice_gives_the_same_trace(tmp_path):
    balls = "".join(body(f"B{k}", "<Sphere radius='0.1'/>", f"{0.15 * k} {0.3 + 0.25 * k} 0",
                         "inertia='0.004 0 0 0 0.004 0 0 0 0.004'") for k in range(4))
    shapes = "".join(f"<CollidableShape USE='B{k}S'/>" for k in range(4)) + FLOOR
    scene = collection(balls, shapes, "bounce='0.3' appliedParameters='\"BOUNCE\"'")
    traces = [run(scene_worlds(tmp_path, scene), BACKEND, RunSettings(1.0, DT, 60)).text() for _ in range(2)]
    assert traces[0] == traces[1]


@pytest.mark.parametrize("extra,names", [("linearVelocity='0 0 1'", "RigidBody B linearVelocity"),
                                         ("angularVelocity='1 0 0'", "RigidBody B angularVelocity")])
def test_non_planar_world_is_refused_by_name(tmp_path, extra, names):
    w = scene_worlds(tmp_path, f"<RigidBodyCollection><RigidBody DEF='B' {extra}/></RigidBodyCollection>")[0]
    with pytest.raises(Unsupported, match=f"not planar: {names}"):
        BACKEND.build(w, DT)


def test_declarations():
    d = BACKEND.support
    assert d("DoubleAxisHingeJoint").support is base.Support.UNSUPPORTED
    assert d("SingleAxisHingeJoint.stopBounce").support is base.Support.UNSUPPORTED
    assert d("CollisionCollection.appliedParameters.SPEED-1").support is base.Support.NATIVE
    assert d("CollisionCollection.minBounceSpeed").support is base.Support.APPROXIMATE
