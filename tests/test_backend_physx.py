"""What only the PhysX backend (SAPIEN 3) does: single-precision state read back at the body
origin, joints as point-constraint D6s (a hinge pendulum's period, its stops either way round,
a universal joint's axes, a slider holding a body 10 m away), motors as impulse-bounded
velocity drives, contacts with their normal turned to x3drbp's direction, joined bodies kept
apart, and its refusals. The shared physics is in the conformance cases
(conformance/expectations/physx.toml pins them)."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip("sapien")

from backends.physx import BACKEND  # noqa: E402
from conformance.cases.closed_forms import ellipk  # noqa: E402
from engine_run import (DT, G, TURNED_BODY, TURNED_ORIENTATION, last, pendulum, run_x3d, scene_worlds,  # noqa: E402
                        shape, values)
from x3d_core.semantics import rotation as R  # noqa: E402
from x3d_core.semantics.engine import Unsupported  # noqa: E402

F32 = 3e-5  # PhysX holds state in float32: 240 steps of rounding (measured 1.3e-5 m/s in free fall)


def simulate(tmp_path, body: str, *args, **kwargs):
    return run_x3d(tmp_path, body, *args, **{"backend": BACKEND, **kwargs})


def test_free_fall_is_semi_implicit_euler_in_single_precision(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'><RigidBody DEF='B' position='1 10 -2' "
                           "linearVelocity='0.5 0 0'/></RigidBodyCollection>")
    n = round(1.0 / DT)
    # v_k = -g k dt, y_n = y0 - g dt^2 n (n + 1) / 2: the closed form of the step, to float32
    assert last(s, "B", "position") == pytest.approx([1.5, 10 - G * DT * DT * n * (n + 1) / 2, -2], abs=F32)
    assert last(s, "B", "linearVelocity") == pytest.approx([0.5, -G, 0], abs=F32)


def test_centre_of_mass_and_full_inertia_come_back_at_the_body_origin(tmp_path):
    # a turned body, its centre of mass off the origin, a full inertia tensor (diagonalised for
    # PhysX, its principal frame turned against the body's): it falls without turning
    s = simulate(tmp_path, TURNED_BODY)
    assert s[("B", "position")][0][1] == pytest.approx([1, 2, 3], abs=1e-6)
    q0 = R.from_axis_angle(TURNED_ORIENTATION)
    turn = R.multiply(R.conjugate(q0), R.from_axis_angle(values(s, "B", "orientation")))
    assert np.abs(turn[:, 1:]).max() < 1e-6
    n = round(1.0 / DT)
    assert last(s, "B", "position") == pytest.approx([1, 2 - G * DT * DT * n * (n + 1) / 2, 3], abs=F32)


def test_torque_free_spin_keeps_angular_momentum_with_a_full_tensor(tmp_path):
    inertia = np.array([[0.2, 0.03, 0.01], [0.03, 0.15, -0.02], [0.01, -0.02, 0.1]])
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='B' angularVelocity='1 2 0.5' "
                           "inertia='" + " ".join(map(str, inertia.ravel())) + "'/></RigidBodyCollection>")
    q = R.from_axis_angle(values(s, "B", "orientation"))
    w = values(s, "B", "angularVelocity")
    m = R.matrix(q)
    momentum = np.einsum("nij,jk,nlk,nl->ni", m, inertia, m, w)
    assert np.abs(momentum - momentum[0]).max() < 0.01 * np.linalg.norm(momentum[0])


def test_state_read_at_once_is_each_body_s_own(tmp_path):
    """The packed state (PhysxCpuSystem.pack) read with the layout found at build is, body by body,
    what each body's own accessors say: poses and velocities apart and in order, a fixed body and
    the world's anchor among them."""
    w = scene_worlds(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'>"
                               "<RigidBody DEF='Fixed' fixed='true' position='0 3 0'/>"
                               "<RigidBody DEF='A' position='1 2 3' linearVelocity='0.5 -1 2' "
                               "angularVelocity='3 -4 5'/>"
                               "<RigidBody DEF='B' position='0 2 0' orientation='0 0 1 0.4' linearVelocity='-2 0 1'/>"
                               "<BallJoint anchorPoint='0 2.5 0'><RigidBody USE='B' containerField='body1'/>"
                               "</BallJoint></RigidBodyCollection>")[0]
    sim = BACKEND.build(w, DT)
    assert sim.packed is not None
    for _ in range(3):
        sim.step(5)
        each = sim._each()
        assert np.array_equal(sim._read(), each) and len(np.unique(each[:, 7:], axis=0)) == 2
        s = sim.state()
        assert np.array_equal(s.linear_velocity[1:], each[:, 7:10]) and np.array_equal(s.position[1:], each[:, 4:7])


