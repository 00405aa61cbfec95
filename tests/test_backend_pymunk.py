"""What only the pymunk backend does: its planar checks (a world that leaves the plane is refused
by name), a stop where Chipmunk's 10 iterations converge (hinge_limits' light arm on a long pivot
is a measured fail), the CollisionSensor contact it reports (sensor_geometry is refused as not
planar) with contactSurfaceThickness as its collision slop, determinism, and its declarations.
The shared physics (free fall, pendulum, slider stops, bounce, incline, conveyor) is in the
conformance cases (conformance/cases/)."""

from __future__ import annotations

import functools

import pytest

pytest.importorskip("pymunk")

from backends import base  # noqa: E402
from backends.pymunk import BACKEND  # noqa: E402
from engine_run import DT, run_x3d, scene_worlds, shape, values  # noqa: E402
from x3d_core.semantics.engine import Unsupported  # noqa: E402
from x3d_core.semantics.evaluator import RunSettings, run  # noqa: E402


simulate = functools.partial(run_x3d, backend=BACKEND)

FLOOR = shape("<Box size='10 1 2'/>", "Floor", "translation='0 -0.5 0'")  # top face at y = 0


def collection(bodies: str, collidables: str, params: str = "", extra: str = "") -> str:
    return (f"<RigidBodyCollection gravity='0 -9.81 0' {extra}>{bodies}"
            f"<CollisionCollection DEF='C' containerField='collider' {params}>{collidables}</CollisionCollection>"
            "</RigidBodyCollection>")


def body(name: str, geometry: str, position: str, extra: str = "") -> str:
    return (f"<RigidBody DEF='{name}' position='{position}' {extra}>"
            f"{shape(geometry, name + 'S', container='geometry')}</RigidBody>")


def test_hinge_limit_holds_a_rod(tmp_path):
    """A uniform rod (m L^2 / 12 about its centre, comparable to m r^2 about the pivot, so that
    10 sweeps converge) falls onto minAngle: it may pass the stop by one step's travel
    (w dt, w <= sqrt(3 g / L) ~ 5.4 rad/s: 0.023 rad) before the stop's ERP takes it back."""
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'>"
                 "<RigidBody DEF='Rod' mass='1' position='1 0 0' inertia='0.0833 0 0 0 0.0833 0 0 0 0.0833'/>"
                 "<SingleAxisHingeJoint DEF='H' axis='0 0 1' minAngle='-0.6' maxAngle='0.4' forceOutput='\"angle\"'>"
                 "<RigidBody USE='Rod' containerField='body1'/></SingleAxisHingeJoint></RigidBodyCollection>",
                 duration=3.0)
    angle = values(s, "H", "angle")[:, 0]
    assert angle.min() >= -0.6 - 0.023
    assert angle[-1] == pytest.approx(-0.6, abs=1e-3)


def test_an_unstopped_slider_slides_on_at_any_speed(tmp_path):
    """minSeparation > maxSeparation: no stops (37.4.13). Chipmunk's groove has ends; the groove
    that follows body1 (backends/pymunk.py, _Track) never lets it reach one, even at 5 km/s
    (20.8 m a step, past the groove's 1 m reach at rest), and holds it on the line."""
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='Rail' fixed='true'/>"
                 "<RigidBody DEF='Block' linearVelocity='3000 -4000 0' inertia='0.01 0 0 0 0.01 0 0 0 0.01'/>"
                 "<SliderJoint axis='0.6 -0.8 0' minSeparation='0.3' maxSeparation='0'>"
                 "<RigidBody USE='Block' containerField='body1'/><RigidBody USE='Rail' containerField='body2'/>"
                 "</SliderJoint></RigidBodyCollection>")
    assert values(s, "Block", "position")[-1] == pytest.approx([3000, -4000, 0], abs=1e-9)
    assert values(s, "Block", "linearVelocity")[-1] == pytest.approx([3000, -4000, 0], abs=1e-9)


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
