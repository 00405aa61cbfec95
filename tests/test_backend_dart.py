"""What only the DART backend does: skeletons built from the joint forest (body frames, centres
of mass, sleeping off), stops and motors mirrored for whichever body is the child, damping and
motor torques through its Jacobians, loops closed as constraints with its class-wide ERP and CFM,
ODE's hinge2 built from links, its refusals and declarations; against MuJoCo where both integrate
the same tree (DART integrates semi-implicit Euler: velocity first, then position with the new
velocity). The shared physics (free fall, gravity off, loads, damping, pendulum) is in the
conformance cases (conformance/cases/)."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("dartpy")

from backends import base  # noqa: E402
from backends.dart import BACKEND  # noqa: E402
from engine_run import (DT, G, ODD_SCENE, assert_odd_body_reads_back, last, run_x3d, scene_worlds, times,  # noqa: E402
                        values)
from x3d_core.semantics import rotation as R  # noqa: E402
from x3d_core.semantics.engine import Unsupported  # noqa: E402


def simulate(tmp_path, body: str, *args, **kwargs):
    return run_x3d(tmp_path, body, *args, **{"backend": BACKEND, **kwargs})


def test_registered_under_its_name():
    assert base.load("dart") is BACKEND
    assert BACKEND.version().startswith("6.")


def test_matrix_to_quaternion_inverts_rotation_matrix():
    rng = np.random.default_rng(1)
    q = rng.normal(size=(200, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    q[:4] = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]  # every branch of the choice
    back = R.from_matrix(R.matrix(q))
    assert np.allclose(back * np.sign(np.sum(back * q, axis=1))[:, None], q, atol=1e-12)


def test_centre_of_mass_offset_and_orientation_read_back_as_given(tmp_path):
    s = simulate(tmp_path, ODD_SCENE, duration=0.1)
    # DART's body frame is the X3D body frame (the centre of mass is an offset in it), so
    # the pose comes back as given, and the velocities (linear at the centre of mass) too
    assert_odd_body_reads_back(s)


def test_spin_about_the_centre_of_mass_keeps_it_in_place(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='B' position='1 2 3' "
                           "orientation='0 1 0 0.5' centerOfMass='0.3 0 0' angularVelocity='0 2 0' "
                           "inertia='0.1 0 0 0 0.1 0 0 0 0.1'/></RigidBodyCollection>", duration=0.5)
    q0 = R.from_axis_angle(np.array([0, 1, 0, 0.5]))
    com0 = np.array([1, 2, 3]) + R.rotate(q0, [0.3, 0, 0])
    q = R.from_axis_angle(last(s, "B", "orientation"))
    com = last(s, "B", "position") + R.rotate(q, [0.3, 0, 0])
    # linearVelocity 0 is the centre of mass's: the origin circles it. DART integrates the
    # free joint at the origin, so Euler lets the centre of mass wander by at most about
    # r w^2 dt t = 0.3 * 4 * dt * 0.5 over the run (the same bound as MuJoCo's)
    assert np.linalg.norm(com - com0) < 0.3 * 4 * DT * 0.5
    assert last(s, "B", "angularVelocity") == pytest.approx([0, 2, 0], abs=1e-12)


def test_forces_act_at_an_offset_centre_of_mass(tmp_path):
    # DART's body frame is X3D's, the centre of mass an offset in it: the forces go there, so a
    # turned body with an offset centre of mass takes no spin from them
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'>"
                           "<RigidBody DEF='F' mass='2' useGlobalGravity='false' forces='1 0 0, 3 0 0' "
                           "orientation='0 0 1 0.7' centerOfMass='0.2 0.1 0'/></RigidBodyCollection>")
    assert last(s, "F", "linearVelocity") == pytest.approx([2.0, 0, 0], abs=1e-12)
    assert np.abs(values(s, "F", "angularVelocity")).max() < 1e-12


def test_sleeping_is_off(tmp_path):
    # DART's deactivation is on by default (bodies under 1 cm/s for 0.5 s may be put to
    # sleep); X3D bodies sleep only where autoDisable says so
    world = scene_worlds(tmp_path, "<RigidBodyCollection><RigidBody/></RigidBodyCollection>")[0]
    assert not BACKEND.build(world, DT).dart_world.getDeactivationOptions().mEnabled
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='B' linearVelocity='0.001 0 0'/>"
                           "</RigidBodyCollection>", duration=2.0)
    assert last(s, "B", "position")[0] == pytest.approx(0.002, abs=1e-12)


PENDULUM = """<RigidBodyCollection gravity='0 -9.81 0' {damp}>
  <RigidBody DEF='Anchor' fixed='true'/>
  <RigidBody DEF='Bob' position='{x} {y} 0' inertia='{i} 0 0 0 {i} 0 0 0 {i}' {body}/>
  <SingleAxisHingeJoint DEF='H' axis='0 0 1' forceOutput='"ALL"' {limits}>
    <RigidBody USE='Anchor' containerField='body1'/><RigidBody USE='Bob' containerField='body2'/>
  </SingleAxisHingeJoint></RigidBodyCollection>"""


def pendulum(theta0: float, limits: str = "", body: str = "", i: float = 1e-3) -> str:
    return PENDULUM.format(x=math.sin(theta0), y=-math.cos(theta0), i=i, limits=limits, body=body, damp="")


def upward_crossings(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Times where x passes upward through 0, linearly interpolated between samples."""
    k = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    return t[k] - x[k] * (t[k + 1] - t[k]) / (x[k + 1] - x[k])


