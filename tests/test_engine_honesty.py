"""A run an engine silently got wrong is never a result: each case here once exited 0 (or
aborted the process) and must now be a verdict: blown up (the frames before it kept),
refused up front by value (exit 3), or, for ODE's own aborts, one line and exit 1."""

from __future__ import annotations

import importlib.util
import subprocess
import sys

import pytest

from conftest import ROOT

HEAD = ("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Immersive' version='4.0'><head>"
        "<component name='RigidBodyPhysics' level='2'/></head><Scene>{}</Scene></X3D>")
BALL = "<RigidBodyCollection {collection}><RigidBody DEF='Ball' position='0 1 0' {ball}/>{more}</RigidBodyCollection>"


def scene(tmp_path, collection="", ball="", more="") -> str:
    path = tmp_path / "s.x3d"
    path.write_text(HEAD.format(BALL.format(collection=collection, ball=ball, more=more)))
    return str(path)


def needs(module: str, backend: str):
    if importlib.util.find_spec(module) is None:
        pytest.skip(f"{backend}: {module} is not installed")
    if backend == "ode":
        try:
            import backends.ode_lib  # noqa: F401
        except ImportError as e:
            pytest.skip(f"ODE is not installed: {e}")


def run(path: str, backend: str, trace: str) -> tuple[int, list[str]]:
    r = subprocess.run([sys.executable, "-m", "x3drbp", "run", path, "--backend", backend,
                        "--duration", "0.5", "--trace", trace], cwd=ROOT, capture_output=True, text=True, timeout=120)
    lines = [ln for ln in r.stderr.splitlines() if ln.strip() and "pybullet build time" not in ln]
    assert not any("Traceback" in ln or "Warning" in ln or "WARNING" in ln for ln in lines), r.stderr
    return r.returncode, lines


def blew_up(path: str, backend: str, trace, says: str) -> None:
    rc, lines = run(path, backend, str(trace))
    assert rc == 1 and len(lines) == 1, lines
    assert "blew up" in lines[0] and says in lines[0] and "the frames before it written to" in lines[0], lines
    assert trace.exists()


def refused(path: str, backend: str, trace, says: str) -> None:
    rc, lines = run(path, backend, str(trace))
    assert rc == 3 and len(lines) == 1, lines
    assert f"unsupported by {backend}" in lines[0] and says in lines[0], lines
    assert not trace.exists()


# 1: pybullet holds every velocity component at the clamp the backend sets (1e6)
def test_bullet_at_its_speed_clamp_blows_up(tmp_path):
    needs("pybullet", "bullet")
    blew_up(scene(tmp_path, collection="gravity='0 -1e308 0'"), "bullet", tmp_path / "o.csv", "speed clamp")


# pybullet turns a free base or a ball joint at most pi/4 a step: 188.5 rad/s at dt 1/240
def test_bullet_spinning_past_its_turn_limit_blows_up(tmp_path):
    needs("pybullet", "bullet")
    blew_up(scene(tmp_path, collection="gravity='0 0 0'", ball="angularVelocity='0 -1000 0'"), "bullet",
            tmp_path / "o.csv", "spins at 1000 rad/s, past what pybullet turns in a step")


def test_bullet_a_ball_joint_spinning_past_its_turn_limit_blows_up(tmp_path):
    needs("pybullet", "bullet")
    joint = ("<BallJoint containerField='joints' anchorPoint='0 1 0'><RigidBody USE='Ball' containerField='body1'/>"
             "<RigidBody USE='Arm' containerField='body2'/></BallJoint>")
    blew_up(scene(tmp_path, collection="gravity='0 0 0'", ball="angularVelocity='0 -1000 0'",
                  more=f"<RigidBody DEF='Arm' position='0 1 0' fixed='true'/>{joint}"), "bullet",
            tmp_path / "o.csv", "spins at 1000 rad/s")


def test_bullet_under_its_turn_limit_follows_the_closed_form(tmp_path):
    """150 rad/s about -y for 0.1 s turns 15 rad: pybullet integrates it exactly."""
    needs("pybullet", "bullet")
    out = tmp_path / "o.csv"
    rc, lines = run(scene(tmp_path, collection="gravity='0 0 0'", ball="angularVelocity='0 -150 0'"), "bullet",
                    str(out))
    assert rc == 0, lines
    from x3d_core.semantics import rotation as R
    from x3d_core.traces.trace import TraceView, read_trace
    times, rotations = TraceView(read_trace(str(out))).series("Ball", "orientation")
    q = R.from_axis_angle(rotations[-1])
    expected = R.from_axis_angle([0.0, -1.0, 0.0, 150 * times[-1]])
    assert abs(abs(float(q @ expected)) - 1) < 1e-9  # the same rotation, up to the quaternion's sign


