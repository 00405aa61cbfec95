"""X_ITE on the conformance cases: per case what it gets right, what it ignores and what it
gets wrong, each measured by the suite's ordinary checks (`x3drbp validate`'s, unchanged).

- Each case's runs are recorded in X_ITE at the case's frame rate (or, where that is beyond
  what X_ITE draws, 80 frames/s, at the case's rate / k for the least k under it) and duration
  (conformance.browsers.x_ite.harness), and judged as any browser's traces are (conformance.analyses.validation): the
  case's expectation at the step X_ITE takes, and every backend run at that step.
- A case it passes is RIGHT; one where only convention measures fail (a reading of a point
  the spec leaves open that is not ODE's) is CONVENTIONS: it conforms.
- A case it fails is probed: for each field the case exercises (Case.exercises, where the
  feature is a field of a node type), the scene is recorded again with that field removed
  from every node of the type, i.e. at its default, and compared with the scene recorded
  with it. The scene is first made so X_ITE can show the field (variants.ready: a body's
  collidable for its mass distribution, a fixed body where a static floor lies and a
  CollisionSensor for contacts), the field is removed from that same scene, and the
  verdict names what was changed. A probe tells only where its own run shows the thing
  probed (`_untold`): a contact (the sensor active in some frame) for a contact's field, a
  body that turns for its inertia or centre of mass, a body the joint joins that moves (from
  the first step on) for a joint's field, a body that moves for any other, nothing for a field
  whose effect is the motion itself (a force, a torque, a motor's target, gravity); else
  the verdict says the probe could not tell, and why. A field the scene gives its default
  value is not probed (removing it changes nothing). A field whose removal leaves X_ITE's
  trace identical, byte for byte, in a probe that tells, has no effect in X_ITE: it
  IGNORES it. (Runs are bit-identical, so any effect at all shows.) For a joint's field the
  scene is also recorded without every joint of that type: where the bodies' rows are then the
  same though a body it joins moves, the joint has no effect at all, and the verdict names that
  as the cause. A failed case with no
  ignored field is WRONG.
- A case whose state stops being finite blew up: WRONG, its fields not probed (a trace cut
  short says nothing of what a field would have changed later); it is recorded again
  without each joint type it has, and the types without which it runs are named as the
  cause.
- A case X_ITE cannot run (its page throws, the browser crashes or times out, the scene
  has an output the page cannot name) is an ERROR, with the reason.
- The clock is read once, for every case (`read_clock`): a body falling freely in a scene
  of its own, at each frame rate and stepping (iterations, preferAccuracy) the cases are
  recorded at, shows the physics time X_ITE's
  state has reached at each frame (v = g tau, exact for every one-step scheme). That
  reading is judged once, by 37.2.2.1's sentence (closed_forms.CLOCK), and each case is
  judged at the physics time X_ITE's own state shows (its trace's frames retimed to it),
  so that a clock that lags fails the clock's sentence once and never a field's.

For every case where X_ITE's trace and a backend's part, a rerun recording shows X_ITE
beside every backend with the divergence series, written by the recorder the caller passes
(the command line's: reports/rerun_recording.py; the suite renders nothing itself).
"""

from __future__ import annotations

import filecmp
import os
import time

import numpy as np
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, field

from x3d_core.encodings.load import load
from x3d_core.files import atomic
from x3d_core.model import schema
from x3d_core.model.scene import Scene
from x3d_core.semantics.world import node_names, worlds
from x3d_core.traces.trace import TraceView, read_trace

from conformance import results
from conformance.cases.case import Case
from conformance.cases.closed_forms import CLOCK
from conformance.analyses.trace_check import check_trace
from conformance.analyses.validation import check_case, compare_with_backends
from conformance.results import PairComparison, Validation
from conformance.browsers.x_ite.harness import NotRecordable, Recording, outputs, reachable_rate, record, step
from conformance.browsers.x_ite.variants import ADDED, CONTACT, SENSOR, needs, ready, without, without_nodes

RIGHT, CONVENTIONS, IGNORES, WRONG, ERROR = "right", "conventions", "ignores", "wrong", "error"
NAME = "x_ite"  # X_ITE's name beside the backends' in comparisons and recordings
# Writes the recording of a case where X_ITE and a backend part, and gives its path: from the
# case's name, its scene, each run's trace by name (X_ITE's first) and the pairs compared
Recorder = Callable[[str, Scene, list[tuple[str, TraceView]], list[PairComparison]], str]


