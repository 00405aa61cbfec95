"""index.html as a first-time reader meets it: laid out in a real browser (headless Chromium, as
tests/page_check.py drives it) at 1400 and 900 px, nothing runs off the page or scrolls inside
it and every plot loads, each sweep's front stands beside its plot where there is room; and
what the page says first: what decides the backend for a scene, that a planar engine is
planar-only, how to judge your own browser, and no path into a run's deleted temporary files.

The page is built from small result files written here (tables as wide as a real report's:
seven backends, long feature and case names, a long evidence column), not from a report run.
"""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

import page_check
from conformance.results import BackendRun, Comparison, Crossing, Divergence, PairComparison
from reports.advice_text import decided, markdown as advice_markdown
from reports.report_page import breakable, report_markdown, write_report
from reports.text import untemporary

BACKENDS = ["bullet", "mujoco", "dart", "ode", "pymunk", "physx", "drake"]
TEMPORARY = "/tmp/x3drbp-sweep-k2j3h4l5/scene.x3d"  # a run's copy of the scene, deleted when it ended
CASES = ["anisotropic_friction", "double_pendulum_energy", "intermediate_axis_tumble"]
FEATURES = ["DoubleAxisHingeJoint.suspensionErrorCorrection", "CollisionCollection.softnessConstantForceMix"]
IGNORED = [f"RigidBody.{f}" for f in ("autoDisable", "disableAngularSpeed", "disableLinearSpeed", "disableTime",
                                       "finiteRotationAxis", "inertia", "useFiniteRotation")]  # X_ITE's, in one case
SETTINGS = {"dts": [1 / 60, 1 / 240], "duration": 5.0, "window": 1.0, "budget": 1.0, "tolerance": 1e-3,
            "repeats": 3, "verdicts": "pinned"}


def _write(path: str, data: dict | str) -> None:
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(data if isinstance(data, str) else json.dumps(data))


def _option(backend: str, dt: float, error: float | None, cpu: float | None, reason: str = "") -> dict:
    o = {"backend": backend, "dt": dt, "verdict": "measured" if error is not None else "blew up", "reason": reason,
         "error": error, "self_error": error, "parts": {b: None for b in BACKENDS[:3] if b != backend}}
    if cpu is not None:
        o.update(cpu_per_sim_s=cpu, cpu_low=cpu * 0.9, cpu_high=cpu * 1.1)
    return o


def _scene(path: str, rule: str, settled: str, best: dict, runner: dict, reference_error: float = 1e-9) -> dict:
    judged = {b: {"refused": [], "approximated": [], "failing": {}, "passing": 3, "beyond_bound": []}
              for b in BACKENDS}
    bad = _option("ode", 1 / 60, None, None, f"{TEMPORARY}: ode: blew up at t=0.5: Ball has a non-finite state "
                                           f"(the frames before it written to {TEMPORARY[:-9]}trace.npz)")
    return {"scene": path, "kind": "joints and contacts", "rule": rule, "said": rule + ": " + (settled or "the fastest"),
            "settled": settled, "reference": {"backend": "drake", "method": "error-controlled", "dt": 1 / 240,
                                              "error": reference_error, "said": "drake's error-controlled run"},
            "judged": judged, "options": [best, runner, bad], "recommended": {"backend": best["backend"], "dt": best["dt"]},
            "runners_up": [{"backend": runner["backend"], "dt": runner["dt"]}]}