def test_bullet_refuses_a_free_body_it_would_take_as_static(tmp_path):
    needs("pybullet", "bullet")
    refused(scene(tmp_path, ball="mass='1e-320'"), "bullet", tmp_path / "o.csv", "mass 9.99989e-321")


# 2: MuJoCo resets a state beyond 1e10 and goes on: the other body's fall started over
def test_mujoco_reset_is_a_blow_up(tmp_path):
    needs("mujoco", "mujoco")
    path = scene(tmp_path, more="<RigidBody DEF='Far' position='1e11 0 0'/>")
    blew_up(path, "mujoco", tmp_path / "o.csv", "huge position")


# 3: ODE aborted the process (exit 134, no trace) on these
@pytest.mark.parametrize("collection,ball,says", [
    ("constantForceMix='1e308'", "", "RigidBodyCollection.constantForceMix = 1e+308"),
    ("", "inertia='1e-320 0 0 0 1e-320 0 0 0 1e-320' angularVelocity='1 2 3'", "RigidBody.inertia = 1e-320"),
    ("", "mass='1e-320'", "RigidBody.mass = 1e-320"),
])
def test_ode_refuses_what_it_would_abort_on(tmp_path, collection, ball, says):
    needs("ctypes", "ode")
    more = "<BallJoint anchorPoint='0 2 0'><RigidBody USE='Ball' containerField='body1'/></BallJoint>" \
        if collection else ""
    refused(scene(tmp_path, collection=collection, ball=ball, more=more), "ode", tmp_path / "o.csv", says)


def test_ode_refuses_a_size_it_cannot_square(tmp_path):
    needs("ctypes", "ode")
    shape = ("<CollidableShape DEF='{n}' containerField='{f}'><Shape containerField='shape'>{g}</Shape>"
             "</CollidableShape>")
    path = tmp_path / "s.x3d"
    path.write_text(HEAD.format(
        "<RigidBodyCollection><CollisionCollection containerField='collider'>"
        + shape.format(n="Huge", f="collidables", g="<Box size='1e308 1e308 1e308'/>")
        + shape.format(n="Small", f="collidables", g="<Sphere radius='0.1'/>") + "</CollisionCollection>"
        "<RigidBody DEF='A' position='0 1 0'><CollidableShape USE='Huge' containerField='geometry'/></RigidBody>"
        "<RigidBody DEF='B' position='0 3 0'><CollidableShape USE='Small' containerField='geometry'/></RigidBody>"
        "</RigidBodyCollection>"))
    refused(str(path), "ode", tmp_path / "o.csv", "Huge: a box 1e+308 m across")


def test_an_ode_abort_is_a_blow_up_with_the_frames_before_it(tmp_path):
    """A torque of 1e308 spins the body to infinity inside a step, where ODE asserts (once
    exit 134 and no trace): its error handler ends the run as a blow-up, frame 0 kept."""
    needs("ctypes", "ode")
    blew_up(scene(tmp_path, ball="torques='0 1e308 0'"), "ode", tmp_path / "o.csv",
            "blew up by t=0.0166667: ODE internal error")
    from x3d_core.traces.trace import read_trace
    assert {row.time for row in read_trace(str(tmp_path / "o.csv"))} == {0.0}


# 2b: MuJoCo's compiler stopped on these (exit 1, "mass and inertia of moving bodies must be larger
# than mjMINVAL", "inertia must have positive eigenvalues"): refused, as the other engines refuse
@pytest.mark.parametrize("ball,says", [
    ("mass='1e-300'", "RigidBody Ball: mass 1e-300 kg, least principal moment 1 kg m^2"),
    ("inertia='1e-300 0 0 0 1e-300 0 0 0 1e-300'", "RigidBody Ball: mass 1 kg, least principal moment 1e-300 kg m^2"),
])
def test_mujoco_refuses_a_body_too_light_for_its_compiler(tmp_path, ball, says):
    needs("mujoco", "mujoco")
    refused(scene(tmp_path, ball=ball), "mujoco", tmp_path / "o.csv", says + ": MuJoCo refuses a moving body's "
                                                                           "mass or inertia under mjMINVAL (1e-15)")


# 4: values that froze a body, exit 0
@pytest.mark.parametrize("ball,says", [("mass='1e308'", "its weight overflows"),
                                       ("mass='1e-320'", "RigidBody.mass = 1e-320")])
def test_dart_refuses_a_mass_that_would_freeze_the_body(tmp_path, ball, says):
    needs("dartpy", "dart")
    refused(scene(tmp_path, ball=ball), "dart", tmp_path / "o.csv", says)


# 5: numpy's overflow warnings stay off stderr where the code checks finiteness itself
def test_an_overflowing_weight_warns_nothing(tmp_path):
    needs("pymunk", "pymunk")
    rc, lines = run(scene(tmp_path, ball="mass='1e308'"), "pymunk", str(tmp_path / "o.csv"))
    assert rc in (0, 1) and len(lines) <= 1, lines
