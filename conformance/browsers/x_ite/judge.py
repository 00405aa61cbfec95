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
  with it. Both are first made so X_ITE can show the field (variants.ready: a body's
  collidable for its mass distribution, a fixed body under a static floor for contacts),
  and the verdict names what was changed. A field whose removal leaves X_ITE's trace
  identical, byte for byte, has no effect in X_ITE: it IGNORES it. (Runs are
  bit-identical, so any effect at all shows.) A failed case with no ignored field is WRONG.
- A case whose state stops being finite blew up: WRONG, its fields not probed (a trace cut
  short says nothing of what a field would have changed later); it is recorded again
  without each joint type it has, and the types without which it runs are named as the
  cause.
- A case X_ITE cannot run (its page throws, the browser crashes or times out, the scene
  has an output the page cannot name) is an ERROR, with the reason.

For every case where X_ITE's trace and a backend's part, a rerun recording shows X_ITE
beside every backend with the divergence series (reports/rerun_recording.py).
"""

from __future__ import annotations

import filecmp
import os
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, field

from x3d_core import schema
from x3d_core.load import load
from x3d_core.trace import TraceView

from conformance import results
from conformance.cases.case import Case
from conformance.analyses.trace_check import check_trace
from conformance.analyses.validation import check_case, compare_with_backends
from conformance.results import TraceComparison, Validation
from conformance.browsers.x_ite.harness import NotRecordable, Recording, outputs, reachable_rate, record, step
from conformance.browsers.x_ite.variants import needs, ready, without, without_nodes

RIGHT, CONVENTIONS, IGNORES, WRONG, ERROR = "right", "conventions", "ignores", "wrong", "error"
NAME = "x_ite"  # X_ITE's name beside the backends' in comparisons and recordings


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
           thresholds: Mapping[str, float], timeout: float, recordings: str | None) -> None:
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
    result = check_case(case, views, dt, [r.frame_rate for r in c.runs])
    comparisons = [compare_with_backends(case.path, r.out, rows, dt, backends, info, thresholds, timeout, NAME)
                   for r, rows in zip(c.runs, rows_of)]
    v = Validation(case.path, [r.out for r in c.runs], dict(thresholds), result, comparisons)
    verdict = {results.PASS: RIGHT, results.CONVENTIONS: CONVENTIONS}.get(result.verdict, WRONG)
    detail = result.accuracy_text() if verdict == RIGHT else result.meaning()  # a right case's grade
    c.verdict = CaseVerdict(case.name, verdict, detail, dt, agreeing=v.agreeing(), wall_s=wall, messages=messages, validation=v.to_json())
    parted = [b for b in comparisons[0].pairs if comparisons[0].verdict(b) != "agrees"]
    if recordings is not None and parted:
        c.verdict.recording = _record_divergence(case, views[0], comparisons[0], recordings)


def _record_divergence(case: Case, theirs: TraceView, comparison: TraceComparison, folder: str) -> str:
    from reports.rerun_recording import write_recording  # rerun is imported when a recording is written
    os.makedirs(folder, exist_ok=True)
    out = os.path.join(folder, f"{case.name}.rrd")
    runs = [(NAME, theirs), *comparison.views.items()]
    write_recording(out, load(case.path), runs, list(comparison.pairs.values()))
    return out


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
            if without(c.case.path, t, f, variant):
                if changes:
                    ready(variant, variant, need)
                r = Recording(variant, variant[:-4] + ".csv", first.frame_rate, first.duration, base.what)
                c.probes.append((f"{t}.{f}", r, base))
                c.verdict.variants[f"{t}.{f}"] = changes
                probes.append(r)
        c.verdict.probed = [name for name, _, _ in c.probes]
    record(probes, timeout_per_run * max(1, len(probes)))
    for c in cases:
        if c.verdict is not None and c.verdict.blew_up_probed:
            c.verdict.blow_up_causes = [name for name, r, _ in c.probes if r.ok and not r.blew_up]
            continue
        ignored = [name for name, r, base in c.probes
                   if r.ok and base.ok and filecmp.cmp(r.out, base.out, shallow=False)]
        if ignored:
            c.verdict.verdict, c.verdict.ignored = IGNORES, ignored


def _blow_up_probes(c: _Case) -> list[Recording]:
    """The case's scene without each of its joint types, to be recorded."""
    first, out = c.runs[0], []
    for t in sorted({n.type_name for n in load(c.case.path).nodes() if schema.node_type(n.type_name) is not None
                     and schema.node_type(n.type_name).is_a("X3DRigidJointNode")}):
        variant = os.path.join(c.folder, f"{c.case.name}.without-{t}.x3d")
        if without_nodes(c.case.path, t, variant):
            r = Recording(variant, variant[:-4] + ".csv", first.frame_rate, first.duration, outputs(load(variant)))
            c.probes.append((t, r, first))
            out.append(r)
    c.verdict.blew_up_probed = [name for name, _, _ in c.probes]
    return out


def run_cases(cases: Sequence[Case], folder: str, backends: Sequence[str], info: Mapping[str, results.BackendInfo],
              thresholds: Mapping[str, float], timeout: float, recordings: str | None,
              progress: Callable[[str], None] = lambda _: None) -> list[CaseVerdict]:
    """Every case through X_ITE in one browser, judged; traces and probe scenes in `folder`."""
    prepared = [_prepare(case, folder) for case in cases]
    runs = [r for c in prepared for r in c.runs]
    started = time.perf_counter()
    record(runs, timeout * max(1, len(runs)))
    progress(f"recorded {len(runs)} runs in X_ITE in {time.perf_counter() - started:.1f} s")
    for c in prepared:
        if c.verdict is None:
            _judge(c, backends, info, thresholds, timeout, recordings)
        c.verdict.frame_rates = [r.frame_rate for r in c.runs]
        progress(f"{c.case.name}: {c.verdict.verdict}")
    started = time.perf_counter()
    _probe(prepared, timeout)
    progress(f"probed the failed cases' fields in {time.perf_counter() - started:.1f} s")
    return [c.verdict for c in prepared]
