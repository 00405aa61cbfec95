"""The conformance suite: every case on every installed backend, and the verdict machinery.

The (case, backend) tests run through conformance.runner, each pair in its own child
process; the pairs this session selected are run together in parallel, once, by the
`matrix` fixture. Each result must be exactly its pin in conformance/expectations
(verdict, failing measures, refusal reason): regenerate the pins with `x3drbp
expectations` when a change is meant.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
import re
import shutil
import sys

import numpy as np
import pytest

from conformance import cases as C
from conformance.cases import CaseError
from conformance.cases import (bounce_apex as BA, box_stack as BS, erp_cfm_spring as SPRING, hinge_bounce as BOUNCE,
                               incline as INC, newtons_cradle as NC, resting_penetration as RP, sensor_geometry as SG)
from conformance.cases.closed_forms import GHOST_START, KEPT_START, G, ballistic, ellipk
from conformance.cases.case import Case, Mutation
from conformance.cases.pendulum_period import pendulum_period
from conformance import results
from conformance import expectations
from conformance.results import Expected, Settings
from conformance.runner import children, probe, verdicts
from x3drbp import main as cli_main
from x3d_core.encodings.load import load
from x3d_core.semantics.analysis import features
from x3d_core.traces.trace import Row, TraceView

from fake_child import fake_python

INFO = probe.backend_table()
INSTALLED = [n for n, i in INFO.items() if i.usable]
REFERENCE = "mujoco" if "mujoco" in INSTALLED else (INSTALLED[0] if INSTALLED else None)

# every verdict is pinned (conformance/expectations/BACKEND.toml): the test fails on any
# difference, a fail that starts passing or a case a backend starts refusing alike
PINS = {b: expectations.load(b) for b in INSTALLED}


def _pairs():
    out = [pytest.param(c, b, id=f"{c.name}-{b}") for c in C.CASES for b in INSTALLED]
    return out or [pytest.param(None, None, id="no-backend",
                                marks=pytest.mark.skip(reason="no backend is installed: "
                                                       + "; ".join(f"{n}: {i.unavailable}" for n, i in INFO.items())))]


@pytest.fixture(scope="module")
def matrix(request):
    """Every (case, backend) pair this session selected, run in parallel once."""
    wanted = []
    for item in request.session.items:
        if getattr(item, "originalname", None) == "test_case_on_backend" and hasattr(item, "callspec"):
            p = item.callspec.params
            if p["case"] is not None:
                wanted.append((p["case"], p["backend"]))
    results = verdicts.run_many([lambda c=c, b=b: verdicts.run_pair(c, b) for c, b in wanted])
    return {(c.name, b): r for (c, b), r in zip(wanted, results)}


@pytest.mark.parametrize("case,backend", _pairs())
def test_case_on_backend(case, backend, matrix):
    r = matrix.get((case.name, backend)) or verdicts.run_pair(case, backend)
    pin = PINS[backend].get(case.name, Expected(results.PASS))
    assert expectations.mismatch(r, pin) is None, expectations.mismatch(r, pin)
    if r.verdict == results.UNSUPPORTED:
        assert r.reason.strip(), "an unsupported verdict must carry the backend's reason"
    if r.verdict == results.PASS:
        assert r.measures and all(m.ok for m in r.measures if not m.graded)
    unstated = [m.quantity for m in r.measures if m.basis is None]
    assert not unstated, f"{case.name}: measures without a basis (spec or convention): {unstated}"


# -- the cases themselves ---------------------------------------------------------------

@pytest.mark.parametrize("case", C.CASES, ids=lambda c: c.name)
def test_scene_is_clean_and_exercises_its_fields(case):
    scene = load(case.path)
    assert not scene.errors, [str(d) for d in scene.diagnostics]
    # no warning but those the case provokes on purpose (Case.warned), each once
    assert sorted(d.subject for d in scene.warnings) == sorted(case.warned), [str(d) for d in scene.diagnostics]
    used = set(features(scene))
    assert case.exercises and set(case.exercises) <= used, set(case.exercises) - used
    with open(case.path, encoding="utf-8") as f:
        assert "<!-- Conformance:" in f.read(), "each scene states what it checks in a leading comment"


def test_elliptic_integral_by_agm():
    assert ellipk(0.0) == pytest.approx(math.pi / 2, rel=1e-15)
    assert ellipk(math.sin(math.radians(15))) == pytest.approx(1.5981420021120, rel=1e-12)  # tables
    assert ellipk(math.sin(math.radians(45))) == pytest.approx(1.8540746773013719, rel=1e-12)
    # small amplitude: the period tends to 2 pi sqrt(I_p / (m g L))
    assert pendulum_period(1e-6) == pytest.approx(2 * math.pi * math.sqrt(1.001 / 9.81), rel=1e-12)


# -- the verdict machinery ----------------------------------------------------------------

def _rows(node: str, fields: dict[str, list[str]], times: list[float]) -> list[Row]:
    return [Row(t, node, f, vals[k]) for k, t in enumerate(times) for f, vals in fields.items()]


def test_free_fall_expectation_fails_when_gravity_is_ignored():
    case = C.BY_NAME["free_fall"]
    times = [k / 60 for k in range(61)]
    rows = _rows("Ball", {"position": ["0 10 0"] * 61, "linearVelocity": ["0 0 0"] * 61}, times)
    r = verdicts.evaluate(case, "fake", [TraceView(rows)], case.runs)
    assert r.verdict == results.FAIL
    pos = r.measure("Ball.position")
    assert pos.error == pytest.approx(0.5 * 9.81, rel=1e-12) and pos.error > pos.tolerance
    assert "Ball.position" in r.reason and "tolerance" in r.reason


def test_free_fall_expectation_passes_the_exact_discrete_solution():
    """Semi-implicit Euler's own free fall, y_n = y0 - g dt^2 n(n+1)/2, is within tolerance,
    and the default gravity (9.8 instead of 9.81) is not."""
    case = C.BY_NAME["free_fall"]
    dt = case.runs[0].dt
    times = [k / 60 for k in range(61)]

    def trace(g):
        n = [round(t / dt) for t in times]
        return TraceView(_rows("Ball", {"position": [f"0 {10 - g * dt * dt * k * (k + 1) / 2!r} 0" for k in n],
                                          "linearVelocity": [f"0 {-g * k * dt!r} 0" for k in n]}, times))
    assert verdicts.evaluate(case, "fake", [trace(9.81)], case.runs).verdict == results.PASS
    wrong = verdicts.evaluate(case, "fake", [trace(9.8)], case.runs)
    assert wrong.verdict == results.FAIL and not wrong.measure("Ball.linearVelocity").ok


def test_joint_expectations_fail_on_a_broken_joint():
    times = [0.0, 0.5, 1.0]
    zero = {"angularVelocity": ["0 0 0"] * 3}
    chain = C.BY_NAME["ball_chain"]

    def apart(gap: float) -> results.Result:
        """The chain at rest with Joint3's anchors `gap` m apart after its first frame."""
        rows = []
        for k in range(1, 6):
            off = f"0.2 0 {gap!r}" if k == 3 else "0.2 0 0"
            rows += _rows(f"Joint{k}", {"body1AnchorPoint": ["0.2 0 0"] * 3, "body2AnchorPoint": ["0.2 0 0", off, off]},
                          times)
            rows += _rows(f"Link{k}", zero, times)
        rows += _rows("Anchor", zero, times)
        return verdicts.evaluate(chain, "fake", [TraceView(rows)], chain.runs)
    soft = apart(0.001)  # 1 mm: a soft joint's gap, graded beyond the rigid bound, no violation
    assert soft.verdict == results.PASS and soft.accuracy() > 1 and "Joint3" in soft.accuracy_text()
    # 6 cm: more than half an anchor's lever arm; told by the outputs alone (the links' poses say nothing here), which
    # the clause gives in each body's frame as well as comparable (spec-loose-ends 22): x3drbp's reading, a convention
    broken = apart(0.06)
    assert broken.verdict == results.CONVENTIONS and "Joint3" in broken.reason
    uj = C.BY_NAME["universal_joint"]
    anchor = ["0.6 -0.8 0"] * 3  # the arms report no pose: each carries the anchor where the scene puts it

    def crossed(middle: str) -> results.Result:
        rows = _rows("Cross", {"body1Axis": ["0.8 0.6 0"] * 3, "body2Axis": ["-0.6 0.8 0", middle, "-0.6 0.8 0"],
                               "body1AnchorPoint": anchor, "body2AnchorPoint": anchor},
                     times) + _rows("Upper", zero, times) + _rows("Lower", zero, times)
        return verdicts.evaluate(uj, "fake", [TraceView(rows)], uj.runs)
    drifted = crossed("-0.6 0.81 0")  # 0.34 degrees off perpendicular: an integrator's drift, graded
    assert drifted.verdict == results.PASS and drifted.accuracy() > 1 and "Cross" in drifted.accuracy_text()
    folded = crossed("0 1 0")  # 53 degrees apart (|cos| 0.6): the joint no longer keeps them perpendicular
    assert folded.verdict == results.FAIL and "Cross |body1Axis . body2Axis|" in folded.reason