def _advice() -> dict:
    long = "scenes/examples/a_folder_with_a_long_name/newtons_cradle_with_a_long_name.x3dv"
    return {"settings": SETTINGS, "backends": {b: "1" for b in BACKENDS}, "scenes": [
        _scene(long, "within the tolerance", "the fastest", _option("pymunk", 1 / 240, 7.9e-4, 1.03e-3),
               _option("mujoco", 1 / 240, 7.9e-4, 7.3e-4)),
        _scene("scenes/examples/pendulum.x3d", "within the tolerance", "tied on speed; tie-break 5: the backend's name",
               _option("bullet", 1 / 240, 8.1e-4, 2.25e-3), _option("mujoco", 1 / 240, 8.1e-4, 1.5e-3)),
        _scene("scenes/examples/car.x3d", "none within the tolerance: the most accurate", "",
               _option("ode", 1 / 240, 3.2e-3, 1.9e-3), _option("mujoco", 1 / 240, 3.5e-3, 1e-3)),
        _scene("scenes/examples/bouncing_ball.x3dj", "accuracy cannot be ranked",
               "tied on speed; tie-break 2: fewer cases graded beyond their bound",
               _option("bullet", 1 / 60, 0.0327, 5.6e-4), _option("dart", 1 / 60, 0.0327, 1.1e-3), 0.168)]}


def _sweep() -> dict:
    points = []
    for b, backend in enumerate(BACKENDS):
        for k, dt in enumerate((1 / 60, 1 / 240, 1 / 1000)):
            for its in (10, 50):
                points.append({"scene": "pendulum_period", "backend": backend, "dt": dt, "iterations": its,
                               "prefer_accuracy": False, "verdict": "pass", "reason": "",
                               "error": 10.0 ** -(3 + 2 * k + b % 3) * (1 + its / 100), "self_error": None,
                               "cpu_per_sim_s": 4e-4 * (1 + b / 7) * 4 ** k * (1 + its / 100),
                               "cpu_low": None, "cpu_high": None, "pareto_scene": its == 10 and b % 3 == 2,
                               "pareto_backend": its == 10, "tie_scene": None, "tie_backend": None,
                               "dt_label": ("1/60", "1/240", "1/1000")[k],
                               "label": f"{backend} {('1/60', '1/240', '1/1000')[k]} it={its} acc=FALSE"})
    points.append({**points[0], "backend": "ode", "verdict": "blew up", "error": None, "cpu_per_sim_s": None,
                   "pareto_scene": False, "pareto_backend": False,
                   "reason": f"{TEMPORARY}: ode: blew up at t=0.25: Bob has a non-finite state"})
    return {"measured": {"speed": "CPU time", "error": "closed form", "self_error": "fine step", "ties": "ties"},
            "settings": {"iterations": [10, 50], "accuracy": "false", "repeats": 1, "reference_refinement": 8,
                         "window": 1.0},
            "backends": {b: {"version": "1", "iterations": True, "preferAccuracy": True} for b in BACKENDS},
            "scenes": [{"name": "pendulum_period", "reference": "closed form", "quantity": "Bob.period", "unit": "s"}],
            "points": points, "wall_s": 10.0}


def _comparison() -> dict:
    """Three backends' pairs (a triangle of three panels: the plot is drawn, but cheaply)."""
    times = np.linspace(0.0, 1.0, 61)

    def pair(a: str, b: str, parts_at: float | None) -> PairComparison:
        gap = times * 2e-3 / parts_at if parts_at else times * 1e-4
        first = Crossing(parts_at, ["Ball"], [2e-3]) if parts_at else None
        return PairComparison(a, b, times, ["Ball"], [], [],
                              Divergence("position", "m", 1e-3, 1e-4, 1e-3, 0.5, "Ball", first, gap, gap),
                              Divergence("orientation", "rad", 1e-3, 0.0, 0.0, 0.0, "Ball", None, 0 * times, 0 * times),
                              [], [], [])
    runs = [BackendRun(b, "ran", simulated_s=1.0, simulation_wall_s=0.01) for b in BACKENDS[:3]]
    return Comparison("scenes/examples/pendulum.x3d", 1.0, 1 / 240, 60.0, {"position": 1e-3, "orientation": 1e-3},
                      runs, [pair("bullet", "mujoco", None), pair("bullet", "dart", 0.5),
                             pair("mujoco", "dart", 0.25)]).to_json()


