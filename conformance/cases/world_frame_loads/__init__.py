"""world_frame_loads: RigidBody.forces / torques are world vectors: a turned or spinning body is pushed along them.

The clause says the loads are "applied to the object every frame" and names no frame. What any
frame gives is the size of a load's effect on a body that does not turn, or turns about a
fixed axis: |v| = |F| t / m, |w| = |tau| t / I (spec). Their direction, world axes rather than
the body's, is x3drbp's reading and ODE's (dBodyAddForce, dBodyAddTorque; Xj3D calls them): a
convention, which a browser turning the loads with the body (dBodyAddRelForce) fails."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case, Mutation
from conformance.cases.closed_forms import FORCES, ROUNDING, ROUNDING_ANGLE, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, convention


WORLD_LOADS = convention(
    "forces and torques are vectors in world coordinates, forces acting at the centre of mass (x3drbp; ODE's "
    "dBodyAddForce and dBodyAddTorque, which Xj3D calls); alternative: vectors in the body's frame, turning with it "
    "(ODE's dBodyAddRelForce and dBodyAddRelTorque)")

# world_frame_loads.x3d
WFL_PUSHED = (1.5, np.array([0.0, 0.0, 0.0]), (0.0, 0.0, 1.0, 1.2), np.array([3.0, 0.0, 0.0]))  # m, p0, q0, F
WFL_TWISTED = (0.2, (1.0, 0.0, 0.0, 1.0), np.array([0.0, 0.0, 0.4]))  # isotropic I, q0, torque
WFL_SPINNING = (1.0, np.array([0.0, -3.0, 0.0]), 4.0, np.array([2.0, 0.0, 0.0]))  # m, p0, spin about z, F
WFL_INERTIA_DEFAULT = 1.0  # the inertia field's default (identity): Twisted's tensor ignored


def _about(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Quaternions turning by each angle about one world axis."""
    return R.from_axis_angle(np.column_stack([np.tile(axis, (len(angle), 1)), angle]))


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Accuracy bounds: under a constant acceleration, velocities exact (ROUNDING) and positions and
    angles within |a| T h/2 (closed_forms' argument); Spinning's push is constant in the world
    frame whatever its spin, so the same bound holds.

    Spec tolerances (closed_forms.honoured, half the nearest misreading at T): Pushed's speed, the
    force ignored (2 T) or read as an acceleration, the mass ignored (|F| T - |F| T/m = 1 m/s);
    Twisted's rate, the torque ignored (2 T) or the inertia ignored (the default identity:
    0.4 t, 1.6 rad/s apart). Both hold in either frame.

    Convention tolerances: half the body frame's error, from its closed form: Pushed accelerates
    along R0 F, |R0 a - a| T^2/2 off; Twisted turns by q0 Rz(alpha t^2/2), not Rz(alpha t^2/2) q0;
    Spinning's push turns with it, p = p0 + (F/(m w^2)) (1 - cos wt, wt - sin wt, 0)."""
    tr, s = traces[0], settings[0]
    h = s.dt
    out = []

    m, p0, q0, force = WFL_PUSHED
    t, p = tr.series("Pushed", "position")
    _, v = tr.series("Pushed", "linearVelocity")
    tp = physics_time(t, h)
    T = float(tp[-1])
    a = force / m
    a_body = R.rotate(R.from_axis_angle(np.asarray(q0)), a)
    speed_bound = ROUNDING * (1 + float(np.linalg.norm(a)) * T)
    out.append(Measure("Pushed speed |linearVelocity| - |F| t / m", float(np.max(np.abs(
        np.linalg.norm(v, axis=1) - np.linalg.norm(a) * tp))),
        honoured(speed_bound, np.linalg.norm(a) * T, np.linalg.norm(force - a) * T), "m/s", FORCES, speed_bound))
    path_bound = 0.5 * float(np.linalg.norm(a)) * T * h + ROUNDING * (1 + float(np.linalg.norm(a)) * T * T)
    out.append(Measure("Pushed.position - p0 - F t^2 / 2m (world F)", max_norm(p - p0 - np.outer(0.5 * tp ** 2, a)),
                       honoured(path_bound, 0.5 * float(np.linalg.norm(a_body - a)) * T * T), "m", WORLD_LOADS,
                       path_bound))

    inertia, q0, torque = WFL_TWISTED
    t, rot = tr.series("Twisted", "orientation")
    _, w = tr.series("Twisted", "angularVelocity")
    tp = physics_time(t, h)
    alpha = float(np.linalg.norm(torque)) / inertia
    axis = torque / np.linalg.norm(torque)
    start = R.from_axis_angle(np.asarray(q0))
    turn = _about(axis, 0.5 * alpha * tp ** 2)
    exact = R.multiply(turn, start)
    rate_bound = ROUNDING * (1 + alpha * T)
    out.append(Measure("Twisted |angularVelocity| - |tau| t / I", float(np.max(np.abs(np.linalg.norm(w, axis=1)
                                                                                    - alpha * tp))),
                       honoured(rate_bound, alpha * T, (alpha - alpha * inertia / WFL_INERTIA_DEFAULT) * T), "rad/s",
                       FORCES, rate_bound))
    angle_bound = 0.5 * alpha * T * h + ROUNDING_ANGLE
    body_frame = float(R.angle_between(R.multiply(start, turn[-1]), exact[-1]))
    out.append(Measure("Twisted.orientation - Rz(alpha t^2/2) q0 (world torque)",
                       float(np.max(R.angle_between(R.from_axis_angle(rot), exact))),
                       honoured(angle_bound, body_frame), "rad", WORLD_LOADS, angle_bound))

    m, p0, spin, force = WFL_SPINNING
    t, p = tr.series("Spinning", "position")
    tp = physics_time(t, h)
    a = force / m
    k = float(np.linalg.norm(a)) / spin ** 2
    turning = p0 + k * np.array([1 - np.cos(spin * T), spin * T - np.sin(spin * T), 0.0])
    world = p0 + 0.5 * a * T * T
    path_bound = 0.5 * float(np.linalg.norm(a)) * T * h + ROUNDING * (1 + float(np.linalg.norm(p0)))
    out.append(Measure("Spinning.position - p0 - F t^2 / 2m (world F, whatever the spin)",
                       max_norm(p - p0 - np.outer(0.5 * tp ** 2, a)),
                       honoured(path_bound, float(np.linalg.norm(turning - world))), "m", WORLD_LOADS, path_bound))
    return out


CASE = Case("world_frame_loads", "world_frame_loads.x3d",
            "RigidBody.forces / torques on turned and spinning bodies: |v| = |F| t/m and |w| = |tau| t/I (spec); "
            "along the world vectors, whatever the body's orientation or spin (ODE's reading)",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.forces", "RigidBody.torques", "RigidBody.orientation", "RigidBody.angularVelocity"),
            # each load turned by its body's start orientation: what a backend reading loads in the body's frame
            # applies (exactly, as Pushed keeps its orientation and Twisted turns about the turned axis)
            mutations=(Mutation("forces='3 0 0'", "forces='1.0870732634300209 2.796117257901679 0'", spec=False),
                       Mutation("torques='0 0 0.4'", "torques='0 -0.33658839392315865 0.2161209223472559'",
                                spec=False)))
