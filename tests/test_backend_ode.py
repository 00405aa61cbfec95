"""What only the ODE backend does: its ctypes binding (double precision, a missing library as an
import error), bodies at the centre of mass read back at the X3D origin, state in bulk, finite
rotation, refusals of input ODE would abort on, stops mirrored for either body (ODE's reversed
attach), the hinge2 suspension as ODE's soft row, and preferAccuracy TRUE as dWorldStep: the
conformance cases run ODE's quick-step (X3D's default), whose 10 sweeps leave the pendulum, stop and
bounce cases failing (tests/test_conformance.py), so the joint tests here run dWorldStep with
constantForceMix 0 where the closed form is for a rigid joint. The shared physics (free fall,
gravity off, loads, the hinge2 motor) is in the conformance cases (conformance/cases/)."""

from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest

from backends import base

try:
    from backends.ode import BACKEND
except ImportError as e:  # the library is missing: only the unavailable path is tested
    pytest.skip(f"ODE is not installed: {e}", allow_module_level=True)

from backends import ode_lib  # noqa: E402
from conformance.cases.closed_forms import ellipk  # noqa: E402
from engine_run import (DT, G, ODD_BODY, ODD_SCENE, assert_odd_body_reads_back, last, run_x3d,  # noqa: E402
                        same_rotation, scene_worlds, times, values)
from x3d_core.semantics import rotation as R  # noqa: E402
from x3d_core.semantics.engine import Unsupported  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def simulate(tmp_path, body: str, *args, **kwargs):
    return run_x3d(tmp_path, body, *args, **{"backend": BACKEND, **kwargs})


RIGID = "preferAccuracy='true' constantForceMix='0'"


def test_registered_under_its_name_in_double_precision():
    assert base.load("ode") is BACKEND
    assert BACKEND.version().startswith("0.16")
    assert ode_lib.lib.dCheckConfiguration(b"ODE_double_precision") == 1


_NO_LIBODE = """
import ctypes, ctypes.util
find = ctypes.util.find_library
ctypes.util.find_library = lambda name: None if name == "ode" else find(name)
class CDLL(ctypes.CDLL):
    def __init__(self, name, *args, **kwargs):
        if name and "libode" in str(name):
            raise OSError(name + ": cannot open shared object file")
        super().__init__(name, *args, **kwargs)
ctypes.CDLL = CDLL
from backends import base
found = base.available()
print(found["ode"])
print(sorted(n for n, b in found.items() if not isinstance(b, str)))
"""


def test_a_missing_library_is_an_import_error_naming_the_install_command():
    out = subprocess.run([sys.executable, "-c", _NO_LIBODE], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    reason, usable = out.stdout.strip().splitlines()
    assert reason.startswith("unavailable:") and "apt-get install libode8" in reason
    assert "ode" not in usable and "mujoco" in usable  # the others load as before


def test_centre_of_mass_offset_and_orientation_read_back_as_given(tmp_path):
    # ODE's body sits at the centre of mass: the X3D origin comes back by taking the offset off
    assert_odd_body_reads_back(simulate(tmp_path, ODD_SCENE, duration=0.1))


def test_spin_about_the_centre_of_mass_keeps_it_exactly_in_place(tmp_path):
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='B' position='1 2 3' "
                           "orientation='0 1 0 0.5' centerOfMass='0.3 0 0' angularVelocity='0 2 0' "
                           "inertia='0.1 0 0 0 0.1 0 0 0 0.1'/></RigidBodyCollection>", duration=0.5)
    q0 = R.from_axis_angle(np.array([0, 1, 0, 0.5]))
    com0 = np.array([1, 2, 3]) + R.rotate(q0, [0.3, 0, 0])
    for p, r in zip(values(s, "B", "position"), values(s, "B", "orientation")):
        # ODE integrates at the centre of mass, which does not move: only rounding is left
        assert p + R.rotate(R.from_axis_angle(r), [0.3, 0, 0]) == pytest.approx(com0, abs=1e-12)