def test_no_moving_body_reads_the_start(tmp_path):
    """A world of fixed bodies alone has nothing packed to read: its state is the start, every call."""
    w = scene_worlds(tmp_path, "<RigidBodyCollection><RigidBody DEF='Fixed' fixed='true' position='0 3 0' "
                               "linearVelocity='1 0 0'/></RigidBodyCollection>")[0]
    sim = BACKEND.build(w, DT)
    sim.step(2)
    s = sim.state()
    assert s.position.tolist() == [[0, 3, 0]] and s.linear_velocity.tolist() == [[0, 0, 0]]
    assert s.orientation.tolist() == [[1, 0, 0, 0]]


def test_gravity_off_and_forces_in_the_world_frame(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'>"
                           "<RigidBody DEF='F' mass='2' useGlobalGravity='false' centerOfMass='0.2 0 0' "
                           "orientation='0 0 1 1' forces='1 0 0, 3 0 0'/></RigidBodyCollection>")
    assert last(s, "F", "linearVelocity") == pytest.approx([2.0, 0, 0], abs=F32)
    assert last(s, "F", "angularVelocity") == pytest.approx([0, 0, 0], abs=F32)




def test_hinge_pendulum_period_and_length(tmp_path):
    theta0 = 0.5
    s = simulate(tmp_path, pendulum(theta0), duration=4.5, frame_rate=240)
    p = values(s, "Bob", "position")
    assert np.abs(np.linalg.norm(p, axis=1) - 1).max() < 1e-4  # the two point constraints hold the arm
    assert np.abs(p[:, 2]).max() < 1e-4  # and the plane
    t = np.array([time for time, _ in s[("Bob", "position")]])
    x = p[:, 0]
    k = np.flatnonzero(np.signbit(x[:-1]) != np.signbit(x[1:]))
    crossings = t[k] - x[k] * (t[k + 1] - t[k]) / (x[k + 1] - x[k])
    period = 2 * np.diff(crossings).mean()
    # T = 4 sqrt(I_p / (m g L)) K(sin(theta0/2)), I_p = m L^2 + 1e-6
    expected = 4 * math.sqrt((1 + 1e-6) / G) * ellipk(math.sin(theta0 / 2))
    assert period == pytest.approx(expected, rel=2e-3)


@pytest.mark.parametrize("bob_is_body1", [False, True])
def test_hinge_limits_hold_whichever_body_is_the_child(tmp_path, bob_is_body1):
    # released at 0.8 rad, the bob swings through the stop at 0.3: body1 relative to body2 the angle
    # falls (bob is body1) or rises (bob is body2) to the stop and stays there
    s = simulate(tmp_path, pendulum(0.8, "minAngle='-0.5' maxAngle='0.5'", bob_is_body1), duration=2.0)
    angle = values(s, "H", "angle")[:, 0]
    assert angle.max() < 0.5 + 1e-3 and angle.min() > -0.5 - 1e-3
    assert angle[-1] == pytest.approx(-0.5 if bob_is_body1 else 0.5, abs=1e-3)