def _results(out: str) -> None:
    """Every step's result files, written by hand, each table as wide as a real report makes it."""
    from reports.plots import sweep_plot
    wide = "| case | checks | " + " | ".join(BACKENDS) + " |\n|---|---|" + "---|" * len(BACKENDS) + "\n"
    wide += "".join(f"| {c} | frictionCoefficients 0.2 0.6 with disableCollisionsBetweenLinkedBodies | "
                    + " | ".join(["unsupported"] * len(BACKENDS)) + " |\n" for c in CASES)
    _write(f"{out}/report.json", {"generated": "2026-12-02T00:00:00+00:00", "backends": {b: "1" for b in BACKENDS},
                                  "cpus": 2, "failed": [], "quick": False,
                                  "timings_s": {"conformance": 1.0, "sweep": 1.0, "x_ite": 1.0, "total": 3.0}})
    _write(f"{out}/conformance/matrix.md", f"# x3drbp conformance\n\n{wide}")
    _write(f"{out}/conformance/matrix.json", {
        "backends": {b: {"version": "1", "unavailable": None, "run": True,
                         "scope": "planar scenes only" if b == "pymunk" else None} for b in BACKENDS},
        "results": [{"case": c, "backend": b, "verdict": "unsupported" if b == "pymunk" else "pass"}
                    for c in CASES for b in BACKENDS]})
    _write(f"{out}/stability/stability.md", "# x3drbp stability\n\n" + wide.replace("| checks |", "| dt |"))
    _write(f"{out}/stability/stability.json", {"results": []})
    cell = {"support": "native", "note": "", "cases": [{"case": c, "verdict": "conventions"} for c in CASES]}
    _write(f"{out}/features.json", {"features": [{"feature": f, "backends": {b: cell for b in BACKENDS}}
                                                 for f in FEATURES],
                                    "declared": {b: {"native": 3, "approximate": 1, "unsupported": 0} for b in BACKENDS},
                                    "not_passing": {b: {} for b in BACKENDS}})
    _write(f"{out}/advice/advice.json", _advice())
    sweep = _sweep()
    _write(f"{out}/sweep/sweep.json", sweep)
    sweep_plot(sweep, "pendulum_period", f"{out}/sweep/sweep_pendulum_period.png")
    _write(f"{out}/compare/pendulum.json", _comparison())
    evidence = ("violates the spec: Along1.linearVelocity slows at mu1 g or mu2 g (V3 pre-3.3, \"37.2.5.3 Collision "
                "contact description: The CollisionCollection node specifies a set of default coefficients\"): "
                "error 17.6 m/s > tolerance 0.25 m/s; every field its probes could tell has an effect "
                "(CollisionCollection.frictionCoefficients, CollisionCollection.appliedParameters)")
    _write(f"{out}/x_ite/recordings/anisotropic_friction.rrd", "")
    _write(f"{out}/x_ite/x_ite.json", {
        "versions": {"x_ite": "15.0.1", "chromium": "Chromium 150"}, "wall_s": 1.0, "clock": [],
        "cases": [{"case": c, "verdict": "wrong", "detail": evidence, "ignored": IGNORED if c == CASES[0] else [],
                   "probed": [], "dt": 1 / 600,
                   "frame_rates": [60.0], "agreeing": [], "messages": [],
                   "recording": "recordings/anisotropic_friction.rrd"} for c in CASES]})


def _html(page: str) -> str:
    """The page's HTML without the <wbr> breakable() puts where a name may break."""
    with open(page, encoding="utf-8") as f:
        return f.read().replace("<wbr>", "")


@pytest.fixture(scope="module")
def page(tmp_path_factory) -> str:
    out = str(tmp_path_factory.mktemp("report"))
    _results(out)
    return write_report(out)