SLIDERS = """<RigidBodyCollection gravity='0 -9.81 0'>
  <RigidBody DEF='One' position='0 0 0'/><RigidBody DEF='Two' position='1 0 0'/>
  <SliderJoint DEF='S1' axis='0 1 0' minSeparation='-0.1' maxSeparation='0.2' forceOutput='"separation"'>
    <RigidBody USE='One' containerField='body1'/></SliderJoint>
  <SliderJoint DEF='S2' axis='0 1 0' minSeparation='-0.1' maxSeparation='0.2' forceOutput='"separation"'>
    <RigidBody USE='Two' containerField='body2'/></SliderJoint></RigidBodyCollection>"""


def test_slider_stops_hold_on_either_side(tmp_path):
    s = simulate(tmp_path, SLIDERS, frame_rate=240)
    # separation is body1 relative to body2 along the axis: One's drop is +separation, Two's
    # is -separation, so the stops catch One at -0.1 (min) and Two at -0.2 (max, mirrored)
    one, two = values(s, "S1", "separation")[:, 0], values(s, "S2", "separation")[:, 0]
    assert one.min() >= -0.1 - 1e-9 and two.max() <= 0.2 + 1e-9
    # DART's limits are predictive: the step that would pass the stop ends on it, and the
    # stop holds after; only rounding is left
    assert one[-1] == pytest.approx(-0.1, abs=1e-9) and two[-1] == pytest.approx(0.2, abs=1e-9)
    assert last(s, "One", "position") == pytest.approx([0, -0.1, 0], abs=1e-9)
    assert last(s, "Two", "position") == pytest.approx([1, -0.2, 0], abs=1e-9)


@pytest.mark.parametrize("bob", ["body1", "body2"])
def test_hinge_stops_hold_on_either_side(tmp_path, bob):
    anchor = "body2" if bob == "body1" else "body1"
    s = simulate(tmp_path, f"""<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='Anchor' fixed='true'/>
      <RigidBody DEF='Bob' position='1 0 0' inertia='1e-3 0 0 0 1e-3 0 0 0 1e-3'/>
      <SingleAxisHingeJoint DEF='H' axis='0 0 1' minAngle='-0.5' maxAngle='0.3' forceOutput='"angle"'>
        <RigidBody USE='Anchor' containerField='{anchor}'/><RigidBody USE='Bob' containerField='{bob}'/>
      </SingleAxisHingeJoint></RigidBodyCollection>""", frame_rate=240)
    angle = values(s, "H", "angle")[:, 0]
    # released horizontal, Bob turns clockwise about z: as body1 the angle falls to the
    # minimum, as body2 (the angle is then the anchor's relative to Bob) it rises to the maximum
    stop = -0.5 if bob == "body1" else 0.3
    assert angle[-1] == pytest.approx(stop, abs=1e-9)
    assert angle.min() >= -0.5 - 1e-9 and angle.max() <= 0.3 + 1e-9


def test_auto_damp_on_a_jointed_body_fits_through_the_jacobians(tmp_path):
    mujoco_backend = pytest.importorskip("backends.mujoco").BACKEND
    scene = PENDULUM.format(x=math.sin(0.8), y=-math.cos(0.8), i=1e-3, limits="", damp="",
                            body="autoDamp='true' angularDampingFactor='0.01' linearDampingFactor='0.01'")
    d, m = simulate(tmp_path, scene), simulate(tmp_path, scene, backend=mujoco_backend)
    assert np.abs(values(d, "H", "angle") - values(m, "H", "angle")).max() < 1e-3
    undamped = simulate(tmp_path, pendulum(0.8))
    assert np.abs(values(d, "H", "angleRate")).max() < 0.9 * np.abs(values(undamped, "H", "angleRate")).max()


