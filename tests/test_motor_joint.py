"""MotorJoint as 37.4.9 words it, in x3d_core for every backend: "The motorAxis1 field is anchored
to the global frame. The motorAxis2 field is anchored to body1's frame of reference, and the
motorAxis3 field is anchored to body2's frame of reference" (the torques and the outputs); a zero
axis is "disabled and the motor does not apply a force or torque along that axis" (no refusal, no
warning, outputs 0); and "the rate ... that the motor is turning" in user-calculated mode too.

The states are given, so every expected figure is exact: quarter turns and their quaternions are
exact to rounding, ~1e-16 per product on numbers of order 1."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

from backends import base
from conftest import ROOT
from x3d_core.encodings.load import load
from x3d_core.semantics import rotation as R
from x3d_core.semantics.evaluator import RunSettings, run
from x3d_core.semantics.joint_outputs import JointOutputs
from x3d_core.semantics.world import State, undirected, worlds
from x3d_core.traces.trace import TraceView, read_trace

INSTALLED = [n for n, b in base.available().items() if not isinstance(b, str)]
EXACT = 1e-14  # a few roundings of products of order-1 numbers


def scene(tmp_path, body: str, version: str = "4.0"):
    p = tmp_path / "s.x3d"
    p.write_text(f"<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='{version}'><Scene>\n"
                 f"<RigidBodyCollection gravity='0 0 0'>{body}</RigidBodyCollection>\n</Scene></X3D>\n")
    s = load(str(p))
    assert not s.errors and not s.warnings, [str(d) for d in s.diagnostics]
    return s


def quarter(axis: str) -> np.ndarray:
    """A quarter turn about x, y or z."""
    v = {"x": [1.0, 0.0, 0.0], "y": [0.0, 1.0, 0.0], "z": [0.0, 0.0, 1.0]}[axis]
    return R.from_axis_angle(np.array([*v, math.pi / 2]))


def ends(joint: str, body1: str | None, body2: str | None) -> str:
    """The MotorJoint element `joint` opens, with its bodies (None: NULL)."""
    uses = "".join(f"<RigidBody USE='{b}' containerField='{f}'/>" for b, f in ((body1, "body1"), (body2, "body2")) if b)
    return f"{joint}{uses}</MotorJoint>"


class _Posed:
    """An engine that stands still with the given bodies (row -> quaternion) turned, keeping every load it is given."""
    name = "posed"

    def __init__(self, turns: dict[int, np.ndarray]):
        self.turns = turns
        self.loads: list[tuple[np.ndarray, np.ndarray]] = []

    def build(self, world, dt):
        engine = self

        class Sim:
            def step(self, n=1):
                pass

            def state(self):
                s = State.initial(world.bodies)
                for row, q in engine.turns.items():
                    s.orientation[row] = q
                return s

            def set_loads(self, forces, torques):
                engine.loads.append((forces.copy(), torques.copy()))
        return Sim()


XYZ = "enabledAxes='3' motor1Axis='1 0 0' motor2Axis='0 1 0' motor3Axis='0 0 1'"


def test_motor_torques_act_along_the_axes_as_anchored(tmp_path):
    """Torques 1, 2, 4 along x, y, z as given at the start, with body1 (A) turned a quarter about z
    and body2 (B) a quarter about x: axis 1 stays x, axis 2 turns with A to -x, axis 3 with B to -y,
    so A gets x - 2x - 4y and B its opposite. Where body1 is NULL (D's motor, D turned as B) axis 2
    stays in the world: x + 2y - 4y on nothing, its opposite on D."""
    s = scene(tmp_path, "<RigidBody DEF='A'/><RigidBody DEF='B' position='1 0 0'/><RigidBody DEF='D' position='3 0 0'/>"
                        + ends(f"<MotorJoint DEF='M' {XYZ} axis1Torque='1' axis2Torque='2' axis3Torque='4'>", "A", "B")
                        + ends(f"<MotorJoint DEF='Half' {XYZ} axis1Torque='1' axis2Torque='2' axis3Torque='4'>",
                               None, "D"))
    engine = _Posed({0: quarter("z"), 1: quarter("x"), 2: quarter("x")})
    run(worlds(s), engine, RunSettings(1 / 240, 1 / 240, 240))
    forces, torques = engine.loads[-1]
    assert np.allclose(torques, [[-1.0, -4.0, 0.0], [1.0, 4.0, 0.0], [-1.0, 2.0, 0.0]], rtol=0, atol=EXACT)
    assert not forces.any()


def test_a_disabled_motor_axis_pushes_nothing(tmp_path):
    """Torques on every axis, axis 2 disabled (0 0 0): A gets axis 1's and axis 3's torques only,
    x + 4z with neither body turned, B their opposite; with X3D 4.0's default axis 0 1 0 it would
    get 2y more."""
    s = scene(tmp_path, "<RigidBody DEF='A'/><RigidBody DEF='B' position='1 0 0'/>"
                        + ends("<MotorJoint enabledAxes='3' motor1Axis='1 0 0' motor2Axis='0 0 0' motor3Axis='0 0 1' "
                               "axis1Torque='1' axis2Torque='2' axis3Torque='4'>", "A", "B"))
    engine = _Posed({})
    run(worlds(s), engine, RunSettings(1 / 240, 1 / 240, 240))
    assert np.allclose(engine.loads[-1][1], [[1.0, 0.0, 4.0], [-1.0, 0.0, -4.0]], rtol=0, atol=EXACT)


MOTOR = ("<RigidBody DEF='A'/><RigidBody DEF='B' position='1 0 0'/>"
         "<MotorJoint DEF='M' {axes} autoCalc='{auto}' axis1Angle='0.1' axis2Angle='0.2' axis3Angle='0.3' "
         "forceOutput='\"ALL\"'><RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/>"
         "</MotorJoint>")


def _outputs(tmp_path, axes: str, auto: bool, q1: np.ndarray, q2: np.ndarray) -> dict[str, float]:
    """M's outputs with A (body1) turned to q1 and spinning at (1, 2, 3), B (body2) turned to q2 and
    spinning at (0.5, 0, 0)."""
    (w,) = worlds(scene(tmp_path, MOTOR.format(axes=axes, auto=str(auto).lower())))
    s = State.initial(w.bodies)
    s.orientation[:] = [q1, q2]
    s.angular_velocity[:] = [[1.0, 2.0, 3.0], [0.5, 0.0, 0.0]]
    return {f: v for _, f, v in JointOutputs(w.joints, w.bodies).values(s)}


@pytest.mark.parametrize("auto", [True, False], ids=["autoCalc", "user"])
def test_motor_outputs_are_about_the_axes_as_anchored(tmp_path, auto):
    """Both bodies turned a quarter about z, A then a further 0.4 about x: A's turn relative to B is
    0.4 about the world's x. Axis 1 (x, the world's) sees all of it; axis 2 (y, turning with A, now
    -x) sees -0.4; axis 3 (z, turning with B, still z) none. The rates, in either mode, are
    axis . (w1 - w2) = axis . (0.5, 2, 3) about those axes: 0.5, -0.5, 3. In user-calculated mode
    the angles are the user's."""
    alpha = 0.4
    q2 = quarter("z")
    q1 = R.multiply(R.from_axis_angle(np.array([1.0, 0.0, 0.0, alpha])), q2)
    out = _outputs(tmp_path, XYZ, auto, q1, q2)
    angles = [alpha, -alpha, 0.0] if auto else [0.1, 0.2, 0.3]
    assert [out[f"motor{k}Angle"] for k in (1, 2, 3)] == pytest.approx(angles, rel=0, abs=EXACT)
    assert [out[f"motor{k}AngleRate"] for k in (1, 2, 3)] == pytest.approx([0.5, -0.5, 3.0], rel=0, abs=EXACT)


