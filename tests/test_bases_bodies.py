"""Bases of the body and joint cases' measures: each spec measure holds on a trace in ODE's reading
and on the same motion in another legitimate reading (a sign, a reference, when damping acts);
the convention measures tell the two apart; a trace that breaks the spec fails a spec measure.
Plus: every measure of these cases, on a real mujoco run, states its basis."""

from __future__ import annotations

import math

import numpy as np
import pytest

from x3d_core.traces.trace import Row, TraceView, read_trace

from conformance import cases as C
from conformance import results
from conformance.cases import damping as DAMP, erp_cfm_spring as SPRING, hinge_bounce as BOUNCE
from conformance.cases import hinge_limits as LIMITS, slider_stops as SLIDE
from conformance.runner import verdicts

CASES = ("free_fall", "projectile", "pendulum_period", "torque_free", "constant_force", "constant_torque",
         "gravity_off", "damping", "slider_stops", "hinge_limits", "ball_chain", "universal_joint", "frame_rate",
         "hinge_bounce", "motor_speed", "motor_joint_torque", "erp_cfm_spring", "double_pendulum_energy")
BACKEND = "mujoco"


def _rows(node: str, fields: dict[str, np.ndarray], times: np.ndarray) -> list[Row]:
    out = []
    for f, vals in fields.items():
        vals = np.asarray(vals, dtype=np.float64).reshape(len(times), -1)
        out += [Row(float(t), node, f, " ".join(repr(float(x)) for x in v)) for t, v in zip(times, vals)]
    return out


def _judge(name: str, rows: list[Row] | list[list[Row]]) -> results.Result:
    case = C.BY_NAME[name]
    views = [TraceView(r) for r in (rows if rows and isinstance(rows[0], list) else [rows])]
    return verdicts.evaluate(case, "test", views, case.runs)


def _failing(r: results.Result, kind: str) -> list[str]:
    return [m.quantity for m in r.failing(kind)]


def _split(ode: results.Result, other: results.Result, broken: results.Result) -> None:
    """ODE's reading passes; the other reading conforms but differs in conventions; the broken trace
    violates the spec."""
    assert ode.verdict == results.PASS, ode.reason
    assert other.verdict == results.CONVENTIONS and _failing(other, results.CONVENTION), other.reason
    assert broken.verdict == results.FAIL and _failing(broken, results.SPEC), broken.reason


@pytest.fixture(scope="module")
def real(tmp_path_factory):
    """Every case of this file on mujoco, the traces kept: name -> (result, [TraceView per run])."""
    folder = tmp_path_factory.mktemp("bases")
    found = verdicts.run_many([lambda c=C.BY_NAME[n]: verdicts.run_pair(c, BACKEND, keep=str(folder)) for n in CASES])
    out = {}
    for name, r in zip(CASES, found):
        n = len(C.BY_NAME[name].runs)
        paths = [folder / f"{name}-{BACKEND}{f'-{k}' if n > 1 else ''}.csv" for k in range(n)]
        out[name] = (r, [read_trace(str(p)) for p in paths if p.exists()])
    return out


def test_every_measure_states_its_basis(real):
    for name in CASES:
        r, _ = real[name]
        if name == "hinge_bounce":  # mujoco refuses stopBounce; the synthetic traces below judge it
            assert r.verdict == results.UNSUPPORTED
            continue
        assert r.verdict in results.JUDGED and r.measures, (name, r.verdict, r.reason)
        missing = [m.quantity for m in r.measures if m.basis is None]
        assert not missing, (name, missing)
        for m in r.measures:
            assert m.basis.kind in results.KINDS
            if m.basis.kind == results.SPEC:
                assert m.basis.text.startswith("37."), (name, m.basis.text)


# -- damping: once a step (ODE, x3drbp), once a frame (the clause's words), a force (Xj3D), per second (X_ITE)