@pytest.mark.skipif(page_check.unavailable() is not None, reason=f"layout: {page_check.unavailable()}")
def test_nothing_runs_off_the_page_and_every_plot_loads_at_1400_and_900_px(page):
    """The X_ITE table ran off a 1400 px page, the advice, conformance and feature tables off a
    900 px one (names such as disableCollisionsBetweenLinkedBodies set a table's narrowest
    width), the advice's reasons ran off in a <pre> line; every <details> is opened first, as
    a reader opens them."""
    seen = page_check.layout(page, (1400, 900))
    assert set(seen) == {1400, 900}
    for viewport, found in seen.items():
        assert found["off_page"] == [] and found["scrolls"] == [], viewport
        assert found["page_width"] == found["width"], viewport  # no sideways scroll
        assert len(found["images"]) == 2 and all(i["loaded"] for i in found["images"]), found["images"]
    # the sweep's front stands beside its plot where the page has room, above it where it has not
    assert seen[1400]["sides"] == ["beside"] and seen[900]["sides"] == ["below"]
    sweep = next(i for i in seen[900]["images"] if i["src"].startswith("sweep/"))
    assert sweep["shown_px"] >= 700  # at its own size, not shrunk: its words stay readable


def test_which_backend_says_first_what_decides_and_that_a_planar_engine_is_planar_only(page):
    html = _html(page)
    text = report_markdown(os.path.dirname(page))
    section = text[text.index("## Which backend for which scene"):text.index("## Where the backends part")]
    first = section.split("\n")[2]
    assert first.startswith("What decides: the fastest run within 1 mm of the scene's reference (over the first 1 s)")
    answers = text[text.index("## Answers"):text.index("## Conformance")]
    assert "What decides: the fastest run within 1 mm" in answers
    assert answers.count("pymunk (planar scenes only) at dt 1/240") == 1  # the table
    assert section.count("pymunk (planar scenes only) at dt 1/240") == 2  # and the reasons, folded
    assert "pymunk (planar scenes only) at dt 1/240 (within the tolerance" in section
    assert "mujoco (planar" not in text  # a runner-up is not recommended: nothing to warn of
    assert "<td>pymunk (planar scenes only) at dt 1/240</td>" in html


@pytest.mark.parametrize("rule, settled, reference_error, says", [
    ("within the tolerance", "the fastest", 1e-9, "fastest within 1 mm of the reference"),
    ("within the tolerance", "tied on speed; tie-break 5: the backend's name", 1e-9,
     "within 1 mm of the reference, tied on speed; tie-break 5: the backend's name"),
    ("none within the tolerance: the most accurate", "", 1e-9, "most accurate: none within 1 mm of the reference"),
    ("none within the tolerance: the most accurate", "tied on speed; tie-break 1: fewer approximations", 1e-9,
     "most accurate: none within 1 mm of the reference; tied on speed; tie-break 1: fewer approximations"),
    ("accuracy cannot be ranked", "the fastest", 0.168,
     "fastest; accuracy cannot be ranked (the reference's uncertainty, 0.168 m, exceeds 1 mm)"),
    ("accuracy cannot be ranked", "tied on speed; tie-break 2: fewer cases graded beyond their bound", 0.168,
     "tied on speed; tie-break 2: fewer cases graded beyond their bound; accuracy cannot be ranked (the "
     "reference's uncertainty, 0.168 m, exceeds 1 mm)"),
    ("a branch not yet known", "its own words", 1e-9, "a branch not yet known; its own words"),
])
def test_chosen_as_leads_with_what_decided(rule, settled, reference_error, says):
    scene = _scene("s.x3d", rule, settled, _option("bullet", 1 / 60, 1e-4, 1e-3), _option("ode", 1 / 60, 1e-4, 1e-3),
                   reference_error)
    assert decided(scene, SETTINGS) == says
    assert f"| {says} |" in advice_markdown({"settings": SETTINGS, "scenes": [scene]}, details=False)
    scene["recommended"] = None
    assert decided(scene, SETTINGS) == f"none: {rule}"