def test_slider_keeps_its_axis_and_stops(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'><RigidBody DEF='Block' "
                           "inertia='0.01 0 0 0 0.01 0 0 0 0.01'/><SliderJoint DEF='S' axis='0.6 -0.8 0' "
                           "minSeparation='0' maxSeparation='0.3' forceOutput='\"separation\"'>"
                           "<RigidBody USE='Block' containerField='body1'/></SliderJoint></RigidBodyCollection>",
                 duration=1.0)
    p = values(s, "Block", "position")
    off_axis = p - np.outer(p @ np.array([0.6, -0.8, 0]), [0.6, -0.8, 0])
    assert np.abs(off_axis).max() < 1e-4
    assert values(s, "S", "separation")[-1, 0] == pytest.approx(0.3, abs=1e-3)
    turn = R.from_axis_angle(values(s, "Block", "orientation"))
    assert np.abs(turn[:, 1:]).max() < 1e-4  # a slider turns nothing


STEP_GAIN = G * DT * DT  # 1.7e-4 m: one step's travel from rest under g, what a constraint met each step leaves


@pytest.mark.parametrize("gravity", ["-9.81 0 0", "0 -9.81 0"], ids=["pull_along", "pull_across"])
@pytest.mark.parametrize("offset", ["10 0 0", "0 10 0"], ids=["10m_along", "10m_across"])
@pytest.mark.parametrize("base", ["fixed='true'",
                                  "mass='1e6' inertia='1e4 0 0 0 1e4 0 0 0 1e4' useGlobalGravity='false'"],
                         ids=["fixed", "heavy"])
def test_slider_holds_a_body_started_far_from_the_origin(tmp_path, base, offset, gravity):
    # a slider has no anchor (x3d_core's is the world origin): a 1 kg Car (body2) 10 m from the Base
    # (body1, fixed, or free and heavy: its turn under the Car's pull, m g r t / I = 0.02 rad/s after
    # 2 s, adds omega^2 r < 0.01 m/s^2 to g) slides along x between stops [0, 1] of separation (body1
    # relative to body2, from the start): pulled along -x it rises to the max stop, pulled across it
    # stays at 0; in the Base's frame the Car never leaves its line. The old anchor at the origin
    # swung it 10 m round it (pulled across) or 1.1 m off, to a separation of 4.6 (pulled along).
    s = simulate(tmp_path, f"<RigidBodyCollection gravity='{gravity}'><RigidBody DEF='Base' {base}/>"
                           f"<RigidBody DEF='Car' position='{offset}' inertia='0.01 0 0 0 0.01 0 0 0 0.01'/>"
                           "<SliderJoint DEF='S' axis='1 0 0' minSeparation='0' maxSeparation='1' "
                           "forceOutput='\"separation\"'><RigidBody USE='Base' containerField='body1'/>"
                           "<RigidBody USE='Car' containerField='body2'/></SliderJoint></RigidBodyCollection>",
                 duration=2.0)
    q = R.from_axis_angle(values(s, "Base", "orientation"))
    rel = R.rotate(R.conjugate(q), values(s, "Car", "position") - values(s, "Base", "position"))
    assert np.abs(rel[:, 1:] - rel[0, 1:]).max() < STEP_GAIN
    separation = values(s, "S", "separation")[:, 0]
    assert separation.min() > -STEP_GAIN and separation.max() < 1 + STEP_GAIN
    assert separation[-1] == pytest.approx(1.0 if gravity.startswith("-") else 0.0, abs=STEP_GAIN)


