"""What only the pybullet backend does: multibody trees read back at the body origin, loads and
damping through pybullet's joints, limits and motor targets mirrored where the child is body2,
loops as constraints, its refusals (suspension, hinge loops, degrees of freedom) and clients;
against MuJoCo where both integrate the same tree. The shared physics (free fall, loads,
pendulum, stops, universal joint, damping) is in the conformance cases (conformance/cases/)."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("pybullet")

from backends import base  # noqa: E402
from backends.bullet import BACKEND  # noqa: E402
from engine_run import (DT, G, TURNED_BODY, TURNED_ORIENTATION, last, pendulum, run_x3d, scene_worlds,  # noqa: E402
                        values)
from x3d_core.semantics import rotation as R  # noqa: E402
from x3d_core.semantics.engine import Unsupported  # noqa: E402


def simulate(tmp_path, body: str, *args, **kwargs):
    return run_x3d(tmp_path, body, *args, **{"backend": BACKEND, **kwargs})


def test_centre_of_mass_and_orientation_come_back_at_the_body_origin(tmp_path):
    # a rotated body with an off-centre centre of mass and a full inertia tensor (so
    # pybullet's inertial frame is both offset and turned against the body frame)
    s = simulate(tmp_path, TURNED_BODY)
    assert s[("B", "position")][0][1] == pytest.approx([1, 2, 3], abs=1e-12)
    q0 = R.from_axis_angle(TURNED_ORIENTATION)
    turn = R.multiply(R.conjugate(q0), R.from_axis_angle(values(s, "B", "orientation")))
    assert np.abs(turn[:, 1:]).max() < 1e-12  # never turns: no torque about the centre of mass
    # the centre of mass falls as a point does (Euler at the centre of mass, as above)
    n = round(1.0 / DT)
    expected = np.array([1, 2 - G * DT * DT * n * (n + 1) / 2, 3])
    assert last(s, "B", "position") == pytest.approx(expected, abs=1e-12)


def test_spinning_body_turns_about_its_centre_of_mass(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='B' position='1 2 3' "
                           "orientation='0 1 0 0.5' centerOfMass='0.3 0 0' angularVelocity='0 2 0' "
                           "inertia='0.1 0 0 0 0.1 0 0 0 0.1'/></RigidBodyCollection>", duration=0.5)
    assert s[("B", "linearVelocity")][0][1] == pytest.approx([0, 0, 0], abs=1e-12)
    assert s[("B", "angularVelocity")][0][1] == pytest.approx([0, 2, 0], abs=1e-12)
    # pybullet integrates a base at its centre of mass, which stays put: the origin circles
    # it at 0.3 m, 2 rad/s times 0.5 s from where it started (exact rotation update)
    com = np.array([1, 2, 3]) + 0.3 * np.array([math.cos(0.5), 0, -math.sin(0.5)])
    angle = 0.5 + 2 * 0.5
    assert last(s, "B", "position") == pytest.approx(com - 0.3 * np.array([math.cos(angle), 0, -math.sin(angle)]),
                                                     abs=1e-12)
    assert last(s, "B", "linearVelocity") == pytest.approx([0, 0, 0], abs=1e-12)


def test_gravity_off_and_forces_act_at_an_offset_centre_of_mass(tmp_path):
    # pybullet has no per-body gravity switch: the backend applies -m g at the centre of mass,
    # where the forces go too, so an offset centre of mass takes no spin from either
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'>"
                           "<RigidBody DEF='F' mass='2' useGlobalGravity='false' centerOfMass='0.2 0 0' "
                           "forces='1 0 0, 3 0 0'/></RigidBodyCollection>")
    assert last(s, "F", "linearVelocity") == pytest.approx([2.0, 0, 0], abs=1e-12)
    assert last(s, "F", "angularVelocity") == pytest.approx([0, 0, 0], abs=1e-12)


def test_prefer_accuracy_substeps_keep_the_loads(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0' preferAccuracy='true'>"
                           "<RigidBody DEF='F' mass='2' useGlobalGravity='false' forces='4 0 0'/>"
                           "<RigidBody DEF='B' position='0 10 0'/></RigidBodyCollection>")
    # four substeps of dt/4: loads act on every substep (v exact), and the Euler lag in
    # position is that of the substep, g (dt/4) t / 2
    assert last(s, "F", "linearVelocity") == pytest.approx([2.0, 0, 0], abs=1e-12)
    assert last(s, "B", "position")[1] == pytest.approx(10 - G / 2 - G * DT / 4 / 2, abs=1e-12)


def test_auto_damp_on_jointed_bodies_goes_through_the_joints(tmp_path):
    # two wheels on hinges (two multibodies), centres of mass off the axes, spinning in zero
    # gravity: each step keeps 1 - 0.01 of their velocities, as joint velocities (exact,
    # since the damped velocities are still ones the hinges allow)
    s = simulate(tmp_path, """<RigidBodyCollection gravity='0 0 0'>
      <RigidBody DEF='W1' position='0.5 0 0' linearVelocity='0 1 0' angularVelocity='0 0 2' autoDamp='true'
          linearDampingFactor='0.01' angularDampingFactor='0.01'/>
      <RigidBody DEF='W2' position='3 0.5 0' centerOfMass='0 -0.2 0' linearVelocity='0 0 -0.3'
          angularVelocity='-1 0 0' autoDamp='true' linearDampingFactor='0.02' angularDampingFactor='0.02'/>
      <SingleAxisHingeJoint DEF='H1' axis='0 0 1' forceOutput='"angleRate" "body1AnchorPoint"'>
        <RigidBody USE='W1' containerField='body1'/></SingleAxisHingeJoint>
      <SingleAxisHingeJoint DEF='H2' anchorPoint='3 0 0' axis='1 0 0' forceOutput='"angleRate"'>
        <RigidBody USE='W2' containerField='body2'/></SingleAxisHingeJoint></RigidBodyCollection>""")
    for (t, rate1), (_, rate2) in zip(s[("H1", "angleRate")], s[("H2", "angleRate")]):
        n = round(t / DT)
        assert rate1[0] == pytest.approx(2 * 0.99 ** n, rel=1e-9)
        assert rate2[0] == pytest.approx(1 * 0.98 ** n, rel=1e-9)  # body1 (static) relative to W2
    assert np.abs(values(s, "H1", "body1AnchorPoint")).max() < 1e-12




@pytest.mark.parametrize("bob_is_body1", [False, True])
def test_hinge_limits_hold_whichever_body_is_the_child(tmp_path, bob_is_body1):
    # released at 0.8 rad, the bob swings down through the stop; body1 relative to body2 the
    # angle falls (bob is body1) or rises (bob is body2) to the stop and stays there
    s = simulate(tmp_path, pendulum(0.8, "minAngle='-0.5' maxAngle='0.5'", bob_is_body1), duration=2.0)
    angle = values(s, "H", "angle")[:, 0]
    # pybullet's limit is a hard constraint row with ERP 0.8 (split impulse off): it can
    # overshoot by one step of motion at most; the bob meets the stop at
    # sqrt(2 g (cos 0.3 - cos 0.8)) = 2.25 rad/s, under 3 rad/s * dt = 0.0125 rad
    assert angle.max() < 0.5 + 0.0125 and angle.min() > -0.5 - 0.0125
    assert angle[-1] == pytest.approx(-0.5 if bob_is_body1 else 0.5, abs=1e-3)


def test_slider_stops_are_mirrored_when_the_child_is_body2(tmp_path):
    # slider_stops has the block as body1; here it is body2 (pybullet's child coordinate is then
    # minus the separation), turned, with an offset centre of mass
    s = simulate(tmp_path, """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='Rail' fixed='true'/>
      <RigidBody DEF='Block' position='0 1 0' orientation='0 0 1 0.5' centerOfMass='0.1 0 0'/>
      <SliderJoint DEF='S' axis='0.6 -0.8 0' minSeparation='-0.2' maxSeparation='0.3' forceOutput='"ALL"'>
        <RigidBody USE='Rail' containerField='body1'/><RigidBody USE='Block' containerField='body2'/>
      </SliderJoint></RigidBodyCollection>""", duration=1.0, frame_rate=240)
    sep = values(s, "S", "separation")[:, 0]
    # the block (body2) slides down the axis, so body1 relative to body2 goes to minSeparation;
    # it arrives at sqrt(2 * 0.8 g * 0.2) = 1.8 m/s, and one step of that is 7.5 mm: "a few mm"
    assert sep.min() > -0.2 - 0.0075 and sep.max() < 0.3 + 1e-12
    assert sep[-1] == pytest.approx(-0.2, abs=1e-3)
    # off the axis it does not move at all
    off = values(s, "Block", "position") - np.outer(sep, [-0.6, 0.8, 0]) - [0, 1, 0]
    assert np.abs(off).max() < 1e-9


def test_ball_joint_loop_stays_joined(tmp_path):
    # A and B both hang from the world; J2 joins them and closes the loop as a
    # point-to-point constraint. Off-diagonal inertias and offset centres of mass check that
    # the pivots are placed in pybullet's (turned) centre-of-mass frames.
    s = simulate(tmp_path, """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='Top' fixed='true'/>
      <RigidBody DEF='A' position='0 -0.5 0' orientation='0 0 1 0.3' centerOfMass='0.05 0 0'
          inertia='0.02 0.005 0 0.005 0.02 0.002 0 0.002 0.03' linearVelocity='0 0 1'/>
      <RigidBody DEF='B' position='0.5 -0.5 0' orientation='1 0 0 0.5' centerOfMass='0 0.05 0.02'
          inertia='0.03 0 0.004 0 0.025 0 0.004 0 0.015'/>
      <BallJoint DEF='J1' anchorPoint='0 0 0'><RigidBody USE='Top' containerField='body1'/>
        <RigidBody USE='A' containerField='body2'/></BallJoint>
      <BallJoint DEF='J2' anchorPoint='0.25 -0.5 0' forceOutput='"ALL"'><RigidBody USE='A' containerField='body1'/>
        <RigidBody USE='B' containerField='body2'/></BallJoint>
      <BallJoint DEF='J3' anchorPoint='0.5 0 0'><RigidBody USE='Top' containerField='body1'/>
        <RigidBody USE='B' containerField='body2'/></BallJoint></RigidBodyCollection>""", duration=1.0)
    gaps = np.linalg.norm(values(s, "J2", "body1AnchorPoint") - values(s, "J2", "body2AnchorPoint"), axis=1)
    # at worst the solver leaves one step's gravity unresolved, g dt^2 = 0.17 mm, and ERP
    # takes 80% of any gap away at the next step (measured: 2 micrometres)
    assert gaps.max() < G * DT * DT
    assert np.abs(values(s, "A", "position")[-1] - [0, -0.5, 0]).max() > 0.01  # and it did move


@pytest.mark.parametrize("wheel_is_body1", [True, False])
def test_hinge2_motor_is_a_bounded_velocity_constraint(tmp_path, wheel_is_body1):
    first, second = ("Wheel", "Car") if wheel_is_body1 else ("Car", "Wheel")
    s = simulate(tmp_path, f"""<RigidBodyCollection gravity='0 0 0'>
      <RigidBody DEF='Car' fixed='true'/>
      <RigidBody DEF='Wheel' position='1 0 0' inertia='0.1 0 0 0 0.1 0 0 0 0.1'/>
      <DoubleAxisHingeJoint DEF='H2' anchorPoint='1 0 0' axis1='0 1 0' axis2='1 0 0' desiredAngularVelocity1='-1'
          maxTorque1='0.5' desiredAngularVelocity2='3' maxTorque2='5' minAngle1='-0.3' maxAngle1='0.5'
          forceOutput='"ALL"'>
        <RigidBody USE='{first}' containerField='body1'/><RigidBody USE='{second}' containerField='body2'/>
      </DoubleAxisHingeJoint></RigidBodyCollection>""", duration=1.0, frame_rate=240)
    rate2 = {round(t * 240): v[0] for t, v in s[("H2", "hinge2AngleRate")]}
    # ODE's motor reaches its target in one step if the torque allows: 5 N m on 0.1 kg m^2
    # is 50 rad/s^2, so 1.25 rad/s after 6 steps, then held at the target
    assert rate2[6] == pytest.approx(50 * 6 * DT, rel=1e-9)
    assert rate2[240] == pytest.approx(3.0, abs=1e-9)
    # motor 1 drives hinge 1 (body1 relative to body2) down to minAngle1 at 1 rad/s and
    # holds it there: at most one step (1 rad/s * dt) past the stop
    hinge1 = values(s, "H2", "hinge1Angle")[:, 0]
    assert hinge1.min() > -0.3 - 1 * DT and hinge1[-1] == pytest.approx(-0.3, abs=1e-3)


def test_suspension_is_refused(tmp_path):
    scene_text = ("<RigidBodyCollection><RigidBody DEF='A' fixed='true'/><RigidBody DEF='B' position='1 0 0'/>"
                  "<DoubleAxisHingeJoint suspensionForce='0.01'><RigidBody USE='A' containerField='body1'/>"
                  "<RigidBody USE='B' containerField='body2'/></DoubleAxisHingeJoint></RigidBodyCollection>")
    assert BACKEND.support("DoubleAxisHingeJoint.suspensionForce").support is base.Support.UNSUPPORTED
    with pytest.raises(Unsupported, match="suspensionForce"):
        BACKEND.build(scene_worlds(tmp_path, scene_text)[0], DT)


def test_hinge_closing_a_loop_is_refused(tmp_path):
    scene_text = ("<RigidBodyCollection><RigidBody DEF='A' position='0 -1 0'/>"
                  "<SingleAxisHingeJoint><RigidBody USE='A' containerField='body1'/></SingleAxisHingeJoint>"
                  "<SingleAxisHingeJoint anchorPoint='1 0 0'><RigidBody USE='A' containerField='body1'/>"
                  "</SingleAxisHingeJoint></RigidBodyCollection>")
    with pytest.raises(Unsupported, match="closes a loop"):
        BACKEND.build(scene_worlds(tmp_path, scene_text)[0], DT)


def test_every_simulation_has_its_own_client(tmp_path):
    import pybullet
    world = scene_worlds(tmp_path, pendulum(0.5))[0]
    a, b = BACKEND.build(world, DT), BACKEND.build(world, DT)
    a.step(100)
    assert b.state().position == pytest.approx(world.bodies.position, abs=1e-12)
    assert np.abs(a.state().position - world.bodies.position).max() > 0.01
    a.close()
    assert not pybullet.isConnected(a.client) and pybullet.isConnected(b.client)
    a.close()  # twice is harmless
    b.close()


# -- against MuJoCo: the same scene, the same outputs ---------------------------------

TREE = """<RigidBodyCollection gravity='0 -9.81 0'>
  <RigidBody DEF='Top' fixed='true'/>
  <RigidBody DEF='Arm' mass='1' position='0.5 -0.8 0.1' orientation='1 1 0 0.4' centerOfMass='0 -0.1 0'
      inertia='0.05 0 0.01 0 0.03 0 0.01 0 0.04' angularVelocity='0.5 0 1'/>
  <RigidBody DEF='Tip' mass='0.5' position='0.6 -1.2 0.3' orientation='0 1 0 1.2'
      inertia='0.01 0 0 0 0.01 0 0 0 0.02' angularVelocity='0 0 3'/>
  <RigidBody DEF='Foot' mass='0.3' position='0.6 -1.4 0.3'/>
  <SingleAxisHingeJoint DEF='H' anchorPoint='0.3 -0.5 0' axis='0 0.6 0.8' forceOutput='"angle" "angleRate"'>
    <RigidBody USE='{hinge1}' containerField='body1'/><RigidBody USE='{hinge2}' containerField='body2'/>
  </SingleAxisHingeJoint>
  <BallJoint DEF='B' anchorPoint='0.55 -1.0 0.2' forceOutput='"ALL"'>
    <RigidBody USE='Arm' containerField='body1'/><RigidBody USE='Tip' containerField='body2'/></BallJoint>
  <UniversalJoint DEF='U' anchorPoint='0.6 -1.2 0.3' axis1='1 0 0' axis2='0 0 1' forceOutput='"ALL"'>
    <RigidBody USE='{u1}' containerField='body1'/><RigidBody USE='{u2}' containerField='body2'/>
  </UniversalJoint>