@dataclass
class CaseVerdict:
    case: str
    verdict: str  # RIGHT, CONVENTIONS, IGNORES, WRONG or ERROR
    detail: str  # the failing measures, or what stopped the run
    dt: float | None = None  # the step X_ITE takes in this case
    # the frame rates its runs were recorded at: the case's, or under X_ITE's maximum (80/s)
    frame_rates: list[float] = field(default_factory=list)
    ignored: list[str] = field(default_factory=list)  # TYPE.field with no effect on X_ITE's trace
    probed: list[str] = field(default_factory=list)  # every TYPE.field probed (the scene sets it)
    # TYPE.field -> what its probe's scene changed so that X_ITE could show the field (variants.ready)
    variants: dict[str, list[str]] = field(default_factory=dict)
    untold: dict[str, str] = field(default_factory=dict)  # TYPE.field -> why its probe could not tell
    # joint types of probed fields whose removal, every node of the type, leaves the trace identical: no effect
    # at all, the cause of their fields' none
    inert: list[str] = field(default_factory=list)
    blew_up_probed: list[str] = field(default_factory=list)  # joint types taken out of a case that blew up
    blow_up_causes: list[str] = field(default_factory=list)  # those without which it no longer blows up
    agreeing: list[str] = field(default_factory=list)  # backends whose runs agree with X_ITE's
    recording: str | None = None  # the rerun recording, relative to the output folder
    wall_s: float = 0.0  # X_ITE's own recording time, all runs of the case
    messages: list[str] = field(default_factory=list)  # what X_ITE printed as errors or warnings
    validation: dict | None = None  # Validation.to_json()

    def to_json(self) -> dict:
        return asdict(self)

    @classmethod
    def from_json(cls, d: dict) -> CaseVerdict:
        return cls(**d)


@dataclass
class ClockReading:
    """X_ITE's physics clock at one frame rate and stepping (a collection's iterations and
    preferAccuracy: X_ITE steps its frame in `iterations` equal substeps where it prefers
    accuracy, else through Bullet's fixed-substep accumulator), read off a freely falling body."""
    frame_rate: float
    iterations: int
    prefer_accuracy: bool
    lag_s: float | None  # the largest |frame time - physics time| over the run; None: not read
    tolerance_s: float  # one frame and one step, as closed_forms.ballistic's clock measure allows
    error: str | None = None  # why it could not be read
    physics_times: list[float] = field(default_factory=list)  # at frame k, the physics time X_ITE's state shows

    @property
    def ok(self) -> bool:
        return self.lag_s is not None and self.lag_s <= self.tolerance_s

    def to_json(self) -> dict:
        return {**asdict(self), "ok": self.ok, "basis": CLOCK.text}


CLOCK_BODY = "XITE_CLOCK"
_CLOCK_G = 9.8  # the clock scene's gravity, X3D's default
ClockKey = tuple[float, int, bool]  # frame rate, iterations, preferAccuracy


def clock_key(scene_path: str, frame_rate: float) -> ClockKey:
    """How X_ITE steps the scene at this frame rate (its first enabled collection's stepping)."""
    found = worlds(load(scene_path))
    return (frame_rate, found[0].iterations, found[0].prefer_accuracy) if found else (frame_rate, 10, False)


def _clock_scene(iterations: int, prefer_accuracy: bool) -> str:
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<X3D profile='Full' version='4.0'><Scene>
  <RigidBodyCollection DEF='XITE_CLOCK_WORLD' iterations='{iterations}' preferAccuracy='{str(prefer_accuracy).lower()}'>
    <RigidBody DEF='{CLOCK_BODY}'>
      <CollidableShape containerField='geometry'><Shape containerField='shape'><Sphere radius='0.1'/></Shape></CollidableShape>
    </RigidBody>
  </RigidBodyCollection>