def test_forces_act_at_an_offset_centre_of_mass(tmp_path):
    # the forces go to ODE's body, at the centre of mass: an offset one takes no spin from them
    s = simulate(tmp_path, "<RigidBodyCollection gravity='0 -9.81 0'>"
                           "<RigidBody DEF='F' mass='2' useGlobalGravity='false' forces='1 0 0, 3 0 0' "
                           "centerOfMass='0.2 0.1 0'/></RigidBodyCollection>")
    assert last(s, "F", "linearVelocity") == pytest.approx([2.0, 0, 0], abs=1e-12)
    assert np.abs(values(s, "F", "angularVelocity")).max() < 1e-12


def _pendulum(limits: str = "", ends: tuple[str, str] = ("Bob", "Pivot"), theta0: float = 0.1,
              extra: str = "") -> str:
    x, y = math.sin(theta0), -math.cos(theta0)
    return (f"<RigidBodyCollection gravity='0 -9.81 0' {RIGID}><RigidBody DEF='Pivot' fixed='true'/>"
            f"<RigidBody DEF='Bob' position='{x!r} {y!r} 0' inertia='1e-3 0 0 0 1e-3 0 0 0 1e-3'/>"
            f"<SingleAxisHingeJoint DEF='H' axis='0 0 1' {limits} {extra} forceOutput='\"ALL\"'>"
            f"<RigidBody USE='{ends[0]}' containerField='body1'/><RigidBody USE='{ends[1]}' containerField='body2'/>"
            "</SingleAxisHingeJoint></RigidBodyCollection>")


def test_pendulum_period(tmp_path):
    theta0 = 0.1
    s = simulate(tmp_path, _pendulum(theta0=theta0), duration=4.0, frame_rate=240)
    angle, t = values(s, "H", "angle")[:, 0] + theta0, times(s, "H", "angle")  # from the vertical
    up = np.flatnonzero((angle[:-1] < 0) & (angle[1:] >= 0))
    crossings = t[up] - angle[up] * DT / (angle[up + 1] - angle[up])
    period = float(np.mean(np.diff(crossings)))
    exact = 4 * math.sqrt(1.001 / G) * ellipk(math.sin(theta0 / 2))  # I_p = m L^2 + I
    # symplectic Euler shifts the frequency by (w h)^2 / 24 ~ 7e-6 relative; reading zero
    # crossings by linear interpolation between steps costs ~ (w h)^2 / 8 of a step, 1e-7 s
    assert period == pytest.approx(exact, rel=3e-5)


@pytest.mark.parametrize("ends,stop", [(("Bob", "Pivot"), -0.6), (("Pivot", "Bob"), 0.6)],
                         ids=["body1-moves", "body2-moves"])
def test_hinge_stops_hold_either_way_round(tmp_path, ends, stop):
    # the bob falls from the horizontal; the angle is body1's relative to body2, so with the
    # bob as body2 it rises and meets maxAngle: ODE's reversed attach keeps the convention
    lo, hi = (-0.6, 0.4) if stop < 0 else (-0.4, 0.6)
    s = simulate(tmp_path, _pendulum(f"minAngle='{lo}' maxAngle='{hi}'", ends, theta0=math.pi / 2), duration=1.5)
    angle = values(s, "H", "angle")[:, 0]
    v = math.sqrt(2 * G * math.sin(0.6))  # the bob's speed at the stop, 1 m out: rad/s
    # ODE's stops act once the angle is past them: at most a step's travel beyond
    assert angle.min() >= lo - v * DT and angle.max() <= hi + v * DT
    assert angle[-1] == pytest.approx(stop, abs=1e-3)


