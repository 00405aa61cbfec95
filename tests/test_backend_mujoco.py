"""The MuJoCo backend against closed forms, with tolerances argued from its integrator."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("mujoco")

from backends.mujoco import BACKEND  # noqa: E402
from engine_run import DT, last, run_x3d  # noqa: E402


def simulate(tmp_path, body: str, *args, **kwargs):
    return run_x3d(tmp_path, body, *args, **{"backend": BACKEND, **kwargs})


def test_free_fall_is_semi_implicit_euler_exactly(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'><RigidBody DEF='B' position='0 10 0'/>"
                           "</RigidBodyCollection>")
    # v_n = -g n dt, y_n = y0 - g dt^2 n (n + 1) / 2: MuJoCo's Euler updates velocity first
    for t, pos in s[("B", "position")]:
        n = round(t / DT)
        assert pos[1] == pytest.approx(10 - 9.81 * DT * DT * n * (n + 1) / 2, abs=1e-12)
    assert last(s, "B", "linearVelocity")[1] == pytest.approx(-9.81, abs=1e-12)


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


def test_forces_torques_and_gravity_off(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'>"
                           "<RigidBody DEF='F' mass='2' useGlobalGravity='false' forces='1 0 0, 3 0 0'/>"
                           "<RigidBody DEF='T' useGlobalGravity='false' inertia='0.5 0 0 0 0.5 0 0 0 0.5' "
                           "torques='0 0 1'/>"
                           "<RigidBody DEF='G' useGlobalGravity='false' position='0 5 0'/></RigidBodyCollection>")
    # a = F/m = 2 m/s^2 and alpha = tau/I = 2 rad/s^2: velocities are exact under Euler
    assert last(s, "F", "linearVelocity") == pytest.approx([2.0, 0, 0], abs=1e-12)
    assert last(s, "T", "angularVelocity") == pytest.approx([0, 0, 2.0], abs=1e-9)
    assert last(s, "G", "position") == pytest.approx([0, 5, 0], abs=1e-12)


def test_auto_damp_takes_a_fraction_of_velocity_each_step(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='B' linearVelocity='1 0 0' "
                           "angularVelocity='0 0 1' autoDamp='true' linearDampingFactor='0.01' "
                           "angularDampingFactor='0.02'/></RigidBodyCollection>")
    n = round(1.0 / DT)
    assert last(s, "B", "linearVelocity")[0] == pytest.approx(0.99 ** n, rel=1e-9)
    assert last(s, "B", "angularVelocity")[2] == pytest.approx(0.98 ** n, rel=1e-9)


PENDULUM = """<RigidBodyCollection gravity='0 -9.81 0'>
  <RigidBody DEF='Anchor' fixed='true'/>
  <RigidBody DEF='Bob' position='{x} {y} 0' inertia='1e-6 0 0 0 1e-6 0 0 0 1e-6'/>
  <SingleAxisHingeJoint DEF='H' axis='0 0 1' forceOutput='"ALL"' {limits}>
    <RigidBody USE='Anchor' containerField='body1'/><RigidBody USE='Bob' containerField='body2'/>
  </SingleAxisHingeJoint></RigidBodyCollection>"""


def test_pendulum_keeps_its_anchor_and_its_period(tmp_path):
    theta0 = 0.05
    s = simulate(tmp_path, PENDULUM.format(x=math.sin(theta0), y=-math.cos(theta0), limits=""),
                 duration=2.5, frame_rate=240)
    anchors = np.array([v for _, v in s[("H", "body2AnchorPoint")]])
    assert np.abs(anchors).max() < 1e-9  # the tree joint cannot drift
    angle = np.array([v[0] for _, v in s[("H", "angle")]])
    times = np.array([t for t, _ in s[("H", "angle")]])
    # the angle (body1 relative to body2) starts at 0 and swings to +2 theta0 at half a period
    assert angle.max() == pytest.approx(2 * theta0, rel=0.01)
    crossings = times[1:][(angle[:-1] - theta0) * (angle[1:] - theta0) < 0]
    period = 2 * (crossings[1] - crossings[0])
    small_angle = 2 * math.pi * math.sqrt(1 / 9.81) * (1 + theta0 ** 2 / 16)
    assert period == pytest.approx(small_angle, rel=0.005)  # a few steps of 1/240 s over 2 s


def test_hinge_limits_hold(tmp_path):
    theta0 = 0.8
    s = simulate(tmp_path, PENDULUM.format(x=math.sin(theta0), y=-math.cos(theta0),
                                           limits="minAngle='-0.2' maxAngle='0.5'"), duration=2.0)
    angle = np.array([v[0] for _, v in s[("H", "angle")]])
    # MuJoCo's limits are soft: penetration of the order g*dt^2*... stays well under 0.05 rad
    assert angle.max() < 0.5 + 0.05 and angle.min() > -0.2 - 0.05
    assert angle.max() > 0.45  # and it did reach the stop


def test_frame_rate_does_not_change_the_physics(tmp_path):
    body = PENDULUM.format(x=math.sin(0.5), y=-math.cos(0.5), limits="")
    a = simulate(tmp_path, body, frame_rate=30)
    b = simulate(tmp_path, body, frame_rate=144)
    assert a[("Bob", "position")][-1][0] == b[("Bob", "position")][-1][0] == 1.0
    assert np.array_equal(a[("Bob", "position")][-1][1], b[("Bob", "position")][-1][1])
    uneven = np.cumsum([0.013, 0.041, 0.007, 0.1, 0.339, 0.5])
    c = simulate(tmp_path, body, times=uneven)
    assert np.array_equal(c[("Bob", "position")][-1][1], a[("Bob", "position")][-1][1])


def test_universal_joint_keeps_its_axes_perpendicular(tmp_path):
    s = simulate(tmp_path, """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='Top' fixed='true'/>
      <RigidBody DEF='Arm' position='0.3 -1 0.2' angularVelocity='1 0 2'/>
      <UniversalJoint DEF='U' axis1='1 0 0' axis2='0 0 1' forceOutput='"body1Axis" "body2Axis"'>
        <RigidBody USE='Top' containerField='body1'/><RigidBody USE='Arm' containerField='body2'/>
      </UniversalJoint></RigidBodyCollection>""", duration=2.0)
    for (_, a1), (_, a2) in zip(s[("U", "body1Axis")], s[("U", "body2Axis")]):
        assert abs(a1 @ a2) < 1e-9


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


def test_hinge2_motor_reaches_its_speed_within_its_torque(tmp_path):
    s = simulate(tmp_path, HINGE2.format(g=0, m=1, cfm=0), duration=0.5, frame_rate=240)
    rate = {round(t * 240): v[0] for t, v in s[("H2", "hinge2AngleRate")]}
    # torque-limited: 5 N m on 0.1 kg m^2 is 50 rad/s^2, so 1.25 rad/s after 6 steps (25 ms)
    assert rate[6] == pytest.approx(50 * 6 * DT, rel=1e-6)
    assert rate[120] == pytest.approx(3.0, abs=1e-9)  # then held at the target
    assert s[("H2", "hinge1AngleRate")][-1][1][0] == pytest.approx(0, abs=1e-12)


def test_hinge2_suspension_is_odes_spring(tmp_path):
    # k = ERP / (h CFM): a 2 kg wheel under 9.81 m/s^2 along axis 1 settles at m g / k
    cfm, erp = 0.001, 0.5
    s = simulate(tmp_path, HINGE2.format(g=-9.81, m=2, cfm=cfm), duration=2.0)
    k = erp / (DT * cfm)
    assert last(s, "Wheel", "position")[1] == pytest.approx(-2 * 9.81 / k, rel=1e-3)


def test_motor_joint_applies_equal_and_opposite_torques(tmp_path):
    s = simulate(tmp_path, """<RigidBodyCollection gravity='0 0 0'>
      <RigidBody DEF='A' inertia='0.5 0 0 0 0.5 0 0 0 0.5'/>
      <RigidBody DEF='B' position='2 0 0' inertia='0.25 0 0 0 0.25 0 0 0 0.25'/>
      <MotorJoint DEF='M' enabledAxes='1' motor1Axis='0 0 1' axis1Torque='1' autoCalc='true'
          forceOutput='"motor1Angle" "motor1AngleRate"'>
        <RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/>
      </MotorJoint></RigidBodyCollection>""")
    # body1 gets +1 N m about z (alpha 2), body2 -1 N m (alpha -4): the rate grows at 6 rad/s^2
    assert last(s, "A", "angularVelocity") == pytest.approx([0, 0, 2.0], abs=1e-9)
    assert last(s, "B", "angularVelocity") == pytest.approx([0, 0, -4.0], abs=1e-9)
    assert last(s, "M", "motor1AngleRate")[0] == pytest.approx(6.0, abs=1e-9)


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
          disableAngularSpeed='0.1' disableTime='0.5'/></RigidBodyCollection>""", duration=1.0, frame_rate=240)
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
