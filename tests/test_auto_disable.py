"""autoDisable (x3d_core/semantics/evaluator.py _AutoDisable), engine-free: a scripted simulation
integrates free bodies and reports the contacts a test gives it, counting every read.

The clause: "Once any one of these values is achieved, the body is considered as being at rest,
unless acted upon by an external force (e.g., collision or action of connected joint)". And the
auto_disable case's expectation fails where a body never stops or never wakes."""

from __future__ import annotations

import numpy as np
import pytest

from x3d_core.encodings.load import load
from x3d_core.semantics.collision import ContactPoints
from x3d_core.semantics.evaluator import RunSettings, _AutoDisable, run
from x3d_core.semantics.world import State, worlds
from x3d_core.traces.trace import TraceView

from engine_run import scene_worlds

DT = 1 / 240
N = 60  # disableTime 0.25 s at 1/240 s
BOX = ("<CollidableShape DEF='{0}Shape' containerField='geometry'>"
       "<Shape containerField='shape'><Box size='0.2 0.2 0.2'/></Shape></CollidableShape>")


class Scripted:
    """Free bodies (semi-implicit Euler, no rotation of the pose) with the contacts
    `touching(step)` names as geometry pairs; counts contacts() calls."""
    name = "scripted"

    def __init__(self, touching=lambda step: ()):
        self.touching = touching
        self.reads = 0
        self.sims = []

    def build(self, world, dt):
        engine = self

        class Sim:
            def __init__(self):
                self.s = State.initial(world.bodies)
                self.steps = 0
                b = world.bodies
                self.forces, self.torques = b.forces.copy(), b.torques.copy()

            def step(self, n=1):
                b = world.bodies
                for _ in range(n):
                    a = self.forces / b.mass[:, None] + world.gravity * b.use_gravity[:, None]
                    self.s.linear_velocity = self.s.linear_velocity + a * dt
                    self.s.position = self.s.position + self.s.linear_velocity * dt
                    self.steps += 1

            def state(self):
                return State(self.s.position.copy(), self.s.orientation.copy(), self.s.linear_velocity.copy(),
                             self.s.angular_velocity.copy())

            def set_velocities(self, linear, angular):
                self.s.linear_velocity, self.s.angular_velocity = linear.copy(), angular.copy()

            def set_loads(self, forces, torques):
                self.forces, self.torques = forces.copy(), torques.copy()

            def contacts(self):
                engine.reads += 1
                pairs = list(engine.touching(self.steps))
                k = len(pairs)
                return ContactPoints(np.zeros((k, 3)), np.tile([0.0, 1.0, 0.0], (k, 1)), np.zeros(k),
                                     np.array([p[0] for p in pairs], dtype=int),
                                     np.array([p[1] for p in pairs], dtype=int))
        sim = Sim()
        self.sims.append(sim)
        return sim


def series(trace, node: str, field: str) -> tuple[np.ndarray, np.ndarray]:
    return TraceView(trace.rows).series(node, field)


THRESHOLDS = "autoDisable='true' disableLinearSpeed='0.1' disableAngularSpeed='0.1' disableTime='0.25'"


def test_any_one_speed_under_its_threshold_disables_after_disable_time(tmp_path):
    # SlowSpinning: linear speed under, angular over: at rest by "any one of these values" (ODE: never)
    (w,) = scene_worlds(tmp_path, f"""<RigidBodyCollection gravity='0 0 0'>
      <RigidBody DEF='SlowSpinning' linearVelocity='0.05 0 0' angularVelocity='0 0 0.5' {THRESHOLDS}/>
      <RigidBody DEF='Fast' linearVelocity='0.5 0 0' angularVelocity='0 0 0.5' {THRESHOLDS}/>
      <RigidBody DEF='Plain' linearVelocity='0.05 0 0'/></RigidBodyCollection>""")
    trace = run([w], Scripted(), RunSettings(0.5, DT, 240))
    t, p = series(trace, "SlowSpinning", "position")
    _, v = series(trace, "SlowSpinning", "linearVelocity")
    _, om = series(trace, "SlowSpinning", "angularVelocity")
    n = np.round(t / DT)
    assert np.all(v[n < N, 0] == 0.05) and np.all(v[n >= N] == 0) and np.all(om[n >= N] == 0)
    assert np.all(p[n >= N, 0] == pytest.approx(0.05 * N * DT, abs=1e-12))
    _, v = series(trace, "Fast", "linearVelocity")
    assert np.all(v[:, 0] == 0.5)  # neither speed under its threshold
    _, v = series(trace, "Plain", "linearVelocity")
    assert np.all(v[:, 0] == 0.05)  # no autoDisable
    # the collection's thresholds where the body's own autoDisable is FALSE
    (w,) = scene_worlds(tmp_path, f"""<RigidBodyCollection gravity='0 0 0' {THRESHOLDS}>
      <RigidBody DEF='B' angularVelocity='0 0 0.5'/></RigidBodyCollection>""")
    d = _AutoDisable(w, DT)
    assert d.candidates.tolist() == [True] and d.needed.tolist() == [N]


