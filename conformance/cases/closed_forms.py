"""Closed forms, tolerances and trace readers that more than one conformance case uses.

The closed forms' parameters are written in each case, not read from the scene through
x3d_core, so that the expectation does not share the evaluator's reading of the file: a field the
evaluator misread or dropped fails the case instead of moving the target with it. Each
scene's leading comment states the same numbers.

Conventions of the argument (the reference integrator is semi-implicit Euler, which
Bullet, DART, ODE and MuJoCo's default all use):
- State at a frame ending at time t is the world after n = floor(t/dt) steps
  (x3d_core.semantics.evaluator); closed forms are evaluated at the physics time n*dt.
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

Spec tolerances and accuracy bounds are two numbers (conformance.results.Measure). The bounds
above are accuracy: what a first-order integrator with an exact, rigid solve reaches at the
scene's step; a run past them is graded (k times the bound), never accused. Clause 37 says what
a field means and, of accuracy, only that it trades against stability (37.2.1: "Most of the
node definitions in this component include factors that can be modified to trade off accuracy
in visual output for the stability of the calculations"): its joints carry a default
constantForceMix that makes them soft, and an implementation picks its solver and runs the
scene's `iterations`. So where a bound assumes a rigid or converged solve, the spec tolerance is
honoured(): a run honours the sentence while its result lies nearer the sentence's reading than
any misreading of it that browsers make (the field ignored, read in another frame, sign or
unit): half the distance between the two, never less than the bound. A misreading is then
always caught, and no solver that converges to the right answer is accused.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import numpy as np

from x3d_core.model import fields as F
from x3d_core.semantics import rotation as R
from x3d_core.semantics.applied import canonical
from x3d_core.traces.trace import TraceView

from conformance.cases.case import Expectation
from conformance.results import Basis, Measure, Settings, accuracy, convention, spec

ROUNDING = 1e-9
ROUNDING_ANGLE = 1e-7  # rad
STEP_SLACK = 1e-9  # as x3d_core.semantics.evaluator: a frame within 1e-9 step of a step boundary is on it
G = 9.81  # the non-default gravity the scenes use
G_DEFAULT = 9.8
# the spec's sentences more than one case enforces (clause 37's text, conformance.results.EDITION)
GRAVITY = spec("37.4.11 RigidBodyCollection: The gravity field indicates direction and strength of the local gravity "
               "vector for this collection of bodies. The default gravity is standard earth gravity of 9.8m/s2 "
               "downwards.")
AT_REST = spec("37.4.10 RigidBody: These values define tolerances for which the physics model should start to ignore "
               "this object in any calculation, thus resulting in them being actually at rest and not subject to "
               "these instability conditions. Once any one of these values is achieved, the body is considered as "
               "being at rest unless acted upon by an external force (e. g., collision or action of connected "
               "joint).")
FORCES = spec("37.4.10 RigidBody: The torques and forces fields define zero or more sets of torque and force "
              "values that are applied to the object every frame. These are continuously applied until reset to "
              "zero by the user.")
HINGE2 = spec("37.4.8 DoubleAxisHingeJoint: The DoubleAxisHingeJoint node represents a joint that has two independent "
              "axes that are located around a common anchor point. Axis 1 is specified relative to the first body "
              "(specified by the body1 field) and axis 2 is specified relative to the second body (specified by the "
              "body2 field). Axis 1 can have limits and a motor, axis 2 can only have a motor.")
HINGE2_LIMITS = spec("37.4.8 DoubleAxisHingeJoint: The minAngle1 and maxAngle1 fields are used to control the maximum "
                     "angles through which the hinge is allowed to travel. A hinge may not travel more than π radians "
                     "in either direction from it's initial position.")
HINGE2_OUTPUTS = spec("37.4.8 DoubleAxisHingeJoint: The hingeXAngle output fields report the current relative angle "
                      "between the two bodies in radians and the hingeXAngleRate field describes the rate at which "
                      "that angle is currently changing in radians per second.")
SLIDER_STOPS = spec("37.4.13 SliderJoint: If minSeparation is greater than maxSeparation, the stops become ineffective "
                    "as if the object has no stops at all.")
SLIDER_BOUNCE = spec("37.4.13 SliderJoint: The stopBounce field describes how much the joint should bounce the body "
                     "back if the joint limit has been reached or exceeded. A value of zero indicates no bounce at "
                     "all, and a value of one indicates that it should bounce with velocity equal and opposite to "
                     "the collision velocity of the contact.")
# constraint drift, shared by the ball chain and the universal joint
ERROR_CORRECTION = 0.8  # RigidBodyCollection.errorCorrection default: the scenes leave it


SINGLE = 2.0 ** -23  # single precision's unit roundoff


def single(bound: float, scale: float, operations: float) -> float:
    """The tolerance of a measure held to its bound up to rounding (double precision's, in the
    bound), for an engine that keeps state in single precision, which the clause does not rule
    out (PhysX, Ammo's Bullet): the bound plus `operations` roundings of a quantity of size
    `scale`. The bound stays the grade."""
    return bound + SINGLE * scale * operations


def honoured(bound: float, *misreadings: float) -> float:
    """The spec tolerance of a measure whose accuracy bound is `bound`, where `misreadings` are
    the errors the measure shows for the misreadings of its field (the module's argument): half
    the nearest, never less than the bound."""
    return max(bound, 0.5 * min(abs(m) for m in misreadings))


def steps(t: np.ndarray, dt: float) -> np.ndarray:
    return np.floor(np.asarray(t) / dt + STEP_SLACK)


def physics_time(t: np.ndarray, dt: float) -> np.ndarray:
    """The simulated time of the state recorded at frame time t: floor(t/dt) steps."""
    return steps(t, dt) * dt


def max_norm(a: np.ndarray) -> float:
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


PHYSICS_CLOCK = convention(
    "the physics clock: the state at frame time t is the world after floor(t/dt) steps of dt from the scene's start "
    "(x3drbp's evaluator, ODE-based browsers stepping a fixed dt); the clause makes the physics keep pace with the "
    "frames (CLOCK) but does not say when its clock starts or whether a frame shows the last step before its end: "
    "browsers that step once per frame, or start a frame late, differ here and nowhere else")


CLOCK = spec("37.2.2.1 Event model evaluation: An implementation of this specification shall be responsible for "
             "keeping the physics fixed time interval evaluations synchronized with the varying visual frame time "
             "intervals.")


UNTIMED = accuracy("an acceleration fitted whatever the clock is exact for a fixed step only; a physics step that "
                   "varies (a clock that does not keep pace) leaves up to a^2 (h_max - h_min) T / 2 in the positions, "
                   "which cannot be told from the field's own effect: graded, and the clock's measure judges the run")


CORRECTION = spec("37.4.11 RigidBodyCollection: The errorCorrection field describes how quickly the system should "
                  "resolve intersection errors due to floating point inaccuracies.",
                  also=("37.4.11 RigidBodyCollection: A value of 0 means no correction at all while a value of 1 "
                        "indicates that all errors should be corrected in a single step.",))
INITIAL = spec("37.4.10 RigidBody: The position and orientation fields are used to set the initial conditions of this "
               "body's location in world space.")


def clock_lag(t: np.ndarray, p: np.ndarray, v: np.ndarray, a: np.ndarray) -> float | None:
    """How far the physics clock strays from the frame clock over the run: the largest
    |(t_k - t_1) - (tau_k - tau_1)|, tau the physics time the state itself shows. Under a
    constant acceleration a, tau_k - tau_1 = (v_k - v_1) . a / |a|^2, exact for every one-step
    scheme; with none, (p_k - p_1) . v / |v|^2. Only differences from the first frame count, so a
    starting velocity misread, or a clock that starts late and then keeps pace, is not read as a
    clock that drifts. None where the body neither accelerates nor moves (nothing shows its time)."""
    if np.linalg.norm(a) > 0:
        tau = (v - v[0]) @ a / float(a @ a)
    else:
        w = np.mean(v, axis=0)
        if not np.any(w):
            return None
        tau = (p - p[0]) @ w / float(w @ w)
    return float(np.max(np.abs((t - t[0]) - tau)))


def clock_free_acceleration(p: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The acceleration the motion shows whatever its clock. Under a constant acceleration every
    one-step scheme's positions are the parabola plus a lag linear in time, p = p1 + v1 T + a T^2/2
    + l T (T the physics time since the first frame, the scheme's l = -a h/2 for semi-implicit
    Euler, 0 for a second-order one), and its velocities exact, v = v1 + a T. Eliminating T
    component by component: 1/2 (v^2 - v1^2) = a (p - p1) - l (v - v1), exact, so a least-squares
    fit on (p - p1, v - v1) gives a to rounding with no time at all (for a fixed step: UNTIMED
    says what a step that varies leaves)."""
    x, dv = p - p[0], v - v[0]
    y = 0.5 * (v * v - v[0] * v[0])
    out = np.zeros(p.shape[1])
    for i in range(p.shape[1]):  # three components: a fit each, not a loop over frames
        columns = [c for c in (x[:, i], dv[:, i]) if np.any(c)]
        if columns and np.any(x[:, i]):
            out[i] = np.linalg.lstsq(np.column_stack(columns), y[:, i], rcond=None)[0][0]
    return out


def ballistic(body: str, p0: Sequence[float], v0: Sequence[float], a: Sequence[float],
              basis: Basis | None = None, misread: Sequence[Sequence[float]] | None = None) -> Expectation:
    """A body under a constant acceleration a: p = p0 + v0 t + a t^2/2, v = v0 + a t.

    Spec, the start (INITIAL, 37.4.10): the first frame after the start lies within the motion
    of a frame and a step (past the first frame's time) of the file's position: a browser that
    moves the body elsewhere at its first step breaks the initial conditions; the half of the
    file position's distance from the origin (the field ignored) is its tolerance. The clock and
    the acceleration are read from that frame on, so that such a jump is this measure's alone.

    Spec, the clock (CLOCK, 37.2.2.1): the physics time the state shows (clock_lag) keeps pace
    with the frame times the trace gives, to one physics step (the state of the last step before
    the frame's end) and one frame (37.2.2.1 lets outputs be reported "at the start of the next
    frame"); its bound is one step, what a fixed step from the start gives.

    Spec (held to `basis`, the sentence of the spec that gives the body that acceleration): the
    acceleration the motion shows whatever its clock (clock_free_acceleration: exact to rounding
    for every one-step scheme, so a clock's fault is the clock measure's alone, never the
    field's), and where the body starts moving and the clock keeps pace, the velocity a line
    fitted over the run's second half against frame time gives at t = 0 (only a time base gives
    it). Accuracy: velocities are exact for any one-step scheme (ROUNDING, and a slope's from
    it); the tolerance is half the nearest misreading's error (honoured): for the acceleration,
    the accelerations `misread` gives (default: nothing acting, or X3D's default gravity
    (0 -9.8 0) in its place); for the start, the initial velocity ignored. Where the clock does
    not keep pace its step varies, and the acceleration is only graded (UNTIMED): the run fails
    by the clock's sentence, never by the field's.

    Convention (PHYSICS_CLOCK): the closed form at physics time floor(t/dt) dt, the velocity
    exact up to ROUNDING, the position within |a| t dt / 2 (the module's argument; evaluated at
    the last frame, where it is largest): what a fixed step from the scene's start gives, and
    one step late is twice that off. Both are graded against the same bounds."""
    p0, v0, a = (np.asarray(x, dtype=np.float64) for x in (p0, v0, a))
    wrong = [(0.0, 0.0, 0.0), (0.0, -G_DEFAULT, 0.0)] if misread is None else misread
    misreadings = [d for d in (float(np.linalg.norm(a - np.asarray(w, dtype=np.float64))) for w in wrong) if d > 0]

    def held(bound: float) -> float:
        return honoured(bound, *misreadings) if misreadings else bound

    def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
        tr, s = traces[0], settings[0]
        t, p = tr.series(body, "position")
        _, v = tr.series(body, "linearVelocity")
        tp = physics_time(t, s.dt)[:, None]
        p_exact = p0 + v0 * tp + 0.5 * a * tp ** 2
        v_exact = v0 + a * tp
        T = float(tp[-1, 0])
        scale = 1.0 + np.linalg.norm(p0) + np.linalg.norm(v0) * T + np.linalg.norm(a) * T * T
        v_round = ROUNDING * (1.0 + np.linalg.norm(v0) + np.linalg.norm(a) * T)
        out = []
        # from the first frame after the start on: a body that leaves its file position at the first step (a
        # browser that ignores the field) is the INITIAL measure's, never the clock's or the acceleration's
        k = 1 if len(t) > 3 else 0
        if k:
            w = float(t[1]) + 1.0 / s.rate + s.dt  # the physics time of the first frame, a frame and a step late
            start = float(np.linalg.norm(v0)) * w + 0.5 * float(np.linalg.norm(a)) * w * w + ROUNDING * scale
            out.append(Measure(f"{body} first frame after the start - its file position (the motion starts there)",
                               float(np.linalg.norm(p[1] - p0)), honoured(start, float(np.linalg.norm(p0)))
                               if np.any(p0) else start, "m", INITIAL, start))
        fitted_a = clock_free_acceleration(p[k:], v[k:])
        window = max(float(t[-1] - t[k]), s.dt)
        a_bound = 4 * v_round / window
        lag = clock_lag(t[k:], p[k:], v[k:], fitted_a)
        in_step = True
        if lag is not None:
            rate_round = v_round / float(np.linalg.norm(fitted_a)) if np.any(fitted_a) else ROUNDING * (1.0 + T)
            clock = Measure(f"{body} physics clock against the frame clock (largest lag)", lag,
                            s.dt + 1.0 / s.rate + rate_round, "s", CLOCK, s.dt + rate_round)
            in_step = clock.ok
            out.append(clock)
        if in_step:
            out.append(Measure(f"{body} acceleration (whatever the clock) - {_vec(a)}",
                               float(np.linalg.norm(fitted_a - a)), held(a_bound), "m/s^2", basis, a_bound))
        else:
            out.append(Measure(f"{body} acceleration (graded only: the clock does not keep pace) - {_vec(a)}",
                               float(np.linalg.norm(fitted_a - a)), a_bound, "m/s^2", UNTIMED))
        half = t >= 0.5 * t[-1]
        if in_step and np.any(v0) and np.count_nonzero(half) >= 3 and t[half][-1] > t[half][0]:
            start = np.polyfit(t[half], v[half], 1)[1]
            v0_bound = 4 * v_round / max(float(t[half][-1] - t[half][0]), s.dt) * float(t[-1]) + v_round
            out.append(Measure(f"{body} starting velocity (the fit at t = 0) - {_vec(v0)}",
                               float(np.linalg.norm(start - v0)),
                               honoured(v0_bound, float(np.linalg.norm(v0))), "m/s", basis, v0_bound))
        elif len(t) < 3:  # too few frames to fit
            out.append(Measure(f"{body} acceleration (too few frames) - {_vec(a)}", math.inf, 0.0, "m/s^2", basis))
        p_bound = 0.5 * float(np.linalg.norm(a)) * T * s.dt + ROUNDING * scale
        n = float(steps(t[-1:], s.dt)[0]) + 1
        v_scale = 1.0 + float(np.linalg.norm(v0)) + float(np.linalg.norm(a)) * T
        return out + [Measure(f"{body}.linearVelocity", max_norm(v - v_exact), single(v_round, v_scale, n), "m/s",
                              PHYSICS_CLOCK, v_round),
                      Measure(f"{body}.position", max_norm(p - p_exact), single(p_bound, scale, n), "m", PHYSICS_CLOCK,
                              p_bound)]
    return expect


def _vec(x: np.ndarray) -> str:
    return "(" + " ".join(f"{c:g}" for c in x) + ")"


# hinge_limits.x3d and hinge_max_limit.x3d: an arm (1 kg, 1 m out, I 0.001 about its centre) falls
# from horizontal onto a SingleAxisHingeJoint's stop (its default stopErrorCorrection 0.8)
ARM_M, ARM_L, ARM_I, ARM_ERP = 1.0, 1.0, 0.001, 0.8
HINGE_LIMITS = spec("37.4.12 SingleAxisHingeJoint: The minAngle and maxAngle fields are used to control the maximum "
                    "angles through which the hinge is allowed to travel. A hinge may not travel more than π radians "
                    "in either direction from its initial position.")
HINGE_TRAVEL = accuracy("a rigid stop acting on the step after the one that crosses it holds the arm, by the end, "
                        "within one step's travel and the error correction's steady state of the limit "
                        "(closed_forms.stop_overshoot)")


def hinge_limit(tr: TraceView, s: Settings, joint: str, lo: float, hi: float, ode_limit: float) -> list[Measure]:
    """An arm falls from horizontal onto the stops [lo, hi]; with ODE's sign (body1 relative to
    body2) its fall reaches ode_limit, with the other the other limit. Impact rate at most
    w = sqrt(2 m g L sin(max |limit|) / I_p), angular acceleration at most m g L / I_p.

    Accuracy: a rigid stop acting on the step after the one that crosses it lets the arm past by
    stop_overshoot with the hinge's default stopErrorCorrection 0.8 (about 0.014 rad at
    dt = 1/240), and holds it there: the bound on the angle beyond the limits and on the rest
    angle at the end, whichever limit the fall meets.

    Spec: the limits bound the hinge's travel, so the farthest the arm goes is the limit its
    fall reaches. The tolerance (closed_forms.honoured) is half the nearest misreading's error:
    the limits read in degrees (the arm stops within |limit| degrees of the start) or ignored
    (the arm swings to the vertical at least: pi/2 - |limit| past it), taken at whichever limit
    gives the larger, so that the other sign's reading (the fall reaching the other limit) is
    held as this one is. The angle beyond the limits is the spec's too ("the maximum angles
    through which the hinge is allowed to travel"), with the same tolerance: a stop that yields
    less (ODE's quick-step at the scene's 10 iterations: 0.23 rad past, then thrown back) is
    graded against the bound, not accused; one that lets the arm go past by more than half what
    ignoring the limits would fails. Where the arm is at the end is graded only (the clause fixes
    the limits of travel, not a rest).

    Convention (ODE's sign): the fall reaches ode_limit, not the other (hi - lo apart)."""
    _, ang = tr.series(joint, "angle")
    ang = ang[:, 0]
    i_p = ARM_I + ARM_M * ARM_L ** 2
    w = math.sqrt(2 * ARM_M * G * ARM_L * math.sin(max(-lo, hi)) / i_p)
    bound = stop_overshoot(w, ARM_M * G * ARM_L / i_p, s.dt, ARM_ERP)
    beyond = max(float(np.max(ang)) - hi, lo - float(np.min(ang)), 0.0)
    extreme = float(ang[np.argmax(np.abs(ang))])
    limit = lo if extreme <= 0 else hi
    # the same tolerance whichever limit the fall reaches: which one it is, is a convention (the sign), and
    # the nearer limit's would accuse a reading of the other sign for a stop that yields as ODE's does
    travel = max(honoured(bound, abs(x) - math.radians(abs(x)), math.pi / 2 - abs(x)) for x in (lo, hi))
    end = float(ang[-1])
    named = "minAngle" if ode_limit == lo else "maxAngle"
    ode_sign = convention(
        f"angle of body1 relative to body2 about the axis, from the initial configuration (ODE's dJointGetHingeAngle): "
        f"the arm falls to {'negative' if ode_limit < 0 else 'positive'} angles and reaches {named}; alternative: "
        f"body2 relative to body1, or the axis's other sense: the fall is the other way and the arm reaches "
        f"{'maxAngle' if named == 'minAngle' else 'minAngle'}")
    return [Measure(f"{joint}.angle farthest - the limit the fall reaches", abs(extreme - limit), travel, "rad",
                    HINGE_LIMITS, bound),
            Measure(f"{joint}.angle beyond limits", beyond, travel, "rad", HINGE_LIMITS, bound),
            Measure(f"{joint}.angle at the end - the limit the fall reaches", abs(end - (lo if end <= 0 else hi)),
                    bound, "rad", HINGE_TRAVEL),
            Measure(f"{joint}.angle farthest - {named}", abs(extreme - ode_limit), honoured(bound, hi - lo), "rad",
                    ode_sign)]


def stop_rebound(r: np.ndarray, bounce: float, pop: float, softness: float, unit: str, what: str, bounces: Basis,
                 law: Basis) -> list[Measure]:
    """A joint's relative rate r (one sample a step), nothing acting on it but its stops: the first
    step after which r changes sign is the first impact; before = |r| before it, after = |r| after.
    Spec (`bounces`, the stop bounce sentence): the stop sends the motion back part way, faster
    than its error correction alone could (`pop`: a step's depth corrected at the stop's error
    correction; the row's softness only slows that) and slower than it came (by the softness), to
    ROUNDING.
    Convention (`law`, ODE's): after = bounce x before, within the softness (the row yields by
    CFM times its force; to 0.1 %, what an iterative solve leaves of the rows coupled with it),
    held to half the distance to no bounce or a full one."""
    turned = np.flatnonzero(r[:-1] * r[1:] < 0)
    names = (f"{what}'s rebound from the first stop, part way back (shortfall)",
             "rebound rate - stop bounce x impact rate")
    bound = softness * 1.001 + ROUNDING * (1 + float(np.max(np.abs(r))))
    if not turned.size:  # no stop turned it back
        return [Measure(names[0], math.inf, ROUNDING, unit, bounces),
                Measure(names[1], math.inf, bound, unit, law, bound)]
    k = int(turned[0])
    before, after = abs(float(r[k])), abs(float(r[k + 1]))
    return [Measure(names[0], max(pop - after, after - (before - softness), 0.0), ROUNDING, unit, bounces),
            Measure(names[1], abs(after - bounce * before), honoured(bound, bounce * before, (1 - bounce) * before),
                    unit, law, bound)]


def stop_overshoot(speed: float, accel: float, dt: float, error_correction: float) -> float:
    """How far past a hard stop a body may get: the stop acts on the step after the one that
    crosses it, so a step at the impact speed and acceleration lands up to speed*dt + accel*dt^2
    beyond (first order); no bounce (stopBounce 0), and the stop's error correction e (ERP)
    removes a fraction e of what is left each step, so the gravity that keeps pushing adds at
    most accel*dt^2/e in the steady state."""
    return speed * dt + accel * dt * dt / error_correction


def infinitesimal_lag(omega: float, dt: float) -> float:
    """How far a body spinning at a constant omega falls behind each second under the
    infinitesimal rotation update (ODE's default, without finite rotation: q += h/2 w q, then
    normalised), which turns it by 2 atan(omega h/2) a step instead of omega h: omega^3 h^2/12
    to leading order. The exponential map (the finite model, every other engine here) has none."""
    return (omega * dt - 2.0 * math.atan(0.5 * omega * dt)) / dt


def omega(tr: TraceView, body: str) -> np.ndarray:
    """|angular velocity| per frame (a fixed body is in the trace too, at rest)."""
    return np.linalg.norm(tr.series(body, "angularVelocity")[1], axis=1)


# -- collisions ---------------------------------------------------------------------------
# x3d_core/semantics/collision.py states what x3drbp reads: ODE's contacts. The argument below follows
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

# the sentences the contact cases enforce (clause 37's text; the UOM's where it has none), and the
# readings they check where it is silent
# the collection's coefficients, frictionCoefficients among them (its SFVec2f fields): the text's
# Table 37.2, where the UOM reads FRICTION_COEFFICIENT-2 "Apply frictionCoefficients values", has no rows
FRICTION = spec("37.2.5.3 Collision contact description: The CollisionCollection node specifies a set of default "
                "coefficients to use for all contacts unless overridden by geometry-specific information. These "
                "coefficients are generally described using SFVec2f fields. The 2D vector describes the coefficients "
                "for the primary direction for the first value and secondary direction for the second value.")
BOUNCE = spec("37.4.4 CollisionCollection: The bounce field indicates how bouncy the surface contact is. A value "
              "of 0 indicates no bounce at all while a value of 1 indicates maximum bounce.")
FRICTION_DIRECTIONS = convention(
    "ODE's friction directions: without USER_FRICTION, direction 1 is dPlaneSpace of the normal (-x, then +z, "
    "for an upward normal), which frictionCoefficients, surfaceSpeed and slipFactors components 1 and 2 follow; "
    "the spec says only that the system computes a direction perpendicular to the normal, and other engines "
    "take other tangents (MuJoCo's first is world z, Bullet's follows the relative velocity)")


def friction_fit(tr: TraceView, s: Settings, name: str, mu: float, v0: float, target: float,
                 direction: np.ndarray) -> tuple[float, float]:
    """A box whose velocity along a friction direction changes at mu g until it reaches its target
    (0 for a pushed box, the surface speed on a belt): max |v - closed form| over the run, and its
    tolerance. Friction is mu times the normal impulse, which over [0, t] is m g t up to the box's
    vertical momentum (its vertical speed within g h, the contact acting at most a step late), and
    a first step without contact loses mu g h of friction: |v - closed form| <= 2 mu g h (and the
    rate of a row at its target: a velocity row is on it, or a step at mu g off it)."""
    t, v = tr.series(name, "linearVelocity")
    tp = physics_time(t, s.dt)
    gap = v0 - target
    along = target + np.sign(gap) * np.maximum(abs(gap) - mu * G * tp, 0.0)
    return (max_norm(v - np.outer(along, direction)),
            2 * mu * G * s.dt + ROUNDING * (1 + abs(v0) + abs(target)))


# the sentences of 37.4.5 and 37.4.7 that every case reading a CollisionSensor's rows enforces
SENSOR_ACTIVE = spec("37.4.5 CollisionSensor: The CollisionSensor is active (isActive is TRUE) when contacts were "
                     "located as a result of the movement of the watched objects from last frame.")
SENSOR_INTERSECTIONS = spec("37.4.5 CollisionSensor: The intersections field is used to report the colliding "
                            "geometry that was detected in this last frame.")
SENSOR_CONTACTS = spec("37.4.5 CollisionSensor: The contacts field is used to report contacts that were generated as "
                       "a result of the scene graph changes last frame. This field generates instances of the Contact "
                       "node.")
CONTACT_NORMAL = spec("37.4.7 Contact: The contactNormal field is a unit vector describing the normal between the two "
                      "colliding bodies.")
CONTACT_DEPTH = spec("37.4.7 Contact: The depth field indicates how deep the current intersection is along the "
                     "normal vector.")


def sensor_contacts(tr: TraceView, sensor: str, values: Sequence[str] = (),
                    texts: Sequence[str] = ()) -> dict[float, list[dict]]:
    """A CollisionSensor's contacts per frame time: position, contactNormal, depth (arrays) and
    body1, body2, geometry1, geometry2 (names), from its contacts[i].FIELD rows; and the Contact
    fields named in `values` (arrays; None where a contact lacks the row) and `texts` (as written)."""
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
        more: dict[str, dict] = {}
        for f in (*values, *texts):
            key = f"contacts[{i}].{f}"
            if (sensor, key) in tr.keys():
                at, got = tr.series(sensor, key)
                more[f] = dict(zip(at.tolist(), got))
            elif (sensor, key) in tr.text_keys():
                more[f] = dict(zip(*tr.text(sensor, key)))
            else:
                more[f] = {}
        for k, t in enumerate(times.tolist()):
            c = {"position": pos[k], "contactNormal": normal[k], "depth": float(depth[k, 0])}
            c.update({f: names[f].get(t) for f in names})
            c.update({f: more[f].get(t) for f in more})
            out.setdefault(t, []).append(c)
    return out


def applied_names(text: object) -> set[str | None] | None:
    """The names a Contact's appliedParameters row holds (an MFString as the trace writes it,
    '"A" "B"'), each in X3D 4.0's spelling, so that either spelling and any order read alike
    (x3d_core.semantics.applied); None in the set for a value that names nothing; None for no row, or a row
    the view read as numbers."""
    if not isinstance(text, str):
        return None
    return {canonical(v) for v in F.parse_xml(F.FIELD_TYPES["MFString"], text)}


# collision_filtering.x3d and routed_contacts.x3d: two 1 kg balls start at rest touching the floor,
# Kept, whose shape collides with it, and Ghost, whose shape does not
KEPT_START, GHOST_START, BALL_MASS = np.array([-0.5, 0.1, 0.0]), np.array([0.5, 0.1, 0.0]), 1.0


def carried(tr: TraceView, body: str, point: Sequence[float], start: Sequence[float]) -> np.ndarray:
    """Per frame, where a point fixed in a body is, from the body's pose (the body starts unturned
    at start, the point where the scene puts it; a body not in the trace stays put)."""
    local = np.asarray(point, dtype=np.float64) - np.asarray(start, dtype=np.float64)
    if (body, "position") not in tr.keys():
        return np.asarray(point, dtype=np.float64)[None, :]
    _, p = tr.series(body, "position")
    _, q = tr.series(body, "orientation")
    return p + R.rotate(R.from_axis_angle(q), local)


def anchor_gap(tr: TraceView, body1: str, body2: str, anchor: Sequence[float], start1: Sequence[float],
               start2: Sequence[float]) -> np.ndarray:
    """Per frame, how far apart the joint's anchor point is as each body carries it, from the
    bodies' own poses (not the joint's outputs)."""
    return np.linalg.norm(carried(tr, body1, anchor, start1) - carried(tr, body2, anchor, start2), axis=1)


ANCHOR_OUTPUTS = convention(
    "body1AnchorPoint and body2AnchorPoint are the anchor point as each body carries it, in world coordinates "
    "(x3drbp's and ODE's dJointGetBallAnchor/dJointGetBallAnchor2: comparable, as 37.4.1 uses them to show a "
    "separation); alternative: in each body's own frame, as the UOM's \"relative to local coordinate reference "
    "frame\" reads")


def anchor_outputs(tr: TraceView, joint: str, body1: str, body2: str, anchor: Sequence[float],
                   start1: Sequence[float], start2: Sequence[float]) -> Measure:
    """The joint's reported anchor points against the anchor as each body carries it (from the
    bodies' poses, both starting unturned), to rounding; the tolerance half the error of the other
    reading (each body's own frame: at the start off by the body's distance from the world origin)."""
    _, a1 = tr.series(joint, "body1AnchorPoint")
    _, a2 = tr.series(joint, "body2AnchorPoint")
    bound = ROUNDING * (1 + float(np.linalg.norm(anchor)))
    error = max(max_norm(a1 - carried(tr, body1, anchor, start1)), max_norm(a2 - carried(tr, body2, anchor, start2)))
    apart = max(float(np.linalg.norm(start1)), float(np.linalg.norm(start2)))
    return Measure(f"{joint}.body1AnchorPoint, body2AnchorPoint - the anchor as each body carries it", error,
                   honoured(bound, apart), "m", ANCHOR_OUTPUTS, bound)


def stops_at(tr: TraceView, s: Settings, body: str, p0: Sequence[float], v0: Sequence[float], w0: Sequence[float],
             time: float, basis: Basis) -> list[Measure]:
    """A free body drifting at v0 and turning at w0 (nothing acting) until it is disabled after
    ceil(time/h) steps, then still: p = p0 + v0 h min(n, N), v = v0 and w = w0 while n < N, 0
    after. Exact but for rounding (the evaluator zeroes a disabled body's velocities): ROUNDING
    the bound, single() the tolerance."""
    h = s.dt
    p0, v0, w0 = (np.asarray(x, dtype=np.float64) for x in (p0, v0, w0))
    t, p = tr.series(body, "position")
    _, v = tr.series(body, "linearVelocity")
    _, w = tr.series(body, "angularVelocity")
    n = steps(t, h)[:, None]
    stop = np.ceil(time / h - 1e-9)
    moving = n < stop
    ops = float(n[-1, 0]) + 1
    p_bound = ROUNDING * (1.0 + np.linalg.norm(p0))
    return [Measure(f"{body}.position (stops at disableTime)", max_norm(p - (p0 + v0 * h * np.minimum(n, stop))),
                    single(p_bound, 1.0 + float(np.linalg.norm(p0)) + float(np.linalg.norm(v0)) * time, ops), "m",
                    basis, p_bound),
            Measure(f"{body}.linearVelocity", max_norm(v - np.where(moving, v0, 0.0)),
                    single(ROUNDING, 1.0 + float(np.linalg.norm(v0)), ops), "m/s", basis, ROUNDING),
            Measure(f"{body}.angularVelocity", max_norm(w - np.where(moving, w0, 0.0)),
                    single(ROUNDING, 1.0 + float(np.linalg.norm(w0)), ops), "rad/s", basis, ROUNDING)]


def held(tr: TraceView, body: str, position: Sequence[float], orientation: Sequence[float],
         basis: Basis) -> list[Measure]:
    """A body no physics runs on: whatever it reports against its file state, with no tolerance
    beyond rounding (a body the engine never gets is moved by nothing; a run reporting no rows
    for it has nothing moved: error 0)."""
    p0, q0 = np.asarray(position, dtype=np.float64), R.from_axis_angle(np.asarray(orientation, dtype=np.float64))
    checks = {"position": (lambda p: max_norm(p - p0), ROUNDING * (1 + float(np.linalg.norm(p0))), "m"),
              "orientation": (lambda q: float(np.max(R.angle_between(R.from_axis_angle(q), q0))), ROUNDING_ANGLE,
                              "rad"),
              "linearVelocity": (max_norm, ROUNDING, "m/s"),
              "angularVelocity": (max_norm, ROUNDING, "rad/s")}
    out = []
    for field, (moved, tolerance, unit) in checks.items():
        values = tr.series(body, field)[1] if (body, field) in tr.keys() else None
        out.append(Measure(f"{body}.{field} - its file value (where reported at all)",
                           0.0 if values is None else moved(values), tolerance, unit, basis))
    return out


def rests(tr: TraceView, s: Settings, body: str, start: Sequence[float], basis: Basis,
          mass: float = BALL_MASS) -> list[Measure]:
    """A body put down touching a static floor stays: at rest within one step of unresisted fall
    (g h^2, g h) and ODE's softness (sinking to CFM m g h / ERP, at a speed at most CFM m g):
    accuracy bounds; the tolerances are half the misreading's error, the floor not colliding (it
    falls g T^2 / 2 and gains g T)."""
    h, T = s.dt, s.duration
    _, p = tr.series(body, "position")
    _, v = tr.series(body, "linearVelocity")
    sink = G * h * h + CFM_DEFAULT * mass * G * h / ERP_DEFAULT + ROUNDING
    creep = G * h + CFM_DEFAULT * mass * G + ROUNDING
    return [Measure(f"{body} |position - start| (rests on the floor)", max_norm(p - np.asarray(start)),
                    honoured(sink, 0.5 * G * T * T), "m", basis, sink),
            Measure(f"{body} |linearVelocity|", max_norm(v), honoured(creep, G * T), "m/s", basis, creep)]


def falls(traces: Sequence[TraceView], settings: Sequence[Settings], body: str, start: Sequence[float],
          basis: Basis) -> list[Measure]:
    """A body nothing touches: the ballistic closed form from rest under the scenes' gravity."""
    return [dataclasses.replace(m, quantity=m.quantity + " (falls through the floor)")
            for m in ballistic(body, start, (0, 0, 0), (0, -G, 0), basis)(traces, settings)]


def kept_rests_ghost_falls(basis: Basis, kept: Basis | None = None) -> Expectation:
    """Ghost falls (nothing touches it), Kept rests on the floor (rests). Every measure held to
    `basis`: the sentence that says which shapes collide; Kept's to `kept` where given (`basis`
    with sentences only a body that collides shows)."""
    def expect(traces: Sequence[TraceView], settings: Sequence[Settings]) -> list[Measure]:
        return (rests(traces[0], settings[0], "Kept", KEPT_START, basis if kept is None else kept)
                + falls(traces, settings, "Ghost", GHOST_START, basis))
    return expect