def test_hinge_stop_bounce(tmp_path):
    s = simulate(tmp_path, _pendulum("minAngle='-0.6' maxAngle='0.4'", theta0=math.pi / 2,
                                     extra="stopBounce='0.5'"), duration=1.0, frame_rate=240)
    rate = values(s, "H", "angleRate")[:, 0]
    k = int(np.argmax(rate > 0))  # the first step moving back up
    # ODE's bounce sets the speed after the impact step to -bounce times the speed before it
    # (which still holds up to one step's gravity, g h / L at most)
    assert rate[k] == pytest.approx(-0.5 * rate[k - 1], abs=0.5 * G * DT + 1e-6)


@pytest.mark.parametrize("ends,stop", [(("Car", "Base"), -0.3), (("Base", "Car"), 0.3)],
                         ids=["body1-moves", "body2-moves"])
def test_slider_stops_either_way_round(tmp_path, ends, stop):
    # the car falls: its separation (body1 relative to body2 along the axis) falls with the car
    # as body1 and rises with it as body2, onto the stop 0.3 m away either way
    s = simulate(tmp_path, f"""<RigidBodyCollection gravity='0 -9.81 0' {RIGID}>
      <RigidBody DEF='Base' fixed='true'/><RigidBody DEF='Car' position='0 1 0'/>
      <SliderJoint DEF='S' axis='0 1 0' minSeparation='{min(stop, -0.2 * np.sign(stop))}'
          maxSeparation='{max(stop, -0.2 * np.sign(stop))}' forceOutput='"separation"'>
        <RigidBody USE='{ends[0]}' containerField='body1'/><RigidBody USE='{ends[1]}' containerField='body2'/>
      </SliderJoint></RigidBodyCollection>""", duration=1.0)
    sep = values(s, "S", "separation")[:, 0]
    v = math.sqrt(2 * G * 0.3)  # the speed at the stop; ODE stops act once past them: a step's travel
    assert np.abs(sep).max() <= 0.3 + v * DT and sep[-1] == pytest.approx(stop, abs=1e-6)
    assert np.abs(values(s, "Car", "position")[:, [0, 2]]).max() < 1e-12  # only along the axis


_PUSHED = """<RigidBodyCollection gravity='0 0 0' {rigid}>
  <RigidBody DEF='Rail' fixed='true'/><RigidBody DEF='Car' linearVelocity='0 {v0} 0'/>{extra}
  <SliderJoint DEF='S' axis='0 1 0' minSeparation='-0.5' maxSeparation='{hi!r}' {fields}
      forceOutput='"separation" "separationRate"'>
    <RigidBody USE='Car' containerField='body1'/><RigidBody USE='{other}' containerField='body2'/>
  </SliderJoint></RigidBodyCollection>"""


def test_a_slider_stop_at_bounce_0_corrects_its_depth_and_sends_nothing_back(tmp_path):
    # stopBounce 0, "no bounce at all", and the default stopErrorCorrection 1, "all error should be
    # corrected in a single step" (37.4.13): the car, pushed at v0 into the max stop, ends the step
    # that crosses it 0.6 v0 h past (ODE's stops act once past them); the next step stops it and puts
    # it back on the stop. ODE's StopERP 1 made that correction a velocity that stayed: 0.6 v0 back
    v0, hi = 2.0, 0.3 + 0.4 * 2.0 * DT
    s = simulate(tmp_path, _PUSHED.format(rigid=RIGID, v0=v0, hi=hi, extra="", fields="", other="Rail"),
                 duration=0.5, frame_rate=240)
    sep, rate = values(s, "S", "separation")[:, 0], values(s, "S", "separationRate")[:, 0]
    k = int(np.argmax(sep > hi))  # the step that crosses the stop
    assert sep[k] == pytest.approx(hi + 0.6 * v0 * DT, abs=1e-12) and rate[k] == pytest.approx(v0, abs=1e-12)
    assert np.abs(sep[k + 1:] - hi).max() < 1e-12 and np.abs(rate[k + 1:]).max() < 1e-12


