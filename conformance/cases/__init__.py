"""Conformance cases: a scene of scenes/conformance/, how to run it, and what must come out.

A case is one scene file, the run settings (one run, or several that must agree), and an
expectation: a function of the traces that returns Measures, each a measured error with
the tolerance it must not exceed. Every tolerance is argued below from the step size and
the order of the integrators the engines use, never tuned until a backend passes.

The closed forms' parameters are written here, not read from the scene through x3d_core,
so that the expectation does not share the evaluator's reading of the file: a field the
evaluator misread or dropped fails the case instead of moving the target with it. Each
scene's leading comment states the same numbers.

Conventions of the argument (the reference integrator is semi-implicit Euler, which
Bullet, DART, ODE and MuJoCo's default all use):
- State at a frame ending at time t is the world after n = floor(t/dt) steps
  (x3d_core.evaluator); closed forms are evaluated at the physics time n*dt.
- Velocities under a constant acceleration are exact for every one-step scheme; what is
  left is rounding. ROUNDING = 1e-9 (relative to the quantity's scale) covers it with
  room to spare: at most ~500 steps of float64 arithmetic on O(10) numbers make ~1e-13.
- Angles read from a rotation are worse off: an engine that keeps rotations as matrices or
  rotation vectors recovers the angle from a cosine (acos, the log map), which near the
  identity is only good to sqrt(2 eps) ~ 2e-8 rad per conversion, and some convert every
  step. ROUNDING_ANGLE = 1e-7 rad covers a few such losses (DART's free joint shows 2.7e-9
  rad, gathered while the angle is small).
- Positions under a constant acceleration a: every scheme in use advances position with
  a velocity between the step's start and end velocities, which keeps it within
  |a| t dt / 2 of the exact parabola. Semi-implicit Euler reaches that bound exactly
  (y_n = y0 - g dt^2 n(n+1)/2), explicit Euler too with the other sign, second-order
  schemes err by 0. So the tolerance is c*dt with c = |a| t / 2: first order, as the
  global error of a first-order method is.
- Invariants held by constraints (joints, stops) are argued from one step's error and the
  error correction (ERP) that removes a fraction of it each step; see each case.

To add a case: a scene scenes/conformance/NAME.x3d whose leading comment says what it
checks and the closed form, exercising its field at a non-default value; an expectation
here with its tolerance argued in the docstring; a Case in CASES naming the features it
exercises (tests/test_conformance.py checks the scene uses them, and runs it everywhere).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from x3d_core import rotation as R
from x3d_core.trace import TraceView

from conformance.results import Measure, Settings

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "scenes", "conformance")
ROUNDING = 1e-9
ROUNDING_ANGLE = 1e-7  # rad
_STEP_SLACK = 1e-9  # as x3d_core.evaluator: a frame within 1e-9 step of a step boundary is on it


# -- what a case is -----------------------------------------------------------------------

Expectation = Callable[[Sequence[TraceView], Sequence[Settings]], list[Measure]]


@dataclass(frozen=True)
class Case:
    name: str
    scene: str  # file name under scenes/conformance (or an absolute path)
    checks: str  # one line: the field(s) exercised and the closed form or invariant
    runs: tuple[Settings, ...]
    expect: Expectation
    # the Measure whose error is against a continuous closed form, so that its decrease with
    # dt (the fitted order) shows convergence; None where the check is exact or an invariant
    convergence: str | None = None
    expected_order: float | None = None  # what semi-implicit Euler gives, for the reader
    # the feature names (x3d_core.analysis) the case exercises with non-default values: the
    # case would fail if a backend ignored them
    exercises: tuple[str, ...] = field(default_factory=tuple)

    @property
    def path(self) -> str:
        return self.scene if os.path.isabs(self.scene) else os.path.join(SCENES, self.scene)

    def at_dt(self, dt: float) -> tuple[Settings, ...]:
        return tuple(s.with_dt(dt) for s in self.runs)


# -- helpers ------------------------------------------------------------------------------

def steps(t: np.ndarray, dt: float) -> np.ndarray:
    return np.floor(np.asarray(t) / dt + _STEP_SLACK)


def physics_time(t: np.ndarray, dt: float) -> np.ndarray:
    """The simulated time of the state recorded at frame time t: floor(t/dt) steps."""
    return steps(t, dt) * dt


def _max_norm(a: np.ndarray) -> float:
    a = np.asarray(a, dtype=np.float64)
    n = np.linalg.norm(a.reshape(len(a), -1), axis=1) if a.ndim > 1 else np.abs(a)
    return float(np.max(n)) if n.size else math.nan


def agm(a: float, b: float) -> float:
    """Arithmetic-geometric mean."""
    for _ in range(64):
        a, b = 0.5 * (a + b), math.sqrt(a * b)
        if abs(a - b) <= 1e-16 * a:
            break
    return a


def ellipk(k: float) -> float:
    """Complete elliptic integral of the first kind K(k), modulus k: pi / (2 AGM(1, sqrt(1-k^2)))."""
    return math.pi / (2.0 * agm(1.0, math.sqrt(1.0 - k * k)))


def ballistic(body: str, p0: Sequence[float], v0: Sequence[float], a: Sequence[float]) -> Expectation:
    """A body under a constant acceleration a: p = p0 + v0 t + a t^2/2, v = v0 + a t.

    Velocity: exact for any one-step scheme, so only ROUNDING. Position: |a| t dt / 2 (the
    module's argument), evaluated at the last frame, where the error is largest."""
    p0, v0, a = (np.asarray(x, dtype=np.float64) for x in (p0, v0, a))

    def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
        tr, s = traces[0], settings[0]
        t, p = tr.series(body, "position")
        _, v = tr.series(body, "linearVelocity")
        tp = physics_time(t, s.dt)[:, None]
        p_exact = p0 + v0 * tp + 0.5 * a * tp ** 2
        v_exact = v0 + a * tp
        T = float(tp[-1, 0])
        scale = 1.0 + np.linalg.norm(p0) + np.linalg.norm(v0) * T + np.linalg.norm(a) * T * T
        return [Measure(f"{body}.linearVelocity", _max_norm(v - v_exact),
                        ROUNDING * (1.0 + np.linalg.norm(v0) + np.linalg.norm(a) * T), "m/s"),
                Measure(f"{body}.position", _max_norm(p - p_exact),
                        0.5 * float(np.linalg.norm(a)) * T * s.dt + ROUNDING * scale, "m")]
    return expect


# -- the cases ----------------------------------------------------------------------------

G = 9.81  # the non-default gravity the scenes use
G_DEFAULT = 9.8


def _free_fall() -> Case:
    return Case("free_fall", "free_fall.x3d",
                "RigidBodyCollection.gravity 0 -9.81 0: y = y0 - g t^2/2, v = -g t",
                (Settings(1.0, 1 / 240),),
                ballistic("Ball", (0, 10, 0), (0, 0, 0), (0, -G, 0)),
                convergence="Ball.position", expected_order=1.0, exercises=("RigidBodyCollection.gravity",))


def _projectile() -> Case:
    return Case("projectile", "projectile.x3d",
                "RigidBody.linearVelocity 3 4 1: p = p0 + v0 t + g t^2/2",
                (Settings(1.0, 1 / 240),),
                ballistic("Shot", (0, 1, 0), (3, 4, 1), (0, -G, 0)),
                convergence="Shot.position", expected_order=1.0, exercises=("RigidBody.linearVelocity",))


# pendulum_period.x3d: a compound pendulum released 30 degrees from the vertical
PEND_M, PEND_L, PEND_I, PEND_THETA0 = 1.0, 1.0, 0.001, math.radians(30.0)


def pendulum_period(theta0: float = PEND_THETA0, m: float = PEND_M, length: float = PEND_L,
                    inertia: float = PEND_I, g: float = G) -> float:
    """T = 4 sqrt(I_p / (m g L)) K(sin(theta0/2)), I_p = I + m L^2 (exact, any amplitude)."""
    i_pivot = inertia + m * length * length
    return 4.0 * math.sqrt(i_pivot / (m * g * length)) * ellipk(math.sin(0.5 * theta0))


def _crossings(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Times where x changes sign, by linear interpolation between samples."""
    k = np.flatnonzero(np.signbit(x[:-1]) != np.signbit(x[1:]))
    return t[k] - x[k] * (t[k + 1] - t[k]) / (x[k + 1] - x[k])


def _pendulum_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Period measured as twice the mean time between successive passes through the vertical
    (differences of crossings: the O(dt) phase offset of a first-order scheme cancels).

    Tolerance, for a first-order integrator:
    (a) the discrete oscillator's frequency error is second order; the worst of the Euler
        family (explicit Euler, cos-phase atan(w dt)) gives |dT| <= T (w0 dt)^2 / 3
        (semi-implicit Euler: T (w0 dt)^2 / 24);
    (b) a non-symplectic first-order scheme gains (or loses) energy at a relative rate up to
        w0^2 dt per second (explicit Euler: |eigenvalue|^2 = 1 + (w0 dt)^2 per step), which
        changes the amplitude by dtheta = (dE/E) (1 - cos theta0) / sin theta0 by the last
        crossing t_c, and the period by |dT/dtheta0| dtheta: first order, c*dt with
        c = |dT/dtheta0| (1 - cos theta0)/sin theta0 w0^2 t_c.
    The crossings are read from a frame after every step by linear interpolation: at the
    vertical x'' = 0, so the interpolation error is O(dt^3 w^3), far below (a) and (b)."""
    tr, s = traces[0], settings[0]
    t, p = tr.series("Bob", "position")
    tp = physics_time(t, s.dt)
    c = _crossings(tp, p[:, 0])
    T = pendulum_period()
    w0 = math.sqrt(PEND_M * G * PEND_L / (PEND_I + PEND_M * PEND_L ** 2))
    h = 1e-6
    dT = abs(pendulum_period(PEND_THETA0 + h) - pendulum_period(PEND_THETA0 - h)) / (2 * h)
    t_c = float(c[-1]) if c.size else float(tp[-1])
    drift = w0 ** 2 * s.dt * t_c * (1 - math.cos(PEND_THETA0)) / math.sin(PEND_THETA0)
    tol = T * (w0 * s.dt) ** 2 / 3.0 + dT * drift
    if c.size < 2:
        return [Measure("Bob.period", math.inf, tol, "s")]
    measured = 2.0 * (c[-1] - c[0]) / (c.size - 1)
    return [Measure("Bob.period", abs(measured - T), tol, "s")]


def _pendulum() -> Case:
    return Case("pendulum_period", "pendulum_period.x3d",
                "SingleAxisHingeJoint, 30 degree release: T = 4 sqrt(I_p/(m g L)) K(sin(theta0/2)) = "
                f"{pendulum_period():.5f} s",
                (Settings(2.0, 1 / 240, None),), _pendulum_expect,
                convergence="Bob.period", expected_order=2.0,
                exercises=("SingleAxisHingeJoint", "SingleAxisHingeJoint.axis", "RigidBody.inertia"))


# torque_free.x3d
TF_INERTIA = np.array([[0.2, 0.03, 0.01], [0.03, 0.15, -0.02], [0.01, -0.02, 0.1]])
TF_ORIENTATION = (1.0, 1.0, 0.0, 0.7)
TF_OMEGA = np.array([1.0, 2.0, 0.5])


def torque_free_bounds(inertia: np.ndarray = TF_INERTIA, orientation=TF_ORIENTATION,
                       omega: np.ndarray = TF_OMEGA) -> dict[str, float]:
    """E0, L0 and the per-second, per-dt drift constants of a first-order rotational update.

    Euler's equations I w' = (I w) x w in body axes. A first-order step updates w with the
    gyroscopic torque tau = (I w) x w at one end of the step (explicit: the start; implicit:
    the end) and turns the body with the new w. Writing I = Ibar + D, Ibar = (Imax+Imin)/2,
    |D| = dI/2 with dI = Imax - Imin, tau = (D w) x w, so |tau| <= (dI/2) |w|^2. Then per step
      energy:   dE = dt^2/2 tau . I^-1 tau <= dt^2/2 (dI/2)^2 |w|^4 / Imin
      momentum: L_world changes by dt^2 [(I^-1 tau) x L + w x tau + 1/2 w x (w x L)]
                <= dt^2 |w|^3 (dI/2) (Imax/Imin + 3/2)
    (the exact flow keeps both; expand R exp(dt w') (L + dt L x w) to second order). Summed
    over t/dt steps: c*t*dt, first order. |w| is bounded through the energy: |w|^2 <= 2E/Imin."""
    q0 = R.from_axis_angle(np.asarray(orientation, dtype=np.float64))
    rot = R.matrix(q0)
    i_world = rot @ inertia @ rot.T
    e0 = 0.5 * omega @ i_world @ omega
    l0 = i_world @ omega
    ev = np.linalg.eigvalsh(inertia)
    i_min, i_max = float(ev[0]), float(ev[-1])
    half_spread = 0.5 * (i_max - i_min)
    w_max = math.sqrt(2.0 * e0 / i_min)
    return {"E0": float(e0), "L0": l0,
            "energy_rate": 0.5 * half_spread ** 2 * w_max ** 4 / i_min / e0,  # relative, x t dt
            "momentum_rate": w_max ** 3 * half_spread * (i_max / i_min + 1.5)}  # kg m^2/s, x t dt


def _torque_free_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    tr, s = traces[0], settings[0]
    t, rot = tr.series("Tumbler", "orientation")
    _, w = tr.series("Tumbler", "angularVelocity")
    b = torque_free_bounds()
    mats = R.matrix(R.from_axis_angle(rot))
    i_world = mats @ TF_INERTIA @ np.swapaxes(mats, 1, 2)
    lw = np.einsum("nij,nj->ni", i_world, w)
    energy = 0.5 * np.einsum("ni,ni->n", w, lw)
    T = float(physics_time(t, s.dt)[-1])
    scale_l = float(np.linalg.norm(b["L0"]))
    return [Measure("Tumbler.energy (relative)", float(np.max(np.abs(energy - b["E0"]))) / b["E0"],
                    b["energy_rate"] * T * s.dt + ROUNDING, ""),
            Measure("Tumbler.angularMomentum (world)", _max_norm(lw - b["L0"]),
                    b["momentum_rate"] * T * s.dt + ROUNDING * (1 + scale_l), "kg m^2/s")]


def _torque_free() -> Case:
    return Case("torque_free", "torque_free.x3d",
                "RigidBody.inertia off-diagonal, angularVelocity, orientation: E = 1/2 w.Iw and world "
                "L = R I R^T w constant",
                (Settings(1.0, 1 / 240),), _torque_free_expect,
                convergence="Tumbler.energy (relative)", expected_order=1.0,
                exercises=("RigidBody.inertia.offDiagonal", "RigidBody.angularVelocity", "RigidBody.orientation"))


def _constant_force() -> Case:
    return Case("constant_force", "constant_force.x3d",
                "RigidBody.forces (4 0 0) + (0 0 -2) N on 2 kg: a = F/m + g",
                (Settings(1.0, 1 / 240),),
                ballistic("Pushed", (0, 5, 0), (0, 0, 0), (2.0, -G_DEFAULT, -1.0)),
                convergence="Pushed.position", expected_order=1.0, exercises=("RigidBody.forces",))


# constant_torque.x3d
CT_TORQUE, CT_IZZ = 0.4, 0.4


def _constant_torque_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """w = alpha t exact for any scheme (ROUNDING); rotation angle alpha t^2/2 about z within
    alpha t dt / 2 (the constant-acceleration argument, on the angle); any rotation off the z
    axis counts in the same error (the angle of q_measured * conj(q_exact))."""
    tr, s = traces[0], settings[0]
    t, rot = tr.series("Spun", "orientation")
    _, w = tr.series("Spun", "angularVelocity")
    alpha = CT_TORQUE / CT_IZZ
    tp = physics_time(t, s.dt)
    w_exact = np.outer(alpha * tp, [0.0, 0.0, 1.0])
    q_exact = R.from_axis_angle(np.column_stack([np.zeros((len(tp), 2)), np.ones(len(tp)), 0.5 * alpha * tp ** 2]))
    T = float(tp[-1])
    return [Measure("Spun.angularVelocity", _max_norm(w - w_exact), ROUNDING * (1 + alpha * T), "rad/s"),
            Measure("Spun.orientation", float(np.max(R.angle_between(R.from_axis_angle(rot), q_exact))),
                    0.5 * alpha * T * s.dt + ROUNDING_ANGLE, "rad")]


def _constant_torque() -> Case:
    return Case("constant_torque", "constant_torque.x3d",
                "RigidBody.torques (0 0 0.15) + (0 0 0.25) N m, I_zz 0.4: w = alpha t, angle = alpha t^2/2",
                (Settings(1.0, 1 / 240),), _constant_torque_expect,
                convergence="Spun.orientation", expected_order=1.0,
                exercises=("RigidBody.torques", "RigidBody.inertia"))


def _gravity_off_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Floating: at rest, p = p0 and v = 0 up to ROUNDING (nothing acts on it). Falling: the
    ballistic closed form with the default gravity."""
    tr = traces[0]
    _, p = tr.series("Floating", "position")
    _, v = tr.series("Floating", "linearVelocity")
    rest = [Measure("Floating.position", _max_norm(p - np.array([0.0, 2.0, 0.0])), ROUNDING * 3, "m"),
            Measure("Floating.linearVelocity", _max_norm(v), ROUNDING, "m/s")]
    return rest + ballistic("Falling", (1, 2, 0), (0, 0, 0), (0, -G_DEFAULT, 0))(traces, settings)


def _gravity_off() -> Case:
    return Case("gravity_off", "gravity_off.x3d",
                "RigidBody.useGlobalGravity FALSE: that body stays at rest while its neighbour falls",
                (Settings(1.0, 1 / 240),), _gravity_off_expect,
                convergence="Falling.position", expected_order=1.0, exercises=("RigidBody.useGlobalGravity",))


# damping.x3d
DAMP_V0, DAMP_W0 = np.array([2.0, 0.0, -1.0]), np.array([0.0, 0.0, 3.0])
DAMP_LINEAR, DAMP_ANGULAR = 0.01, 0.02


def _damping_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """x3drbp's definition (ODE's): each step multiplies each velocity by (1 - d), so after
    n = floor(t/dt) steps v_n = v0 (1-d)^n. No gravity, no force, isotropic inertia: nothing
    else changes the velocities, under any integrator. The check is exact up to ROUNDING
    (n multiplications, each within an ulp). There is no continuous limit to converge to:
    at a fixed d the decay per second depends on dt by definition."""
    tr, s = traces[0], settings[0]
    t, v = tr.series("Damped", "linearVelocity")
    _, w = tr.series("Damped", "angularVelocity")
    n = steps(t, s.dt)[:, None]
    v_exact = DAMP_V0 * (1.0 - DAMP_LINEAR) ** n
    w_exact = DAMP_W0 * (1.0 - DAMP_ANGULAR) ** n
    return [Measure("Damped.linearVelocity", _max_norm(v - v_exact), ROUNDING * np.linalg.norm(DAMP_V0), "m/s"),
            Measure("Damped.angularVelocity", _max_norm(w - w_exact), ROUNDING * np.linalg.norm(DAMP_W0), "rad/s")]


def _damping() -> Case:
    return Case("damping", "damping.x3d",
                "RigidBody.autoDamp, linearDampingFactor 0.01, angularDampingFactor 0.02: v_n = v0 (1-d)^n",
                (Settings(1.0, 1 / 240),), _damping_expect,
                exercises=("RigidBody.autoDamp", "RigidBody.linearDampingFactor", "RigidBody.angularDampingFactor"))


def stop_overshoot(speed: float, accel: float, dt: float, error_correction: float) -> float:
    """How far past a hard stop a body may get: the stop acts on the step after the one that
    crosses it, so a step at the impact speed and acceleration lands up to speed*dt + accel*dt^2
    beyond (first order); no bounce (stopBounce 0), and the stop's error correction e (ERP)
    removes a fraction e of what is left each step, so the gravity that keeps pushing adds at
    most accel*dt^2/e in the steady state."""
    return speed * dt + accel * dt * dt / error_correction


# slider_stops.x3d
SLIDE_AXIS = np.array([0.6, -0.8, 0.0])
SLIDE_MIN, SLIDE_MAX, SLIDE_ERP = -0.2, 0.3, 1.0  # SliderJoint.stopErrorCorrection default is 1


def _slider_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Gravity along the axis a = g |axis . (0,-1,0)| = 7.848 m/s^2; the block hits the stop at
    v = sqrt(2 a maxSeparation) = 2.17 m/s. Tolerance: stop_overshoot (v dt + a dt^2, about
    9.2 mm at dt = 1/240), read from a frame after every step. The block must also be at
    the stop at the end (within the same tolerance): a block that never moved, or stopped at
    the default 1 m, fails."""
    tr, s = traces[0], settings[0]
    _, sep = tr.series("Slide", "separation")
    sep = sep[:, 0]
    a = G * abs(SLIDE_AXIS @ np.array([0.0, -1.0, 0.0]))
    tol = stop_overshoot(math.sqrt(2 * a * SLIDE_MAX), a, s.dt, SLIDE_ERP)
    beyond = max(float(np.max(sep)) - SLIDE_MAX, SLIDE_MIN - float(np.min(sep)), 0.0)
    return [Measure("Slide.separation beyond stops", beyond, tol, "m"),
            Measure("Slide.separation at the end - maxSeparation", abs(float(sep[-1]) - SLIDE_MAX), tol, "m")]


def _slider() -> Case:
    return Case("slider_stops", "slider_stops.x3d",
                "SliderJoint minSeparation -0.2 / maxSeparation 0.3, axis 0.6 -0.8 0: separation stays within "
                "the stops",
                (Settings(1.0, 1 / 240, None),), _slider_expect,
                exercises=("SliderJoint.minSeparation", "SliderJoint.maxSeparation", "SliderJoint.axis"))


# hinge_limits.x3d
HINGE_MIN, HINGE_MAX, HINGE_ERP = -0.6, 0.4, 0.8  # SingleAxisHingeJoint.stopErrorCorrection default
HINGE_M, HINGE_L, HINGE_I = 1.0, 1.0, 0.001


def _hinge_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The arm falls from horizontal through |minAngle| = 0.6 rad: impact rate
    w = sqrt(2 m g L sin 0.6 / I_p) = 3.33 rad/s, angular acceleration at most m g L / I_p;
    tolerance stop_overshoot with the hinge's default stopErrorCorrection 0.8 (about 0.014 rad
    at dt = 1/240). The arm must rest at minAngle at the end, within the same tolerance."""
    tr, s = traces[0], settings[0]
    _, ang = tr.series("Hinge", "angle")
    ang = ang[:, 0]
    i_p = HINGE_I + HINGE_M * HINGE_L ** 2
    w = math.sqrt(2 * HINGE_M * G * HINGE_L * math.sin(-HINGE_MIN) / i_p)
    tol = stop_overshoot(w, HINGE_M * G * HINGE_L / i_p, s.dt, HINGE_ERP)
    beyond = max(float(np.max(ang)) - HINGE_MAX, HINGE_MIN - float(np.min(ang)), 0.0)
    return [Measure("Hinge.angle beyond limits", beyond, tol, "rad"),
            Measure("Hinge.angle at the end - minAngle", abs(float(ang[-1]) - HINGE_MIN), tol, "rad")]


def _hinge() -> Case:
    return Case("hinge_limits", "hinge_limits.x3d",
                "SingleAxisHingeJoint minAngle -0.6 / maxAngle 0.4: angle stays within the limits",
                (Settings(1.0, 1 / 240, None),), _hinge_expect,
                exercises=("SingleAxisHingeJoint.limits", "SingleAxisHingeJoint.minAngle",
                           "SingleAxisHingeJoint.maxAngle"))


# constraint drift, shared by the ball chain and the universal joint
ERROR_CORRECTION = 0.8  # RigidBodyCollection.errorCorrection default: the scenes leave it


def _omega(tr: TraceView, body: str) -> np.ndarray:
    """|angular velocity| per frame (a fixed body is in the trace too, at rest)."""
    return np.linalg.norm(tr.series(body, "angularVelocity")[1], axis=1)


# ball_chain.x3d: link k joins Link k (body1) to Link k-1 (body2, Anchor for k = 1), anchors
# at each link's end, 0.1 m from the link's centre
CHAIN_LINKS, CHAIN_R, CHAIN_MASS, CHAIN_I, CHAIN_LENGTH = 5, 0.1, 0.2, 0.001, 1.0


def _omega_cap(inertia: float) -> float:
    """No link can spin faster than if all the energy the chain can release (its whole mass
    falling its whole length) went into its rotation: w^2 <= 2 M g L / I."""
    return math.sqrt(2 * CHAIN_LINKS * CHAIN_MASS * G * CHAIN_LENGTH / inertia)


def _chain_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """|body1AnchorPoint - body2AnchorPoint| per joint and frame.

    Engines that build the chain as a kinematic tree (generalized coordinates) hold it exactly:
    rounding only. An engine that ties free bodies with velocity-level constraints makes the two
    anchors' velocities agree, and one step then leaves them apart by the difference of their
    arcs and chords: at most dt^2/2 (|w1|^2 r1 + |w2|^2 r2) (centripetal terms; r = the anchor's
    distance from the body's origin); error correction (ERP, 0.8 by default) removes that
    fraction of the gap each step, so it settles below dt^2/(2 ERP) (|w1|^2 r1 + |w2|^2 r2):
    second order per step, with the rates read from the trace at every step (capped by the
    energy the chain can release, so that a runaway cannot widen its own tolerance)."""
    tr, s = traces[0], settings[0]
    errors, bounds = [], []
    for k in range(1, CHAIN_LINKS + 1):
        _, a1 = tr.series(f"Joint{k}", "body1AnchorPoint")
        _, a2 = tr.series(f"Joint{k}", "body2AnchorPoint")
        cap = _omega_cap(CHAIN_I)
        w1 = np.minimum(_omega(tr, f"Link{k}"), cap)
        w2 = np.minimum(_omega(tr, "Anchor" if k == 1 else f"Link{k - 1}"), cap)
        r2 = 0.0 if k == 1 else CHAIN_R
        errors.append(_max_norm(a1 - a2))
        bounds.append(float(np.max(w1 ** 2 * CHAIN_R + w2 ** 2 * r2)) * s.dt ** 2 / (2 * ERROR_CORRECTION))
    worst = int(np.argmax(np.array(errors) / (np.array(bounds) + ROUNDING)))
    return [Measure(f"Joint{worst + 1} anchor gap (worst joint)", errors[worst], bounds[worst] + ROUNDING, "m")]


def _chain() -> Case:
    return Case("ball_chain", "ball_chain.x3d",
                "BallJoint chain of 5 links: body1AnchorPoint = body2AnchorPoint for every joint",
                (Settings(1.5, 1 / 240, None),), _chain_expect, exercises=("BallJoint.anchorPoint",))


UJ_INERTIA = {"Upper": 0.02, "Lower": 0.01}
# the most energy gravity can give the arms: Upper's centre (0.5 m from the fixed shoulder, at
# y = -0.4) can fall 0.1 m; Lower's (at most 1.0 + 0.5 m from the shoulder, at y = -0.8) 0.7 m
UJ_ENERGY = 1.0 * G * 0.1 + 0.5 * G * 0.7


def _universal_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """|body1Axis . body2Axis| (the cosine; the joint keeps it 0).

    Tree-built joints: rounding only. Velocity-level constraints keep d/dt (a1 . a2) = 0; one
    step's second-order term is at most dt^2/2 |d^2/dt^2 (a1 . a2)| <= dt^2/2 (|w1| + |w2|)^2,
    and error correction settles the drift below dt^2/(2 ERP) (|w1| + |w2|)^2, with the rates
    read from the trace at every step (each capped by the energy the arms can release)."""
    tr, s = traces[0], settings[0]
    _, a1 = tr.series("Cross", "body1Axis")
    _, a2 = tr.series("Cross", "body2Axis")
    w1 = np.minimum(_omega(tr, "Upper"), math.sqrt(2 * UJ_ENERGY / UJ_INERTIA["Upper"]))
    w2 = np.minimum(_omega(tr, "Lower"), math.sqrt(2 * UJ_ENERGY / UJ_INERTIA["Lower"]))
    with np.errstate(invalid="ignore", divide="ignore"):  # an axis of length 0 is NaN: a failure
        cos = np.abs(np.einsum("ni,ni->n", a1, a2)) / (np.linalg.norm(a1, axis=1) * np.linalg.norm(a2, axis=1))
    bound = float(np.max((w1 + w2) ** 2)) * s.dt ** 2 / (2 * ERROR_CORRECTION)
    return [Measure("Cross |body1Axis . body2Axis|", float(np.max(cos)), bound + ROUNDING, "")]


def _universal() -> Case:
    return Case("universal_joint", "universal_joint.x3d",
                "UniversalJoint axis1 0.8 0.6 0 / axis2 -0.6 0.8 0: body1Axis stays perpendicular to body2Axis",
                (Settings(1.5, 1 / 240, None),), _universal_expect,
                exercises=("UniversalJoint.axis1", "UniversalJoint.axis2", "UniversalJoint.anchorPoint"))


def _frame_rate_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Tolerance 0: both runs have taken the same floor(1.0/dt) = 240 steps of a deterministic
    engine when t = 1.0 s, and frames only read state (x3d_core.evaluator's contract). Any
    difference, even in the last digit (traces keep every digit), is frame-dependent physics."""
    t_end = 1.0
    a, b = traces[0].at(t_end), traces[1].at(t_end)
    if not a or set(a) != set(b):
        missing = sorted(set(a) ^ set(b))
        detail = f" (outputs in one run only: {missing[:4]})" if missing else " (no rows at t = 1)"
        return [Measure("state at t = 1 s, 30 Hz vs 144 Hz" + detail, math.inf, 0.0)]
    diff = max(float(np.max(np.abs(a[k] - b[k]))) for k in a)
    return [Measure("state at t = 1 s, 30 Hz vs 144 Hz (max difference)", diff, 0.0)]


def _frame_rate() -> Case:
    return Case("frame_rate", "frame_rate.x3d",
                "frame-rate independence: 30 Hz and 144 Hz frames, dt 1/240, identical state at t = 1 s",
                (Settings(1.0, 1 / 240, 30.0), Settings(1.0, 1 / 240, 144.0)), _frame_rate_expect,
                exercises=("RigidBody.autoDamp", "SingleAxisHingeJoint", "RigidBody.inertia.offDiagonal"))


# hinge_bounce.x3d: the hinge_limits arm, with a bouncing stop
BOUNCE, BOUNCE_MIN, BOUNCE_ERP, BOUNCE_CFM = 0.5, -0.6, 0.2, 1e-6
BOUNCE_M, BOUNCE_L, BOUNCE_I = 1.0, 1.0, 0.001


def _bounce_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """ODE's stop bounce (dxJointLimitMotor::addLimot): on a step that starts with the joint past
    the stop and moving into it at rate v, the stop's row targets the rate -stopBounce x v (or the
    error correction's stopErrorCorrection x penetration / h, if larger: at most 0.2 |v| here, so
    never). Measured from a frame after every step: the impact is the first frame i after which
    angleRate stops falling (gravity makes it fall every step until then); before = -angleRate[i],
    after = angleRate[i+1], and after = 0.5 x before.

    Tolerance. Frames i and i+1 are one step apart, and engines differ in where in that step
    they meet the stop: ODE on the step after the one that crossed it (then after = 0.5 before
    exactly), a predictive engine part way through the step. Gravity changes the rate by at
    most a h in a step (a = m g L / I_p, the largest angular acceleration it can give): before
    the impact, that raises the impact speed above the measured one (which the bounce halves);
    after it, it slows the rebound; so after - 0.5 before lies in [-a h, 0.5 a h]: |error| <= a h.
    ODE's stop row also yields by CFM times its force (a stop starts with the world's CFM), a
    rate CFM I_p (1 + e) v / h with v at most sqrt(2 m g L / I_p) (all of the arm's fall);
    at CFM 1e-6 about 1.6 mm/s. The impact must also happen at the stop: the frame before it is
    at most one step's travel (v + a h) h from minAngle, on either side."""
    tr, s = traces[0], settings[0]
    _, ang = tr.series("Hinge", "angle")
    _, rate = tr.series("Hinge", "angleRate")
    ang, rate = ang[:, 0], rate[:, 0]
    i_p = BOUNCE_I + BOUNCE_M * BOUNCE_L ** 2
    accel = BOUNCE_M * G * BOUNCE_L / i_p
    w_cap = math.sqrt(2 * BOUNCE_M * G * BOUNCE_L / i_p)
    softness = BOUNCE_CFM * i_p * ((1 + BOUNCE) * w_cap + accel * s.dt) / s.dt
    tol_rate = accel * s.dt + softness + ROUNDING * (1 + w_cap)
    names = (f"Hinge.angleRate after the impact - {BOUNCE:g} x speed before", "Hinge.angle at the impact - minAngle")
    rising = np.flatnonzero(np.diff(rate) > 0)
    if not rising.size or rate[rising[0]] >= 0:  # no impact, or a stop that never turned the arm
        return [Measure(names[0], math.inf, tol_rate, "rad/s"),
                Measure(names[1], math.inf, (w_cap + accel * s.dt) * s.dt + ROUNDING_ANGLE, "rad")]
    i = int(rising[0])
    before, after = -rate[i], rate[i + 1]
    tol_angle = (min(before, w_cap) + accel * s.dt) * s.dt + ROUNDING_ANGLE
    return [Measure(names[0], abs(after - BOUNCE * before), tol_rate, "rad/s"),
            Measure(names[1], abs(ang[i] - BOUNCE_MIN), tol_angle, "rad")]


def _hinge_bounce() -> Case:
    return Case("hinge_bounce", "hinge_bounce.x3d",
                "SingleAxisHingeJoint stopBounce 0.5 at minAngle -0.6: angleRate after the impact = -0.5 x "
                "angleRate before (ODE's stop bounce)",
                (Settings(1.0, 1 / 240, None),), _bounce_expect,
                exercises=("SingleAxisHingeJoint.stopBounce", "SingleAxisHingeJoint.stopErrorCorrection",
                           "SingleAxisHingeJoint.minAngle", "RigidBodyCollection.constantForceMix"))


# motor_speed.x3d: a wheel (body2) on a fixed chassis (body1), its axle motor on axis2
MOTOR_TARGET, MOTOR_MAX_TORQUE, MOTOR_I = 4.0, 0.2, 0.05
MOTOR_AXIS2 = np.array([0.0, 0.0, 1.0])


def _motor_speed_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """ODE's joint motor is a velocity constraint whose force is bounded by maxTorque: each step
    it reaches the target rate if a torque within the bound can, else it pushes with maxTorque.
    The rate (hinge2AngleRate = axis2 . (w1 - w2), the wheel being body2 on a fixed body1) is
    alpha n h for steps n < n* = t*/h, alpha = maxTorque/I, and w from step n* on; the wheel's
    angular velocity is -rate along axis2 (its centre of mass on the anchor, its axle a principal
    axis: no other torque acts).

    Ramp (steps n < n*): a constant torque, so the rate is exact for every one-step scheme:
    ROUNDING. Hold (steps n >= n*): a velocity constraint is exactly on the target; a motor acting
    through a torque computed at the start of the step (a servo) can be off it, but by no more
    than one step at the torque limit can change the rate: alpha h."""
    tr, s = traces[0], settings[0]
    t, w = tr.series("Wheel", "angularVelocity")
    n = steps(t, s.dt)
    alpha = MOTOR_MAX_TORQUE / MOTOR_I
    n_star = math.ceil(MOTOR_TARGET / (alpha * s.dt) - _STEP_SLACK)
    rate = np.minimum(alpha * n * s.dt, MOTOR_TARGET)
    error = np.linalg.norm(w - np.outer(-rate, MOTOR_AXIS2), axis=1)
    ramp, hold = n < n_star, n >= n_star
    rounding = ROUNDING * (1 + MOTOR_TARGET)
    return [Measure("Wheel.angularVelocity, torque-limited ramp (t < t*)",
                    float(np.max(error[ramp])) if ramp.any() else math.inf, rounding, "rad/s"),
            Measure("Wheel.angularVelocity, at the target (t >= t*)",
                    float(np.max(error[hold])) if hold.any() else math.inf, alpha * s.dt + rounding, "rad/s")]


def _motor_speed() -> Case:
    t_star = MOTOR_I * MOTOR_TARGET / MOTOR_MAX_TORQUE
    return Case("motor_speed", "motor_speed.x3d",
                "DoubleAxisHingeJoint desiredAngularVelocity2 4 / maxTorque2 0.2, I 0.05: rate = (maxTorque/I) t "
                f"until t* = I w / maxTorque = {t_star:g} s, then w",
                (Settings(1.5, 1 / 240, None),), _motor_speed_expect,
                exercises=("DoubleAxisHingeJoint.desiredAngularVelocity2", "DoubleAxisHingeJoint.maxTorque2",
                           "DoubleAxisHingeJoint.axis2", "RigidBody.inertia"))


# motor_joint_torque.x3d: an AMotor between two free bodies, no gravity
MJ_TORQUE, MJ_I1, MJ_I2 = 0.6, 0.2, 0.4  # the moments about the motor's axis z
MJ_AXIS = np.array([0.0, 0.0, 1.0])


def _motor_joint_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """body1 gets +tau about the axis, body2 -tau, every step; the axis is a principal axis of
    both, so neither turns off it (no gyroscopic torque) and each has a constant angular
    acceleration: w1 = tau t / I1, w2 = -tau t / I2, and motor1AngleRate = axis . (w1 - w2) =
    (1/I1 + 1/I2) tau t. Velocities under a constant acceleration are exact for every one-step
    scheme: ROUNDING."""
    tr, s = traces[0], settings[0]
    t, w1 = tr.series("Rotor", "angularVelocity")
    _, w2 = tr.series("Stator", "angularVelocity")
    _, rate = tr.series("Motor", "motor1AngleRate")
    tp = physics_time(t, s.dt)
    a1, a2 = MJ_TORQUE / MJ_I1, -MJ_TORQUE / MJ_I2
    T = float(tp[-1])
    return [Measure("Rotor.angularVelocity", _max_norm(w1 - np.outer(a1 * tp, MJ_AXIS)),
                    ROUNDING * (1 + abs(a1) * T), "rad/s"),
            Measure("Stator.angularVelocity", _max_norm(w2 - np.outer(a2 * tp, MJ_AXIS)),
                    ROUNDING * (1 + abs(a2) * T), "rad/s"),
            Measure("Motor.motor1AngleRate", _max_norm(rate[:, 0] - (a1 - a2) * tp),
                    ROUNDING * (1 + (a1 - a2) * T), "rad/s")]


def _motor_joint() -> Case:
    return Case("motor_joint_torque", "motor_joint_torque.x3d",
                "MotorJoint axis1Torque 0.6 about motor1Axis 0 0 1, two free bodies (I_zz 0.2, 0.4): w1 = tau t/I1, "
                "w2 = -tau t/I2, motor1AngleRate = (1/I1 + 1/I2) tau t",
                (Settings(1.0, 1 / 240),), _motor_joint_expect,
                exercises=("MotorJoint.axis1Torque", "MotorJoint.motor1Axis", "MotorJoint.autoCalc",
                           "RigidBody.inertia"))


# erp_cfm_spring.x3d: two weights, each on a vertical slider (the tree joint) and a ball joint
# at its centre of mass (the joint that closes the loop, and the only one that holds it up)
SPRING_ERP, SPRING_CFM = 0.2, 1e-5
SPRING_WEIGHTS = {"Light": (1.0, np.array([0.0, 1.0, 0.0])), "Heavy": (4.0, np.array([1.0, 1.0, 0.0]))}
SPRING_SETTLED = 0.5  # s: measured from here on


def spring_constants(dt: float, erp: float = SPRING_ERP, cfm: float = SPRING_CFM) -> tuple[float, float]:
    """ODE's soft constraint as a spring and damper: k = ERP/(h CFM), c = (1 - ERP)/CFM."""
    return erp / (dt * cfm), (1.0 - erp) / cfm


def _spring_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """The gap body1AnchorPoint - body2AnchorPoint of each loop-closing ball joint, from 0.5 s on,
    must be (0, -m g / k, 0).

    Why this configuration. A joint of the tree is exact in the engines that build joints in
    reduced coordinates (no ERP/CFM acts on it), so only a joint that closes a loop is a soft
    constraint there; and in ODE, where every joint is soft, two joints that both carry the
    load share it in a way that depends on both. Here the tree joint is a vertical slider: it
    has no constraint row along its axis, so the weight rests on the ball joint's vertical row
    alone, in either formulation, and the ball's other rows carry nothing (the slider already
    holds the weight's horizontal position and its orientation, and gravity acts at the anchor).

    Why the closed form holds exactly. At rest J v = 0 in ODE's row J v = (ERP/h)(-error) +
    CFM lambda, so lambda = (ERP/(h CFM)) error = k error, and lambda = m g: error = m g / k is a
    fixed point of the step itself, not only of the continuous spring. Two masses (1 and 4 kg)
    show that the spring's constant does not depend on what hangs from it: an engine whose
    softness is scaled by a row's effective mass matches at one mass only.

    Tolerance. The spring-damper is overdamped (c^2 >> 4 k m) and settles with the time constant
    c/k = (1 - ERP) h / ERP = 4 steps; from rest at the unsprung position the gap's distance from
    its fixed point stays below sag exp(-t k / c) (the slow mode; the fast one, m/c, is shorter
    than a step), 1e-13 of the sag by 0.5 s. What is left is rounding of the positions (O(1) m):
    ROUNDING per metre."""
    tr, s = traces[0], settings[0]
    k, c = spring_constants(s.dt)
    out = []
    for name, (m, anchor) in SPRING_WEIGHTS.items():
        t, a1 = tr.series(f"{name}Hold", "body1AnchorPoint")
        _, a2 = tr.series(f"{name}Hold", "body2AnchorPoint")
        late = physics_time(t, s.dt) >= SPRING_SETTLED
        sag = m * G / k
        error = _max_norm((a1 - a2)[late] - np.array([0.0, -sag, 0.0])) if late.any() else math.inf
        tol = sag * math.exp(-SPRING_SETTLED * k / c) + ROUNDING * (1 + float(np.linalg.norm(anchor)))
        out.append(Measure(f"{name}Hold gap - (0, -m g/k, 0), m = {m:g} kg", error, tol, "m"))
    return out


def _spring() -> Case:
    k, _ = spring_constants(1 / 240)
    return Case("erp_cfm_spring", "erp_cfm_spring.x3d",
                "RigidBodyCollection errorCorrection 0.2 / constantForceMix 1e-5: a loop-closing BallJoint is a "
                f"spring k = ERP/(h CFM) = {k:.3g} N/m; static sag m g/k (1 and 4 kg)",
                (Settings(1.0, 1 / 240),), _spring_expect,
                exercises=("RigidBodyCollection.errorCorrection", "RigidBodyCollection.constantForceMix",
                           "BallJoint.anchorPoint"))


# double_pendulum_energy.x3d: absolute angles phi from the downward vertical, about +z
DP_M1, DP_D1, DP_L1, DP_I1 = 2.0, 0.5, 1.0, 0.16  # mass, shoulder-centre, shoulder-elbow, I_zz
DP_M2, DP_D2, DP_I2 = 1.5, 0.4, 0.08  # mass, elbow-centre, I_zz
DP_PHI = (math.radians(30.0), math.radians(45.0))
DP_INERTIA = {"Upper": np.diag([0.1, 0.1, DP_I1]), "Lower": np.diag([0.05, 0.05, DP_I2])}
DP_MASS = {"Upper": DP_M1, "Lower": DP_M2}


def _dp_matrices(phi1: float, phi2: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mass matrix M(q), potential Hessian K(q) and generalized gravity force f(q) = -dV/dq of
    the chain in the absolute angles q = (phi1, phi2):
    T = 1/2 [A phi1'^2 + 2 B cos(phi1 - phi2) phi1' phi2' + C phi2'^2],
    V = -P1 g cos phi1 - P2 g cos phi2."""
    a = DP_I1 + DP_M1 * DP_D1 ** 2 + DP_M2 * DP_L1 ** 2
    b = DP_M2 * DP_L1 * DP_D2 * math.cos(phi1 - phi2)
    c = DP_I2 + DP_M2 * DP_D2 ** 2
    p1, p2 = (DP_M1 * DP_D1 + DP_M2 * DP_L1) * G, DP_M2 * DP_D2 * G
    return (np.array([[a, b], [b, c]]), np.diag([p1 * math.cos(phi1), p2 * math.cos(phi2)]),
            np.array([-p1 * math.sin(phi1), -p2 * math.sin(phi2)]))


def double_pendulum() -> dict[str, float | np.ndarray]:
    """E0 and E_min (both links hanging down), the larger normal-mode frequency at rest, and
    the initial angular accelerations (at rest the Coriolis terms vanish: M q'' = f)."""
    p1, p2 = DP_PHI
    y1 = -DP_D1 * math.cos(p1)
    y2 = -DP_L1 * math.cos(p1) - DP_D2 * math.cos(p2)
    e0 = G * (DP_M1 * y1 + DP_M2 * y2)
    e_min = -G * (DP_M1 * DP_D1 + DP_M2 * (DP_L1 + DP_D2))
    m0, k0, _ = _dp_matrices(0.0, 0.0)
    mq, kq, f = _dp_matrices(p1, p2)
    omega_max = math.sqrt(float(np.max(np.linalg.eigvals(np.linalg.solve(m0, k0)).real)))
    return {"E0": e0, "Emin": e_min, "omega_max": omega_max, "accel0": np.linalg.solve(mq, f),
            "stiffness0": float(np.linalg.norm(np.linalg.solve(mq, kq), 2))}


def _dp_energy(tr: TraceView) -> tuple[np.ndarray, np.ndarray]:
    """Times and E = sum m g y + 1/2 m |v|^2 + 1/2 w.(R I R^T) w, with the scene's masses and inertias."""
    total, t = 0.0, None
    for name, m in DP_MASS.items():
        t, p = tr.series(name, "position")
        _, v = tr.series(name, "linearVelocity")
        _, w = tr.series(name, "angularVelocity")
        _, rot = tr.series(name, "orientation")
        mats = R.matrix(R.from_axis_angle(rot))
        i_world = mats @ DP_INERTIA[name] @ np.swapaxes(mats, 1, 2)
        total = total + m * (G * p[:, 1] + 0.5 * np.einsum("ni,ni->n", v, v)) + \
            0.5 * np.einsum("ni,nij,nj->n", w, i_world, w)
    return t, total


def _double_pendulum_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Energy: max |E(t) - E0| over 2 s.

    Tolerance for a first-order integrator, argued on the linearised chain (two normal modes,
    frequencies w1 < w2): explicit Euler, the worst of the Euler family, multiplies each mode's
    energy by |eigenvalue|^2 = 1 + (w h)^2 per step; semi-implicit Euler (symplectic) keeps it
    within an O(w h) oscillation with no drift; implicit Euler loses it. So over n steps
    |E - E0| <= (E0 - E_min) ((1 + (w2 h)^2)^n - 1) ~ (E0 - E_min) w2^2 h t: first order.
    Away from rest the local frequencies are lower (the potential's Hessian falls as cos phi, and
    the largest eigenvalue of M(q)^-1 K(q) over |phi1| <= 90, |phi2| <= 120 degrees is at rest),
    so w2 at rest bounds them along the motion. The step is 1 ms: at 1/240 s this bound is 57%
    of the oscillation's energy, too loose to see an inertia ignored; at 1 ms it is 11%.

    The energy is blind to a motion that never starts (a hinge axis ignored, along gravity), so
    the first step is checked too: from rest every one-step scheme of the Euler family gives
    w(h) = h q''(0), q''(0) = M(q0)^-1 f(q0) (Coriolis terms vanish at rest), exact up to
    ROUNDING; a scheme evaluating the acceleration elsewhere in the step differs by at most
    h |M^-1 K| h^2 |q''(0)| (the configuration moves by h^2 |q''| in a step)."""
    tr, s = traces[0], settings[0]
    d = double_pendulum()
    t, energy = _dp_energy(tr)
    n = steps(t, s.dt)
    drift = (d["E0"] - d["Emin"]) * ((1.0 + (d["omega_max"] * s.dt) ** 2) ** float(n[-1]) - 1.0)
    out = [Measure("double pendulum |E - E0|", float(np.max(np.abs(energy - d["E0"]))),
                   drift + ROUNDING * (1 + abs(d["E0"])), "J")]
    first = np.flatnonzero(n == 1)
    for k, name in enumerate(DP_MASS):
        a0 = float(d["accel0"][k])
        tol = ROUNDING * (1 + abs(a0) * s.dt) + s.dt ** 3 * d["stiffness0"] * abs(a0)
        if not first.size:
            out.append(Measure(f"{name}.angularVelocity after one step (no frame there)", math.inf, tol, "rad/s"))
            continue
        _, w = tr.series(name, "angularVelocity")
        out.append(Measure(f"{name}.angularVelocity after one step - h q''(0)",
                           _max_norm(w[first[:1]] - np.array([0.0, 0.0, a0 * s.dt])), tol, "rad/s"))
    return out


def _double_pendulum() -> Case:
    d = double_pendulum()
    return Case("double_pendulum_energy", "double_pendulum_energy.x3d",
                "two SingleAxisHingeJoints, masses 2 / 1.5 kg, I_zz 0.16 / 0.08, released at 30 / 45 degrees: "
                f"E = {d['E0']:.4f} J constant within the first-order bound; first step w = h q''(0)",
                (Settings(2.0, 1 / 1000, None),), _double_pendulum_expect,
                convergence="double pendulum |E - E0|", expected_order=1.0,
                exercises=("SingleAxisHingeJoint.axis", "SingleAxisHingeJoint.anchorPoint", "RigidBody.mass",
                           "RigidBody.inertia"))


CASES: tuple[Case, ...] = (_free_fall(), _projectile(), _pendulum(), _torque_free(), _constant_force(),
                           _constant_torque(), _gravity_off(), _damping(), _slider(), _hinge(), _chain(),
                           _universal(), _frame_rate(), _hinge_bounce(), _motor_speed(),
                           _motor_joint(), _spring(), _double_pendulum())
BY_NAME = {c.name: c for c in CASES}
CONVERGENCE_DTS = (1 / 60, 1 / 120, 1 / 240, 1 / 480)


def select(names: Sequence[str] | None) -> list[Case]:
    """The named cases (all when None); KeyError naming the unknown ones."""
    if not names:
        return list(CASES)
    unknown = [n for n in names if n not in BY_NAME]
    if unknown:
        raise KeyError(f"unknown case(s) {', '.join(unknown)}; known: {', '.join(BY_NAME)}")
    return [BY_NAME[n] for n in names]


# -- collisions ---------------------------------------------------------------------------
# x3d_core/collision.py states what x3drbp reads: ODE's contacts. The argument below follows
# ODE's contact step, which the other engines approximate (each declares how):
# - a contact exists on a step that STARTS with the geometries overlapping, and is solved in that
#   step together with gravity (the step's velocity is the contact's unknown): a body meets a
#   surface at most one step late, and a resting body feels no unresisted step of gravity;
# - its normal row targets max(ERP max(depth - contactSurfaceThickness, 0) / h, e v_in), the
#   bounce e v_in only where the incoming speed v_in (at the step's start) exceeds minBounceSpeed;
#   ERP is errorCorrection unless ERROR_REDUCTION applies;
# - every row is softened by CFM (constantForceMix, 1e-4 in every scene: Bullet cannot set it):
#   a row carrying a force f lets its velocity off target by CFM f (x3drbp's ODE reading, as in
#   erp_cfm_spring), so a resting body sinks to CFM f h / ERP beyond the layer, a friction row
#   holding a load f creeps at CFM f, and an impact impulse P yields CFM P / h of the bounce;
# - friction is Coulomb's pyramid: |f_k| <= mu_k N along ODE's friction directions; each case
#   moves bodies along one friction direction, where the pyramid and a cone agree.
# Where a bound needs "one step of unresisted gravity", it is an engine that lets a body fall
# one step before its contact acts (a contact found after the step, as Bullet's are): g h of
# velocity and g h^2 of position. The contact loads are bounded by a whole interface's load on
# one contact point (ODE shares it among up to 4 box corners: 4 times less).
CFM_DEFAULT, ERP_DEFAULT = 1e-4, 0.8


def _runs(series: np.ndarray) -> list[tuple[int, int]]:
    """Maximal runs [i, j] (inclusive) of True in a boolean array."""
    out, start = [], None
    for i, flag in enumerate(series.tolist() + [False]):
        if flag and start is None:
            start = i
        elif not flag and start is not None:
            out.append((start, i - 1))
            start = None
    return out


def flights(tp: np.ndarray, vy: np.ndarray, g: float) -> list[tuple[int, int]]:
    """The ball's flights, in order: maximal runs of frames joined by free-fall intervals
    (vertical velocity falling by exactly g per second: nothing touched the ball between the two
    frames), as (first frame, last frame). Whatever is not free fall is contact: an impact, or
    rest. The first flight is the drop from frame 0."""
    free = np.abs(np.diff(vy) + g * np.diff(tp)) <= 1e-6 + ROUNDING * np.abs(vy[1:])
    return [(i, j + 1) for i, j in _runs(free)]


# bounce_apex.x3d: per ball (collection's bounce e, drop height h0 of its bottom above the floor)
BA_G, BA_R, BA_M, BA_MIN, BA_ERP = G, 0.05, 0.01, 0.5, 0.1
BA_BALLS = {"High02": (0.2, 1.0), "Low02": (0.2, 0.0637), "High05": (0.5, 1.0), "Low05": (0.5, 0.1019),
            "High08": (0.8, 1.0), "Low08": (0.8, 0.0389)}


@dataclass(frozen=True)
class BounceSchedule:
    """What a ball's bounces must be, and how well, at one step size."""
    speeds: list[float]  # closed-form impact speeds v_k = e^k sqrt(2 g h0), k = 0, 1, ...
    speed_errors: list[float]  # how far a first-order engine's impact speed may be from v_k
    apexes: list[float]  # h_n = e^(2n) h0 after impact n-1 (n = 1 .. bounces)
    apex_errors: list[float]
    bounces: int  # impacts surely faster than minBounceSpeed (they bounce)
    stops: bool  # impact `bounces` is surely slower than minBounceSpeed (it does not)
    pop: float  # the highest apex the error correction can throw the ball to after that impact
    times: list[float]  # closed-form impact times


def bounce_schedule(e: float, h0: float, dt: float, g: float = BA_G, v_min: float = BA_MIN, mass: float = BA_M,
                    erp: float = BA_ERP, cfm: float = CFM_DEFAULT, frame: float | None = None) -> BounceSchedule:
    """Impact by impact, the closed form and its tolerance, carried from one bounce to the next.

    Impact k. The closed-form speed is v_k; an engine's differs by S_k:
    - finding the impact: a contact acts at the start of the first step that begins overlapping,
      at most one step after the crossing (g h more speed), and a first-order scheme's fall lags
      the parabola by at most g t h / 2, which moves the crossing by at most h/2 (v = g t): so
      1.5 g h (a predictive contact, acting up to a step early, stays inside it);
    - rebound: u_k = e v_k, less ODE's softness: the impulse P = m (1 + e) v (plus a step of
      gravity) yields CFM P / h of it, gamma = CFM m / h: U_k = e S_k + gamma ((1 + e) v + g h);
    - the ball leaves from up to (v + S) h inside the floor (a step's travel), so it is back at
      the floor's top slower, by at most g (v + S) h / (u - U) (energy: u^2 - 2 g depth);
    - so S_(k+1) = U_k + g (v_k + S_k) h / (u_k - U_k) + 1.5 g h.
    Apex n (after impact k = n-1): z = depth + u^2 / (2 g), so it is off by at most the depth
    (v + S) h, plus (2 u U + U^2) / (2 g) from the rebound speed, plus u h / 2 for the scheme's
    lag over the rise (as above) and g h^2 for rounding of the lag's bound, plus g tau^2 / 8 for
    reading the top between frames tau apart.
    An impact is sure to bounce if v_k - S_k > minBounceSpeed, sure not to if v_k + S_k <
    minBounceSpeed; else ambiguous, and nothing after it is predicted. After the first impact
    sure not to bounce, only the error correction can throw the ball: depth at most (v + S) h,
    so a speed at most ERP (v + S) + g h, and an apex at most that squared / 2 g (plus u h / 2).
    """
    h = dt
    tau = frame if frame is not None else dt
    gamma = cfm * mass / h
    speeds, errors, apexes, apex_errors, times = [math.sqrt(2 * g * h0)], [1.5 * g * h], [], [], [math.sqrt(2 * h0 / g)]
    while True:
        v, s = speeds[-1], errors[-1]
        if v - s > v_min:
            u = e * v
            big_u = e * s + gamma * ((1 + e) * (v + s) + g * h)
            depth = (v + s) * h
            apexes.append(u * u / (2 * g))
            apex_errors.append(depth + (2 * u * big_u + big_u ** 2) / (2 * g) + (u + big_u) * h / 2 + g * h * h
                               + g * tau * tau / 8)
            speeds.append(u)
            errors.append(big_u + g * depth / max(u - big_u, 1e-12) + 1.5 * g * h)
            times.append(times[-1] + 2 * u / g)
            continue
        stops = v + s < v_min
        throw = erp * (v + s) + g * h
        pop = throw * throw / (2 * g) + throw * h / 2 + g * tau * tau / 8
        return BounceSchedule(speeds, errors, apexes, apex_errors, len(apexes), stops, pop, times)


BA_SETTINGS = Settings(2.5, 1 / 2000, 500.0)


def _bounce_apex_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Per ball, from its flights (free-fall runs of frames, see flights()): the apex of its bottom
    above the floor after bounce n against e^(2n) h0, within bounce_schedule()'s carried
    tolerance, for each bounce the schedule is sure of and the run sees end 0.1 s before its end;
    for a ball whose schedule ends on an impact sure to be slower than minBounceSpeed: no later
    flight rises above the error correction's throw (bouncing has ended), and over the last
    0.25 s the ball is at rest: |v| within one step of unresisted gravity, g h."""
    tr, s = traces[0], settings[0]
    out = []
    for name, (e, h0) in BA_BALLS.items():
        t, p = tr.series(name, "position")
        _, v = tr.series(name, "linearVelocity")
        tp = physics_time(t, s.dt)
        z = p[:, 1] - BA_R
        found = flights(tp, v[:, 1], BA_G)
        sched = bounce_schedule(e, h0, s.dt, frame=1.0 / s.rate)
        for n in range(1, sched.bounces + 1):
            if sched.times[n] + 0.1 > s.duration:
                break
            apex = float(np.max(z[found[n][0]:found[n][1] + 1])) if n < len(found) else 0.0
            out.append(Measure(f"{name} (e = {e:g}) apex after bounce {n} - e^{2 * n} h0",
                               abs(apex - sched.apexes[n - 1]), sched.apex_errors[n - 1], "m"))
        if sched.stops and sched.times[sched.bounces] + 0.1 < s.duration:
            later = [float(np.max(z[i:j + 1])) for i, j in found[sched.bounces + 1:]]
            out.append(Measure(f"{name} highest flight after impact {sched.bounces + 1} (slower than minBounceSpeed)",
                               max(later + [0.0]), sched.pop, "m"))
            end = tp >= tp[-1] - 0.25
            out.append(Measure(f"{name} |linearVelocity| over the last 0.25 s (at rest)", _max_norm(v[end]),
                               BA_G * s.dt + ROUNDING, "m/s"))
    return out


def _bounce_apex() -> Case:
    return Case("bounce_apex", "bounce_apex.x3d",
                "CollisionCollection bounce 0.2 / 0.5 / 0.8, minBounceSpeed 0.5: apex h_n = e^(2n) h0 while impacts "
                "beat minBounceSpeed; the first slower impact ends the bouncing",
                (BA_SETTINGS,), _bounce_apex_expect,
                exercises=("CollisionCollection", "CollisionCollection.bounce", "CollisionCollection.minBounceSpeed",
                           "CollisionCollection.appliedParameters.BOUNCE", "CollidableShape.geometry.Sphere",
                           "CollidableShape.geometry.Box", "RigidBodyCollection.errorCorrection"))


# incline.x3d: boxes (1 kg, 0.1 m thick) on inclines (0.2 m thick) turned about +z by theta; each
# starts at rest 2 m up the slope from the centre of its incline's top face
INC_MU, INC_M, INC_UP, INC_OFFSET = 0.5, 1.0, 2.0, 0.1 + 0.05
INC_BOXES = {"Stuck": (math.radians(20.0), -1.0), "Slider": (math.radians(35.0), 1.0)}
INC_FIT_FROM = 0.25  # s


def incline_frame(theta: float, z: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Start position, downhill unit vector and slope normal of a box on an incline."""
    uphill = np.array([math.cos(theta), math.sin(theta), 0.0])
    normal = np.array([-math.sin(theta), math.cos(theta), 0.0])
    return np.array([0.0, 0.0, z]) + INC_OFFSET * normal + INC_UP * uphill, -uphill, normal


def fitted_acceleration(t: np.ndarray, s: np.ndarray) -> tuple[float, float]:
    """Least-squares a of s = c0 + c1 t + a t^2/2, and how much a bounded velocity disturbance
    moves it: a = sum w_i s_i; a velocity error eps(t) adds int_t0^t_i eps to s_i, so a moves by
    int eps(t) W(t) dt, W(t) = sum over t_i > t of w_i: at most max|eps| int |W| dt (returned)."""
    design = np.column_stack([np.ones_like(t), t - t[0], 0.5 * (t - t[0]) ** 2])
    w = np.linalg.pinv(design)[2]
    tail = np.cumsum(w[::-1])[::-1]  # tail[k] = sum_{i >= k} w_i
    return float(w @ s), float(np.sum(np.abs(tail[1:]) * np.diff(t)))


def _incline_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Stuck: |p - p0| over 2 s. Static friction holds it exactly in a hard-contact engine; ODE's
    rows yield by CFM times their force: the friction rows creep at CFM m g sin(theta) (the whole
    load on one row) and the normal rows sink to CFM m g cos(theta) h / ERP; a contact acting a step
    late lets the box fall g h^2 once. Bound: CFM m g (sin T + cos h / ERP) + g h^2 (sin + cos).

    Slider: a fitted to the distance down the slope over [0.25 s, 2 s] against
    g (sin theta - mu cos theta). Under a constant acceleration every one-step scheme's positions
    are an exact quadratic in t (semi-implicit Euler: a t^2/2 + a h t/2; the O(h) term is linear
    and the fit's c1 takes it), so the fit is exact; what remains is the contact's departure from
    its steady state: friction's impulse over any interval is mu times the normal impulse, which is
    m g cos(theta) per second up to the change in the box's normal velocity (within g h when
    contacts act at most a step late), and a step without contact adds g sin(theta) h of slide:
    the velocity along the slope strays from the straight line by at most
    eps = g h (2 mu cos theta + sin theta); fitted_acceleration turns that into the bound on a."""
    tr, s = traces[0], settings[0]
    out = []
    h, T = s.dt, s.duration
    for name, (theta, z) in INC_BOXES.items():
        start, down, _ = incline_frame(theta, z)
        t, p = tr.series(name, "position")
        tp = physics_time(t, h)
        sin, cos = math.sin(theta), math.cos(theta)
        if math.tan(theta) <= INC_MU:
            tol = CFM_DEFAULT * INC_M * G * (sin * T + cos * h / ERP_DEFAULT) + G * h * h * (sin + cos)
            out.append(Measure(f"{name} (tan {math.degrees(theta):g} deg <= mu) |position - start|",
                               _max_norm(p - start), tol + ROUNDING * (1 + float(np.linalg.norm(start))), "m"))
            continue
        a_exact = G * (sin - INC_MU * cos)
        window = tp >= INC_FIT_FROM
        a, spread = fitted_acceleration(tp[window], (p[window] - start) @ down)
        eps = G * h * (2 * INC_MU * cos + sin)
        out.append(Measure(f"{name} (tan {math.degrees(theta):g} deg > mu) fitted acceleration - g (sin - mu cos)",
                           abs(a - a_exact), eps * spread + ROUNDING * (1 + a_exact), "m/s^2"))
    return out


def _incline() -> Case:
    return Case("incline", "incline.x3d",
                "CollisionCollection frictionCoefficients 0.5 on static inclines: at 20 degrees the box sticks; at 35 "
                "it slides at g (sin - mu cos) = 1.6088 m/s^2",
                (Settings(2.0, 1 / 240),), _incline_expect,
                exercises=("CollisionCollection.frictionCoefficients", "CollidableShape.rotation",
                           "CollidableShape.geometry.Box", "RigidBody.orientation"))


# anisotropic_friction.x3d: boxes pushed at 3 m/s along ODE's two friction directions of an
# upward normal (-x, +z)
AF_MU, AF_V0 = (0.2, 0.6), 3.0
AF_BOXES = {"Along1": (0, np.array([-1.0, 0.0, 0.0])), "Along2": (1, np.array([0.0, 0.0, 1.0]))}


def _friction_velocity_expect(boxes: dict[str, tuple[float, float, float, np.ndarray]]) -> Expectation:
    """Boxes (name -> mu, v0, target, direction) whose velocity along a friction direction changes
    at mu g until it reaches its target (0 for a pushed box, the surface speed on a belt). Friction
    is mu times the normal impulse, which over [0, t] is m g t up to the box's vertical momentum
    (its vertical speed within g h, the contact acting at most a step late), and a first step
    without contact loses mu g h of friction: |v - closed form| <= 2 mu g h (and the rate of a
    row at its target: a velocity row is on it, or a step at mu g off it)."""
    def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
        tr, s = traces[0], settings[0]
        out = []
        for name, (mu, v0, target, direction) in boxes.items():
            t, v = tr.series(name, "linearVelocity")
            tp = physics_time(t, s.dt)
            gap = v0 - target
            along = target + np.sign(gap) * np.maximum(abs(gap) - mu * G * tp, 0.0)
            out.append(Measure(f"{name}.linearVelocity (mu = {mu:g} along {direction.tolist()})",
                               _max_norm(v - np.outer(along, direction)),
                               2 * mu * G * s.dt + ROUNDING * (1 + abs(v0) + abs(target)), "m/s"))
        return out
    return expect


def _anisotropic() -> Case:
    boxes = {name: (AF_MU[k], AF_V0, 0.0, d) for name, (k, d) in AF_BOXES.items()}
    return Case("anisotropic_friction", "anisotropic_friction.x3d",
                "frictionCoefficients 0.2 0.6 with FRICTION_COEFFICIENT-2: a box pushed along -x (ODE's first friction "
                "direction) slows at mu1 g, one pushed along +z at mu2 g",
                (Settings(2.0, 1 / 240),), _friction_velocity_expect(boxes),
                exercises=("CollisionCollection.frictionCoefficients",
                           "CollisionCollection.appliedParameters.FRICTION_COEFFICIENT-2", "RigidBody.linearVelocity"))


# conveyor.x3d: the box ends moving at surfaceSpeed along ODE's first friction direction (-x)
CV_MU, CV_SPEED = 0.5, 1.5


def _conveyor() -> Case:
    boxes = {"Parcel": (CV_MU, 0.0, CV_SPEED, np.array([-1.0, 0.0, 0.0]))}
    return Case("conveyor", "conveyor.x3d",
                "surfaceSpeed 1.5 0 with SPEED-1, mu 0.5, static belt: v = (-min(mu g t, 1.5), 0, 0) (ODE's motion1 "
                "along its first friction direction, -x)",
                (Settings(1.5, 1 / 240),), _friction_velocity_expect(boxes),
                exercises=("CollisionCollection.surfaceSpeed", "CollisionCollection.appliedParameters.SPEED-1",
                           "CollisionCollection.frictionCoefficients"))


def sensor_contacts(tr: TraceView, sensor: str) -> dict[float, list[dict]]:
    """A CollisionSensor's contacts per frame time: position, contactNormal, depth (arrays) and
    body1, body2, geometry1, geometry2 (names), from its contacts[i].FIELD rows."""
    out: dict[float, list[dict]] = {}
    for i in range(10_000):
        try:
            times, pos = tr.series(sensor, f"contacts[{i}].position")
        except KeyError:
            break
        _, normal = tr.series(sensor, f"contacts[{i}].contactNormal")
        _, depth = tr.series(sensor, f"contacts[{i}].depth")
        names = {f: dict(zip(*tr.text(sensor, f"contacts[{i}].{f}")))
                 for f in ("body1", "body2", "geometry1", "geometry2")}
        for k, t in enumerate(times.tolist()):
            c = {"position": pos[k], "contactNormal": normal[k], "depth": float(depth[k, 0])}
            c.update({f: names[f].get(t) for f in names})
            out.setdefault(t, []).append(c)
    return out


# resting_penetration.x3d: boxes (1 kg, 0.2 m tall) on a floor whose top is y = 0
RP_LAYER, RP_M, RP_HALF = 0.01, 1.0, 0.1
RP_BOXES = {"Sunk": (1.0, RP_LAYER), "Touching": (-1.0, 0.0)}  # x of the box, depth it starts at


def _resting_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Depth of each box, from the sensor's contacts (every contact the box has, frames after the
    first step) and from its height (0.1 - y, every frame).

    Sunk starts at depth = layer, where ODE's error correction pushes nothing: it stays, sinking
    only by the softness CFM m g h / ERP (the whole weight on one contact) and, in an engine whose
    contact acts a step late, one step of fall g h^2: |depth - 0.01| within their sum.
    Touching starts at depth 0: nothing pushes it in, but ODE's softness lets a resting body creep
    in at CFM m g until it reaches the layer: |depth| <= CFM m g T + g h^2 over the run T (an engine
    that makes the layer a target rather than an allowance pulls it 1 cm in and fails)."""
    tr, s = traces[0], settings[0]
    h = s.dt
    contacts = sensor_contacts(tr, "Sensor")
    out = []
    for name, (x, start_depth) in RP_BOXES.items():
        if start_depth > 0:
            tol = CFM_DEFAULT * RP_M * G * h / ERP_DEFAULT + G * h * h
        else:
            tol = CFM_DEFAULT * RP_M * G * s.duration + G * h * h
        tol += ROUNDING
        _, p = tr.series(name, "position")
        out.append(Measure(f"{name} depth from its height - {start_depth:g}",
                           _max_norm((RP_HALF - p[:, 1]) - start_depth), tol, "m"))
        times, _ = tr.series(name, "position")
        worst, missing = 0.0, 0
        for t, n in zip(times.tolist(), steps(times, h).tolist()):
            if n < 1:
                continue
            mine = [c["depth"] for c in contacts.get(t, []) if (c["position"][0] > 0) == (x > 0)]
            if not mine:
                missing += 1
                continue
            worst = max(worst, max(abs(d - start_depth) for d in mine))
        out.append(Measure(f"{name} CollisionSensor contact depth - {start_depth:g}",
                           worst if not missing else math.inf, tol, "m"))
    return out


def _resting() -> Case:
    return Case("resting_penetration", "resting_penetration.x3d",
                "RigidBodyCollection contactSurfaceThickness 0.01: a box resting 1 cm into the floor stays there "
                "(CollisionSensor depth 0.01); one resting on it stays at ~0",
                (Settings(1.0, 1 / 240),), _resting_expect,
                exercises=("RigidBodyCollection.contactSurfaceThickness", "CollisionSensor"))


# box_stack.x3d: five 0.2 kg boxes, 0.2 m tall, 0.4 m wide; gravity (1, -9.81, 0)
BS_N, BS_M, BS_HEIGHT, BS_WIDTH, BS_GRAVITY = 5, 0.2, 0.2, 0.4, np.array([1.0, -9.81, 0.0])


def _stack_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Each box's |position - start| and rotation angle over 10 s. Interface i (i = 1 under the
    bottom box) carries n_i = 6 - i boxes. Box j moves with every interface under it:
    - vertically, each may let its boxes fall one step before acting (g h^2) and ODE's normal rows
      sink to CFM n_i m g h / ERP;
    - sideways, each may slip one step of the sideways load (a_x h^2), and ODE's friction rows,
      holding n_i m a_x, creep at CFM n_i m a_x for the whole run T;
    - tilting: uneven sinking of an interface's edges, at most twice its vertical bound over the
      box's width.
    A hard-contact engine holds the stack exactly (no load is near friction's limit: 0.10 < 0.3).
    The bound assumes each step's contacts solved: an iterative solver stopped short of that lets
    the stack walk (ODE 0.16's own dWorldQuickStep at the default 10 iterations: the top box
    5.6 cm in 10 s, measured; its dWorldStep stays within 0.19 of the bound)."""
    tr, s = traces[0], settings[0]
    h, T = s.dt, s.duration
    ax, gy = abs(float(BS_GRAVITY[0])), abs(float(BS_GRAVITY[1]))
    out = []
    vertical = sideways = tilt = 0.0
    for j in range(1, BS_N + 1):
        n = BS_N + 1 - j  # boxes on interface j
        sink = gy * h * h + CFM_DEFAULT * n * BS_M * gy * h / ERP_DEFAULT
        vertical += sink
        sideways += ax * h * h + CFM_DEFAULT * n * BS_M * ax * T
        tilt += 2 * sink / BS_WIDTH
        start = np.array([0.0, BS_HEIGHT * (j - 0.5), 0.0])
        _, p = tr.series(f"Box{j}", "position")
        _, rot = tr.series(f"Box{j}", "orientation")
        out.append(Measure(f"Box{j} |position - start|", _max_norm(p - start),
                           vertical + sideways + ROUNDING * (1 + float(np.linalg.norm(start))), "m"))
        out.append(Measure(f"Box{j} rotation angle", float(np.max(R.angle_between(
            R.from_axis_angle(rot), np.array([1.0, 0.0, 0.0, 0.0])))), tilt + ROUNDING_ANGLE, "rad"))
    return out


def _stack() -> Case:
    return Case("box_stack", "box_stack.x3d",
                "five boxes stacked, frictionCoefficients 0.3, gravity 1 -9.81 0: every box stays put for 10 s",
                (Settings(10.0, 1 / 240),), _stack_expect,
                exercises=("CollisionCollection.frictionCoefficients", "RigidBodyCollection.gravity",
                           "CollidableShape.geometry.Box"))


# collision_filtering.x3d: two 1 kg balls touching the floor; Ghost's shape is not in the collider
CF_KEPT, CF_GHOST, CF_M = np.array([-0.5, 0.1, 0.0]), np.array([0.5, 0.1, 0.0]), 1.0


def _filtering_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Ghost: the ballistic closed form (nothing touches it). Kept: at rest on the floor within one
    step of unresisted fall (g h^2, g h) and ODE's softness (sinking to CFM m g h / ERP, at a speed
    at most CFM m g)."""
    tr, s = traces[0], settings[0]
    h = s.dt
    _, p = tr.series("Kept", "position")
    _, v = tr.series("Kept", "linearVelocity")
    kept = [Measure("Kept |position - start| (rests on the floor)", _max_norm(p - CF_KEPT),
                    G * h * h + CFM_DEFAULT * CF_M * G * h / ERP_DEFAULT + ROUNDING, "m"),
            Measure("Kept |linearVelocity|", _max_norm(v), G * h + CFM_DEFAULT * CF_M * G + ROUNDING, "m/s")]
    ghost = ballistic("Ghost", CF_GHOST, (0, 0, 0), (0, -G, 0))(traces, settings)
    return kept + [Measure(m.quantity + " (falls through the floor)", m.error, m.tolerance, m.unit) for m in ghost]


def _filtering() -> Case:
    return Case("collision_filtering", "collision_filtering.x3d",
                "CollisionCollection collidables: a body whose shape is in the collider rests on the floor, one whose "
                "shape is not falls through it",
                (Settings(1.0, 1 / 240),), _filtering_expect,
                exercises=("CollisionCollection", "CollidableShape.geometry.Sphere"))


def _routed_contacts() -> Case:
    return Case("routed_contacts", "routed_contacts.x3d",
                "CollisionSensor contacts ROUTEd to set_contacts: the body whose shape the sensor watches rests on "
                "the floor, the other falls through it",
                (Settings(1.0, 1 / 240),), _filtering_expect,
                exercises=("RigidBodyCollection.set_contacts.fromSensor", "CollisionSensor"))


# sensor_geometry.x3d: Ball (0.2 kg, r 0.1) on Block (1 kg, 0.4 x 0.2 x 0.4) on the static Floor
SG_BALL_M, SG_BLOCK_M, SG_R, SG_BLOCK_HALF, SG_WIDTH = 0.2, 1.0, 0.1, 0.1, 0.4
SG_LOWER = {frozenset(("Floor", "BlockShape")): "Floor", frozenset(("BlockShape", "BallShape")): "BlockShape"}
SG_BODY = {"Floor": "NULL", "BlockShape": "Block", "BallShape": "Ball"}


def _sensor_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Every contact of every frame after the first step (the sensor reports the last step's).

    Depth: the resting penetration (no surface layer): one step of unresisted fall g h^2 plus ODE's
    softness CFM f h / ERP, f the largest load on a contact (ball and block on the floor).
    Normal: (0, +-1, 0) by which geometry is lower; the block may tilt by uneven sinking of its
    edges, at most twice the depth bound over its width, and its faces' normals with it.
    Ball's contact position: (x, z) of the ball's centre (off by at most r times the tilt) and
    y at the block's top face (Block's centre + 0.1), within the depth bound (engines put the
    point on either surface or between them). Names: exact."""
    tr, s = traces[0], settings[0]
    h = s.dt
    depth_tol = G * h * h + CFM_DEFAULT * (SG_BALL_M + SG_BLOCK_M) * G * h / ERP_DEFAULT + ROUNDING
    tilt = 2 * depth_tol / SG_WIDTH
    contacts = sensor_contacts(tr, "Sensor")
    times, ball = tr.series("Ball", "position")
    _, block = tr.series("Block", "position")
    try:
        active = dict(zip(*tr.text("Sensor", "isActive")))
    except KeyError:  # no sensor output at all: inactive on every frame
        active = {}
    hits = {}
    for k in range(100):
        try:
            for t, name in zip(*tr.text("Sensor", f"intersections[{k}]")):
                hits.setdefault(t, set()).add(name)
        except KeyError:
            break
    normal_err = depth_err = horizontal_err = vertical_err = 0.0
    wrong_names = inactive = no_ball_contact = missing_hits = 0
    for frame, (t, n) in enumerate(zip(times.tolist(), steps(times, h).tolist())):
        if n < 1:
            continue
        inactive += active.get(t) != "true"
        missing_hits += hits.get(t, set()) != set(SG_BODY)
        ball_contacts = 0
        for c in contacts.get(t, []):
            g1, g2 = c["geometry1"], c["geometry2"]
            lower = SG_LOWER.get(frozenset((g1, g2)))
            if lower is None or g1 == g2:
                wrong_names += 1
                continue
            wrong_names += (c["body1"], c["body2"]) != (SG_BODY[g1], SG_BODY[g2])
            want = np.array([0.0, 1.0 if g1 == lower else -1.0, 0.0])
            normal_err = max(normal_err, float(np.linalg.norm(c["contactNormal"] - want)))
            depth_err = max(depth_err, abs(c["depth"]))
            if lower == "BlockShape":
                ball_contacts += 1
                d = c["position"] - ball[frame]
                horizontal_err = max(horizontal_err, math.hypot(d[0], d[2]))
                vertical_err = max(vertical_err, abs(c["position"][1] - (block[frame][1] + SG_BLOCK_HALF)))
        no_ball_contact += ball_contacts == 0
    return [Measure("frames after the first step with isActive FALSE", inactive, 0),
            Measure("frames whose intersections do not name Floor, BlockShape and BallShape", missing_hits, 0),
            Measure("contacts whose geometry1/geometry2/body1/body2 are not a touching pair and its bodies",
                    wrong_names, 0),
            Measure("frames with no BallShape-BlockShape contact", no_ball_contact, 0),
            Measure("contactNormal - (0, +-1, 0) from geometry1 towards geometry2 (worst contact)", normal_err,
                    tilt + ROUNDING_ANGLE),
            Measure("|depth| (worst contact)", depth_err, depth_tol, "m"),
            Measure("ball contact position - ball centre, horizontally", horizontal_err, SG_R * tilt + ROUNDING, "m"),
            Measure("ball contact position - block top face, vertically", vertical_err, depth_tol, "m")]


def _sensor() -> Case:
    return Case("sensor_geometry", "sensor_geometry.x3d",
                "CollisionSensor contacts of a ball on a block on the floor: contactNormal (0, +-1, 0) from geometry1 "
                "towards geometry2, bodies named, position under the ball's centre at the block's top, depth small",
                (Settings(1.0, 1 / 240),), _sensor_expect,
                exercises=("CollisionSensor", "CollidableShape.geometry.Sphere", "CollidableShape.geometry.Box"))


# newtons_cradle.x3d: balls 0.1 kg, r 0.05, I 1e-4, 0.5 m below pivots 0.104 m apart
NC_M, NC_R, NC_I, NC_L, NC_GAP, NC_BALLS, NC_THETA0 = 0.1, 0.05, 1e-4, 0.5, 0.004, 5, math.radians(30.0)


def _cradle_expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
    """Ball1's impact speed v: its speed on the frame before Ball2 first moves (a frame after every
    step: the velocity the impact step starts from, which ODE's bounce reflects). Then
    max |v(Ball5)| / v against 1, and the speed left in Ball1 .. Ball4 just after Ball5 leaves
    (5 steps after its fastest frame) against 0.

    Soft contacts. Each impact is binary (the gap outlasts a step's travel) between equal
    effective masses m' = m + I/L^2 (a hinged ball moving tangentially at the bottom); elastic, it
    hands the whole velocity on. ODE's contact row yields by CFM times its force: the row targets
    the relative speed v and gets (v - gamma v)/(1 + gamma), gamma = CFM (m'/2) / h (reduced
    mass), which leaves v / (1 + gamma) to the struck ball and gamma v / (1 + gamma) to the
    striker. After four impacts Ball5 has v / (1 + gamma)^4 (gamma = 5.0e-3 at dt = 1 ms: 2%),
    and each striker keeps at most gamma v.
    Gravity. Each ball strikes up to x = gap + v h past its lowest point, where gravity's
    tangential pull g x / L has slowed it for x / v: together at most 4 g x^2 / (L v) (1.8e-3 v).
    The line of centres and the velocity tilt by x / L or less (cosines within 1.1e-4 of 1)."""
    tr, s = traces[0], settings[0]
    h = s.dt
    speed = {k: np.linalg.norm(tr.series(f"Ball{k}", "linearVelocity")[1], axis=1) for k in range(1, NC_BALLS + 1)}
    m_eff = NC_M + NC_I / NC_L ** 2
    gamma = CFM_DEFAULT * 0.5 * m_eff / h
    moved = np.flatnonzero(speed[2] > 1e-3)
    names = ("Ball5 max speed / Ball1 impact speed - 1", "Ball1 .. Ball4 speed after Ball5 leaves / Ball1 impact speed")
    v_est = math.sqrt(2 * G * NC_L * (1 - math.cos(NC_THETA0)) * NC_M * NC_L ** 2 / (NC_M * NC_L ** 2 + NC_I))
    x = NC_GAP + v_est * h
    drag = 4 * G * x * x / (NC_L * v_est * v_est) + 2 * x / NC_L
    tol_pass = 1 - (1 + gamma) ** -(NC_BALLS - 1) + drag
    tol_left = gamma + drag
    if not moved.size or moved[0] == 0:
        return [Measure(names[0], math.inf, tol_pass), Measure(names[1], math.inf, tol_left)]
    v = float(speed[1][moved[0] - 1])
    fastest = int(np.argmax(speed[5]))
    after = min(fastest + 5, len(speed[5]) - 1)
    left = max(float(speed[k][after]) for k in range(1, NC_BALLS))
    return [Measure(names[0], abs(float(speed[5][fastest]) / v - 1), tol_pass),
            Measure(names[1], left / v, tol_left)]


def _cradle() -> Case:
    return Case("newtons_cradle", "newtons_cradle.x3d",
                "CollisionCollection bounce 1, minBounceSpeed 0: five hinged balls, 4 mm apart; Ball5 leaves with "
                "Ball1's impact speed (less ODE's contact softness, 2%), Ball1 .. Ball4 stop",
                (Settings(0.6, 1 / 1000, None),), _cradle_expect,
                exercises=("CollisionCollection.bounce", "CollisionCollection.minBounceSpeed",
                           "CollidableShape.geometry.Sphere", "SingleAxisHingeJoint"))


COLLISION_CASES: tuple[Case, ...] = (_bounce_apex(), _incline(), _anisotropic(), _conveyor(), _resting(), _stack(),
                                     _filtering(), _routed_contacts(), _sensor(), _cradle())
CASES = CASES + COLLISION_CASES
BY_NAME.update({c.name: c for c in COLLISION_CASES})