def _damped(per: str, d_lin: float = DAMP.DAMP_LINEAR, d_ang: float = DAMP.DAMP_ANGULAR) -> list[Row]:
    """The case's body damped under one reading: each frame's velocity the last one's times r."""
    s = C.BY_NAME["damping"].runs[0]
    times = np.arange(int(s.duration * s.rate) + 1) / s.rate
    frames = np.round(times * s.rate)
    h = 1.0 / s.rate

    def ratio(d: float, inertia: float) -> np.ndarray:
        return {"step": (1 - d) ** np.round(times / s.dt), "frame": (1 - d) ** frames,
                "force": (1 - d * h / inertia) ** frames, "second": (1 - d) ** (h * frames)}[per][:, None]
    undamped = _rows("Undamped", {"linearVelocity": np.tile(DAMP.DAMP_V0, (len(times), 1)),
                                  "angularVelocity": np.tile(DAMP.DAMP_W0, (len(times), 1))}, times)  # autoDamp FALSE
    return undamped + _rows("Damped", {"linearVelocity": DAMP.DAMP_V0 * ratio(d_lin, DAMP.DAMP_MASS),
                                       "angularVelocity": DAMP.DAMP_W0 * ratio(d_ang, DAMP.DAMP_MOMENT)}, times)


@pytest.mark.parametrize("per", ["frame", "force", "second"])
def test_every_reading_of_damping_conforms_and_differs_from_once_a_step(per):
    _split(_judge("damping", _damped("step")), _judge("damping", _damped(per)),
           _judge("damping", _damped(per, d_lin=0.001)))  # the default factor, read the same way
    assert sorted(_failing(_judge("damping", _damped(per)), results.CONVENTION)) == [
        "Damped.angularVelocity = w0 (1-d)^steps", "Damped.linearVelocity = v0 (1-d)^steps"]


def test_damping_ignored_violates_the_spec():
    """A browser that leaves the factors at their default (0.001) or does not damp at all fails
    under every reading, and the readings are far apart at the case's settings: after 1 s,
    0.0896 of v0 once a step, 0.547 once a frame, 0.990 as a force (m = 1) or per second."""
    for per in ("step", "frame", "force", "second"):
        ignored = _judge("damping", _damped(per, d_lin=0.001, d_ang=0.001))
        assert len(_failing(ignored, results.SPEC)) == 2, (per, ignored.reason)
    still = _judge("damping", _damped("step", d_lin=0.0, d_ang=0.0))
    assert len(_failing(still, results.SPEC)) == 2, still.reason
    assert (1 - DAMP.DAMP_LINEAR) ** 240 == pytest.approx(0.0896, abs=1e-4)
    assert (1 - DAMP.DAMP_LINEAR) ** 60 == pytest.approx(0.547, abs=1e-3)
    assert (1 - DAMP.DAMP_LINEAR / 60) ** 60 == pytest.approx(0.990, abs=1e-3)


def test_damping_that_turns_the_velocity_violates_the_spec():
    rows = _damped("step")
    def swap(value: str) -> str:  # x and z exchanged: the velocity turns
        return " ".join(repr(float(x)) for x in np.array(value.split(), float)[[2, 1, 0]])
    turned = [r if r.field != "linearVelocity" or r.time == 0 else Row(r.time, r.node, r.field, swap(r.value))
              for r in rows]
    assert [q for q in _failing(_judge("damping", turned), results.SPEC) if q.startswith("Damped.linearVelocity")]


# -- slider_stops: which stop the block rests at is the sign's ------------------------------

def _slide(end: float) -> list[Row]:
    s = C.BY_NAME["slider_stops"].runs[0]
    times = np.arange(int(round(s.duration / s.dt)) + 1) * s.dt
    a = 7.848
    return _rows("Slide", {"separation": np.clip(0.5 * a * times ** 2, 0.0, end) if end else np.zeros_like(times)},
                 times)