AGREEMENT = {
    # the hinge's child is body2 (limits mirrored) and then body1
    # the limits are wide enough not to be reached, but would be if they were not mirrored
    "hinge, child body2": pendulum(0.6, limits="minAngle='-0.2' maxAngle='1.3'"),
    "hinge, child body1": """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='Bob' position='0.6 -0.8 0' orientation='1 0 0 0.5' inertia='0.01 0 0 0 0.02 0 0 0 0.03'/>
      <SingleAxisHingeJoint DEF='H' axis='0 0 1' minAngle='-1.4' maxAngle='0.3' forceOutput='"ALL"'>
        <RigidBody USE='Bob' containerField='body1'/></SingleAxisHingeJoint></RigidBodyCollection>""",
    "double pendulum": """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='A' position='0.5 0 0' inertia='0.01 0 0 0 0.01 0 0 0 0.01'/>
      <RigidBody DEF='B' position='1.5 0 0' orientation='0 1 0 0.3' centerOfMass='0.1 0 0'/>
      <SingleAxisHingeJoint DEF='H1' axis='0 0 1' forceOutput='"ALL"'>
        <RigidBody USE='A' containerField='body2'/></SingleAxisHingeJoint>
      <SingleAxisHingeJoint DEF='H2' anchorPoint='1 0 0' axis='0 0 1' forceOutput='"ALL"'>
        <RigidBody USE='B' containerField='body1'/><RigidBody USE='A' containerField='body2'/>
      </SingleAxisHingeJoint></RigidBodyCollection>""",
    "slider, child body2": """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='Rail' fixed='true'/><RigidBody DEF='Cart' position='0 0 0' centerOfMass='0 0.2 0'/>
      <SliderJoint DEF='S' axis='0.6 -0.8 0' minSeparation='-5' maxSeparation='0.1' forceOutput='"ALL"'>
        <RigidBody USE='Rail' containerField='body1'/><RigidBody USE='Cart' containerField='body2'/>
      </SliderJoint></RigidBodyCollection>""",
    "universal": """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='Top' fixed='true'/>
      <RigidBody DEF='Arm' position='0.3 -1 0.2' angularVelocity='1 0 2' inertia='0.02 0 0 0 0.01 0 0 0 0.03'/>
      <UniversalJoint DEF='U' axis1='1 0 0' axis2='0 0 1' forceOutput='"ALL"'>
        <RigidBody USE='Top' containerField='body1'/><RigidBody USE='Arm' containerField='body2'/>
      </UniversalJoint></RigidBodyCollection>""",
    "ball chain": """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='A' position='0.5 0 0.2' angularVelocity='0 1 0'/><RigidBody DEF='B' position='1 -0.5 0.2'/>
      <BallJoint DEF='J1' forceOutput='"ALL"'><RigidBody USE='A' containerField='body1'/></BallJoint>
      <BallJoint DEF='J2' anchorPoint='1 0 0.2' forceOutput='"ALL"'>
        <RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/>
      </BallJoint></RigidBodyCollection>""",
}


@pytest.mark.parametrize("name", list(AGREEMENT))
def test_joint_outputs_agree_with_mujoco(tmp_path, name):
    mujoco_backend = pytest.importorskip("backends.mujoco").BACKEND
    d = simulate(tmp_path, AGREEMENT[name])
    m = simulate(tmp_path, AGREEMENT[name], backend=mujoco_backend)
    assert d.keys() == m.keys()
    compared = 0
    for (node, field), series in d.items():
        if field in ("angle", "separation", "position", "body1AnchorPoint", "body2AnchorPoint",
                     "body1Axis", "body2Axis"):
            # both integrate the same tree in generalized coordinates with semi-implicit
            # Euler; they differ in rounding and (ball joints) in how a rotation is
            # integrated, O(dt^2) a step, and no run reaches a stop (MuJoCo's are soft,
            # DART's hard). 1e-3 (rad or m) over 1 s
            gap = np.abs(values(d, node, field) - values(m, node, field)).max()
            assert gap < 1e-3, (node, field, gap)
            compared += 1
    assert compared >= 3