def test_frame_rate_expectation_sees_the_last_digit():
    case = C.BY_NAME["frame_rate"]
    a = TraceView([Row(1.0, "Link1", "position", "0.1 0.2 0.30000000000000004")])
    b = TraceView([Row(1.0, "Link1", "position", "0.1 0.2 0.3")])
    assert verdicts.evaluate(case, "fake", [a, a], case.runs).verdict == results.PASS
    # bit-equality across frame rates is x3drbp's fixed step, a convention (Xj3D and X_ITE step by the frame)
    assert verdicts.evaluate(case, "fake", [a, b], case.runs).verdict == results.CONVENTIONS
    c = TraceView([Row(0.5, "Link1", "position", "0 0 0")])
    assert verdicts.evaluate(case, "fake", [a, c], case.runs).verdict == results.CONVENTIONS  # no spec measure


def test_expectation_that_cannot_read_the_trace_is_an_error():
    case = C.BY_NAME["free_fall"]
    r = verdicts.evaluate(case, "fake", [TraceView([Row(0.0, "Other", "position", "0 0 0")])], case.runs)
    assert r.verdict == results.ERROR and "Ball.position" in r.reason


def test_an_expectation_that_raises_is_its_cells_error_and_the_command_writes_every_other(tmp_path, monkeypatch,
                                                                                        capsys):
    """One cell, one fault: newtons_cradle's expectation once divided by zero where an engine got
    fixed bodies wrong, and the traceback ended the whole command."""
    if REFERENCE is None:
        pytest.skip("no backend is installed")
    free_fall = C.BY_NAME["free_fall"]

    def faulty(traces, settings):
        return [results.Measure("x", 1.0 / (len(traces) - 1), 1.0)]  # one trace: ZeroDivisionError
    broken = dataclasses.replace(free_fall, expect=faulty)
    r = verdicts.evaluate(broken, "fake", [TraceView([])], free_fall.runs)
    assert r.verdict == results.ERROR
    assert r.reason.startswith("the expectation failed: ZeroDivisionError: ") and "test_conformance.py:" in r.reason
    monkeypatch.setitem(C.BY_NAME, "free_fall", broken)
    monkeypatch.setattr(C, "CASES", tuple(broken if c.name == "free_fall" else c for c in C.CASES))
    out = tmp_path / "conf"
    assert cli_main(["conformance", "--cases", "free_fall,damping", "--backends", REFERENCE, "--out", str(out)]) == 0
    data = json.loads((out / "matrix.json").read_text())
    got = {r["case"]: r["verdict"] for r in data["results"]}
    assert got == {"free_fall": results.ERROR, "damping": results.PASS}
    assert "the expectation failed: ZeroDivisionError" in (out / "matrix.md").read_text()


def test_classify():
    assert children.classify(0, "").verdict is None
    out = children.classify(3, "s.x3d: unsupported by bullet: SliderJoint.limits: no stops\n"
                             "s.x3d: unsupported by bullet: RigidBody.torques: not yet\n", backend="bullet")
    assert out.verdict == results.UNSUPPORTED
    assert out.reason == "SliderJoint.limits: no stops; RigidBody.torques: not yet"
    assert children.classify(-11, "").verdict == results.CRASHED and "SIGSEGV" in children.classify(-11, "").reason
    assert children.classify(1, "s.x3d: dart: blew up at t=0.5: Bob has a non-finite state").verdict == results.BLEW_UP
    assert children.classify(1, "Traceback (most recent call last):\n  ...\nZeroDivisionError: x").verdict == \
        results.CRASHED
    assert children.classify(1, "x3drbp run: backend nope: no backend").verdict == results.ERROR
    assert children.classify(None, "", timed_out=True, timeout=5).verdict == results.TIMED_OUT


def test_nonexistent_backend_is_an_error():
    r = verdicts.run_pair(C.BY_NAME["free_fall"], "no_such_engine")
    assert r.verdict == results.ERROR and "no_such_engine" in r.reason