def test_slider_held_at_the_min_stop_conforms_and_differs_in_sign(real):
    ode_real = _judge("slider_stops", real["slider_stops"][1][0])
    assert ode_real.verdict == results.PASS, ode_real.reason
    _split(_judge("slider_stops", _slide(SLIDE.SLIDE_MAX)), _judge("slider_stops", _slide(0.0)),
           _judge("slider_stops", _slide(1.0)))  # on to the default stop, 1 m


# -- hinge_limits: the arm rests at minAngle (ODE's sign) or at maxAngle (the other) ---------

def _negated(rows: list[Row], fields: set[str], cap: float | None = None) -> list[Row]:
    out = []
    for r in rows:
        if r.field in fields:
            v = -np.array(r.value.split(), dtype=np.float64)
            if cap is not None:
                v = np.minimum(v, cap)
            r = Row(r.time, r.node, r.field, " ".join(repr(float(x)) for x in v))
        out.append(r)
    return out


def test_hinge_resting_at_max_angle_with_the_other_sign_conforms(real):
    rows = real["hinge_limits"][1][0]
    other = _negated(rows, {"angle", "angleRate"}, cap=LIMITS.HINGE_MAX)  # the fall is positive: maxAngle stops it
    # the other sign, but the arm goes on 0.35 rad past maxAngle: more than the yield ODE's own stop shows at
    # minAngle (0.23 rad), which either sign is allowed alike
    broken = [Row(r.time, r.node, r.field, repr(max(float(r.value), LIMITS.HINGE_MAX + 0.35)))
              if r.node == "Hinge" and r.field == "angle" and float(r.value) > LIMITS.HINGE_MAX - 0.05 else r
              for r in _negated(rows, {"angle", "angleRate"})]
    _split(_judge("hinge_limits", rows), _judge("hinge_limits", other), _judge("hinge_limits", broken))
    assert _failing(_judge("hinge_limits", other), results.CONVENTION) == ["Hinge.angle farthest - minAngle"]


def test_an_arm_past_its_stop_breaks_the_limits_sentence(real):
    """37.4.12: minAngle and maxAngle "control the maximum angles through which the hinge is allowed
    to travel": an arm that stops 0.35 rad past minAngle fails it (before, only graded)."""
    rows = real["hinge_limits"][1][0]
    past = [Row(r.time, r.node, r.field, repr(LIMITS.HINGE_MIN - 0.35))  # at the stop, read 0.35 rad past it
            if r.node == "Hinge" and r.field == "angle" and float(r.value) < LIMITS.HINGE_MIN + 0.05 else r
            for r in rows]
    failing = _failing(_judge("hinge_limits", past), results.SPEC)
    assert "Hinge.angle beyond limits" in failing, failing


# -- hinge_bounce: the impact at minAngle (ODE's sign) or maxAngle ---------------------------