def four_bar(loop: str, theta0: float) -> str:
    """A parallelogram hanging from pivots at x = 0 and x = 1: two 1 m cranks A and C and a
    coupler B; B-C closes the loop."""
    s, c, i = math.sin(theta0), math.cos(theta0), 1 / 12
    return f"""<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='A' position='{s / 2} {-c / 2} 0' orientation='0 0 1 {theta0}' inertia='{i} 0 0 0 1e-3 0 0 0 {i}'/>
      <RigidBody DEF='C' position='{1 + s / 2} {-c / 2} 0' orientation='0 0 1 {theta0}'
          inertia='{i} 0 0 0 1e-3 0 0 0 {i}'/>
      <RigidBody DEF='B' position='{0.5 + s} {-c} 0' inertia='1e-3 0 0 0 {i} 0 0 0 {i}'/>
      <SingleAxisHingeJoint DEF='J1' axis='0 0 1' forceOutput='"angle"'>
        <RigidBody USE='A' containerField='body1'/></SingleAxisHingeJoint>
      <SingleAxisHingeJoint DEF='J4' anchorPoint='1 0 0' axis='0 0 1'>
        <RigidBody USE='C' containerField='body1'/></SingleAxisHingeJoint>
      <SingleAxisHingeJoint DEF='J2' anchorPoint='{s} {-c} 0' axis='0 0 1'>
        <RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/>
      </SingleAxisHingeJoint>
      <{loop} DEF='J3' anchorPoint='{1 + s} {-c} 0' {'axis="0 0 1"' if loop != 'BallJoint' else ''}
          forceOutput='"ALL"'>
        <RigidBody USE='B' containerField='body1'/><RigidBody USE='C' containerField='body2'/>
      </{loop}></RigidBodyCollection>"""


@pytest.mark.parametrize("loop", ["SingleAxisHingeJoint", "BallJoint"])
def test_four_bar_loop_stays_closed_and_keeps_its_period(tmp_path, loop):
    theta0 = math.radians(5)
    s = simulate(tmp_path, four_bar(loop, theta0), duration=4.0, frame_rate=240)
    # the loop is a velocity-level constraint: each step leaves a position error of order
    # a dt^2 ~ 1e-4 m that ERP 0.8 takes back at the next, and the default CFM (1e-4,
    # converted to DART's relative form) softens it a little: 1e-4 m bounds the gap
    gaps = np.linalg.norm(values(s, "J3", "body1AnchorPoint") - values(s, "J3", "body2AnchorPoint"), axis=1)
    assert gaps.max() < 1e-4
    assert np.abs(values(s, "B", "position")[:, 2]).max() < 1e-9  # stays in its plane
    # cranks (1/3 kg m^2 each about their pivots) and a translating 1 kg coupler:
    # I = 2/3 + 1 = 5/3, gravity's torque 2 g sin(theta): w^2 = 1.2 g
    swing = values(s, "J1", "angle")[:, 0] + theta0
    crossings = upward_crossings(times(s, "J1", "angle"), swing)
    period = (crossings[-1] - crossings[0]) / (len(crossings) - 1)
    assert period == pytest.approx(2 * math.pi / math.sqrt(1.2 * G) * (1 + theta0 ** 2 / 16), rel=0.01)


def test_hinge_closing_a_loop_over_a_ball_joint_makes_it_a_hinge(tmp_path):
    # A hangs from a ball joint; a hinge about z at the same anchor closes a loop and
    # leaves one turn about z: A's centre of mass, off the plane z = 0, keeps its z while it
    # swings. With the ball joint alone it would swing under the pivot. A is turned, so
    # its local axes are not the world's
    joints = """<BallJoint DEF='B'><RigidBody USE='A' containerField='body1'/></BallJoint>
      <SingleAxisHingeJoint DEF='H' axis='0 0 1' forceOutput='"angle"'>
        <RigidBody USE='A' containerField='body1'/></SingleAxisHingeJoint>"""
    body = """<RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='A' position='0.5 -0.5 0.3' orientation='1 0 0 1.2' inertia='0.02 0 0 0 0.03 0 0 0 0.04'/>
      {joints}</RigidBodyCollection>"""
    loop = simulate(tmp_path, body.format(joints=joints))
    hinge = simulate(tmp_path, body.format(joints=joints.split("</BallJoint>")[1]))
    # as in the four-bar: the loop's position error stays under 1e-4 m
    assert np.abs(values(loop, "A", "position")[:, 2] - 0.3).max() < 1e-4
    assert np.abs(values(hinge, "H", "angle")).max() > 1.0
    assert np.abs(values(loop, "H", "angle") - values(hinge, "H", "angle")).max() < 1e-3