def test_nonexistent_and_broken_scenes_are_errors(tmp_path):
    base = C.BY_NAME["free_fall"]
    missing = Case("missing", str(tmp_path / "nope.x3d"), "", base.runs, base.expect)
    r = verdicts.run_pair(missing, REFERENCE or "mujoco")
    assert r.verdict == results.ERROR and "nope.x3d" in r.reason
    broken = tmp_path / "broken.x3d"
    broken.write_text("<X3D version='4.0'><Scene><RigidBodyCollection><RigidBody mass='0'/>"
                      "</RigidBodyCollection></Scene></X3D>")
    r = verdicts.run_pair(Case("broken", str(broken), "", base.runs, base.expect), REFERENCE or "mujoco")
    assert r.verdict == results.ERROR and "mass" in r.reason


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals and shell scripts")
@pytest.mark.parametrize("script,verdict,reason", [
    ("kill -SEGV $$\n", results.CRASHED, "SIGSEGV"),
    ("echo 's.x3d: fake: blew up at t=0.25: Ball has a non-finite state' >&2; exit 1\n", results.BLEW_UP, "t=0.25"),
    ("echo 's.x3d: unsupported by mujoco: RigidBody.forces: why not' >&2; exit 3\n", results.UNSUPPORTED,
     "RigidBody.forces: why not"),
    ("sleep 30\n", results.TIMED_OUT, "within 0.5 s"),
    ("exit 0\n", results.ERROR, "no trace"),
])
def test_child_process_endings_become_verdicts(tmp_path, monkeypatch, script, verdict, reason):
    monkeypatch.setattr(children.sys, "executable", fake_python(tmp_path, script))
    r = verdicts.run_pair(C.BY_NAME["free_fall"], "mujoco", timeout=0.5)
    assert r.verdict == verdict and reason in r.reason


def test_deliberately_wrong_expectation_fails():
    if REFERENCE is None:
        pytest.skip("no backend is installed")
    base = C.BY_NAME["free_fall"]
    wrong = Case("free_fall_wrong", base.path, "free fall expected at g = 5", base.runs,
                   ballistic("Ball", (0, 10, 0), (0, 0, 0), (0, -5.0, 0)))
    r = verdicts.run_pair(wrong, REFERENCE)
    assert r.verdict == results.FAIL
    v = r.measure("Ball.linearVelocity")
    assert v.error == pytest.approx(4.81, rel=1e-9) and v.error > v.tolerance


def test_fitted_order():
    dts = list(C.CONVERGENCE_DTS)
    assert results.fitted_order(dts, [3.0 * d for d in dts]) == pytest.approx(1.0)
    assert results.fitted_order(dts, [7.0 * d * d for d in dts]) == pytest.approx(2.0)
    assert results.fitted_order(dts, [1e-15, 2e-16, 0.0, 1e-16]) is None  # exact to rounding
    assert results.fitted_order(dts, [None, None, 0.1, None]) is None


def test_command_writes_the_matrix(tmp_path, capsys):
    if REFERENCE is None:
        pytest.skip("no backend is installed")
    out = tmp_path / "conf"
    assert cli_main(["conformance", "--cases", "free_fall,damping", "--backends", REFERENCE, "--out", str(out)]) == 0
    text = (out / "matrix.md").read_text()
    assert text in capsys.readouterr().out
    assert "| free_fall |" in text and f"| case | checks | {REFERENCE} |" in text
    data = json.loads((out / "matrix.json").read_text())
    assert {(r["case"], r["backend"]) for r in data["results"]} == {("free_fall", REFERENCE), ("damping", REFERENCE)}
    assert all(r["verdict"] == "pass" for r in data["results"]) and data["convergence"] is None
    assert cli_main(["conformance", "--cases", "no_such_case", "--out", str(out)]) == 2
    assert cli_main(["conformance", "--backends", "no_such_engine", "--out", str(out)]) == 2


def test_convergence_reports_errors_and_order():
    if REFERENCE is None:
        pytest.skip("no backend is installed")
    case = C.BY_NAME["free_fall"]
    short = Case(case.name, case.path, case.checks, (Settings(0.5, 1 / 240),), case.expect,
                   convergence=case.convergence, expected_order=1.0)
    (cv,) = verdicts.run_convergence([short], [REFERENCE], [1 / 60, 1 / 120, 1 / 240])
    errors = cv.errors()
    assert all(e is not None and e > 0 for e in errors) and errors[0] > errors[1] > errors[2]
    assert cv.order() == pytest.approx(1.0, abs=0.05)  # semi-implicit Euler and its kin
    assert cv.to_json()["order"] == cv.order()


# -- mutations: every case fails when what it checks is ignored -------------------------

@pytest.mark.parametrize("case", C.CASES, ids=lambda c: c.name)
def test_every_case_declares_mutations_that_apply_once(case):
    assert case.mutations, "a case declares at least one mutation (Case.mutations), a scene edit it must catch"
    with open(case.path, encoding="utf-8") as f:
        text = f.read()
    for m in case.mutations:
        assert m.old or m.runs, f"{m}: neither a scene edit nor other runs"
        assert m.on is None or m.on in INFO, f"{m}: judged on {m.on}, which is no backend"
        if m.old:
            assert text.count(m.old) == 1, (case.name, m.old)
            assert m.apply(text) != text


def _mutated(case: Case, k: int, folder) -> Case:
    """The case with its k-th mutation: its scene edited (written into folder), or its runs replaced."""
    m = case.mutations[k]
    with open(case.path, encoding="utf-8") as f:
        text = m.apply(f.read())
    path = folder / f"{case.name}-{k}.x3d"
    path.write_text(text, encoding="utf-8")
    return Case(case.name, str(path), case.checks, m.runs or case.runs, case.expect)


def _judged_on(found: dict[str, results.Result]) -> list[tuple[str, str]]:
    """Where a case's mutations are judged, from its results as it is on each backend, and how:
    "pass": the reference backend, or else the first that passes the case; every mutation must
    make it FAIL there. Where no backend passes it, each of: "measures": the first on which
    some judged measures pass (erp_cfm_spring: the reference misses its spring; hinge_bounce:
    only ODE runs it, differing in a convention); a mutation must make one of them fail there;
    and "refused": where the reference backend refuses the case (it does not support
    stopBounce), the reference, which runs the mutated scene without the field and must FAIL
    there. A mutation is caught where either catches it: a soft engine (ODE's stop at X3D's
    defaults) may not show an edit that a rigid one does. [] where none of these holds."""
    order = [REFERENCE] + [b for b in INSTALLED if b != REFERENCE]
    for b in order:
        if found[b].verdict == results.PASS:
            return [(b, "pass")]
    out = []
    for b in order:
        # (where only conventions fail, a convention that holds: the spec measures may not see the mutation)
        if any(m.ok and not m.graded and (found[b].verdict == results.FAIL or m.convention)
               for m in found[b].measures):
            out.append((b, "measures"))
            break
    if found[REFERENCE].verdict == results.UNSUPPORTED:
        out.append((REFERENCE, "refused"))
    return out


