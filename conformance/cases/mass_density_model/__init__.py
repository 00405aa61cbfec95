"""mass_density_model: RigidBody.massDensityModel: a Box, Sphere or Cone gives the inertia a torque turns against.

The clause says the model's geometry is "used to calculate the mass density"; x3drbp reads it
as a uniform solid of that shape carrying the body's mass, its inertia about its own centroid
taking the place of the inertia field (x3d_core/semantics/world.py, _inertia). A torque about a
principal axis through the centre of mass then gives alpha = tau / I, which the inertia field's
default (the identity) would not."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.semantics import rotation as R
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import ROUNDING, ROUNDING_ANGLE, honoured, max_norm, physics_time
from conformance.results import Measure, Settings, spec


MODEL = spec("37.4.10 RigidBody: The massDensityModel field is used to describe the geometry type and dimensions "
             "used to calculate the mass density in the physics model.")

# mass_density_model.x3d: name -> (torque about z, I_zz of the model, I_zz under each misreading:
# the model ignored (the inertia field's identity), and the nearest misreading of the shape)
MDM_BOX_M, MDM_BOX = 2.0, (0.3, 0.6, 0.9)
MDM_SPHERE_M, MDM_SPHERE_R = 3.0, 0.5
MDM_CONE_M, MDM_CONE_R, MDM_CONE_H = 2.0, 0.5, 1.0
_BOX_IZZ = MDM_BOX_M * (MDM_BOX[0] ** 2 + MDM_BOX[1] ** 2) / 12
_CONE_IZZ = 3 / 20 * MDM_CONE_M * MDM_CONE_R ** 2 + 3 / 80 * MDM_CONE_M * MDM_CONE_H ** 2
MDM_BODIES = {
    # size read as half-extents (four times the inertia)
    "BoxModel": (0.15, _BOX_IZZ, (1.0, 4 * _BOX_IZZ)),
    # a hollow sphere (2/3 m r^2)
    "SphereModel": (0.6, 0.4 * MDM_SPHERE_M * MDM_SPHERE_R ** 2, (1.0, 2 / 3 * MDM_SPHERE_M * MDM_SPHERE_R ** 2)),
    # about the cone's geometric centre, h/4 above its centroid
    "ConeModel": (0.3, _CONE_IZZ, (1.0, _CONE_IZZ + MDM_CONE_M * (MDM_CONE_H / 4) ** 2)),
}


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each body turns about its z axis from rest at alpha = tau / I_zz (2 rad/s^2 for all three):
    w = alpha t, exact for any one-step scheme (ROUNDING), and the angle alpha t^2/2 within
    alpha T h/2 (closed_forms' constant-acceleration argument): the accuracy bounds.

    Spec tolerance (closed_forms.honoured): half the nearest misreading's error, at T:
    |alpha' - alpha| T for w and |alpha' - alpha| T^2/2 for the angle, alpha' = tau / I' with I'
    the identity (the model ignored: the inertia field's default) or the shape misread (the box's
    size as half-extents, a hollow sphere, the cone about its geometric centre rather than its
    centroid)."""
    tr, s = traces[0], settings[0]
    out = []
    for name, (tau, izz, misread) in MDM_BODIES.items():
        t, rot = tr.series(name, "orientation")
        _, w = tr.series(name, "angularVelocity")
        tp = physics_time(t, s.dt)
        T = float(tp[-1])
        alpha = tau / izz
        others = [tau / i - alpha for i in misread]
        turn = np.column_stack([np.zeros((len(tp), 2)), np.ones(len(tp)), 0.5 * alpha * tp ** 2])
        rate_bound = ROUNDING * (1 + alpha * T)
        angle_bound = 0.5 * alpha * T * s.dt + ROUNDING_ANGLE
        out += [Measure(f"{name}.angularVelocity - (0, 0, tau/I_zz t)", max_norm(w - np.outer(alpha * tp, [0, 0, 1])),
                        honoured(rate_bound, *(d * T for d in others)), "rad/s", MODEL, rate_bound),
                Measure(f"{name}.orientation - Rz(tau/I_zz t^2/2)",
                        float(np.max(R.angle_between(R.from_axis_angle(rot), R.from_axis_angle(turn)))),
                        honoured(angle_bound, *(0.5 * d * T * T for d in others)), "rad", MODEL, angle_bound)]
    return out


CASE = Case("mass_density_model", "mass_density_model.x3d",
            "RigidBody.massDensityModel Box, Sphere, Cone (inertia field at its default): a torque about z turns "
            "each at tau / I_zz = 2 rad/s^2, I_zz of a uniform solid of the model's shape",
            (Settings(1.0, 1 / 240),), expect,
            convergence="BoxModel.orientation - Rz(tau/I_zz t^2/2)", expected_order=1.0,
            exercises=("RigidBody.massDensityModel.Box", "RigidBody.massDensityModel.Sphere",
                       "RigidBody.massDensityModel.Cone", "RigidBody.torques"),
            mutations=(("<Box containerField='massDensityModel' size='0.3 0.6 0.9'/>", ""),
                       ("<Sphere containerField='massDensityModel' radius='0.5'/>", ""),
                       ("<Cone containerField='massDensityModel' bottomRadius='0.5' height='1'/>", "")))
