"""What only the Drake backend does: its two modes (a continuous plant under an error-controlled
integrator where nothing collides and no stop acts; a discrete SAP plant otherwise), checked
against closed forms; a ball resting on a box through its hydroelastic contact; its refusals.
The shared physics is in the conformance cases (conformance/cases/)."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("pydrake")

from backends import base  # noqa: E402
from backends.drake import ACCURACY, ACCURATE, BACKEND  # noqa: E402
from engine_run import DT, G, ODD_SCENE, assert_odd_body_reads_back, run_x3d, scene_worlds  # noqa: E402
from x3d_core.semantics.engine import Unsupported, target_accuracy  # noqa: E402


def test_registered_under_its_name_after_the_others():
    assert base.load("drake") is BACKEND
    assert BACKEND.version().startswith("1.")
    assert base.IN_TREE.index("drake") > base.IN_TREE.index("pymunk")  # after the engines x3drbp began with


def test_centre_of_mass_offset_and_orientation_read_back_as_given(tmp_path):
    assert_odd_body_reads_back(run_x3d(tmp_path, ODD_SCENE, duration=0.1, backend=BACKEND))


def _free(extra: str = "") -> str:
    return (f"<RigidBodyCollection gravity='0 -{G} 0'>{extra}<RigidBody DEF='B' position='1 2 3' "
            "linearVelocity='3 4 1' angularVelocity='0 0 0'>"
            "<CollidableShape DEF='S' containerField='geometry'><Shape containerField='shape'><Sphere radius='0.1'/>"
            "</Shape></CollidableShape></RigidBody></RigidBodyCollection>")


def test_free_fall_is_the_closed_form_in_continuous_mode(tmp_path):
    (w,) = scene_worlds(tmp_path, _free())
    sim = BACKEND.build(w, DT)
    assert not sim.discrete
    n = 240
    sim.step(n)
    t = n * DT
    s = sim.state()
    expected = np.array([1, 2, 3]) + np.array([3, 4, 1]) * t + 0.5 * np.array([0, -G, 0]) * t * t
    assert np.abs(s.position[0] - expected).max() < 1e-9
    assert np.abs(s.linear_velocity[0] - (np.array([3, 4, 1]) + np.array([0, -G, 0]) * t)).max() < 1e-9


def test_free_fall_is_semi_implicit_euler_in_discrete_mode(tmp_path):
    collider = "<CollisionCollection containerField='collider'><CollidableShape USE='S'/></CollisionCollection>"
    body = _free().replace("</RigidBody></RigidBodyCollection>", f"</RigidBody>{collider}</RigidBodyCollection>")
    (w,) = scene_worlds(tmp_path, body)
    sim = BACKEND.build(w, DT)
    assert sim.discrete
    n = 240
    sim.step(n)
    # v_k = v0 + k g dt, x_k = x0 + dt sum v_1..v_k = x0 + v0 t + g dt^2 k (k + 1) / 2
    expected = np.array([1, 2, 3]) + np.array([3, 4, 1]) * n * DT + np.array([0, -G, 0]) * DT * DT * n * (n + 1) / 2
    assert np.abs(sim.state().position[0] - expected).max() < 1e-9


def test_gravity_off_and_world_frame_loads(tmp_path):
    (w,) = scene_worlds(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'><RigidBody DEF='B' mass='2' "
                                  "useGlobalGravity='false' orientation='0 0 1 1' forces='1 0 0' "
                                  "inertia='0.1 0 0 0 0.2 0 0 0 0.3'/></RigidBodyCollection>")
    sim = BACKEND.build(w, DT)
    sim.step(240)
    assert np.abs(sim.state().linear_velocity[0] - [0.5, 0, 0]).max() < 1e-9


def _pendulum(limits: str = "") -> str:
    return ("<RigidBodyCollection gravity='0 -9.81 0'>"
            "<RigidBody DEF='Bob' mass='1' position='0.5 0.1339745962155614 0' "
            "inertia='0.01 0 0 0 0.01 0 0 0 0.01'/>"
            f"<SingleAxisHingeJoint DEF='Hinge' containerField='joints' anchorPoint='0 1 0' axis='0 0 1' {limits}>"
            "<RigidBody USE='Bob' containerField='body1'/></SingleAxisHingeJoint></RigidBodyCollection>")


def _agm(a: float, b: float) -> float:
    while abs(a - b) > 1e-16 * a:
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return a


def test_hinge_pendulum_period_is_the_elliptic_closed_form(tmp_path):
    (w,) = scene_worlds(tmp_path, _pendulum())
    sim = BACKEND.build(w, DT)
    assert not sim.discrete  # no stops, nothing collides: the error-controlled continuous plant
    # released 30 degrees from the vertical, L = 1 m: T = 4 sqrt(I_p / (m g L)) K(sin(theta0 / 2))
    k = math.sin(math.radians(30) / 2)
    period = 4 * math.sqrt((0.01 + 1.0) / (G * 1.0)) * math.pi / (2 * _agm(1.0, math.sqrt(1 - k * k)))
    xs = [sim.state().position[0, 0]]
    for _ in range(int(2.2 * period / DT)):
        sim.step()
        xs.append(sim.state().position[0, 0])
    xs = np.array(xs)
    down = np.flatnonzero((xs[:-1] > 0) & (xs[1:] <= 0))  # crossings of the bottom, swinging one way
    crossings = [(i + xs[i] / (xs[i] - xs[i + 1])) * DT for i in down]
    assert len(crossings) >= 2
    # the bottom is an inflection of x(t): linear interpolation there errs by O(dt^3)
    assert abs((crossings[1] - crossings[0]) - period) < 1e-6 * period
    # energy kept to the integrator's accuracy: the bob swings back to its release height
    assert abs(xs.max() - 0.5) < 1e-4


def test_the_simulation_says_its_target_accuracy_which_prefer_accuracy_tightens(tmp_path):
    """What the sweep's child reports, so that a discrete run is never taken for an error-controlled reference."""
    (w,) = scene_worlds(tmp_path, _pendulum())
    assert target_accuracy(BACKEND.build(w, DT)) == ACCURACY
    (w,) = scene_worlds(tmp_path, _pendulum().replace("<RigidBodyCollection ",
                                                      "<RigidBodyCollection preferAccuracy='true' "))
    assert target_accuracy(BACKEND.build(w, DT)) == ACCURATE < ACCURACY
    (w,) = scene_worlds(tmp_path, _pendulum("minAngle='-0.2' maxAngle='0.2'"))
    assert target_accuracy(BACKEND.build(w, DT)) is None  # discrete mode: stepped at the fixed step