def _caught(m, how: str, as_it_is: results.Result, r: results.Result) -> str | None:
    """None where the mutated run `r` shows the edit as `how` asks (see _judged_on), else why not."""
    if m.grades:  # a looser solve, which the clause allows: an accuracy grade goes past its bound
        ok = r.verdict in results.JUDGED and (r.accuracy() or 0) > 1 >= (as_it_is.accuracy() or 0)
        return None if ok else f"no accuracy grade went past its bound: {r.verdict} {r.meaning()}"
    if how == "measures":
        kept = [x.quantity for x in as_it_is.measures if x.ok and not x.graded]
        lost = [q for q in kept if r.measure(q) is not None and not r.measure(q).ok]
        return None if lost else f"what passes as it is ({'; '.join(kept)}) still passes: {r.verdict} {r.reason}"
    if not m.spec:  # the edit stands for a reading of a silent point: a convention fails
        ok = r.verdict in (results.FAIL, results.CONVENTIONS) and r.failing()
        return None if ok else f"{r.verdict} {r.reason}"
    return None if r.verdict == results.FAIL else f"{r.verdict} {r.reason}"


def _places(m: Mutation, found: dict[str, results.Result]) -> list[tuple[str, str]]:
    """Where mutation m is judged: the backend it names (Mutation.on), if that passes the case as
    it is, else nowhere; without one, where the case's mutations are (_judged_on)."""
    if m.on is None:
        return _judged_on(found)
    return [(m.on, "pass")] if m.on in found and found[m.on].verdict == results.PASS else []


@pytest.fixture(scope="module")
def mutated_runs(request, matrix, tmp_path_factory):
    """For every case this session's mutation tests selected: for each of its mutations, per place
    it is judged (backend, how, the case's result there as it is, the mutated result), all run in
    parallel once."""
    wanted = [item.callspec.params["case"] for item in request.session.items
              if getattr(item, "originalname", None) == "test_case_fails_when_mutated" and hasattr(item, "callspec")]
    pairs = [(c, b) for c in wanted for b in INSTALLED]
    found: dict[str, dict[str, results.Result]] = {}
    for (c, b), r in zip(pairs, verdicts.run_many(
            [lambda c=c, b=b: matrix.get((c.name, b)) or verdicts.run_pair(c, b) for c, b in pairs])):
        found.setdefault(c.name, {})[b] = r
    folder = tmp_path_factory.mktemp("mutated")
    places = {(c.name, k): _places(m, found[c.name]) for c in wanted for k, m in enumerate(c.mutations)}
    jobs = [(c.name, k, b, how, lambda m=_mutated(c, k, folder), b=b: verdicts.run_pair(m, b))
            for c in wanted for k in range(len(c.mutations)) for b, how in places[(c.name, k)]]
    out = {c.name: [[] for _ in c.mutations] for c in wanted}
    for (name, k, b, how, _), r in zip(jobs, verdicts.run_many([j[-1] for j in jobs])):
        out[name][k].append((b, how, found[name][b], r))
    return out


@pytest.mark.parametrize("case", C.CASES, ids=lambda c: c.name)
def test_case_fails_when_mutated(case, mutated_runs):
    if REFERENCE is None:
        pytest.skip("no backend is installed")
    absent = []
    for m, places in zip(case.mutations, mutated_runs[case.name]):
        what = f"{case.name}, {m.old.strip()!r} -> {m.new.strip()!r}" + (f" and runs {m.runs}" if m.runs else "")
        if m.on is not None and m.on not in INSTALLED:
            absent.append(f"{what}: judged on {m.on}, which is not installed")
            continue
        assert m.on is None or places, f"{what}: judged on {m.on}, which does not pass the case as it is"
        if not places:
            pytest.skip(f"no installed backend to judge {case.name}'s mutations on")
        missed = [f"on {b} ({how}): {why}" for b, how, as_it_is, mutated in places
                  if (why := _caught(m, how, as_it_is, mutated)) is not None]
        if len(missed) == len(places) and "ode" not in INSTALLED:  # ODE, the base every mutant wraps, judges it
            absent.append(f"{what}: no installed backend but ODE, which is unavailable here, shows it ({'; '.join(missed)})")
            continue
        assert len(missed) < len(places), f"{what}: " + "; ".join(missed)
    if absent:
        pytest.skip("; ".join(absent))


# -- discovery: a case is a folder --------------------------------------------------------

CASE_MODULE = """
from conformance.cases.case import Case
from conformance.cases.closed_forms import G, ballistic
from conformance.results import Settings

CASE = Case("{name}", "{name}.x3d", "free fall, elsewhere", (Settings(0.5, 1 / 240),),
            ballistic("Ball", (0, 10, 0), (0, 0, 0), (0, -G, 0)), mutations=((" gravity='0 -9.81 0'", ""),))
"""


def _case_folder(root, name: str, module: str | None = CASE_MODULE) -> None:
    folder = root / name
    folder.mkdir()
    shutil.copyfile(C.BY_NAME["free_fall"].path, folder / f"{name}.x3d")
    if module is not None:
        folder.joinpath("__init__.py").write_text(module.format(name=name), encoding="utf-8")


def test_cases_are_the_folders_found_sorted():
    names = [c.name for c in C.CASES]
    root = os.path.dirname(C.__file__)
    folders = [d for d in os.listdir(root) if os.path.isdir(os.path.join(root, d)) and not d.startswith("_")]
    assert names == sorted(folders) and len(names) >= 56 and set(C.BY_NAME) == set(names)
    assert all(c.path == os.path.join(os.path.dirname(C.__file__), c.name, f"{c.name}.x3d") for c in C.CASES)
    assert C.discover() == C.CASES
    assert [c.name for c in C.select(["projectile", "free_fall"])] == ["projectile", "free_fall"]
    with pytest.raises(KeyError, match=r"unknown case\(s\) nope; known: anisotropic_friction, auto_disable, ball_chain, "):
        C.select(["free_fall", "nope"])


def test_a_case_written_elsewhere_is_discovered_and_runs(tmp_path):
    _case_folder(tmp_path, "fall_again")
    (case,) = C.discover(str(tmp_path))
    assert case.name == "fall_again" and case.path == str(tmp_path / "fall_again" / "fall_again.x3d")
    assert case.mutations == (Mutation(" gravity='0 -9.81 0'", ""),)
    if REFERENCE is not None:
        assert verdicts.run_pair(case, REFERENCE).verdict == results.PASS