def test_two_collections_keep_their_own_error_correction(tmp_path):
    # DART's loop ERP and CFM are class-wide: each world must set its own before it steps
    soft, stiff = (four_bar("BallJoint", 0.3).replace("gravity='0 -9.81 0'", f"gravity='0 -9.81 0' {extra}")
                   for extra in ("errorCorrection='0.1' constantForceMix='0.01'", "errorCorrection='1'"))
    both = simulate(tmp_path, soft.replace("DEF='", "DEF='s").replace("USE='", "USE='s") + stiff)
    soft_alone, stiff_alone = simulate(tmp_path, soft), simulate(tmp_path, stiff)
    assert np.array_equal(values(both, "sJ1", "angle"), values(soft_alone, "J1", "angle"))
    assert np.array_equal(values(both, "J1", "angle"), values(stiff_alone, "J1", "angle"))
    assert not np.array_equal(values(soft_alone, "J1", "angle"), values(stiff_alone, "J1", "angle"))


@pytest.mark.parametrize("mass", [1.0, 4.0])
def test_constant_force_mix_softens_loops_as_ode_does_for_a_unit_mass(tmp_path, mass):
    # a body on a vertical slider (tree) held up by a ball joint closing a loop: ODE's loop
    # is a spring k = ERP / (dt CFM) and settles m g / k low. DART's relative CFM, converted
    # for a unit effective mass (here 1/m along the slider), gives that sag for 1 kg and
    # (1 + 1/m) / 2 of it otherwise: the approximation the feature table declares
    cfm, erp = 0.01, 0.8
    s = simulate(tmp_path, f"""<RigidBodyCollection gravity='0 -9.81 0' constantForceMix='{cfm}'
        errorCorrection='{erp}'><RigidBody DEF='A' mass='{mass}'/>
      <SliderJoint axis='0 1 0' minSeparation='-1' maxSeparation='1'><RigidBody USE='A' containerField='body1'/>
      </SliderJoint><BallJoint><RigidBody USE='A' containerField='body1'/></BallJoint></RigidBodyCollection>""",
                 duration=2.0)
    ode = mass * G * DT * cfm / erp
    assert -last(s, "A", "position")[1] == pytest.approx(ode * (1 + 1 / mass) / 2, rel=1e-6)


def test_a_slider_closing_a_loop_is_refused(tmp_path):
    with pytest.raises(Unsupported, match="SliderJoint S closes a loop"):
        simulate(tmp_path, """<RigidBodyCollection>
          <RigidBody DEF='A' position='1 0 0'/>
          <SingleAxisHingeJoint DEF='H' axis='0 0 1'><RigidBody USE='A' containerField='body1'/></SingleAxisHingeJoint>
          <SliderJoint DEF='S' axis='1 0 0'><RigidBody USE='A' containerField='body1'/></SliderJoint>
          </RigidBodyCollection>""")


def test_declared_features_use_the_reference_names():
    mujoco_backend = pytest.importorskip("backends.mujoco").BACKEND
    assert set(BACKEND.declared) <= set(mujoco_backend.declared)


# -- DoubleAxisHingeJoint (ODE's hinge2) ------------------------------------------------

HINGE2 = """<RigidBodyCollection gravity='0 {g} 0'>
  <RigidBody DEF='Car' fixed='true'/>
  <RigidBody DEF='Wheel' position='1 0 0' mass='{m}' inertia='0.1 0 0 0 0.1 0 0 0 0.1'/>
  <DoubleAxisHingeJoint DEF='H2' anchorPoint='1 0 0' axis1='0 1 0' axis2='1 0 0' desiredAngularVelocity2='3'
     maxTorque2='5' suspensionForce='{cfm}' suspensionErrorCorrection='{erp}' forceOutput='"ALL"'>
    <RigidBody USE='{b1}' containerField='body1'/><RigidBody USE='{b2}' containerField='body2'/>
  </DoubleAxisHingeJoint></RigidBodyCollection>"""


def hinge2(g: float = 0.0, m: float = 1.0, cfm: float = 0.0, erp: float = 0.5, wheel_is_body1: bool = False) -> str:
    b1, b2 = ("Wheel", "Car") if wheel_is_body1 else ("Car", "Wheel")
    return HINGE2.format(g=g, m=m, cfm=cfm, erp=erp, b1=b1, b2=b2)