def test_stops_make_the_world_discrete_and_hold(tmp_path):
    (w,) = scene_worlds(tmp_path, _pendulum("minAngle='-0.2' maxAngle='0.2'"))
    sim = BACKEND.build(w, DT)
    assert sim.discrete  # Drake's continuous plant ignores joint limits
    sim.step(240)
    bob = sim.state().position[0]
    angle = math.atan2(bob[0], 1 - bob[1])  # from the vertical; the hinge's angle counts from the start (30 deg)
    assert abs(angle - (math.radians(30) - 0.2)) < 1e-3  # swung down onto the stop 0.2 rad from the start


def test_ball_rests_on_a_box(tmp_path):
    scene = ("<RigidBodyCollection gravity='0 -9.81 0'>"
             "<RigidBody DEF='Ball' mass='1' position='0 0.3 0' inertia='0.004 0 0 0 0.004 0 0 0 0.004'>"
             "<CollidableShape DEF='BallShape' containerField='geometry'><Shape containerField='shape'>"
             "<Sphere radius='0.1'/></Shape></CollidableShape></RigidBody>"
             "<CollisionCollection containerField='collider' frictionCoefficients='0.5 0.5'>"
             "<CollidableShape DEF='Block' translation='0 -0.1 0'><Shape containerField='shape'>"
             "<Box size='2 0.2 2'/></Shape></CollidableShape><CollidableShape USE='BallShape'/>"
             "</CollisionCollection></RigidBodyCollection>")
    (w,) = scene_worlds(tmp_path, scene)
    sim = BACKEND.build(w, DT)
    assert sim.discrete
    sim.step(480)
    s = sim.state()
    # on the block's top (y = 0) at its radius, less the compliant contact's sinking (about a millimetre)
    assert 0.1 - 3e-3 < s.position[0, 1] < 0.1 + 1e-5
    assert np.abs(s.linear_velocity[0]).max() < 1e-3
    c = sim.contacts()
    assert len(c.depth) >= 1
    names = {w.collisions.geometries[int(g)].name for g in (*c.geometry1, *c.geometry2)}
    assert names == {"Block", "BallShape"}
    assert np.all(np.abs(np.abs(c.normal[:, 1]) - 1) < 1e-6)
    assert np.all((c.depth > 0) & (c.depth < 3e-3))


def test_loops_are_refused(tmp_path):
    scene = ("<RigidBodyCollection><RigidBody DEF='A' position='1 0 0'/><RigidBody DEF='B' position='2 0 0'/>"
             "<BallJoint containerField='joints' anchorPoint='1.5 0 0'><RigidBody USE='A' containerField='body1'/>"
             "<RigidBody USE='B' containerField='body2'/></BallJoint>"
             "<BallJoint containerField='joints' anchorPoint='1.5 1 0'><RigidBody USE='A' containerField='body1'/>"
             "<RigidBody USE='B' containerField='body2'/></BallJoint></RigidBodyCollection>")
    (w,) = scene_worlds(tmp_path, scene)
    with pytest.raises(Unsupported, match="closes a loop"):
        BACKEND.build(w, DT)


def test_restitution_is_declared_unsupported_and_zero_bounce_native():
    d = BACKEND.support("CollisionCollection.bounce")
    assert d.support is base.Support.UNSUPPORTED and "restitution" in d.note and d.native_at == 0.0
