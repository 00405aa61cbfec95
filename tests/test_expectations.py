"""The pinned verdicts: their files, how a result is held to its pin, and the matrix page
(docs/conformance-matrix.md)."""

from __future__ import annotations

import dataclasses
import os

import pytest

from backends import base
from conformance import cases as C
from conformance import expectations as E
from x3drbp import main as cli_main
from x3drbp.expectations import MATRIX, write_matrix
from conformance.results import CONVENTIONS, FAIL, PASS, UNSUPPORTED, Expected, Measure, Result, accuracy, spec
from reports.expectations_table import BEGIN, END, markdown, replace_section

from conftest import ROOT


def _fail(case: str, *bad: str) -> Result:
    return Result(case, "engine", FAIL, "measured", [Measure(q, 2.0, 1.0) for q in bad] + [Measure("ok", 0.0, 1.0)])


def test_every_pin_names_a_case_and_parses():
    for b in base.IN_TREE:
        pins = E.load(b)
        assert set(pins) <= set(C.BY_NAME), (b, set(pins) - set(C.BY_NAME))
        for case, e in pins.items():
            assert e.verdict != PASS or e.over_bound, (b, case)
            assert (e.verdict in (FAIL, CONVENTIONS)) == bool(e.failing), (b, case)
            assert (e.verdict == UNSUPPORTED) == bool(e.reason), (b, case)
            if e.verdict in (FAIL, CONVENTIONS) or e.over_bound:
                assert e.why, f"{b}: {case}: a pinned fail, or accuracy beyond its bound, says why"


def test_accuracy_beyond_its_bound_is_pinned_and_a_change_in_it_named():
    graded = Measure("period", 3.0, 10.0, "s", spec("37.4.12 SingleAxisHingeJoint: quoted."), bound=1.0)
    r = Result("c", "engine", PASS, "", [graded, Measure("first step", 0.5, 1.0, basis=accuracy("rigid"))])
    pin = E.pinned(r, "why")
    assert pin == Expected(PASS, why="why", over_bound=("period",))
    assert E.mismatch(r, pin) is None
    within = Result("c", "engine", PASS, "", [dataclasses.replace(graded, error=0.5)])
    assert "accuracy beyond its bound in nothing, pinned period" in E.mismatch(within, pin)
    assert E.pinned(within) == Expected(PASS)  # a pass within every bound pins nothing
    text = E.dumps("engine", "1", {"c": pin})
    assert 'over_bound = ["period"]' in text


def test_a_result_must_be_its_pin_exactly():
    pin = E.pinned(_fail("c", "a", "b"), "why")
    assert pin == Expected(FAIL, ("a", "b"), why="why")
    assert E.mismatch(_fail("c", "b", "a"), pin) is None
    assert "fails on a, pinned a, b" in E.mismatch(_fail("c", "a"), pin)
    assert "expected fail, got pass" in E.mismatch(Result("c", "engine", PASS), pin)
    refused = Result("c", "engine", UNSUPPORTED, "X.y: why not")
    assert "expected pass, got unsupported" in E.mismatch(refused, Expected(PASS))
    assert "pinned 'X.y: other'" in E.mismatch(refused, Expected(UNSUPPORTED, reason="X.y: other"))


def test_regenerating_keeps_a_why_only_while_it_holds():
    old = {"c": Expected(FAIL, ("a",), why="a is slow"), "d": Expected(FAIL, ("a",), why="gone")}
    new = E.regenerate([_fail("c", "a"), _fail("d", "b"), Result("e", "engine", PASS)], old)
    assert new == {"c": Expected(FAIL, ("a",), why="a is slow"), "d": Expected(FAIL, ("b",))}


def test_files_round_trip_and_bad_files_are_named(tmp_path):
    table = {"c": Expected(FAIL, ("x \"quoted\"", "y"), why="w\nz"), "d": Expected(UNSUPPORTED, reason="F.g: no")}
    (tmp_path / "engine.toml").write_text(E.dumps("engine", "1.0", table))
    assert E.load("engine", str(tmp_path)) == table
    assert E.load("absent", str(tmp_path)) == {}
    (tmp_path / "bad.toml").write_text('[c]\nverdict = "pass"\n')
    with pytest.raises(ValueError, match=r"bad.toml:2: \[c\]: verdict must be one of"):
        E.load("bad", str(tmp_path))


def test_the_matrix_page_is_the_pins_rendered(tmp_path):
    assert MATRIX == os.path.join(ROOT, "docs", "conformance-matrix.md")
    with open(MATRIX, encoding="utf-8") as f:
        page = f.read()
    table = markdown([c.name for c in C.CASES], {b: E.load(b) for b in base.IN_TREE})
    assert replace_section(page, table) == page, "docs/conformance-matrix.md is stale: run `x3drbp expectations`"
    copy = tmp_path / "conformance-matrix.md"
    copy.write_text(page.replace(table, "typed by hand\n"))
    write_matrix(str(copy))
    assert copy.read_text() == page
    with pytest.raises(ValueError, match="no matrix markers"):
        replace_section("no markers", table)
    assert BEGIN in page and END in page


def test_check_reports_a_verdict_that_left_its_pin(tmp_path, capsys):
    installed = [b for b in ("mujoco", "bullet") if not isinstance(base.available().get(b), str)]
    if not installed:
        pytest.skip("neither mujoco nor bullet is installed")
    b, pins = installed[0], str(tmp_path)
    (tmp_path / f"{b}.toml").write_text(E.dumps(b, "x", {"free_fall": Expected(FAIL, ("Ball.position",), why="w")}))
    assert cli_main(["expectations", "--backends", b, "--cases", "free_fall", "--check", "--pins", pins]) == 1
    assert f"free_fall on {b}: expected fail, got pass" in capsys.readouterr().out
    assert cli_main(["expectations", "--backends", b, "--cases", "free_fall,gravity_off", "--pins", pins]) == 0
    assert E.load(b, pins) == {}
    assert cli_main(["expectations", "--backends", b, "--cases", "free_fall", "--check", "--pins", pins]) == 0