</Scene></X3D>
"""


def _clock_runs(longest: Mapping[ClockKey, float], folder: str) -> dict[ClockKey, Recording]:
    """A recording of the clock scene per frame rate and stepping, as long as the longest run of it."""
    out = {}
    for k, ((rate, iterations, accurate), duration) in enumerate(sorted(longest.items())):
        path = os.path.join(folder, f"x_ite-clock.{k}.x3d")
        atomic.write_text(path, _clock_scene(iterations, accurate))
        out[(rate, iterations, accurate)] = Recording(path, path[:-4] + ".csv", rate, duration, outputs(load(path)))
    return out


def read_clock(key: ClockKey, run: Recording) -> ClockReading:
    """The physics time at each frame, tau_k = -v_y / g (v = g tau exact for every one-step
    scheme, to X_ITE's float32 rounding), and the largest lag behind the frame clock."""
    rate, iterations, accurate = key
    dt = 1.0 / (rate * iterations)  # the step X_ITE takes (harness.step)
    reading = ClockReading(rate, iterations, accurate, None, dt + 1.0 / rate)
    if not run.ok or run.blew_up:
        reading.error = run.error or run.blew_up or "no trace"
        return reading
    t, v = TraceView(read_trace(run.out)).series(CLOCK_BODY, "linearVelocity")
    tau = -v[:, 1] / _CLOCK_G
    reading.lag_s, reading.physics_times = float(np.max(np.abs(t - tau))), [float(x) for x in tau]
    return reading


def _retimed(view: TraceView, clock: ClockReading | None) -> TraceView:
    """The trace with frame k's rows at the physics time X_ITE's state shows there."""
    if clock is None or clock.lag_s is None:
        return view
    tau = np.asarray(clock.physics_times)
    frames = np.arange(tau.size) / clock.frame_rate
    return view.retimed(lambda t: np.interp(t, frames, tau))


def probe_fields(case: Case) -> list[tuple[str, str]]:
    """(node type, field) of each exercised feature that is a field: the ones a scene sets."""
    out = []
    for feature in case.exercises:
        parts = feature.split(".")
        spec = schema.node_type(parts[0])
        if len(parts) >= 2 and spec is not None and parts[1] in spec.fields and (parts[0], parts[1]) not in out:
            out.append((parts[0], parts[1]))
    return out


@dataclass
class _Case:
    """A case under way: its recordings, then its judgement."""
    case: Case
    folder: str
    runs: list[Recording] = field(default_factory=list)
    verdict: CaseVerdict | None = None
    # (TYPE.field or joint TYPE, its recording, the recording it is compared with)
    probes: list[tuple[str, Recording, Recording]] = field(default_factory=list)
    # joint TYPE -> the scene recorded without its nodes, and the recording it is compared with
    controls: dict[str, tuple[Recording, Recording]] = field(default_factory=dict)


def _prepare(case: Case, folder: str) -> _Case:
    c = _Case(case, folder)
    try:
        scene = load(case.path)
        what = outputs(scene)
    except NotRecordable as e:
        c.verdict = CaseVerdict(case.name, ERROR, str(e))
        return c
    c.runs = [Recording(case.path, os.path.join(folder, f"{case.name}.{k}.csv"), reachable_rate(s.rate), s.duration,
                        what) for k, s in enumerate(case.runs)]
    return c


def _judge(c: _Case, backends: Sequence[str], info: Mapping[str, results.BackendInfo],
           thresholds: Mapping[str, float], timeout: float, recorder: Recorder | None,
           clocks: Mapping[ClockKey, ClockReading]) -> None:
    case = c.case
    wall = sum(r.wall_s or 0.0 for r in c.runs)
    messages = sorted({m for r in c.runs for m in r.messages})
    broken = next((r for r in c.runs if not r.ok), None)
    if broken is not None:
        c.verdict = CaseVerdict(case.name, ERROR, broken.error or "no trace", wall_s=wall, messages=messages)
        return
    scene = load(case.path)
    dt = step(scene, c.runs[0].frame_rate)
    blown = next((r for r in c.runs if r.blew_up), None)
    if blown is not None:  # as the evaluator counts a backend's non-finite state
        c.verdict = CaseVerdict(case.name, WRONG, f"blew up: {blown.blew_up}", dt, wall_s=wall, messages=messages)
        return
    views, rows_of = [], []
    for r in c.runs:
        rows, problems = check_trace(r.out, scene)
        if problems:
            c.verdict = CaseVerdict(case.name, ERROR, f"its trace is unreadable: {problems[0]}", dt,
                                    wall_s=wall, messages=messages)
            return
        rows_of.append(rows)
        views.append(TraceView(rows))
    retimed = [_retimed(view, clocks.get(clock_key(case.path, r.frame_rate))) for view, r in zip(views, c.runs)]
    result = check_case(case, retimed, dt, [r.frame_rate for r in c.runs])
    comparisons = [compare_with_backends(case.path, r.out, rows, dt, backends, info, thresholds, timeout, NAME)
                   for r, rows in zip(c.runs, rows_of)]
    v = Validation(case.path, [r.out for r in c.runs], dict(thresholds), result, comparisons)
    verdict = {results.PASS: RIGHT, results.CONVENTIONS: CONVENTIONS}.get(result.verdict, WRONG)
    detail = result.accuracy_text() if verdict == RIGHT else result.meaning()  # a right case's grade
    c.verdict = CaseVerdict(case.name, verdict, detail, dt, agreeing=v.agreeing(), wall_s=wall, messages=messages, validation=v.to_json())
    parted = [b for b in comparisons[0].pairs if comparisons[0].verdict(b) != "agrees"]
    if recorder is not None and parted:
        c.verdict.recording = recorder(case.name, load(case.path), [(NAME, views[0]), *comparisons[0].views.items()],
                                       list(comparisons[0].pairs.values()))


def _probe(cases: Sequence[_Case], timeout_per_run: float) -> None:
    """Records each failed case again without each field it exercises, on a variant of the
    scene where X_ITE can show that field (variants.ready): a field whose removal leaves the
    trace byte-identical to the variant's own is ignored. A case that blew up is recorded
    again without each joint type it has instead: the types without which it no longer
    blows up are the cause."""
    probes: list[Recording] = []
    for c in cases:
        if c.verdict is None or c.verdict.verdict != WRONG:
            continue
        if any(r.blew_up for r in c.runs):  # a trace cut short says nothing of what a field changes later
            probes += _blow_up_probes(c)
            continue
        first = c.runs[0]
        bases: dict[tuple[str, ...], tuple[Recording, list[str]]] = {(): (first, [])}
        for t, f in probe_fields(c.case):
            need = needs(t, f)
            if need not in bases:
                path = os.path.join(c.folder, f"{c.case.name}.x_ite-ready.{len(bases)}.x3d")
                changes = ready(c.case.path, path, need)
                base = Recording(path, path[:-4] + ".csv", first.frame_rate, first.duration,
                                 outputs(load(path))) if changes else first
                bases[need] = (base, changes)
                if changes:
                    probes.append(base)
            base, changes = bases[need]
            variant = os.path.join(c.folder, f"{c.case.name}.without-{t}.{f}.x3d")
            # from the ready scene, the field its one difference; a field the scene gives its default value is
            # no difference at all, and no probe
            if without(base.scene, t, f, variant) and _values(base.scene, t, f) != _values(variant, t, f):
                r = Recording(variant, variant[:-4] + ".csv", first.frame_rate, first.duration, base.what)
                c.probes.append((f"{t}.{f}", r, base))
                c.verdict.variants[f"{t}.{f}"] = changes
                probes.append(r)
                joint = _is_joint(t)
                control = os.path.join(c.folder, f"{c.case.name}.without-{t}.x3d")
                if joint and t not in c.controls and without_nodes(base.scene, t, control):
                    r = Recording(control, control[:-4] + ".csv", first.frame_rate, first.duration,
                                  outputs(load(control)))
                    c.controls[t] = (r, base)
                    probes.append(r)
        c.verdict.probed = [name for name, _, _ in c.probes]
    record(probes, timeout_per_run * max(1, len(probes)))
    for c in cases:
        if c.verdict is not None and c.verdict.blew_up_probed:
            c.verdict.blow_up_causes = [name for name, r, _ in c.probes if r.ok and not r.blew_up]
            continue
        told = [(name, r, base) for name, r, base in c.probes if r.ok and base.ok]
        c.verdict.untold = {name: why for name, _, base in told if (why := _untold(name, base))}
        ignored = [name for name, r, base in told
                   if name not in c.verdict.untold and filecmp.cmp(r.out, base.out, shallow=False)]
        # where a body it joins moves: else the control tells nothing
        c.verdict.inert = [t for t, (r, base) in c.controls.items()
                           if r.ok and base.ok and _bodies_alike(r, base) and _moves(base, _joined(base.scene, t))]
        if ignored:
            c.verdict.verdict, c.verdict.ignored = IGNORES, ignored


# the fields a body shows only by turning
_TURNING = ("RigidBody.inertia", "RigidBody.centerOfMass")
# the fields whose effect is the motion itself: with none, the probe has shown them without effect
_DRIVING = ("RigidBody.forces", "RigidBody.torques", "RigidBody.linearVelocity", "RigidBody.angularVelocity",
            "RigidBodyCollection.gravity", "SliderJoint.sliderForce", "DoubleAxisHingeJoint.desiredAngularVelocity1",
            "DoubleAxisHingeJoint.desiredAngularVelocity2", "MotorJoint.axis1Torque", "MotorJoint.axis2Torque",
            "MotorJoint.axis3Torque")


def _untold(probed: str, base: Recording) -> str | None:
    """Why the probe of `probed` (TYPE.field) cannot tell whether X_ITE uses it: its run,
    with the field, does not show the thing the field acts through; None where it does."""
    if probed in _DRIVING:
        return None
    node_type, fld = probed.split(".", 1)
    if CONTACT in needs(node_type, fld):
        if any(r.node.startswith(SENSOR) and r.field == "isActive" and r.value == "true" for r in read_trace(base.out)):
            return None
        return "no contact happened in its run (the CollisionSensor watching every collision collection never active)"
    turning = probed in _TURNING
    if _is_joint(node_type):  # a joint's field acts through its own bodies
        bodies, where = _joined(base.scene, node_type), f"no body a {node_type} joins"
    else:
        bodies, where = set(base.what["bodies"]), "no body"
    if _moves(base, bodies, turning):
        return None
    return f"{where} turns in its run" if turning else f"{where} moves in its run"


def _is_joint(node_type: str) -> bool:
    spec = schema.node_type(node_type)
    return spec is not None and spec.is_a("X3DRigidJointNode")


def _joined(scene_path: str, node_type: str) -> set[str]:
    """The trace names of the bodies the scene's joints of this type join."""
    scene = load(scene_path)
    names = node_names(scene)
    return {names[id(b)] for j in scene.of_type(node_type) for b in (j.get("body1"), j.get("body2")) if b is not None}


def _moves(run: Recording, bodies: set[str], turning: bool = False) -> bool:
    """Whether one of these bodies (the scene's own) turns, or where not `turning` moves, in the
    run from the first step on: X_ITE moves a body without geometry to the origin at its first
    step, which shows nothing of what a field does."""
    view = TraceView(read_trace(run.out))
    for body in (b for b in run.what["bodies"] if b in bodies and not b.startswith(ADDED)):
        o, p = view.series(body, "orientation")[1][1:], view.series(body, "position")[1][1:]
        if _rotates(o) or not turning and np.any(p != p[:1]):
            return True
    return False


def _bodies_alike(a: Recording, b: Recording) -> bool:
    """Whether two recordings' bodies' rows are the same, row for row (the joints' outputs aside:
    a scene without a joint has none)."""
    def rows(r: Recording) -> list:
        return [x for x in read_trace(r.out) if x.node in b.what["bodies"]]
    return rows(a) == rows(b)


def _values(scene: str, node_type: str, fld: str) -> list:
    """The field's value on every node of the type, as x3d_core reads the scene."""
    return [repr(n.get(fld)) for n in load(scene).of_type(node_type)]


def _rotates(o: np.ndarray) -> bool:
    """Whether axis-angle orientations differ from the first (the same rotation written alike)."""
    return bool(np.any(o != o[:1]))


def _blow_up_probes(c: _Case) -> list[Recording]:
    """The case's scene without each of its joint types, to be recorded."""
    first, out = c.runs[0], []
    for t in sorted({n.type_name for n in load(c.case.path).nodes() if _is_joint(n.type_name)}):
        variant = os.path.join(c.folder, f"{c.case.name}.without-{t}.x3d")
        if without_nodes(c.case.path, t, variant):
            r = Recording(variant, variant[:-4] + ".csv", first.frame_rate, first.duration, outputs(load(variant)))
            c.probes.append((t, r, first))
            out.append(r)
    c.verdict.blew_up_probed = [name for name, _, _ in c.probes]
    return out


def run_cases(cases: Sequence[Case], folder: str, backends: Sequence[str], info: Mapping[str, results.BackendInfo],
              thresholds: Mapping[str, float], timeout: float, recorder: Recorder | None,
              progress: Callable[[str], None] = lambda _: None) -> tuple[list[CaseVerdict], list[ClockReading]]:
    """Every case through X_ITE in one browser, judged, and its clock at each frame rate;
    traces and probe scenes in `folder`."""
    prepared = [_prepare(case, folder) for case in cases]
    runs = [r for c in prepared for r in c.runs]
    longest: dict[ClockKey, float] = {}
    for c in prepared:
        for r in c.runs:
            key = clock_key(c.case.path, r.frame_rate)
            longest[key] = max(longest.get(key, 0.0), r.duration)
    clock_runs = _clock_runs(longest, folder)
    started = time.perf_counter()
    record([*clock_runs.values(), *runs], timeout * max(1, len(runs) + len(clock_runs)))
    progress(f"recorded {len(runs)} runs in X_ITE in {time.perf_counter() - started:.1f} s")
    clocks = {key: read_clock(key, r) for key, r in clock_runs.items()}
    for c in prepared:
        if c.verdict is None:
            _judge(c, backends, info, thresholds, timeout, recorder, clocks)
        c.verdict.frame_rates = [r.frame_rate for r in c.runs]
    started = time.perf_counter()
    _probe(prepared, timeout)
    progress(f"probed the failed cases' fields in {time.perf_counter() - started:.1f} s")
    for c in prepared:  # the verdict once the probes have said what they can
        progress(f"{c.case.name}: {c.verdict.verdict}")
    return [c.verdict for c in prepared], [clocks[key] for key in sorted(clocks)]