@pytest.mark.parametrize("cfm", [0.0, 0.001], ids=["universal", "suspension"])
@pytest.mark.parametrize("wheel_is_body1", [False, True])
def test_hinge2_motor_reaches_its_speed_within_its_torque(tmp_path, cfm, wheel_is_body1):
    s = simulate(tmp_path, hinge2(cfm=cfm, wheel_is_body1=wheel_is_body1), duration=0.5, frame_rate=240)
    rate = {round(t * 240): v[0] for t, v in s[("H2", "hinge2AngleRate")]}
    # ODE's motor reaches its target in one step if its torque allows: 5 N m on 0.1 kg m^2
    # is 50 rad/s^2 (the wheel turns about its centre of mass), 1.25 rad/s after 6 steps,
    # whichever body is the child (the rate is body1's relative to body2 either way). The
    # torque comes from DART's own next-step velocity: only rounding is left, and with the
    # suspension the links between the joints (1e-12 of the wheel; measured 2e-12 relative
    # when hinge 2 is the parent's joint and turns them too)
    assert rate[6] == pytest.approx(50 * 6 * DT, rel=1e-11)
    assert rate[120] == pytest.approx(3.0, abs=1e-12)  # then held at the target
    assert np.abs(values(s, "H2", "hinge1AngleRate")).max() < 1e-12


def odes_suspension(cfm: float, erp: float, m: float, g: float, steps: int) -> np.ndarray:
    """ODE's soft row between a fixed body and a mass m under gravity g along it: an implicit
    spring-damper, m (v' - v) = -h (k (x + h v') + c v' + m g), x' = x + h v'."""
    k, c = erp / (DT * cfm), (1 - erp) / cfm
    x, v, out = 0.0, 0.0, [0.0]
    for _ in range(steps):
        v = (m * v - DT * (k * x + m * g)) / (m + DT * c + DT * DT * k)
        x += DT * v
        out.append(x)
    return np.array(out)


@pytest.mark.parametrize("cfm,erp", [(0.001, 0.5), (0.01, 0.2), (0.01, 0.0)])
def test_hinge2_suspension_is_odes_spring(tmp_path, cfm, erp):
    s = simulate(tmp_path, hinge2(g=-G, m=2, cfm=cfm, erp=erp), duration=2.0, frame_rate=240)
    height = values(s, "Wheel", "position")[:, 1]
    # DART's joint spring-damper is implicit, f = -k (q + h v') - c v': ODE's soft row, so the
    # wheel follows ODE's recurrence step for step (the links between the joints, 1e-12 of
    # the wheel's mass, and rounding are all that is left: 1e-9 of the motion bounds them)
    ode = odes_suspension(cfm, erp, 2.0, G, len(height) - 1)
    assert np.abs(height - ode).max() < 1e-9 * np.abs(ode).max()
    if erp > 0:  # settled at m g / k, k = ERP / (h CFM)
        assert height[-1] == pytest.approx(-2 * G * DT * cfm / erp, rel=1e-9)
    anchors = values(s, "H2", "body1AnchorPoint") - values(s, "H2", "body2AnchorPoint")
    assert anchors[-1] == pytest.approx([0, -height[-1], 0], abs=1e-12)  # the spring stretches along axis 1


@pytest.mark.parametrize("wheel_is_body1", [True, False])
def test_hinge2_limits_hold_when_body1_is_the_moving_body(tmp_path, wheel_is_body1):
    first, second = ("Wheel", "Car") if wheel_is_body1 else ("Car", "Wheel")
    s = simulate(tmp_path, f"""<RigidBodyCollection gravity='0 0 0'>
      <RigidBody DEF='Car' fixed='true'/>
      <RigidBody DEF='Wheel' position='1 0 0' inertia='0.1 0 0 0 0.1 0 0 0 0.1'/>
      <DoubleAxisHingeJoint DEF='H2' anchorPoint='1 0 0' axis1='0 1 0' axis2='1 0 0' minAngle1='-0.3'
          maxAngle1='0.5' desiredAngularVelocity1='-1' maxTorque1='10' forceOutput='"hinge1Angle"'>
        <RigidBody USE='{first}' containerField='body1'/><RigidBody USE='{second}' containerField='body2'/>
      </DoubleAxisHingeJoint></RigidBodyCollection>""", duration=1.0)
    angles = values(s, "H2", "hinge1Angle")[:, 0]
    # driven at -1 rad/s (body1 relative to body2, whichever is the child) into the stop at
    # -0.3: DART's stops are predictive, so the step that would pass it ends on it, short of
    # it by its relative CFM (1e-9 of the last step's 1/240 rad) at most
    assert angles.min() > -0.3 - 1e-9 and angles[-1] == pytest.approx(-0.3, abs=1e-9)