def test_a_slider_stops_correction_moves_each_side_whole_and_keeps_the_centre_of_mass(tmp_path):
    # the Car (1 kg, a 2 kg Tag ball-jointed to it 1 m behind, on the axis) slides away from a free
    # Sled (3 kg) into the max stop: the correction moves Car and Tag together, the sides by the
    # other's share of the mass, so the Tag keeps its place behind the Car and the centre of mass of
    # all three its straight line (every force acts along the one line: nothing turns)
    v0, hi = 2.0, 0.3 + 0.4 * 2.0 * DT
    extra = ("<RigidBody DEF='Tag' mass='2' position='0 -1 0' linearVelocity='0 2 0'/><RigidBody DEF='Sled' mass='3'/>"
             "<BallJoint anchorPoint='0 -0.5 0'><RigidBody USE='Car' containerField='body1'/>"
             "<RigidBody USE='Tag' containerField='body2'/></BallJoint>")
    s = simulate(tmp_path, _PUSHED.format(rigid=RIGID, v0=v0, hi=hi, extra=extra, fields="", other="Sled"),
                 duration=0.5, frame_rate=240)
    car, tag, sled = (values(s, n, "position") for n in ("Car", "Tag", "Sled"))
    sep, rate = values(s, "S", "separation")[:, 0], values(s, "S", "separationRate")[:, 0]
    k = int(np.argmax(sep > hi))
    assert np.abs(sep[k + 1:] - hi).max() < 1e-12 and np.abs(rate[k + 1:]).max() < 1e-12
    assert np.abs(tag - car - [0, -1, 0]).max() < 1e-12
    t = times(s, "Car", "position")
    centre = (1 * car + 2 * tag + 3 * sled) / 6  # momentum 3 v0 along y, all on the Car's side at the start
    assert np.abs(centre - np.outer(t, [0, 0.5 * v0, 0]) - centre[0]).max() < 1e-12


def test_hinge2_suspension_is_odes_spring(tmp_path):
    # body1 is the static environment: a kinematic ODE body stands in (ODE refuses a one-body
    # hinge2), and holds the wheel up on the spring
    erp, cfm, m = 0.2, 1e-3, 2.0
    s = simulate(tmp_path, f"""<RigidBodyCollection gravity='0 -9.81 0' {RIGID}>
      <RigidBody DEF='Chassis' fixed='true'/>
      <RigidBody DEF='Wheel' mass='{m}' position='0 0.5 0' inertia='0.025 0 0 0 0.025 0 0 0 0.05'/>
      <DoubleAxisHingeJoint anchorPoint='0 0.5 0' axis1='0 1 0' axis2='0 0 1'
          suspensionErrorCorrection='{erp}' suspensionForce='{cfm}'>
        <RigidBody USE='Chassis' containerField='body1'/><RigidBody USE='Wheel' containerField='body2'/>
      </DoubleAxisHingeJoint></RigidBodyCollection>""", duration=1.0)
    k = erp / (DT * cfm)  # ODE's soft row at rest: k = ERP / (h CFM); overdamped here, settled in 0.1 s
    assert last(s, "Wheel", "position") == pytest.approx([0, 0.5 - m * G / k, 0], abs=1e-9)


def test_bad_input_is_refused_not_a_crash(tmp_path):
    # ODE aborts the process on a zero axis or a one-sided mass: refused before it sees them
    world = scene_worlds(tmp_path, """<RigidBodyCollection><RigidBody DEF='A' fixed='true'/><RigidBody DEF='B'/>
      <SingleAxisHingeJoint axis='0 0 0'><RigidBody USE='A' containerField='body1'/>
      <RigidBody USE='B' containerField='body2'/></SingleAxisHingeJoint></RigidBodyCollection>""")[0]
    with pytest.raises(Unsupported, match="zero axis"):
        BACKEND.build(world, DT)
    world = scene_worlds(tmp_path, "<RigidBodyCollection><RigidBody/></RigidBodyCollection>")[0]
    world.bodies.mass[0] = 0.0  # the loaders refuse it in a file; a World built otherwise may hold it
    with pytest.raises(Unsupported, match="positive mass"):
        BACKEND.build(world, DT)