def test_a_body_on_a_joint_takes_no_part(tmp_path):
    (w,) = scene_worlds(tmp_path, f"""<RigidBodyCollection gravity='0 0 0'>
      <RigidBody DEF='A' {THRESHOLDS}/><RigidBody DEF='B' position='1 0 0' {THRESHOLDS}/>
      <BallJoint><RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/></BallJoint>
      </RigidBodyCollection>""")
    assert not _AutoDisable(w, DT).active


FLOOR_SCENE = f"""<RigidBodyCollection gravity='0 -9.81 0'>
  <RigidBody DEF='Resting' position='0 0.1 0' {THRESHOLDS}>{BOX.format('Resting')}</RigidBody>
  <RigidBody DEF='Other' position='5 0.1 0'>{BOX.format('Other')}</RigidBody>
  <CollisionCollection containerField='collider'>
    <CollidableShape DEF='Floor' translation='0 -0.1 0'>
      <Shape containerField='shape'><Box size='20 0.2 2'/></Shape></CollidableShape>
    <CollidableShape USE='RestingShape'/><CollidableShape USE='OtherShape'/></CollisionCollection>
</RigidBodyCollection>"""


def _resting(tmp_path, touching):
    """FLOOR_SCENE on the scripted engine (no contact forces: Resting falls, not spinning, so idle
    from the first step), its geometries 0 the floor, 1 Resting, 2 Other; 1 s at a frame a step."""
    (w,) = scene_worlds(tmp_path, FLOOR_SCENE)
    assert [g.name for g in w.collisions.geometries] == ["Floor", "RestingShape", "OtherShape"]
    engine = Scripted(touching)
    return engine, run([w], engine, RunSettings(1.0, DT, 240))


def test_the_contact_a_body_rests_on_does_not_wake_it_a_new_one_does(tmp_path):
    engine, trace = _resting(tmp_path, lambda step: [(1, 0)] + ([(2, 1)] if step == 90 else []))
    t, v = series(trace, "Resting", "linearVelocity")
    n = np.round(t / DT)
    assert np.all(v[(n >= N) & (n <= 90)] == 0)  # held on the floor it touches throughout
    # awake after step 90 (its weight back from step 91), its idle clock restarted there
    again = 90 + N - 1
    assert np.all(v[(n > 90) & (n < again), 1] < 0) and np.all(v[n >= again] == 0)
    # contacts read at the step it stopped, and at every step that starts with it off
    assert engine.reads == 1 + (90 - N) + 1 + (240 - again)


def test_a_contact_with_an_awake_body_wakes_it(tmp_path):
    _, trace = _resting(tmp_path, lambda step: [(1, 0)] + ([(2, 1)] if step >= 30 else []))
    t, v = series(trace, "Resting", "linearVelocity")
    n = np.round(t / DT)
    # Other (no autoDisable: always awake) touches it from step 30: disabled at step N, it is
    # awake again after the next (as ODE wakes a disabled body an enabled one touches)
    assert np.all(v[(n >= N) & (n <= N + 1)] == 0) and np.all(v[(n >= N + 2) & (n < 2 * N), 1] < 0)


