"""constant_torque: RigidBody.torques: two torques summed, a constant angular acceleration."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import FORCES, ROUNDING, ROUNDING_ANGLE, honoured, max_norm, physics_time
from conformance.results import Measure, Settings


# constant_torque.x3d
CT_TORQUE, CT_IZZ = 0.4, 0.4


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """w = alpha t exact for any scheme (ROUNDING); rotation angle alpha t^2/2 about z within
    alpha t dt / 2 (the constant-acceleration argument, on the angle); any rotation off the z
    axis counts in the same error (the angle of q_measured * conj(q_exact)). Those are accuracy
    bounds; the tolerances (closed_forms.honoured) are half the misreading's error, the torque
    ignored (the body stays still: alpha T and alpha T^2 / 2 off at the end)."""
    tr, s = traces[0], settings[0]
    t, rot = tr.series("Spun", "orientation")
    _, w = tr.series("Spun", "angularVelocity")
    alpha = CT_TORQUE / CT_IZZ
    tp = physics_time(t, s.dt)
    w_exact = np.outer(alpha * tp, [0.0, 0.0, 1.0])
    q_exact = R.from_axis_angle(np.column_stack([np.zeros((len(tp), 2)), np.ones(len(tp)), 0.5 * alpha * tp ** 2]))
    T = float(tp[-1])
    w_bound, q_bound = ROUNDING * (1 + alpha * T), 0.5 * alpha * T * s.dt + ROUNDING_ANGLE
    return [Measure("Spun.angularVelocity", max_norm(w - w_exact), honoured(w_bound, alpha * T), "rad/s", FORCES,
                    w_bound),
            Measure("Spun.orientation", float(np.max(R.angle_between(R.from_axis_angle(rot), q_exact))),
                    honoured(q_bound, 0.5 * alpha * T * T), "rad", FORCES, q_bound)]


CASE = Case("constant_torque", "constant_torque.x3d",
            "RigidBody.torques (0 0 0.15) + (0 0 0.25) N m, I_zz 0.4: w = alpha t, angle = alpha t^2/2",
            (Settings(1.0, 1 / 240),), expect,
            convergence="Spun.orientation", expected_order=1.0,
            exercises=("RigidBody.torques", "RigidBody.inertia"),
            mutations=((" torques='0 0 0.15, 0 0 0.25'", ""),))