</RigidBodyCollection>"""


@pytest.mark.parametrize("swap", [False, True])
def test_joint_outputs_agree_with_mujoco(tmp_path, swap):
    mujoco = pytest.importorskip("backends.mujoco", exc_type=ImportError)
    scene = TREE.format(hinge1="Top" if swap else "Arm", hinge2="Arm" if swap else "Top",
                        u1="Foot" if swap else "Tip", u2="Tip" if swap else "Foot")
    ours = simulate(tmp_path, scene)
    theirs = simulate(tmp_path, scene, backend=mujoco.BACKEND)
    # both integrate the same tree in reduced coordinates with semi-implicit Euler; they
    # differ only in rounding (measured: 1e-13 rad after 1 s), so 1e-3 rad catches any sign
    for node, field in [("H", "angle"), ("H", "angleRate"), ("B", "body1AnchorPoint"), ("U", "body1Axis"),
                        ("U", "body2Axis"), ("Tip", "angularVelocity"), ("Foot", "angularVelocity")]:
        assert np.abs(values(ours, node, field) - values(theirs, node, field)).max() < 1e-3, (node, field)
    assert np.abs(values(ours, "H", "angle")).max() > 0.1  # and the joints did move


def test_damping_and_loads_on_a_free_tree_agree_with_mujoco(tmp_path):
    mujoco = pytest.importorskip("backends.mujoco", exc_type=ImportError)
    scene = """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='A' position='0.5 -0.5 0' autoDamp='true' linearDampingFactor='0.01' angularDampingFactor='0.02'
          centerOfMass='0.1 0 0' useGlobalGravity='false' forces='0 -5 1' angularVelocity='0 0 1'/>
      <RigidBody DEF='B' position='1 -0.8 0' torques='0 0.1 0' linearVelocity='0 0 1' angularVelocity='0 1 0'/>
      <RigidBody DEF='C' position='0.2 -0.9 0.1' orientation='1 0 0 0.3' autoDamp='true' angularDampingFactor='0.05'/>
      <SingleAxisHingeJoint DEF='J2' anchorPoint='0.8 -0.6 0' axis='0 1 1' forceOutput='"ALL"'>
        <RigidBody USE='B' containerField='body1'/><RigidBody USE='A' containerField='body2'/></SingleAxisHingeJoint>
      <BallJoint DEF='J3' anchorPoint='0.3 -0.7 0'>
        <RigidBody USE='A' containerField='body1'/><RigidBody USE='C' containerField='body2'/></BallJoint>
    </RigidBodyCollection>"""
    ours, theirs = simulate(tmp_path, scene), simulate(tmp_path, scene, backend=mujoco.BACKEND)
    # rotations agree to rounding (measured 1e-14); MuJoCo moves a free body at its origin,
    # not its centre of mass, so positions may part by O(w^2 r dt t): compare rotations here
    for node, field in [("J2", "angle"), ("J2", "angleRate"), ("A", "angularVelocity"), ("B", "angularVelocity"),
                        ("C", "angularVelocity")]:
        assert np.abs(values(ours, node, field) - values(theirs, node, field)).max() < 1e-6, (node, field)


@pytest.mark.parametrize("links", [40, 41])
def test_a_tree_past_pybullets_degrees_of_freedom_is_refused_not_misread(tmp_path, links):
    """A chain of ball joints from a fixed base: 40 (120 degrees of freedom) reads back where
    it was built; 41 (123) pybullet would report with its first links misplaced by 0.1 m
    (measured), so it is refused."""
    bodies = "<RigidBody DEF='Base' fixed='true'/>" + "".join(
        f"<RigidBody DEF='L{k}' position='{0.1 * k} 0 0'/>" for k in range(1, links + 1))
    joints = "".join(f"<BallJoint anchorPoint='{0.1 * k - 0.05} 0 0'><RigidBody USE='{f'L{k - 1}' if k > 1 else 'Base'}' "
                     f"containerField='body1'/><RigidBody USE='L{k}' containerField='body2'/></BallJoint>"
                     for k in range(1, links + 1))
    body = f"<RigidBodyCollection gravity='0 0 0'>{bodies}{joints}</RigidBodyCollection>"
    if links == 41:
        with pytest.raises(Unsupported, match="123 degrees of freedom"):
            BACKEND.build(scene_worlds(tmp_path, body)[0], DT)
        return
    s = simulate(tmp_path, body, duration=DT)
    assert all(np.abs(last(s, f"L{k}", "position") - [0.1 * k, 0, 0]).max() < 1e-12 for k in range(1, links + 1))
