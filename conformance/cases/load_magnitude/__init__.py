"""load_magnitude: RigidBody.forces and torques: the accelerations they give, to rounding, not to half the load."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from x3d_core.traces.trace import TraceView

from conformance.cases.case import Case
from conformance.cases.closed_forms import FORCES, ROUNDING, honoured, physics_time
from conformance.results import Measure, Settings, also

# load_magnitude.x3d: one body, no gravity, at rest; each load a pair, the second a tenth of the sum
LM_MASS, LM_IZZ = 2.0, 0.4
LM_FORCES = np.array([[1.8, 0.0, 0.0], [0.2, 0.0, 0.0]])
LM_TORQUES = np.array([[0.0, 0.0, 0.36], [0.0, 0.0, 0.04]])
# the linear measure's: F/m with m = 2 kg, so a mass read in another unit (2 g, 2 lb) or ignored (1 kg) is off by
# the acceleration itself at least, at a tolerance of 5 % of it (the angular measure turns on the inertia alone)
FORCES_IN_KG = also(FORCES, "37.2.5.1 Initial coordinate system: Mass is defined in kilograms.",
                    "37.4.10 RigidBody: The mass field indicates the mass of the body in kilograms.")


def misread(loads: np.ndarray) -> list[float]:
    """The errors in the acceleration, as a fraction of it, of the misreadings close to the
    loads' size: either load of the pair dropped (an MF field read as its first or last value),
    the tenth the nearer. Farther ones: the load applied on one step a frame instead of every
    step (three quarters off at the case's four steps a frame), the mass or the inertia ignored."""
    whole = float(np.linalg.norm(loads.sum(axis=0)))
    return [float(np.linalg.norm(x)) / whole for x in loads]


def rate(t: np.ndarray, v: np.ndarray, dt: float) -> np.ndarray:
    """The constant acceleration a velocity shows: the least-squares slope of v - v1 against the
    physics time since the first frame (closed_forms.physics_time), through 0."""
    tau = physics_time(t, dt) - physics_time(t[:1], dt)
    return (v - v[0]).T @ tau / float(tau @ tau)


def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The acceleration the linear velocity shows (rate) against F/m, and the angular one
    against T/I_zz (z principal, from rest: the spin stays along z). Velocities under a constant
    acceleration are exact for every one-step scheme, whatever it does to positions and rotations
    (ODE's first-order rotation update lags the angle, not the spin), and the fit takes only
    differences from the first frame: exact but for rounding, ROUNDING relative (the accuracy
    bound). The spec tolerance (closed_forms.honoured) is half the nearest misreading's error:
    one load of a pair dropped, a tenth of the acceleration, so 5 % of it (constant_force and
    constant_torque, whose nearest misreading is the load ignored, let a load a third short
    pass)."""
    tr, s = traces[0], settings[0]
    t, v = tr.series("Pushed", "linearVelocity")
    _, w = tr.series("Pushed", "angularVelocity")
    out = []
    for what, got, loads, inverse, unit, basis in (
            ("acceleration - sum of forces / mass", rate(t, v, s.dt), LM_FORCES, 1 / LM_MASS, "m/s^2", FORCES_IN_KG),
            ("angular acceleration - sum of torques / I_zz", rate(t, w, s.dt), LM_TORQUES, 1 / LM_IZZ, "rad/s^2",
             FORCES)):
        want = loads.sum(axis=0) * inverse
        size = float(np.linalg.norm(want))
        bound = ROUNDING * (1 + size)
        out.append(Measure(f"Pushed {what}", float(np.linalg.norm(got - want)),
                           honoured(bound, *(m * size for m in misread(loads))), unit, basis, bound))
    return out


CASE = Case("load_magnitude", "load_magnitude.x3d",
            "RigidBody.forces (1.8 0 0) + (0.2 0 0) N on 2 kg, torques (0 0 0.36) + (0 0 0.04) N m on I_zz 0.4: the "
            "fitted accelerations are 1 m/s^2 and 1 rad/s^2 within 5 % (the smaller load dropped: 10 % off)",
            (Settings(1.0, 1 / 240),), expect,
            exercises=("RigidBody.forces", "RigidBody.torques", "RigidBody.mass", "RigidBody.inertia"),
            # the smaller load of each pair dropped
            mutations=((" forces='1.8 0 0, 0.2 0 0'", " forces='1.8 0 0'"),
                       (" torques='0 0 0.36, 0 0 0.04'", " torques='0 0 0.36'")))