@pytest.mark.parametrize("module,message", [
    ("raise RuntimeError('half-written')", "the case does not import: RuntimeError: half-written"),
    ("from conformance.cases.closed_forms import no_such_helper", "the case does not import: ImportError"),
    ("CASE = 'free_fall'", "defines no CASE = Case(...)"),
    (CASE_MODULE.replace('"{name}"', '"other_name"'), "the case is named 'other_name', not after its folder"),
    (None, "a case folder needs an __init__.py defining CASE"),
])
def test_a_broken_case_folder_is_named(tmp_path, module, message):
    _case_folder(tmp_path, "good")
    _case_folder(tmp_path, "broken", module)
    with pytest.raises(CaseError, match=re.escape(str(tmp_path / "broken"))) as e:
        C.discover(str(tmp_path))
    assert message in str(e.value)


# -- reference traces for what no backend runs: ODE's stop bounce and its soft joints

def _ode_hinge_bounce(bounce=0.5, erp=0.2, cfm=1e-6, dt=1 / 240, duration=1.0) -> TraceView:
    """BOUNCE.x3d stepped as ODE does, in the joint angle: semi-implicit Euler, and a stop
    row active on a step that starts past the stop: one-sided, targeting the larger of
    ERP x penetration / h and -bounce x the incoming rate, softened by CFM."""
    i_p = BOUNCE.BOUNCE_I + BOUNCE.BOUNCE_M * BOUNCE.BOUNCE_L ** 2
    angle = rate = 0.0
    rows = [Row(0.0, "Hinge", "angle", "0"), Row(0.0, "Hinge", "angleRate", "0")]
    for n in range(1, round(duration / dt) + 1):
        free = rate - dt * BOUNCE.BOUNCE_M * G * BOUNCE.BOUNCE_L * math.cos(angle) / i_p
        if angle <= BOUNCE.BOUNCE_MIN:
            target = -(erp / dt) * (angle - BOUNCE.BOUNCE_MIN)
            if rate < 0:
                target = max(target, -bounce * rate)
            if free < target:  # the row pushes: rate = target - CFM x force, force = I_p (rate - free) / h
                gamma = cfm * i_p / dt
                free = (target + gamma * free) / (1 + gamma)
        rate = free
        angle += dt * rate
        rows += [Row(n * dt, "Hinge", "angle", repr(angle)), Row(n * dt, "Hinge", "angleRate", repr(rate))]
    return TraceView(rows)


def test_hinge_bounce_expectation_passes_odes_stop_bounce():
    """No backend supports stopBounce: the expectation is checked against ODE's rule itself."""
    case = C.BY_NAME["hinge_bounce"]

    def verdict(**kw):
        return verdicts.evaluate(case, "ode", [_ode_hinge_bounce(**kw)], case.runs)
    ok = verdict()
    assert ok.verdict == results.PASS and ok.accuracy() <= 1, ok.meaning()
    rates = ok.measure("|Hinge.angleRate| after the impact - 0.5 x speed before")
    assert rates.error < 0.05 * rates.tolerance  # only the stop's CFM yield is left
    assert verdict(bounce=0.0).verdict == results.FAIL  # an inelastic stop: no bounce at all
    # 0.4 or 0.6 for 0.5: nearer ODE's law than no bounce is, so within its reading; graded beyond the bound
    for other in (verdict(bounce=0.4), verdict(bounce=0.6)):
        assert other.verdict == results.PASS and other.accuracy() > 1, other.meaning()
    assert verdict(cfm=1e-4).accuracy() > 1  # why the scene sets constantForceMix 1e-6


def _ode_spring(soft=lambda m, dt, cfm: cfm / dt, erp=SPRING.SPRING_ERP, cfm=SPRING.SPRING_CFM,
                settings: Settings | None = None) -> TraceView:
    """SPRING.x3d stepped as ODE does, along the vertical: the free velocity v_free = v - g h,
    then the ball's vertical row (bilateral) with impulse P: v' = v_free + P/m = -(ERP/h) gap - s P,
    s the softness the row's diagonal gets per unit impulse (ODE: CFM/h), so
    v' (1 + s m) = -(ERP/h) gap + s m v_free; then gap += h v'."""
    s = settings or C.BY_NAME["erp_cfm_spring"].runs[0]
    rows = []
    per_frame = round(1 / (s.rate * s.dt))
    for name, (m, anchor) in SPRING.SPRING_WEIGHTS.items():
        gap = v = 0.0
        a = " ".join(repr(float(x)) for x in anchor)
        for n in range(round(s.duration / s.dt) + 1):
            if n % per_frame == 0:
                t = n // per_frame / s.rate
                lower = anchor + np.array([0.0, gap, 0.0])
                rows += [Row(t, f"{name}Hold", "body1AnchorPoint", " ".join(repr(float(x)) for x in lower)),
                         Row(t, f"{name}Hold", "body2AnchorPoint", a)]
            gamma = soft(m, s.dt, cfm) * m
            v = (-(erp / s.dt) * gap + gamma * (v - G * s.dt)) / (1 + gamma)
            gap += s.dt * v
    return TraceView(rows)


def test_erp_cfm_spring_expectation_passes_odes_spring():
    case = C.BY_NAME["erp_cfm_spring"]

    def result(**kw):
        return verdicts.evaluate(case, "ode", [_ode_spring(**kw)], case.runs)
    ok = result()
    assert ok.verdict == results.PASS, ok.reason
    # a spring of another stiffness still sags: only ODE's k = ERP / (h CFM) (a convention) tells them apart
    assert result(cfm=1e-4).verdict == results.CONVENTIONS and result(erp=0.8).verdict == results.CONVENTIONS
    rigid = result(soft=lambda m, dt, cfm: 0.0)  # a hard constraint: no sag at all
    assert rigid.verdict == results.FAIL and not any(m.ok for m in rigid.measures)
    # softness relative to the row's effective mass 1/m, right at 1 kg only (backends/dart.py's conversion)
    scaled = result(soft=lambda m, dt, cfm: (1 / m + 1) * cfm / (2 * dt))
    assert [m.ok for m in scaled.measures] == [True, True, True, False] and scaled.verdict == results.CONVENTIONS


# -- the collision cases: ODE's contact rule itself (as the point-mass stepper below), which
# no backend follows in every detail