def test_the_answers_say_how_to_judge_your_own_browser_beside_the_engines(page):
    text = report_markdown(os.path.dirname(page))
    answers = text[text.index("## Answers"):text.index("## Conformance")]
    engines, browser, x_ite, advice = (answers.index(s) for s in (
        "- **bullet**: ", "**How to judge your own browser**", "**How X_ITE conforms**", "**Which backend"))
    assert engines < browser < x_ite < advice  # right after what conforms, before any one browser's answer
    # a browser's seven fields without effect: counted in its line, listed folded beneath it (60 were a wall of text)
    (line,) = [ln for ln in answers.splitlines() if ln.startswith("**How X_ITE conforms**")]
    assert line.endswith("; 7 fields without effect (listed below).") and "RigidBody.inertia" not in line
    assert '<summary>The 7 fields without effect in X_ITE</summary>' in answers
    assert "\n    x3drbp validate SCENE --trace THEIRS.csv --dt STEP\n" in answers  # one command line, a code block
    assert "<pre><code>x3drbp validate SCENE --trace THEIRS.csv --dt STEP" in _html(page)


def test_a_line_about_a_deleted_temporary_file_keeps_what_it_says_without_the_path(page):
    text = report_markdown(os.path.dirname(page))
    assert "x3drbp-sweep-" not in text
    assert "did not end well: ode at dt 1/60: blew up: ode: blew up at t=0.5: Ball has a non-finite state " \
           "(the frames before it written to trace.npz (temporary))" in text
    assert "- ode: 1 run(s) blew up: ode: blew up at t=0.25: Bob has a non-finite state" in text
    assert untemporary("unreadable trace or timing: [Errno 2] No such file or directory: "
                       "'/var/tmp/x3drbp-stab-ab_12cd3/timing.json'") == \
        "unreadable trace or timing: [Errno 2] No such file or directory: 'timing.json (temporary)'"
    assert untemporary("/home/me/scenes/car.x3d: bullet: blew up") == "/home/me/scenes/car.x3d: bullet: blew up"


def test_the_sweep_s_front_stands_beside_its_plot_each_backend_s_folded(page):
    html = _html(page)
    side = html[html.index('<div class="side">'):]
    table, plot = side.index("<table>"), side.index('<img alt="pendulum_period: error against speed"')
    assert table < plot < side.index("Each backend's own front (21 points)")  # the front beside, then the rest folded
    assert '<a href="sweep/sweep_pendulum_period.png"><img' in side  # a click shows it at full size
    assert '<a href="compare/pendulum.divergence.png"><img' in html


def test_a_long_name_may_break_where_its_parts_meet_and_nowhere_else():
    assert breakable("<td>DoubleAxisHingeJoint.stop1Bounce a_b dt 1/240 0.000762 &lt;x&gt;</td>") == (
        "<td>Double<wbr>Axis<wbr>Hinge<wbr>Joint.<wbr>stop1Bounce a_<wbr>b dt 1/240 0.000762 &lt;x&gt;</td>")
    assert breakable('<a href="a_b/c.png">x</a>') == '<a href="a_b/c.png">x</a>'  # attributes untouched


def test_the_conformance_matrix_says_what_a_backend_is_limited_to():
    """Where the page learns that pymunk is planar-only: the backend declares it
    (backends.base.Backend.scope), the probe reads it, matrix.json carries it."""
    from x3drbp.conformance import to_json
    from conformance.runner import probe
    info = probe.backend_table(120, ["pymunk", "bullet"])
    usable = {n: i for n, i in info.items() if i.usable}
    if "pymunk" not in usable:
        pytest.skip(f"pymunk: {info['pymunk'].unavailable}")
    backends = to_json([], [], list(usable), usable)["backends"]
    assert backends["pymunk"]["scope"] == "planar scenes only"
    assert all(backends[n]["scope"] is None for n in usable if n != "pymunk")