def test_an_applied_force_or_torque_keeps_a_slow_body_awake(tmp_path):
    (w,) = scene_worlds(tmp_path, f"""<RigidBodyCollection gravity='0 0 0'>
      <RigidBody DEF='Pushed' forces='0.02 0 0' {THRESHOLDS}/>
      <RigidBody DEF='Twisted' torques='0 0 0.001' {THRESHOLDS}/>
      <RigidBody DEF='Free' linearVelocity='0.01 0 0' {THRESHOLDS}/></RigidBodyCollection>""")
    trace = run([w], Scripted(), RunSettings(0.5, DT, 240))
    t, v = series(trace, "Pushed", "linearVelocity")
    assert v[-1, 0] == pytest.approx(0.02 * 0.5, rel=1e-9)  # never disabled: v = a t
    _, v = series(trace, "Free", "linearVelocity")
    assert np.all(v[-1] == 0)
    d = _AutoDisable(w, DT)
    assert d.pushed.tolist() == [True, True, False]


def test_wake_resets_the_clock():
    class W:  # the least of a World _AutoDisable reads
        class bodies:
            auto_disable = np.array([True])
            fixed = np.array([False])
            disable_thresholds = np.array([[0.1, 0.1, 0.25]])
            forces = torques = np.zeros((1, 3))

            def __len__(self):
                return 1
        bodies = bodies()
        node = {"autoDisable": False, "disableLinearSpeed": 0, "disableAngularSpeed": 0, "disableTime": 0}
        joints = []
        collisions = None
    d = _AutoDisable(W, DT)
    d.idle[:], d.disabled[:] = 99, True
    d.wake(np.array([0]))
    assert d.idle.tolist() == [0] and d.disabled.tolist() == [False]


def test_a_scene_without_auto_disable_never_reads_contacts(tmp_path):
    (w,) = scene_worlds(tmp_path, FLOOR_SCENE.replace(f" {THRESHOLDS}", ""))
    engine = Scripted(lambda step: [(1, 0)])
    run([w], engine, RunSettings(0.5, DT, 60))
    assert engine.reads == 0
    # with autoDisable, none before a body is disabled
    engine, _ = _resting(tmp_path, lambda step: [(1, 0)])
    assert engine.sims[0].steps == 240 and engine.reads == 240 - N + 1


# the auto_disable case's expectation on runs where a body never stops, or never wakes
@pytest.fixture(scope="module")
def case_on_a_backend():
    from backends.base import available
    from conformance.cases import BY_NAME
    usable = [name for name, b in available().items() if not isinstance(b, str)]
    if not usable:
        pytest.skip("no backend installed")
    name = "ode" if "ode" in usable else usable[0]
    case = BY_NAME["auto_disable"]

    def judge(monkeypatch=None):
        s = case.runs[0]
        trace = run(worlds(load(case.path)), available()[name], RunSettings(s.duration, s.dt, s.rate))
        return {m.quantity: m for m in case.expect([TraceView(trace.rows)], case.runs)}
    return judge


def _failing_spec(measures) -> set[str]:
    return {q for q, m in measures.items() if not m.ok and not m.convention}


def test_the_case_passes_as_x3drbp_runs_it(case_on_a_backend):
    assert not [q for q, m in case_on_a_backend().items() if not m.ok]


def test_the_case_fails_where_a_body_never_wakes(case_on_a_backend, monkeypatch):
    monkeypatch.setattr(_AutoDisable, "_struck", lambda self, pairs: np.zeros(0, dtype=int))
    assert "Resting woken: m (vResting + vStriker).x - m u" in _failing_spec(case_on_a_backend())


def test_the_case_fails_where_a_body_never_stops(case_on_a_backend, monkeypatch):
    init = _AutoDisable.__init__

    def never(self, world, dt):
        init(self, world, dt)
        self.candidates[:] = False
        self.active = False
    monkeypatch.setattr(_AutoDisable, "__init__", never)
    failing = {q for q, m in case_on_a_backend().items() if not m.ok}
    assert any(q.startswith("Drifting") for q in failing)


def test_the_case_fails_under_odes_both_speeds_and_no_wake_on_force(case_on_a_backend, monkeypatch):
    init = _AutoDisable.__init__

    def odes(self, world, dt):  # the evaluator as it was: forces do not wake
        init(self, world, dt)
        self.pushed[:] = False
    monkeypatch.setattr(_AutoDisable, "__init__", odes)
    assert any(q.startswith("Pushed acceleration") for q in _failing_spec(case_on_a_backend()))
