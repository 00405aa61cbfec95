"""What only the MuJoCo backend does: the body origin and centre of mass read back from its free
joint, loops closed by soft equalities, ODE's hinge2 suspension and mirrored limits in its model,
autoDisable, frame times given one by one. The shared physics (free fall, loads, damping,
pendulum, limits, universal joint, motors) is in the conformance cases (conformance/cases/)."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("mujoco")

from backends.mujoco import BACKEND  # noqa: E402
from engine_run import DT, last, run_x3d  # noqa: E402


def simulate(tmp_path, body: str, *args, **kwargs):
    return run_x3d(tmp_path, body, *args, **{"backend": BACKEND, **kwargs})


def test_centre_of_mass_and_orientation_are_read_back_at_the_body_origin(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='B' position='1 2 3' "
                           "orientation='0 1 0 0.5' centerOfMass='0.3 0 0' angularVelocity='0 2 0' "
                           "inertia='0.1 0 0 0 0.1 0 0 0 0.1'/></RigidBodyCollection>", duration=0.5)
    t0 = s[("B", "position")][0][1]
    assert t0 == pytest.approx([1, 2, 3], abs=1e-12)
    assert s[("B", "orientation")][0][1] == pytest.approx([0, 1, 0, 0.5], abs=1e-12)
    # linearVelocity is the centre of mass's: read back as given (0) while the body spins
    assert s[("B", "linearVelocity")][0][1] == pytest.approx([0, 0, 0], abs=1e-12)
    assert s[("B", "angularVelocity")][0][1] == pytest.approx([0, 2, 0], abs=1e-12)
    # spinning at 2 rad/s about y through the centre of mass: the origin circles it at 0.3 m.
    # MuJoCo integrates the free joint at its origin, so Euler lets the centre of mass
    # wander by about r w^2 dt t = 0.3 * 4 * dt * 0.5 = 2.5e-3 m over the run
    com0 = np.array([1, 2, 3]) + 0.3 * np.array([math.cos(0.5), 0, -math.sin(0.5)])
    assert np.linalg.norm(last(s, "B", "position") - com0) == pytest.approx(0.3, abs=0.3 * 4 * DT * 0.5)


PENDULUM = """<RigidBodyCollection gravity='0 -9.81 0'>
  <RigidBody DEF='Anchor' fixed='true'/>
  <RigidBody DEF='Bob' position='{x} {y} 0' inertia='1e-6 0 0 0 1e-6 0 0 0 1e-6'/>
  <SingleAxisHingeJoint DEF='H' axis='0 0 1' forceOutput='"ALL"'>
    <RigidBody USE='Anchor' containerField='body1'/><RigidBody USE='Bob' containerField='body2'/>
  </SingleAxisHingeJoint></RigidBodyCollection>"""


def test_uneven_frame_times_do_not_change_the_physics(tmp_path):
    # frame_rate compares two even frame rates; frames at given, uneven times end the same
    body = PENDULUM.format(x=math.sin(0.5), y=-math.cos(0.5))
    a = simulate(tmp_path, body, frame_rate=30)
    uneven = np.cumsum([0.013, 0.041, 0.007, 0.1, 0.339, 0.5])
    c = simulate(tmp_path, body, times=uneven)
    assert c[("Bob", "position")][-1][0] == 1.0
    assert np.array_equal(c[("Bob", "position")][-1][1], a[("Bob", "position")][-1][1])


def test_ball_joint_loop_stays_joined(tmp_path):
    s = simulate(tmp_path, """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='Top' fixed='true'/>
      <RigidBody DEF='A' position='0 -0.5 0'/><RigidBody DEF='B' position='0.5 -0.5 0'/>
      <BallJoint DEF='J1' anchorPoint='0 0 0'><RigidBody USE='Top' containerField='body1'/>
        <RigidBody USE='A' containerField='body2'/></BallJoint>
      <BallJoint DEF='J2' anchorPoint='0.25 -0.5 0'><RigidBody USE='A' containerField='body1'/>
        <RigidBody USE='B' containerField='body2'/></BallJoint>
      <BallJoint DEF='J3' anchorPoint='0.5 0 0' forceOutput='"ALL"'><RigidBody USE='Top' containerField='body1'/>
        <RigidBody USE='B' containerField='body2'/></BallJoint></RigidBodyCollection>""", duration=1.0)
    gaps = [np.linalg.norm(a - b) for (_, a), (_, b) in zip(s[("J3", "body1AnchorPoint")],
                                                            s[("J3", "body2AnchorPoint")])]
    assert max(gaps) < 2e-3  # the loop-closing equality is soft (solref 2 dt): millimetres at most


HINGE2 = """<RigidBodyCollection gravity='0 {g} 0'>
  <RigidBody DEF='Car' fixed='true'/>
  <RigidBody DEF='Wheel' position='1 0 0' mass='{m}' inertia='0.1 0 0 0 0.1 0 0 0 0.1'/>
  <DoubleAxisHingeJoint DEF='H2' anchorPoint='1 0 0' axis1='0 1 0' axis2='1 0 0' desiredAngularVelocity2='3'
     maxTorque2='5' suspensionForce='{cfm}' suspensionErrorCorrection='0.5' forceOutput='"ALL"'>
    <RigidBody USE='Car' containerField='body1'/><RigidBody USE='Wheel' containerField='body2'/>
  </DoubleAxisHingeJoint></RigidBodyCollection>"""


def test_hinge2_suspension_is_odes_spring(tmp_path):
    # k = ERP / (h CFM): a 2 kg wheel under 9.81 m/s^2 along axis 1 settles at m g / k
    cfm, erp = 0.001, 0.5
    s = simulate(tmp_path, HINGE2.format(g=-9.81, m=2, cfm=cfm), duration=2.0)
    k = erp / (DT * cfm)
    assert last(s, "Wheel", "position")[1] == pytest.approx(-2 * 9.81 / k, rel=1e-3)


def test_hinge2_limits_hold_when_body1_is_the_moving_body(tmp_path):
    s = simulate(tmp_path, """<RigidBodyCollection gravity='0 0 0'>
      <RigidBody DEF='Car' fixed='true'/>
      <RigidBody DEF='Wheel' position='1 0 0' inertia='0.1 0 0 0 0.1 0 0 0 0.1'/>
      <DoubleAxisHingeJoint DEF='H2' anchorPoint='1 0 0' axis1='0 1 0' axis2='1 0 0' minAngle1='-0.3'
          maxAngle1='0.5' desiredAngularVelocity1='-1' maxTorque1='10' forceOutput='"hinge1Angle"'>
        <RigidBody USE='Wheel' containerField='body1'/><RigidBody USE='Car' containerField='body2'/>
      </DoubleAxisHingeJoint></RigidBodyCollection>""", duration=1.0)
    angles = [v[0] for _, v in s[("H2", "hinge1Angle")]]
    # driven at -1 rad/s into the stop at -0.3: held there (soft by at most a few mrad)
    assert min(angles) > -0.3 - 0.01 and angles[-1] == pytest.approx(-0.3, abs=0.01)


def test_auto_disable_stops_a_slow_free_body_after_its_time(tmp_path):
    s = simulate(tmp_path, """<RigidBodyCollection gravity='0 0 0'>
      <RigidBody DEF='Slow' linearVelocity='0.05 0 0' autoDisable='true' disableLinearSpeed='0.1'
          disableAngularSpeed='0.1' disableTime='0.5'/>
      <RigidBody DEF='Fast' linearVelocity='0.5 0 0' autoDisable='true' disableLinearSpeed='0.1'
          disableAngularSpeed='0' disableTime='0.5'/></RigidBodyCollection>""", duration=1.0, frame_rate=240)
    # (Fast does not spin: under the spec's "any one of these values" an angular threshold above 0 would stop it)
    slow = dict((round(t * 240), v) for t, v in s[("Slow", "position")])
    # idle from the first step, disabled once 0.5 s have passed: it moved 0.05 m/s until then
    assert slow[240][0] == slow[120][0] == pytest.approx(0.05 * 120 * DT, abs=1e-12)
    assert last(s, "Slow", "linearVelocity") == pytest.approx([0, 0, 0], abs=0)
    assert last(s, "Fast", "position")[0] == pytest.approx(0.5, abs=1e-9)


def test_a_disabled_body_stays_up_under_gravity_and_a_disabled_node_is_out(tmp_path):
    s = simulate(tmp_path, """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='Held' position='0 1 0' autoDisable='true' disableLinearSpeed='0.1'
          disableAngularSpeed='0.1'/>
      <RigidBody DEF='Off' position='0 2 0' enabled='false'/></RigidBodyCollection>""")
    # disableTime 0: disabled after its first step, having fallen g dt^2 and no more
    assert last(s, "Held", "position")[1] == pytest.approx(1 - 9.81 * DT * DT, abs=1e-12)
    assert ("Off", "position") not in s  # not enabled: not part of the physics, not in the trace