@pytest.mark.parametrize("auto", [True, False], ids=["autoCalc", "user"])
def test_a_disabled_motor_axis_reports_zero(tmp_path, auto):
    """motor2Axis 0 0 0, with A turned 0.4 about y relative to B and spinning about y at 2 rad/s,
    and axis2Angle 0.2 given: angle and rate 0 in either mode (X3D 4.0's default axis 0 1 0 would
    see 0.4 and 2); the other axes report as ever."""
    q1 = R.from_axis_angle(np.array([0.0, 1.0, 0.0, 0.4]))
    out = _outputs(tmp_path, "enabledAxes='3' motor1Axis='1 0 0' motor2Axis='0 0 0' motor3Axis='0 0 1'", auto, q1,
                   R.IDENTITY)
    assert out["motor2Angle"] == 0.0 and out["motor2AngleRate"] == 0.0
    assert out["motor1AngleRate"] == pytest.approx(0.5, rel=0, abs=EXACT)
    assert out["motor3AngleRate"] == pytest.approx(3.0, rel=0, abs=EXACT)


def test_zero_motor_axes_are_neither_refused_nor_warned(tmp_path):
    """X3D 3.x's MotorJoint at its defaults (every motorNAxis 0 0 0): a motor with its axes
    disabled, not a joint of no direction; scene() holds the load to no warning."""
    s = scene(tmp_path, "<RigidBody DEF='Bob'/><MotorJoint axis1Torque='2'><RigidBody USE='Bob' "
                        "containerField='body1'/></MotorJoint>", version="3.3")
    (w,) = worlds(s)
    assert not w.joints[0].axes.any() and undirected(w) == []


@pytest.mark.parametrize("backend", INSTALLED)
def test_every_backend_runs_a_3_3_motor_joint_at_its_defaults(tmp_path, backend):
    """The motor's only axis is X3D 3.3's default 0 0 0, with axis1Torque 2: it runs (exit 0) and
    the spinning body keeps its angular velocity, where it was once refused on every backend.
    Torque-free and isotropic, the velocity is exact but for rounding: at most one float32 rounding
    of 0.8 a step (PhysX keeps float32 state), 60 steps; the torque along 4.0's default axis 1 0 0
    would add 2.5 rad/s."""
    path = tmp_path / "s.x3d"
    path.write_text("<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='3.3'><Scene>"
                    "<RigidBodyCollection gravity='0 0 0'><RigidBody DEF='Bob' angularVelocity='0 0 0.8' "
                    "inertia='0.2 0 0 0 0.2 0 0 0 0.2'/><MotorJoint axis1Torque='2'><RigidBody USE='Bob' "
                    "containerField='body1'/></MotorJoint></RigidBodyCollection></Scene></X3D>\n")
    trace = tmp_path / "t.csv"
    r = subprocess.run([sys.executable, "-m", "x3drbp", "run", str(path), "--backend", backend, "-q",
                        "--duration", "0.25", "--trace", str(trace)], cwd=ROOT, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    _, w = TraceView(read_trace(str(trace))).series("Bob", "angularVelocity")
    assert len(w) > 1 and np.allclose(w, [0.0, 0.0, 0.8], rtol=0, atol=60 * np.finfo(np.float32).eps * 0.8)