def _plane_space(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    from x3d_core.semantics.collision import friction_directions
    t1, t2 = friction_directions(n)
    return t1[0], t2[0]


def _ode_points(bodies: dict, contacts, settings: Settings, gravity=(0.0, -G, 0.0), erp=0.8, cfm=1e-4,
                layer=0.0, bounce=0.0, min_bounce=0.1, mu=(0.0, 0.0), speed=(0.0, 0.0), accel=None,
                sensor=None, iterations=10, layer_target=False) -> TraceView:
    """Point masses stepped with ODE's contact rule: contacts found from the overlap at a step's
    start, solved in that step with gravity (projected Gauss-Seidel, warm-started from the last
    step's impulses): the normal row targets max(ERP max(depth - layer, 0)/h, bounce x the
    incoming speed where it beats min_bounce) (layer_target: ERP (depth - layer)/h, a layer the
    body is pulled into), friction rows are bounded by mu_k x the normal impulse along ODE's
    friction directions and target the surface speeds, every row softened by CFM (an impulse P
    moves it by CFM P / h). bodies: name -> (mass, p0, v0); contacts(p) -> [(a, b, normal from a
    to b, depth, (geometry1, geometry2, body1, body2), point)], body indices (-1: static); the
    names and point make the sensor's rows."""
    names = list(bodies)
    m = np.array([bodies[n][0] for n in names], dtype=float)
    p = np.array([bodies[n][1] for n in names], dtype=float)
    v = np.array([bodies[n][2] for n in names], dtype=float)
    h = settings.dt
    inv = lambda i: 0.0 if i < 0 else 1.0 / m[i]  # noqa: E731
    rows: list[Row] = []
    n_steps = round(settings.duration / h)
    per_frame = max(1, round(1 / (settings.rate * h)))

    def record(step: int, found) -> None:
        t = step // per_frame / settings.rate
        for k, n in enumerate(names):
            rows.extend([Row(t, n, "position", " ".join(repr(float(x)) for x in p[k])),
                         Row(t, n, "linearVelocity", " ".join(repr(float(x)) for x in v[k])),
                         Row(t, n, "orientation", "0 0 1 0"), Row(t, n, "angularVelocity", "0 0 0")])
        if sensor is not None:
            rows.append(Row(t, sensor, "isActive", "true" if found else "false"))
            seen = {}
            for i, (a, b, normal, depth, label, point) in enumerate(found):
                f = f"contacts[{i}]."
                rows.extend([Row(t, sensor, f + "position", " ".join(repr(float(x)) for x in point)),
                             Row(t, sensor, f + "contactNormal", " ".join(repr(float(x)) for x in normal)),
                             Row(t, sensor, f + "depth", repr(float(depth)))])
                rows.extend(Row(t, sensor, f + k, value) for k, value in
                            zip(("geometry1", "geometry2", "body1", "body2"), label))
                seen.setdefault(label[0])
                seen.setdefault(label[1])
            rows.extend(Row(t, sensor, f"intersections[{i}]", g) for i, g in enumerate(seen))

    record(0, [])
    warm: dict[int, np.ndarray] = {}  # impulses of the last step, by contact: PGS starts from them
    for step in range(1, n_steps + 1):
        found = [c for c in contacts(p) if c[3] >= 0]
        new = v + h * np.asarray(gravity) + (h * accel(p) if accel is not None else 0.0)
        rows_of = []
        for c, (a, b, n, depth, _, _) in enumerate(found):
            n = np.asarray(n, dtype=float)
            incoming = float(((v[b] if b >= 0 else 0.0) - (v[a] if a >= 0 else 0.0)) @ n)
            target = erp * (depth - layer if layer_target else max(depth - layer, 0.0)) / h
            if bounce > 0 and -incoming > min_bounce:
                target = max(target, -bounce * incoming)
            t1, t2 = _plane_space(n)
            rows_of.append((a, b, inv(a), inv(b), ((n, target), (t1, speed[0]), (t2, speed[1]))))
        impulses = np.array([warm.get(c, np.zeros(3)) for c in range(len(found))]).reshape(-1, 3)
        for c, (a, b, ia, ib, _) in enumerate(rows_of):  # the warm start's velocities
            for r, (d, _) in enumerate(rows_of[c][4]):
                if b >= 0:
                    new[b] += impulses[c, r] * ib * d
                if a >= 0:
                    new[a] -= impulses[c, r] * ia * d
        soft = cfm / h
        for _ in range(iterations):
            for c, (a, b, ia, ib, row) in enumerate(rows_of):
                for r, (d, goal) in enumerate(row):
                    old = impulses[c, r]
                    rel = (new[b] if b >= 0 else 0.0) - (new[a] if a >= 0 else 0.0)
                    value = old + (goal - float(rel @ d) - soft * old) / (ia + ib + soft)
                    if r == 0:
                        value = max(0.0, value)
                    else:
                        bound = mu[r - 1] * impulses[c, 0]
                        value = min(bound, max(-bound, value))
                    impulses[c, r] = value
                    if b >= 0:
                        new[b] += (value - old) * ib * d
                    if a >= 0:
                        new[a] -= (value - old) * ia * d
        warm = {c: impulses[c] for c in range(len(found))}
        v = new
        p = p + h * v
        if step % per_frame == 0:
            record(step, found)
    return TraceView(rows)


def _evaluate(name: str, trace: TraceView) -> results.Result:
    case = C.BY_NAME[name]
    return verdicts.evaluate(case, "ode-points", [trace], case.runs)


def _bounce_trace(bounce: dict[str, float], min_bounce: float = BA.BA_MIN, erp: float = BA.BA_ERP,
                  cfm: float = 1e-4) -> TraceView:
    """BA.x3d's balls stepped as ODE does, along the vertical (one contact, no friction):
    a contact on a step that starts overlapping, targeting max(ERP depth / h, e v_in) (the bounce
    where v_in > minBounceSpeed), softened by CFM: v' (1 + gamma) = target + gamma v_free."""
    s = C.BY_NAME["bounce_apex"].runs[0]
    h, per_frame = s.dt, round(1 / (s.rate * s.dt))
    gamma = cfm * BA.BA_M / h
    rows = []
    for name, (e, h0) in BA.BA_BALLS.items():
        e = bounce.get(name, e)
        y, v = BA.BA_R + h0, 0.0
        for n in range(round(s.duration / h) + 1):
            if n % per_frame == 0:
                t = n // per_frame / s.rate
                rows += [Row(t, name, "position", f"0 {y!r} 0"), Row(t, name, "linearVelocity", f"0 {v!r} 0")]
            depth, free = BA.BA_R - y, v - BA.BA_G * h
            if depth >= 0:
                target = erp * depth / h
                if e > 0 and -v > min_bounce:
                    target = max(target, -e * v)
                if free < target:
                    free = (target + gamma * free) / (1 + gamma)
            v = free
            y += h * v
    return TraceView(rows)


def test_bounce_apex_expectation_passes_odes_bounce():
    ok = _evaluate("bounce_apex", _bounce_trace({}))
    assert ok.verdict == results.PASS, ok.reason
    assert len(ok.measures) == 26 and max(m.accuracy or 0 for m in ok.measures) > 0.1  # not vacuous
    # another bounce law between the clause's ends: within the readings, graded beyond the bound
    other = _evaluate("bounce_apex", _bounce_trace({"High05": 0.45, "Low05": 0.45}))
    assert other.verdict == results.PASS and other.accuracy() > 1
    # less bounce than a ball with a smaller bounce value: out of the clause's order
    swapped = _evaluate("bounce_apex", _bounce_trace({"High05": 0.15}))
    assert swapped.verdict == results.FAIL and "rise with bounce" in swapped.reason
    slow = _evaluate("bounce_apex", _bounce_trace({}, min_bounce=0.1))  # minBounceSpeed at its default
    assert slow.verdict == results.FAIL and "Low08 highest flight" in slow.reason
    pushed = _evaluate("bounce_apex", _bounce_trace({}, erp=0.8))  # why the scene sets errorCorrection 0.1
    assert pushed.verdict == results.FAIL


def _incline_trace(mu: float = INC.INC_MU) -> TraceView:
    bodies, walls = {}, []
    for k, (name, (theta, z)) in enumerate(INC.INC_BOXES.items()):
        start, _, normal = INC.incline_frame(theta, z)
        bodies[name] = (INC.INC_M, start, (0.0, 0.0, 0.0))
        base = start - 0.05 * normal  # on the incline's top face, under the box's centre
        walls.append((k, normal, base))
    contacts = lambda p: [(-1, k, n, -float((p[k] - base) @ n) + 0.05, ("Incline", "Box", "NULL", "B"), p[k])  # noqa
                          for k, n, base in walls]
    return _ode_points(bodies, contacts, C.BY_NAME["incline"].runs[0], mu=(mu, mu))


def test_incline_expectation_passes_odes_friction():
    ok = _evaluate("incline", _incline_trace())
    assert ok.verdict == results.PASS, ok.reason
    more = _evaluate("incline", _incline_trace(0.45))  # 20 % more slide: graded, the friction still acts
    assert more.verdict == results.PASS and more.accuracy() > 1
    assert _evaluate("incline", _incline_trace(0.0)).verdict == results.FAIL


def _sliding_trace(case: str, boxes: dict, mu=(0.0, 0.0), speed=(0.0, 0.0)) -> TraceView:
    bodies = {n: (1.0, p0, v0) for n, (p0, v0) in boxes.items()}
    contacts = lambda p: [(-1, k, (0.0, 1.0, 0.0), 0.1 - p[k][1], ("Floor", "Box", "NULL", "B"), p[k])  # noqa: E731
                          for k in range(len(boxes))]
    return _ode_points(bodies, contacts, C.BY_NAME[case].runs[0], mu=mu, speed=speed)


def test_friction_expectations_pass_odes_friction_directions():
    boxes = {"Along1": ((2.0, 0.1, -1.0), (-3.0, 0.0, 0.0)), "Along2": ((-2.0, 0.1, -1.0), (0.0, 0.0, 3.0))}
    ok = _evaluate("anisotropic_friction", _sliding_trace("anisotropic_friction", boxes, mu=(0.2, 0.6)))
    assert ok.verdict == results.PASS, ok.reason
    swapped = _evaluate("anisotropic_friction", _sliding_trace("anisotropic_friction", boxes, mu=(0.6, 0.2)))
    # mu1 along ODE's second direction: the spec names no direction, so this is a convention
    assert swapped.verdict == results.CONVENTIONS and not any(m.ok for m in swapped.failing() if not m.convention)
    belt = {"Parcel": ((3.0, 0.1, 0.0), (0.0, 0.0, 0.0))}
    ok = _evaluate("conveyor", _sliding_trace("conveyor", belt, mu=(0.5, 0.5), speed=(1.5, 0.0)))
    assert ok.verdict == results.PASS, ok.reason
    backwards = _evaluate("conveyor", _sliding_trace("conveyor", belt, mu=(0.5, 0.5), speed=(-1.5, 0.0)))
    assert backwards.verdict == results.CONVENTIONS  # the belt's motion along +x instead of ODE's first direction


def _resting_trace(layer: float = RP.RP_LAYER, target: bool = False) -> TraceView:
    bodies = {"Sunk": (RP.RP_M, (1.0, 0.09, 0.0), (0.0,) * 3), "Touching": (RP.RP_M, (-1.0, 0.1, 0.0), (0.0,) * 3)}

    def contacts(p):
        out = []
        for k, n in enumerate(bodies):
            for dx in (-0.2, 0.2):  # two corners each, half the weight on each
                for dz in (-0.2, 0.2):
                    corner = p[k] + np.array([dx, -0.1, dz])
                    out.append((-1, k, (0.0, 1.0, 0.0), -corner[1], ("Floor", n + "Shape", "NULL", n), corner))
        return out
    # four contacts on one point mass: each takes a share (CFM acts per row, as in ODE)
    return _ode_points(bodies, contacts, C.BY_NAME["resting_penetration"].runs[0], layer=layer, sensor="Sensor",
                       layer_target=target)


def test_resting_penetration_expectation_passes_odes_surface_layer():
    ok = _evaluate("resting_penetration", _resting_trace())
    assert ok.verdict == results.PASS, ok.reason
    # "may interpenetrate": pushing the sunk box out, or sinking the touching one to the layer, is allowed;
    # only ODE's surface layer (a convention) leaves each at its landing depth
    no_layer = _evaluate("resting_penetration", _resting_trace(0.0))  # the sunk box pushed out
    assert any(m.convention for m in no_layer.failing())
    assert all(m.ok for m in no_layer.measures if "height" in m.quantity and not m.convention)
    target = _evaluate("resting_penetration", _resting_trace(target=True))
    assert target.verdict == results.CONVENTIONS and "Touching" in target.reason and "Sunk" not in target.reason


STACK_SHORT = Settings(2.0, 1 / 240)  # the case's 10 s in Python PGS would take a minute


def _stack_trace(mu: float = 0.3, iterations: int = 40) -> TraceView:
    bodies = {f"Box{j}": (BS.BS_M, (0.0, BS.BS_HEIGHT * (j - 0.5), 0.0), (0.0,) * 3) for j in range(1, BS.BS_N + 1)}

    def contacts(p):
        out = [(-1, 0, (0.0, 1.0, 0.0), 0.1 - p[0][1], ("Floor", "Box1Shape", "NULL", "Box1"), p[0])]
        for j in range(1, BS.BS_N):
            out.append((j - 1, j, (0.0, 1.0, 0.0), BS.BS_HEIGHT - (p[j][1] - p[j - 1][1]), ("", "", "", ""), p[j]))
        return out[::-1]
    return _ode_points(bodies, contacts, STACK_SHORT, gravity=tuple(BS.BS_GRAVITY), mu=(mu, mu), iterations=iterations)


def test_box_stack_expectation_passes_a_converged_contact_solve():
    """The bound assumes each step's contacts solved: Gauss-Seidel run to convergence holds the
    stack; at 10 iterations (the scene's, RigidBodyCollection.iterations' default) it does not, as
    ODE's quickstep does not (libode 0.16, dWorldQuickStep: the top box walks 5.6 cm in 10 s;
    dWorldStep holds it within 0.19 of the bound)."""
    case = C.BY_NAME["box_stack"]

    def verdict(**kw):
        return verdicts.evaluate(case, "ode-points", [_stack_trace(**kw)], [STACK_SHORT])
    ok = verdict()
    assert ok.verdict == results.PASS, ok.reason
    assert verdict(mu=0.0).verdict == results.FAIL
    short = verdict(iterations=10)  # the scene's own iterations: the stack creeps, graded, not accused
    assert short.verdict == results.PASS and short.accuracy() > 1


def _filtering_trace(ghost_collides: bool = False) -> TraceView:
    bodies = {"Kept": (1.0, KEPT_START, (0.0,) * 3), "Ghost": (1.0, GHOST_START, (0.0,) * 3)}
    touching = (0, 1) if ghost_collides else (0,)
    contacts = lambda p: [(-1, k, (0.0, 1.0, 0.0), 0.1 - p[k][1], ("Floor", "S", "NULL", "B"), p[k])  # noqa: E731
                          for k in touching]
    return _ode_points(bodies, contacts, C.BY_NAME["collision_filtering"].runs[0])


def test_collision_filtering_expectation():
    ok = _evaluate("collision_filtering", _filtering_trace())
    assert ok.verdict == results.PASS, ok.reason
    assert _evaluate("collision_filtering", _filtering_trace(True)).verdict == results.FAIL


def _sensor_trace(flip_ball_normal=False, swap_names=False, shift=0.0) -> TraceView:
    bodies = {"Block": (SG.SG_BLOCK_M, (0.3, 0.1, -0.2), (0.0,) * 3),
              "Ball": (SG.SG_BALL_M, (0.35, 0.3, -0.15), (0.0,) * 3)}

    def contacts(p):
        ball = (("BallShape", "BlockShape", "Ball", "Block") if swap_names
                else ("BlockShape", "BallShape", "Block", "Ball"))
        up = np.array([0.0, -1.0 if flip_ball_normal else 1.0, 0.0])
        point = np.array([p[1][0] + shift, p[0][1] + 0.1, p[1][2]])
        out = [(0, 1, up, 0.2 - (p[1][1] - p[0][1]), ball, point)]
        for dx in (-0.2, 0.2):
            for dz in (-0.2, 0.2):
                corner = p[0] + np.array([dx, -0.1, dz])
                out.append((-1, 0, (0.0, 1.0, 0.0), -corner[1], ("Floor", "BlockShape", "NULL", "Block"), corner))
        return out
    return _ode_points(bodies, contacts, C.BY_NAME["sensor_geometry"].runs[0], mu=(0.5, 0.5), sensor="Sensor")


def test_sensor_geometry_expectation_reads_the_sensors_rows():
    ok = _evaluate("sensor_geometry", _sensor_trace())
    assert ok.verdict == results.PASS, ok.reason
    flipped = _evaluate("sensor_geometry", _sensor_trace(flip_ball_normal=True))
    # reversed in the solver too, the normal drives the ball through the block: a broken run
    assert flipped.verdict == results.FAIL
    # 37.2.5.3 gives the normal its direction, "from body 1 to body 2": reported the other way, it breaks that
    swapped = _evaluate("sensor_geometry", _sensor_trace(swap_names=True))  # names swapped, normal kept
    assert swapped.verdict == results.FAIL and "from geometry1 towards geometry2" in swapped.reason
    assert _evaluate("sensor_geometry", _sensor_trace(shift=0.01)).verdict == results.FAIL


def _cradle_trace(bounce: float = 1.0, touching: bool = False) -> TraceView:
    pitch = 2 * NC.NC_R + (0.0 if touching else NC.NC_GAP)
    pivots = [(k - 2) * pitch for k in range(NC.NC_BALLS)]
    v_hit = math.sqrt(2 * G * NC.NC_L * (1 - math.cos(NC.NC_THETA0)) / (1 + NC.NC_I / (NC.NC_M * NC.NC_L ** 2)))
    # Ball1 starts where a 1/1000-s swing from 30 degrees would put it 20 ms before the gap closes
    m_eff = NC.NC_M + NC.NC_I / NC.NC_L ** 2
    bodies = {f"Ball{k + 1}": (m_eff, (pivots[k] - (0.02 * v_hit if k == 0 else 0.0), -NC.NC_L, 0.0),
                               ((v_hit if k == 0 else 0.0), 0.0, 0.0)) for k in range(NC.NC_BALLS)}
    rest = np.array([[x, -NC.NC_L, 0.0] for x in pivots])

    def contacts(p):
        return [(k, k + 1, (1.0, 0.0, 0.0), 2 * NC.NC_R - (p[k + 1][0] - p[k][0]), ("", "", "", ""), p[k])
                for k in range(NC.NC_BALLS - 1)]
    return _ode_points(bodies, contacts, C.BY_NAME["newtons_cradle"].runs[0], gravity=(0.0, 0.0, 0.0),
                       accel=lambda p: -G * (p - rest) / NC.NC_L * np.array([1.0, 0.0, 0.0]), bounce=bounce,
                       min_bounce=0.0)


def test_newtons_cradle_expectation_passes_binary_elastic_impacts():
    ok = _evaluate("newtons_cradle", _cradle_trace())
    assert ok.verdict == results.PASS, ok.reason
    assert _evaluate("newtons_cradle", _cradle_trace(bounce=0.0)).verdict == results.FAIL
    together = _evaluate("newtons_cradle", _cradle_trace(touching=True))  # ODE's simultaneous impact: 0.4 v
    assert together.verdict == results.FAIL


def test_trace_view_keeps_text_rows_apart():
    """A CollisionSensor writes SFBool, SFNode names and MFString rows: the numbers stay series,
    the rest is text (before, one such row made the whole trace unreadable)."""
    tv = TraceView([Row(0.0, "S", "isActive", "true"), Row(0.0, "S", "contacts[0].body1", "NULL"),
                      Row(0.0, "S", "contacts[0].depth", "0.001"), Row(0.5, "S", "isActive", "false")])
    assert tv.series("S", "contacts[0].depth")[1].tolist() == [[0.001]]
    times, values = tv.text("S", "isActive")
    assert times.tolist() == [0.0, 0.5] and values == ["true", "false"]
    assert tv.text("S", "contacts[0].body1")[1] == ["NULL"]
    with pytest.raises(KeyError):
        tv.text("S", "contacts[0].depth")