LIFT = """<RigidBodyCollection gravity='0 -9.81 0'>
  <RigidBody DEF='Car' fixed='true'/>
  <RigidBody DEF='Wheel' position='1 0 0' centerOfMass='0.1 0 0' inertia='0.1 0 0 0 0.1 0 0 0 0.1'/>
  <DoubleAxisHingeJoint DEF='H2' anchorPoint='1 0 0' axis1='0 0 1' axis2='1 0 0' minAngle1='-0.5' maxAngle1='0'
      desiredAngularVelocity1='-1' maxTorque1='{torque}' {suspension} forceOutput='"hinge1Angle" "hinge1AngleRate"'>
    <RigidBody USE='Car' containerField='body1'/><RigidBody USE='Wheel' containerField='body2'/>
  </DoubleAxisHingeJoint></RigidBodyCollection>"""


@pytest.mark.parametrize("suspension", ["", "suspensionForce='0.001' suspensionErrorCorrection='0.5'"],
                         ids=["universal", "suspension"])
@pytest.mark.parametrize("torque", [0.5, 1.2])
def test_hinge2_motor_leaves_a_stop_only_when_stronger_than_the_load(tmp_path, torque, suspension):
    s = simulate(tmp_path, LIFT.format(torque=torque, suspension=suspension), duration=0.25, frame_rate=240)
    angle, rate = values(s, "H2", "hinge1Angle")[:, 0], values(s, "H2", "hinge1AngleRate")[:, 0]
    # gravity presses hinge 1 on its stop at 0 with m g r = 0.981 N m; the motor pulls it
    # off at maxTorque1. ODE's stop and motor rows act together: the joint leaves only if the
    # motor is the stronger, turning at (T - m g r cos(angle)) / (I + m r^2). (DART's SERVO
    # actuator stayed on the stop here at 1.2 N m: its stop row takes priority)
    if torque < 0.981:
        assert np.abs(angle).max() < 1e-9 and np.abs(rate).max() < 1e-9
    else:
        # by step 30 the angle is 0.016 rad: cos changes the load by 1.3e-4 of itself
        assert rate[30] == pytest.approx(-(torque - 0.981) / 0.11 * 30 * DT, rel=1e-3)
        assert angle[-1] < -0.05


H2_TREE = """<RigidBodyCollection gravity='0 -9.81 0'>
  <RigidBody DEF='Top' fixed='true'/>
  <RigidBody DEF='Car' position='0 -0.5 0' mass='3' inertia='0.05 0 0 0 0.06 0 0 0 0.07' angularVelocity='0 0.5 0'
      {fixed}/>
  <RigidBody DEF='Wheel' position='1 -0.7 0.1' orientation='0 0 1 0.3' centerOfMass='0.1 0 0.05'
      inertia='0.05 0.01 0 0.01 0.08 0 0 0 0.1' angularVelocity='0.5 1 2'/>
  {hang}
  <DoubleAxisHingeJoint DEF='H2' anchorPoint='1 -0.5 0' axis1='0 0.6 0.8' axis2='1 0 0' minAngle1='{lo}'
      maxAngle1='{hi}' desiredAngularVelocity1='-20' maxTorque1='0.05' desiredAngularVelocity2='30' maxTorque2='0.3'
      {suspension} forceOutput='"ALL"'>
    <RigidBody USE='{b1}' containerField='body1'/><RigidBody USE='{b2}' containerField='body2'/>
  </DoubleAxisHingeJoint></RigidBodyCollection>"""
HANG = ("<BallJoint DEF='Hang'><RigidBody USE='Top' containerField='body1'/>"
        "<RigidBody USE='Car' containerField='body2'/></BallJoint>")
# hinge 1's range of motion in each run is inside these stops by 0.1 rad or more, and
# reaches past the mirrored stops (-hi, -lo) were they not mirrored for the child's side
H2_CASES = {"fixed car, wheel body2": (True, False, -0.45, 1.3), "fixed car, wheel body1": (True, True, -1.35, 0.4),
            "hung car, wheel body2": (False, False, -1.3, 0.65), "hung car, wheel body1": (False, True, -0.1, 1.1)}


def h2_tree(name: str, suspension: bool) -> str:
    fixed, wheel_is_body1, lo, hi = H2_CASES[name]
    b1, b2 = ("Wheel", "Car") if wheel_is_body1 else ("Car", "Wheel")
    # a suspension with ERP 0 is a pure damper, c = 1/CFM, which MuJoCo integrates as ODE does
    damper = "suspensionForce='0.01' suspensionErrorCorrection='0'" if suspension else ""
    return H2_TREE.format(fixed="fixed='true'" if fixed else "", hang="" if fixed else HANG, lo=lo, hi=hi, b1=b1,
                          b2=b2, suspension=damper)