def _bounce(stop: float, ratio: float = BOUNCE.BOUNCE) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A falling arm (rate down by c a step) that meets `stop` (< 0) and leaves at ratio x its speed."""
    s = C.BY_NAME["hinge_bounce"].runs[0]
    h, c = s.dt, 5.0 * s.dt
    n = int(round(s.duration / h))
    ang, rate = np.zeros(n + 1), np.zeros(n + 1)
    bounced = False
    for i in range(n):
        if not bounced and ang[i] <= stop:
            rate[i + 1], bounced = -ratio * rate[i], True
        else:
            rate[i + 1] = rate[i] - c
        ang[i + 1] = ang[i] + rate[i + 1] * h
    return np.arange(n + 1) * h, ang, rate


def _bounce_rows(stop: float, sign: float = 1.0, ratio: float = BOUNCE.BOUNCE) -> list[Row]:
    t, ang, rate = _bounce(stop, ratio)
    return _rows("Hinge", {"angle": sign * ang, "angleRate": sign * rate}, t)


def test_bounce_at_max_angle_with_the_other_sign_conforms():
    ode = _judge("hinge_bounce", _bounce_rows(BOUNCE.BOUNCE_MIN))
    other = _judge("hinge_bounce", _bounce_rows(-BOUNCE.BOUNCE_MAX, sign=-1.0))
    broken = _judge("hinge_bounce", _bounce_rows(BOUNCE.BOUNCE_MIN, ratio=0.0))  # no bounce at all
    _split(ode, other, broken)
    assert all(m.basis is not None for m in ode.measures)
    # the impact read with the other sign at minAngle's place (+0.6) is beyond maxAngle: a spec failure
    assert _failing(_judge("hinge_bounce", _bounce_rows(BOUNCE.BOUNCE_MIN, sign=-1.0)), results.SPEC)


# -- motor_speed and motor_joint_torque: which body turns which way is ODE's -----------------

def test_motor_driving_the_other_body_conforms(real):
    rows = real["motor_speed"][1][0]
    other = _negated(rows, {"angularVelocity", "hinge2AngleRate"})
    broken = [Row(r.time, r.node, r.field, " ".join(repr(0.5 * float(x)) for x in r.value.split()))
              if r.node == "Wheel" and r.field == "angularVelocity" else r for r in rows]  # half the target
    _split(_judge("motor_speed", rows), _judge("motor_speed", other), _judge("motor_speed", broken))


def test_motor_joint_torque_the_other_way_round_conforms(real):
    rows = real["motor_joint_torque"][1][0]
    other = _negated(rows, {"angularVelocity", "motor1AngleRate"})
    broken = [Row(r.time, r.node, r.field, " ".join(repr(2.0 * float(x)) for x in r.value.split()))
              if r.node == "UserStator" and r.field == "angularVelocity" else r for r in rows]  # not equal and opposite
    _split(_judge("motor_joint_torque", rows), _judge("motor_joint_torque", other),
           _judge("motor_joint_torque", broken))
    assert sorted(_failing(_judge("motor_joint_torque", other), results.CONVENTION)) == [
        "AutoMotor.motor1AngleRate", "UserRotor.angularVelocity"]


def _zeroed(rows: list[Row], nodes: set[str]) -> list[Row]:
    return [Row(r.time, r.node, r.field, " ".join("0.0" for _ in r.value.split()))
            if r.node in nodes and r.field in ("angularVelocity", "motor1AngleRate") else r for r in rows]


def test_motor_joint_torque_only_in_user_calculated_mode_conforms(real):
    """The UOM's reading: no torque with autoCalc TRUE, so AutoMotor's bodies stay still and report
    rate 0, which is their rate. A rate output that is not the bodies' rate, or a torque ignored in
    user-calculated mode too, violates the spec."""
    rows = real["motor_joint_torque"][1][0]
    gated = _judge("motor_joint_torque", _zeroed(rows, {"AutoRotor", "AutoStator", "AutoMotor"}))
    assert gated.verdict == results.CONVENTIONS, gated.reason
    # (a rate of 0 lies as near ODE's sign as the other: the sign convention holds it; the spec holds
    # it to the bodies' rate, 0 here)
    assert _failing(gated, results.CONVENTION) == [
        "AutoRotor.angularVelocity, either sense (the torque acts with autoCalc TRUE)"]
    stuck_rate = _judge("motor_joint_torque", _zeroed(rows, {"AutoMotor"}))
    assert "|AutoMotor.motor1AngleRate| = |motor1Axis . (w1 - w2)|" in _failing(stuck_rate, results.SPEC)
    no_torque = _judge("motor_joint_torque", _zeroed(rows, {"UserRotor", "UserStator", "UserMotor", "AutoRotor",
                                                            "AutoStator", "AutoMotor"}))
    assert _failing(no_torque, results.SPEC) == ["UserRotor.angularVelocity, either sense"]


# -- erp_cfm_spring: the sag's size is ODE's reading of ERP and CFM --------------------------

def _hanging(sags: dict[str, float]) -> list[Row]:
    s = C.BY_NAME["erp_cfm_spring"].runs[0]
    times = np.arange(int(s.duration * s.rate) + 1) / s.rate
    rows = []
    for name, (_, anchor) in SPRING.SPRING_WEIGHTS.items():
        fixed = np.tile(anchor, (len(times), 1))
        rows += _rows(f"{name}Hold", {"body1AnchorPoint": fixed - np.array([0.0, sags[name], 0.0]),
                                      "body2AnchorPoint": fixed}, times)
    return rows


def test_a_spring_of_other_units_conforms_a_hard_joint_does_not(real):
    k, _ = SPRING.spring_constants(C.BY_NAME["erp_cfm_spring"].runs[0].dt)
    ode = {name: m * 9.81 / k for name, (m, _) in SPRING.SPRING_WEIGHTS.items()}
    _split(_judge("erp_cfm_spring", _hanging(ode)),
           _judge("erp_cfm_spring", _hanging({name: 2.53e-5 for name in ode})),  # mujoco's: one sag for both
           _judge("erp_cfm_spring", _hanging({name: 0.0 for name in ode})))  # hard: no sag
    mujoco = real["erp_cfm_spring"][0]
    assert mujoco.verdict == results.CONVENTIONS and not _failing(mujoco, results.SPEC), mujoco.reason


# -- frame_rate: a step by the frame period differs in convention only -----------------------

def test_frame_rate_differences_are_a_convention(real):
    a, b = real["frame_rate"][1]
    assert _judge("frame_rate", [a, b]).verdict == results.PASS
    nudged = [Row(r.time, r.node, r.field, " ".join(repr(float(x) * (1 + 1e-6)) for x in r.value.split()))
              if r.field == "position" else r for r in b]
    r = _judge("frame_rate", [a, nudged])
    assert r.verdict == results.CONVENTIONS and not any(m.basis.kind == results.SPEC for m in r.measures)
    assert math.isfinite(r.measures[0].error) and r.measures[0].error > 0


def _fall(steps: list[float], g: float = 9.81) -> list[Row]:
    """free_fall's Ball, one semi-implicit Euler step of each given length per 60 Hz frame."""
    y, v, out = 10.0, 0.0, _rows("Ball", {"position": [0.0, 10.0, 0.0], "linearVelocity": [0.0, 0.0, 0.0]},
                                  np.zeros(1))
    for k, h in enumerate(steps, 1):
        v -= g * h
        y += h * v
        out += _rows("Ball", {"position": [0.0, y, 0.0], "linearVelocity": [0.0, v, 0.0]}, np.array([k / 60]))
    return out


