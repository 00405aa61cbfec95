"""`x3drbp report`: the steps' results gathered into one page, and the feature table that sets
each backend's declarations against the verdicts of the cases exercising each feature."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

from backends import base
from conftest import ROOT, SCENES, case_scene
from x3drbp import report as R
from conformance.results import dt_label
from reports.report_page import dead_links, report_markdown

INSTALLED = [n for n, b in base.available().items() if not isinstance(b, str)]
needs_two = pytest.mark.skipif(len(INSTALLED) < 2, reason="a report compares two installed backends or more")


def test_features_set_declarations_against_the_cases_verdicts():
    backend = INSTALLED[0]
    over = {"quantity": "Ball.height", "ok": False, "basis": "spec"}
    graded = {"quantity": "Ball.height order", "ok": False, "basis": "accuracy"}
    matrix = {"results": [{"case": "free_fall", "backend": backend, "verdict": "fail", "measures": [over, graded]},
                          {"case": "projectile", "backend": backend, "verdict": "pass", "measures": []}]}
    tables, why = R.declarations([backend])
    assert tables is not None, why
    table = R.features(matrix, tables)
    gravity = next(r for r in table["features"] if r["feature"] == "RigidBodyCollection.gravity")
    cell = gravity["backends"][backend]
    assert cell["support"] == base.load(backend).support("RigidBodyCollection.gravity").support.value
    assert {"case": "free_fall", "verdict": "fail"} in cell["cases"]
    velocity = next(r for r in table["features"] if r["feature"] == "RigidBody.linearVelocity")
    assert {"case": "projectile", "verdict": "pass"} in velocity["backends"][backend]["cases"]
    # what failed, as measured (an accuracy grade decides no verdict), with the case's pin
    pin = R.expectations.load(backend).get("free_fall")
    assert table["not_passing"] == {backend: {"free_fall": {"verdict": "fail", "measures": ["Ball.height"],
                                                            "why": pin.why if pin else ""}}}
    declared = table["declared"][backend]
    assert sum(declared.values()) == len(base.load(backend).table())


def test_a_step_log_is_written_as_the_step_runs_and_keeps_what_a_failed_step_said(tmp_path):
    """Logs are the one output written in place (not through x3d_core.files.atomic): to be read
    while a step runs, and to say why a step that dies half-way died."""
    log = tmp_path / "sweep.log"
    seen = []

    def step(argv):
        print("measuring bullet at dt 1/60")
        seen.append(log.read_text())  # what someone reading the log sees meanwhile
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        R._run(step, ["sweep"], str(log))
    assert seen == ["$ x3drbp sweep\nmeasuring bullet at dt 1/60\n"]
    assert log.read_text() == seen[0]


def _fake_results(out) -> None:
    """What the steps leave behind, written by hand: the page must need nothing else."""
    (out / "conformance").mkdir(parents=True)
    (out / "conformance" / "matrix.md").write_text("# x3drbp conformance\n\n| case | a |\n|---|---|\n| free_fall | "
                                                   "pass |\n\n## Measures\n\nsee [traces](traces/x.csv)\n")
    (out / "conformance" / "matrix.json").write_text(json.dumps({"results": [
        {"case": c, "backend": b, "verdict": v} for c, b, v in (("free_fall", "a", "pass"), ("incline", "a", "fail"),
                                                                 ("free_fall", "b", "pass"), ("incline", "b", "pass"))]}))
    (out / "stability").mkdir()
    (out / "stability" / "stability.md").write_text("# x3drbp stability\n\n| case | dt | a |\n|---|---|---|\n")
    (out / "stability" / "stability.json").write_text(json.dumps({"results": [
        {"case": c, "backend": b, "dt": dt, "verdict": v} for c, b, dt, v in (
            ("wall", "a", 0.1, "tunnelled"), ("wall", "b", 0.1, "tunnelled"), ("wall", "b", 0.01, "tunnelled"),
            ("chain", "a", 0.1, "survived"), ("chain", "b", 0.1, "blew up"), ("chain", "c", 0.1, "unsupported"))]}))
    (out / "compare").mkdir()
    feature = {"feature": "RigidBody.mass", "backends": {
        "a": {"support": "native", "note": "", "cases": [{"case": "c1", "verdict": "fail"},
                                                         {"case": "c2", "verdict": "fail"}]},
        "b": {"support": "approximate", "note": "", "cases": [{"case": "c1", "verdict": "unsupported"}]}}}
    bounce = {"feature": "CollisionCollection.bounce", "backends": {  # c2's failure: a declared approximation
        "a": {"support": "approximate", "note": "", "cases": [{"case": "c2", "verdict": "fail"}]},
        "b": {"support": "native", "note": "", "cases": [{"case": "c2", "verdict": "pass"}]}}}
    why = "Chipmunk's solver, 10 iterations: the stop fights the pivot"
    (out / "features.json").write_text(json.dumps({"features": [feature, bounce], "declared": {
        "a": {"native": 3, "approximate": 1, "unsupported": 0}, "b": {"native": 1, "approximate": 2, "unsupported": 1}},
        "not_passing": {"a": {"c1": {"verdict": "fail", "measures": ["Arm.angle beyond limits"], "why": why},
                              "c2": {"verdict": "fail", "measures": ["Ball apex"], "why": ""}}, "b": {}}}))
    (out / "report.json").write_text(json.dumps({
        "generated": "2026-11-21T00:00:00+00:00", "backends": {"a": "1", "b": "2"}, "cpus": 2,
        "timings_s": {"conformance": 1.5, "stability": 2.0, "total": 3.5}, "failed": [], "quick": True}))


def test_the_page_gathers_each_section_from_the_files_alone(tmp_path):
    _fake_results(tmp_path)
    text = report_markdown(str(tmp_path))
    assert text.startswith("# x3drbp report") and "in 3.5 s (conformance 1.5 s, stability 2 s)" in text
    assert "# x3drbp conformance" not in text and "### Measures" in text  # titles dropped, headings down one
    assert "[traces](conformance/traces/x.csv)" in text  # links into the step's folder
    assert "Not run (`x3drbp report --quick` leaves it out)" in text  # no sweep
    assert "| RigidBody.mass | **native: 0 pass, 2 not (c1, c2)** | approx.: 0 pass, 1 refused |" in text
    assert "| a | 3 | 1 | 0 |" in text
    answers = text[text.index("## Answers"):text.index("## Conformance")]
    assert "- **a**: 1 of 2 cases pass; 1 fail" in answers and "- **b**: 2 of 2 cases pass" in answers
    # a hard case that ended alike everywhere is a finding; one that did not is not
    assert "wall: tunnelled on every backend that ran it, at every step" in answers and "chain:" not in answers
    assert "runs that held: a 1 of 2, b 0 of 3" in answers
    # blamed on what was measured, not on RigidBody.mass; c2, which a declared approximation explains, is none
    assert ("a: c1: fail on Arm.angle beyond limits; its pin says: Chipmunk's solver, 10 iterations (every "
            "feature it exercises declared native)") in answers
    assert "c2:" not in answers and "declares RigidBody.mass" not in answers
    assert '<details markdown="1"><summary>The matrix' in text  # the long tables folded


@needs_two
def test_the_command_runs_every_step_into_one_page(tmp_path, monkeypatch, capsys):
    """The real steps, made small: one case, one example scene for half a second, one hard case."""
    pair = ",".join(INSTALLED[:2])
    out = str(tmp_path / "report")

    yours = tmp_path / "mine"
    yours.mkdir()
    shutil.copy(case_scene("free_fall"), yours / "drop.x3d")
    (yours / "cut.x3d").write_text("<X3D><Scene><RigidBodyCollection>")  # does not load: left out of every step

    def small(out_dir, backends, quick, x_ite, scenes):
        chosen = ["--backends", ",".join(backends)]
        pendulum = os.path.join(SCENES, "examples", "pendulum.x3d")
        assert scenes == [str(yours / "drop.x3d")]  # --scenes, found in the folder
        return [("conformance", [["conformance", *chosen, "--cases", "free_fall", "--out",
                                   os.path.join(out_dir, "conformance")]]),
                ("compare", [["compare", path, *chosen, "--duration", "0.5", "--json",
                              os.path.join(out_dir, "compare", f"{stem}.json")]
                             for path, stem in zip([pendulum, *scenes], R.stems([pendulum, *scenes]))]),
                ("advise", [["advise", pendulum, *scenes, *chosen, "--dts", "1/60,1/240", "--duration", "0.5",
                             "--repeats", "1", "-q", "--verdicts", os.path.join(out_dir, "conformance", "matrix.json"),
                             "--json", os.path.join(out_dir, "advice", "advice.json")]]),
                ("stability", [["stability", *chosen, "--cases", "four_bar_linkage", "--dts", "1/60", "--out",
                                os.path.join(out_dir, "stability")]])]
    monkeypatch.setattr(R, "_steps", small)
    from x3drbp import main
    assert main(["report", "--out", out, "--backends", pair, "--scenes", str(yours)]) == 1  # a scene left out
    err = capsys.readouterr().err
    assert "links to" not in err  # the command found no dead link
    assert f"x3drbp report: left out of every step: {yours / 'cut.x3d'}:1:" in err
    page = open(os.path.join(out, "index.html"), encoding="utf-8").read()
    assert page.startswith("<!DOCTYPE html>") and page.count("<table>") >= 5
    assert dead_links(out, page) == [] and "compare/pendulum.divergence.png" in page
    assert "```" not in page and "<pre><code>" in page  # the advice's reasons, folded, as code
    text = open(os.path.join(out, "report.md"), encoding="utf-8").read()
    assert "| free_fall |" in text and "### pendulum.x3d" in text and "### drop.x3d" in text
    assert "four_bar_linkage" in text and "[stability](logs/stability.log)" in text
    # the first section answers: what conforms, and a backend and step for each scene, yours included
    answers = text[text.index("## Answers"):text.index("## Conformance")]
    assert f"**{INSTALLED[0]}**: " in answers and "of 1 cases pass" in answers
    advice = json.load(open(os.path.join(out, "advice", "advice.json"), encoding="utf-8"))
    for scene in advice["scenes"]:
        best = scene["recommended"]
        assert best is not None and f"| {best['backend']} at dt {dt_label(best['dt'])} |" in answers
    assert "drop.x3d" in answers and "free bodies" in answers
    meta = json.load(open(os.path.join(out, "report.json"), encoding="utf-8"))
    assert set(meta["timings_s"]) == {"conformance", "compare", "advise", "stability", "total"}
    assert not meta["failed"] and meta["scenes"] == [os.path.relpath(yours / "drop.x3d")]
    (why,) = meta["left_out"].values()
    assert list(meta["left_out"]) == [os.path.relpath(yours / "cut.x3d")] and ": error: " in why
    assert "Left out of every step, as they do not load or simulate nothing: " in text
    assert "$ x3drbp conformance" in open(os.path.join(out, "logs", "conformance.log"), encoding="utf-8").read()


def test_a_step_s_bar_goes_to_the_terminal_and_its_text_to_the_log(tmp_path):
    """Under x3drbp report a step's stderr is its log; its progress bar goes to the report's terminal."""
    import argparse
    import io
    from concurrent.futures import ThreadPoolExecutor
    from x3drbp import options
    from conformance.runner import children
    log, terminal = tmp_path / "step.log", io.StringIO()

    def step(argv):
        print("a result line")
        assert options.progress(argparse.Namespace(quiet=False))  # a log is no terminal; the bars go elsewhere
        with ThreadPoolExecutor(2) as pool:
            children.wait_all([pool.submit(lambda: None) for _ in range(3)], True)
        return 0

    assert R._run(step, ["conformance"], str(log), terminal) == 0
    bar = terminal.getvalue()
    assert "/3 [" in bar and bar.endswith("\r") and "a result line" not in bar  # drawn, then cleared
    assert "/3 [" not in log.read_text() and "a result line" in log.read_text()
    assert children.BARS is None  # the next step, or the report's own lines, write where they did


def test_scenes_that_share_a_stem_get_their_own_results():
    assert R.stems(["a/x.x3d", "b/x.x3dv", "c/y.x3d", "d/x.x3d"]) == ["x", "x-2", "y", "x-3"]


def test_a_link_to_a_missing_file_is_found(tmp_path):
    (tmp_path / "here.png").write_bytes(b"")
    page = ("<a href='here.png'>x</a> <img src=\"gone.png\"> <a href='#answers'>a</a> "
            "<a href='https://example.org/'>e</a> <a href='here.png#frag'>f</a>")
    assert dead_links(str(tmp_path), page) == ["gone.png"]


def test_bad_usage_is_exit_2_without_a_traceback(tmp_path):
    r = subprocess.run([sys.executable, "-m", "x3drbp", "report", "--backends", "nope", "--out",
                        str(tmp_path)], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and "unknown backend(s) nope" in r.stderr and "Traceback" not in r.stderr
    (tmp_path / "empty").mkdir()
    for scenes, said in ((tmp_path / "missing.x3d", "no such file or folder"), (tmp_path / "empty", "no X3D files")):
        r = subprocess.run([sys.executable, "-m", "x3drbp", "report", "--scenes", str(scenes), "--out",
                            str(tmp_path / "out")], cwd=ROOT, capture_output=True, text=True, timeout=120)
        assert r.returncode == 2 and said in r.stderr and "Traceback" not in r.stderr
        assert not (tmp_path / "out" / "logs").exists()  # refused before any step


def test_a_feature_cell_counts_other_conventions_as_conforming():
    from reports.report_page import _cell
    cell = {"support": "native", "cases": [{"case": "a", "verdict": "pass"}, {"case": "b", "verdict": "conventions"}]}
    assert _cell(cell) == "native: 1 pass, 1 conforming in other conventions (b)"  # not bold: no case fails
    cell["cases"].append({"case": "c", "verdict": "fail"})
    assert _cell(cell).startswith("**native: 1 pass, 1 conforming in other conventions (b), 1 not (c)")


def test_compare_findings_name_the_first_pair_to_part_and_an_integration_order_that_explains_it():
    from conformance.results import BackendRun, Comparison, Crossing, Divergence, PairComparison
    from reports.summary import compare_findings

    def pair(a: str, b: str, parts_at: float | None, turns_at: float | None = None) -> PairComparison:
        def crossing(t):
            return None if t is None else Crossing(t, ["Ball"], [2e-3])
        return PairComparison(a, b, np.zeros(3), ["Ball"], [], [],
                              Divergence("position", "m", 1e-3, first_over=crossing(parts_at)),
                              Divergence("orientation", "rad", 1e-3, first_over=crossing(turns_at)), [], [], [])

    runs = [BackendRun("mujoco", "ran", integration="semi-implicit Euler"),
            BackendRun("bullet", "ran", integration="semi-implicit Euler"),
            BackendRun("pymunk", "ran", integration="explicit Euler in position")]
    c = Comparison("scenes/ball.x3d", 5.0, 1 / 240, 60.0, {"position": 1e-3, "orientation": 1e-3}, runs,
                   [pair("mujoco", "bullet", None), pair("mujoco", "pymunk", 0.0333, 0.5), pair("bullet", "pymunk", 0.05, 0.02)])
    (line,) = compare_findings([c])
    assert line.startswith("ball.x3d: mujoco/bullet stay within 0.001 m and 0.001 rad for all 5 s")
    # bullet/pymunk turn apart first (0.02 s), before mujoco/pymunk move apart (0.0333 s)
    assert "first to part: bullet/pymunk at 0.02 s (bullet steps by semi-implicit Euler, pymunk by explicit " \
           "Euler in position: free motion alone parts them)" in line
    c.pairs = c.pairs[:1]
    assert compare_findings([c]) == ["ball.x3d: mujoco/bullet stay within 0.001 m and 0.001 rad for all 5 s"]


def test_your_scenes_go_into_compare_advise_and_sweep_beside_the_examples(tmp_path):
    mine = str(tmp_path / "pendulum.x3d")
    steps = dict(R._steps(str(tmp_path / "out"), ["mujoco", "ode"], False, False, [mine]))
    compared = [argv[1] for argv in steps["compare"]]
    assert compared[-1] == os.path.relpath(mine) and len(compared) == len(os.listdir(R.EXAMPLES)) + 1
    # two pendulum scenes: their results do not overwrite each other
    assert [argv[argv.index("--json") + 1].rsplit(os.sep, 1)[1] for argv in steps["compare"]][-2:] == \
        ["pendulum.json", "pendulum-2.json"]
    (advise,) = steps["advise"]
    assert advise[1:1 + len(compared)] == compared and "--verdicts" in advise
    (sweep,) = steps["sweep"]
    assert sweep[sweep.index("--scenes") + 1].split(",") == [*R.S.DEFAULT_SCENES, mine]
    assert "sweep" not in dict(R._steps(str(tmp_path / "out"), ["mujoco"], True, False, []))  # --quick


def test_your_scenes_are_not_called_example_scenes(tmp_path):
    from conformance.results import Comparison
    from reports.summary import answers
    _fake_results(tmp_path)
    mine = str(tmp_path / "mine" / "car.x3d")
    meta = json.loads((tmp_path / "report.json").read_text())
    (tmp_path / "report.json").write_text(json.dumps({**meta, "scenes": [os.path.relpath(mine)]}))
    scenes = [Comparison(s, 5.0, 1 / 240, 60.0, {"position": 1e-3, "orientation": 1e-3}, [], [])
              for s in (os.path.join(R.EXAMPLES, "pendulum.x3d"), mine)]
    text = answers(str(tmp_path), scenes)
    assert "example scenes' runs part" not in text
    assert "Where the runs of the example scenes and of yours part" in text
    assert "pendulum.x3d: fewer" in text and "car.x3d (yours): fewer than two backends ran it" in text
    assert "### car.x3d (yours)" in report_markdown(str(tmp_path), [("x", c) for c in scenes])