def test_hinge2_motor_is_torque_bounded_and_body1_relative(tmp_path):
    # desiredAngularVelocity2 4 rad/s, maxTorque2 0.2 on a wheel of I 0.05 hinged to a fixed base:
    # the rate ramps at 4 rad/s^2 (torque-bounded: SAPIEN's drive limits are impulses, given
    # maxTorque dt) to hinge2AngleRate = axis2 . (w1 - w2) = 4, body1 the fixed base
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='Base' fixed='true'/>"
                           "<RigidBody DEF='Wheel' inertia='0.05 0 0 0 0.05 0 0 0 0.05'/>"
                           "<DoubleAxisHingeJoint DEF='J' axis1='0 1 0' axis2='1 0 0' desiredAngularVelocity2='4' "
                           "maxTorque2='0.2' forceOutput='\"hinge2AngleRate\"'>"
                           "<RigidBody USE='Base' containerField='body1'/><RigidBody USE='Wheel' containerField='body2'/>"
                           "</DoubleAxisHingeJoint></RigidBodyCollection>", duration=2.0)
    t = np.array([time for time, _ in s[("J", "hinge2AngleRate")]])
    rate = values(s, "J", "hinge2AngleRate")[:, 0]
    ramp = t < 0.95
    assert rate[ramp] == pytest.approx(4 * t[ramp], abs=0.02)
    assert rate[-1] == pytest.approx(4, abs=1e-3)
    assert last(s, "Wheel", "angularVelocity") == pytest.approx([-4, 0, 0], abs=1e-3)


FLOOR = shape("<Box size='10 1 10'/>", "Floor", "translation='0 -0.5 0'")  # top face at y = 0


def collection(bodies: str, collidables: str, params: str = "") -> str:
    return (f"<RigidBodyCollection gravity='0 -9.81 0'>{bodies}"
            f"<CollisionCollection DEF='C' containerField='collider' {params}>{collidables}</CollisionCollection>"
            "</RigidBodyCollection>")


def ball(name: str, y: float, r: float) -> str:
    return (f"<RigidBody DEF='{name}' position='0 {y} 0' inertia='0.004 0 0 0 0.004 0 0 0 0.004'>"
            f"{shape(f'<Sphere radius={chr(39)}{r}{chr(39)}/>', name + 'S', container='geometry')}</RigidBody>")


def test_ball_rests_on_a_box_and_reports_its_contact(tmp_path):
    body = collection(ball("B", 0.5, 0.1), FLOOR + "<CollidableShape USE='BS'/>", "frictionCoefficients='0.5 0.5'")
    s = simulate(tmp_path, body, duration=1.5)
    assert last(s, "B", "position") == pytest.approx([0, 0.1, 0], abs=1e-4)
    assert np.linalg.norm(last(s, "B", "linearVelocity")) < 1e-3
    sim = BACKEND.build(scene_worlds(tmp_path, body.replace("position='0 0.5 0'", "position='0 0.0999 0'"))[0], DT)
    sim.step()
    c = sim.contacts()
    assert len(c.depth) >= 1
    floor, ball_geometry = 0, 1  # the collider's order
    for k in range(len(c.depth)):
        # x3drbp's normal points from geometry1 towards geometry2
        towards = np.array([0, 1, 0]) if (c.geometry1[k], c.geometry2[k]) == (floor, ball_geometry) else -np.array([0, 1, 0])
        assert c.normal[k] == pytest.approx(towards, abs=1e-5)
        assert c.position[k][[0, 2]] == pytest.approx([0, 0], abs=1e-5)
        assert 0 <= c.depth[k] < 1e-3


def test_bounce_follows_restitution_and_threshold(tmp_path):
    # dropped 1 m onto the floor with bounce 0.5: the first apex e^2 h = 0.25 m above contact;
    # with minBounceSpeed above the impact speed (4.4 m/s) it does not bounce at all
    def apex(params: str) -> float:
        s = simulate(tmp_path, collection(ball("B", 1.1, 0.1), FLOOR + "<CollidableShape USE='BS'/>", params),
                     duration=1.5, frame_rate=240)
        t = np.array([time for time, _ in s[("B", "position")]])
        y = values(s, "B", "position")[:, 1]
        return float(y[t > 0.5].max() - 0.1)
    assert apex("appliedParameters='\"BOUNCE\"' bounce='0.5' minBounceSpeed='0.1'") == pytest.approx(0.25, rel=0.1)
    assert apex("appliedParameters='\"BOUNCE\"' bounce='0.5' minBounceSpeed='10'") < 1e-3