def _x_ite_steps(frames: int = 60) -> list[float]:
    """X_ITE's physics step: a moving average of the frame period from 0 (docs/spec-loose-ends.md)."""
    d, out = 0.0, []
    for _ in range(frames):
        d = (14 * d + 1 / 60) / 15
        out.append(d)
    return out


def test_a_clock_that_lags_fails_by_the_clock_s_sentence_alone():
    lagging = _judge("free_fall", _fall(_x_ite_steps()))
    assert [m.basis for m in lagging.failing(results.SPEC)] == [C.closed_forms.CLOCK], lagging.reason
    # the gravity it applies cannot be told from its clock there: graded, never the field's failure
    assert any(m.graded and "clock does not keep pace" in m.quantity for m in lagging.measures)


def test_a_step_a_frame_keeps_pace_and_a_gravity_ignored_is_the_field_s_failure():
    per_frame = _judge("free_fall", _fall([1 / 60] * 60))
    assert per_frame.verdict == results.CONVENTIONS and not per_frame.failing(results.SPEC), per_frame.reason
    weightless = _judge("free_fall", _fall([1 / 60] * 60, g=0.0))
    assert [m.quantity for m in weightless.failing(results.SPEC)] == ["Ball acceleration (whatever the clock) - "
                                                                     "(0 -9.81 0)"], weightless.reason
    default = _judge("free_fall", _fall([1 / 60] * 60, g=9.8))  # X3D's default in the scene's 9.81's place
    assert [m.quantity for m in default.failing(results.SPEC)] == ["Ball acceleration (whatever the clock) - "
                                                                  "(0 -9.81 0)"], default.reason