@pytest.mark.parametrize("suspension", [False, True], ids=["universal", "damper"])
@pytest.mark.parametrize("name", list(H2_CASES))
def test_hinge2_outputs_agree_with_mujoco(tmp_path, name, suspension):
    mujoco_backend = pytest.importorskip("backends.mujoco").BACKEND
    scene = h2_tree(name, suspension)
    d, m = simulate(tmp_path, scene), simulate(tmp_path, scene, backend=mujoco_backend)
    assert d.keys() == m.keys()
    # Both integrate the same tree with semi-implicit Euler (the damper implicitly in both);
    # both motors stay at their torque limits the whole run (targets of -20 and 30 rad/s),
    # where MuJoCo's clipped servo applies exactly maxTorque, as ODE's motor does; no stop is
    # reached. What is left (measured): rounding, 4e-14 with a fixed car; the links between
    # the joints, 1e-11 with the suspension; 3e-9 with the car on a ball joint, which DART
    # turns by the exponential of its whole twist (so for any joint below a ball or free
    # root). 1e-6 is far above these and far below a wrong sign, axis or order (0.1 and up)
    for (node, field), series in d.items():
        gap = np.abs(values(d, node, field) - values(m, node, field)).max()
        assert gap < 1e-6, (node, field, gap)
    hinge1 = values(d, "H2", "hinge1Angle")[:, 0]
    assert np.ptp(hinge1) > 0.9 and np.ptp(values(d, "H2", "hinge2Angle")) > 0.6  # and both hinges turned
    if suspension:  # and the damper gave: the anchors parted along axis 1
        gaps = np.linalg.norm(values(d, "H2", "body1AnchorPoint") - values(d, "H2", "body2AnchorPoint"), axis=1)
        assert gaps.max() > 0.03


def test_hinge2_links_weigh_nothing_measurable(tmp_path, monkeypatch):
    """The links between a suspended hinge2's joints carry _LINK_MASS of the child's mass:
    against MuJoCo's massless joint stack the outputs move in proportion to it, so it is
    their only effect, and at its value the effect is under 1e-10."""
    mujoco_backend = pytest.importorskip("backends.mujoco").BACKEND
    from backends import dart as dart_backend
    scene = h2_tree("fixed car, wheel body1", suspension=True)
    m = simulate(tmp_path, scene, backend=mujoco_backend)

    def gap() -> float:
        d = simulate(tmp_path, scene)
        return max(np.abs(values(d, n, f) - values(m, n, f)).max() for n, f in d)

    default = gap()
    monkeypatch.setattr(dart_backend, "_LINK_MASS", 1e-6)
    heavy = gap()
    assert default < 1e-10
    assert 1e-7 < heavy < 1e-4  # measured 1.2e-5: about 10 times the link mass, rad/s over 1 s
    assert heavy / default > 1e4


def test_hinge2_declarations():
    d = BACKEND.support
    for f in ("DoubleAxisHingeJoint", "DoubleAxisHingeJoint.axis1", "DoubleAxisHingeJoint.limits",
              "DoubleAxisHingeJoint.minAngle1"):
        assert d(f).support is base.Support.NATIVE, f
    for f in ("DoubleAxisHingeJoint.suspensionForce", "DoubleAxisHingeJoint.maxTorque2"):
        assert d(f).support is base.Support.APPROXIMATE and d(f).note, f
    for f in ("DoubleAxisHingeJoint.stop1Bounce", "DoubleAxisHingeJoint.stop1ErrorCorrection",
              "DoubleAxisHingeJoint.stop1ConstantForceMix"):
        assert d(f).support is base.Support.UNSUPPORTED and d(f).note != base.NOT_YET, f


def test_box_bounded_motor_torques_meet_their_optimality_conditions():
    from backends.dart import _box
    rng = np.random.default_rng(3)
    for _ in range(200):
        n = int(rng.integers(1, 6))
        a = rng.normal(size=(n, n))
        s = a @ a.T + 0.1 * np.eye(n)
        r, limit = rng.normal(size=n) * 3, rng.uniform(0.1, 2, size=n)
        x = _box(s, r, limit)
        wants = r - s @ x  # minus the gradient of x.s.x/2 - x.r
        inside = np.abs(x) < limit - 1e-12
        assert np.all(np.abs(x) <= limit + 1e-15)
        assert np.abs(wants[inside]).max(initial=0) < 1e-9  # unbounded ones solve their rows
        assert np.all(wants[~inside] * np.sign(x[~inside]) >= -1e-9)  # bounded ones push against their limit