def test_state_and_velocities_round_trip_in_bulk(tmp_path):
    world = scene_worlds(tmp_path, f"<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='A' {ODD_BODY}/>"
                                   "<RigidBody DEF='F' fixed='true' position='0 1 0'/>"
                                   "<RigidBody DEF='C' position='5 0 0'/></RigidBodyCollection>")[0]
    sim = BACKEND.build(world, DT)
    lin, ang = np.array([[1.0, 2, 3], [4, 5, 6], [7, 8, 9]]), np.array([[0.1, 0.2, 0.3], [1, 1, 1], [0, 0, 1]])
    sim.set_velocities(lin, ang)
    s = sim.state()
    assert s.linear_velocity[[0, 2]] == pytest.approx(lin[[0, 2]], abs=0) and not s.linear_velocity[1].any()
    assert s.angular_velocity[[0, 2]] == pytest.approx(ang[[0, 2]], abs=0)
    assert s.position[1] == pytest.approx([0, 1, 0], abs=0)  # a fixed body is no ODE body


@pytest.mark.parametrize("finite", [True, False])
def test_finite_rotation_turns_by_the_exact_angle_about_its_axis(tmp_path, finite):
    """A torque-free sphere spinning at w = 100 rad/s about y. ODE's finite rotation mode with
    the axis along the spin turns it by exactly w h a step; its default (infinitesimal) mode
    adds h/2 w q to the quaternion and normalises, 2 atan(w h / 2) a step: 1.4% short at
    h = 1/240. Over 60 steps the two differ by 0.35 rad; rounding is ~1e-12 rad."""
    w, steps = 100.0, 60
    s = simulate(tmp_path, f"""<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='Top' angularVelocity='0 {w} 0'
        useFiniteRotation='{str(finite).lower()}' finiteRotationAxis='0 1 0' inertia='0.4 0 0 0 0.4 0 0 0 0.4'/>
        </RigidBodyCollection>""", duration=steps * DT)
    per_step = w * DT if finite else 2 * math.atan(w * DT / 2)
    assert same_rotation(last(s, "Top", "orientation"), np.array([0, 1, 0, math.remainder(steps * per_step,
                                                                                         2 * math.pi)]), 1e-9)


@pytest.mark.parametrize("spin", [[3, 0, 0], [1.2, -2.0, 1.6]], ids=["x", "oblique"])
def test_a_3x_wheel_with_no_finite_rotation_axis_turns_at_its_true_rate(tmp_path, spin):
    """An X3D 3.x RigidBody that sets useFiniteRotation and no finiteRotationAxis has the
    clause's default 0 0 0: ODE's full finite rotation, no axis. A torque-free sphere spinning
    at w keeps w exactly (isotropic inertia: no gyroscopic torque), and each step turns it by
    exactly |w| h about w, so after t its rotation is |w| t about w, to rounding (~1e-16 rad a
    step, 1e-13 over the 240 steps: the bound is 1e-9). X3D 4.0's default 0 1 0 would split
    off the spin across y, which ODE 0.16 integrates at half its rate: 1.5 rad behind for x."""
    w = np.array(spin, dtype=float)
    s = simulate(tmp_path, f"""<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='Wheel' useFiniteRotation='true'
        angularVelocity='{" ".join(map(repr, w.tolist()))}' inertia='0.4 0 0 0 0.4 0 0 0 0.4'/>
        </RigidBodyCollection>""", duration=1.0, version="3.3")
    rate = float(np.linalg.norm(w))
    assert same_rotation(last(s, "Wheel", "orientation"), np.array([*w / rate, math.remainder(rate, 2 * math.pi)]),
                         1e-9)