def test_joined_bodies_never_collide_other_bodies_do(tmp_path):
    # two overlapping boxes in zero gravity: joined by a MotorJoint (no PhysX constraint: the
    # collision groups keep them apart) they stay put; unjoined, the overlap pushes them apart
    boxes = ("<RigidBody DEF='A' inertia='0.01 0 0 0 0.01 0 0 0 0.01'>"
             + shape("<Box size='0.4 0.4 0.4'/>", "AS", container="geometry") + "</RigidBody>"
             "<RigidBody DEF='B' position='0.2 0 0' inertia='0.01 0 0 0 0.01 0 0 0 0.01'>"
             + shape("<Box size='0.4 0.4 0.4'/>", "BS", container="geometry") + "</RigidBody>")
    joint = ("<MotorJoint><RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/>"
             "</MotorJoint>")
    free = collection(boxes, "<CollidableShape USE='AS'/><CollidableShape USE='BS'/>").replace("0 -9.81 0", "0 0 0")
    joined = free.replace("</RigidBodyCollection>", joint + "</RigidBodyCollection>")
    assert np.abs(last(simulate(tmp_path, joined, duration=0.5), "B", "position") - [0.2, 0, 0]).max() < 1e-6
    assert last(simulate(tmp_path, free, duration=0.5), "B", "position")[0] > 0.3


def test_what_physx_cannot_take_is_refused(tmp_path):
    zero = scene_worlds(tmp_path, "<RigidBodyCollection><RigidBody mass='1e-40'/></RigidBodyCollection>")[0]
    with pytest.raises(Unsupported, match="positive mass"):  # under float32's smallest normal: 0 to PhysX
        BACKEND.build(zero, DT)
    huge = scene_worlds(tmp_path, "<RigidBodyCollection><RigidBody position='1e39 0 0'/></RigidBodyCollection>")[0]
    with pytest.raises(Unsupported, match="single precision"):
        BACKEND.build(huge, DT)


def test_a_missing_sapien_leaves_the_other_backends_usable():
    code = ("import sys; sys.modules['sapien'] = None\n"
            "from backends import base\n"
            "try:\n    base.load('physx')\nexcept ImportError as e:\n    assert 'sapien' in str(e), e\n"
            "else:\n    raise AssertionError('physx loaded without sapien')\n"
            "assert 'physx' in base.engines() and base.load('pymunk').name == 'pymunk'\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr


def test_heightfield_and_mesh_lie_as_x3d_places_them(tmp_path):
    # a 3 x 3 grid, 1 m spacing, rising 0.2 per row along z (a static triangle mesh here): a ball
    # placed touching it at (1, z) meets it along the normal (0, 1, -0.2); the same grid as an
    # IndexedFaceSet does the same
    grid = ("<ElevationGrid xDimension='3' zDimension='3' xSpacing='1' zSpacing='1' "
            "height='0 0 0 0.2 0.2 0.2 0.4 0.4 0.4'/>")
    faces = ("<IndexedFaceSet coordIndex='0 3 4 1 -1 1 4 5 2 -1 3 6 7 4 -1 4 7 8 5 -1'><Coordinate point='"
             "0 0 0 1 0 0 2 0 0 0 0.2 1 1 0.2 1 2 0.2 1 0 0.4 2 1 0.4 2 2 0.4 2'/></IndexedFaceSet>")
    r = 0.1
    n = np.array([0, 1, -0.2]) / math.hypot(1, 0.2)
    centre = np.array([1, 0.2, 1]) + (r - 1e-4) * n
    for ground in (grid, faces):
        body = collection(ball("B", centre[1], r).replace("position='0 ", f"position='{centre[0]} ").replace(
            f"{centre[1]} 0'", f"{centre[1]} {centre[2]}'"), shape(ground, "Ground") + "<CollidableShape USE='BS'/>")
        sim = BACKEND.build(scene_worlds(tmp_path, body)[0], DT)
        sim.step()
        c = sim.contacts()
        assert len(c.depth) >= 1
        ground_first = c.geometry1[0] == 0  # the collider's order: Ground, then the ball
        assert c.normal[0] == pytest.approx(n if ground_first else -n, abs=1e-5)  # from geometry1 towards geometry2
