"""forceOutput as 37.3.3 gives it: "ALL" anywhere selects every output, "NONE" selects none
and the values beside it are ignored (warned of, not refused), an empty list is "NONE",
names select themselves and an unknown name is an error unless NONE is given. ALL beside
NONE is where the clause says both: x3drbp takes ALL, `check` says so, and `validate` holds
neither reading against a browser's trace."""

from __future__ import annotations

import os

import pytest

from x3drbp import main as cli_main
from conftest import SCENES, needs_ode
from x3d_core.encodings.load import load
from x3d_core.semantics.world import worlds

PENDULUM = os.path.join(SCENES, "examples", "pendulum.x3d")
HINGE_OUTPUTS = ("angle", "angleRate", "body1AnchorPoint", "body2AnchorPoint")


def _pendulum(tmp_path, value: str) -> str:
    """The example pendulum with its hinge's forceOutput set to value (XML attribute text)."""
    text = open(PENDULUM, encoding="utf-8").read()
    path = tmp_path / "pendulum.x3d"
    path.write_text(text.replace("""forceOutput='"angle" "angleRate"'""", f"forceOutput='{value}'"), encoding="utf-8")
    return str(path)


def _said(path: str) -> tuple[list[str], list[str], tuple[str, ...]]:
    """The forceOutput errors and warnings of the scene, and the outputs its hinge reports."""
    scene = load(path)
    ours = [d for d in scene.diagnostics if d.subject.endswith(".forceOutput")]
    (w,) = worlds(scene)
    return ([d.message for d in ours if d.severity == "error"], [d.message for d in ours if d.severity == "warning"],
            w.joints[0].outputs)


@pytest.mark.parametrize("value, outputs", [
    ('"ALL"', HINGE_OUTPUTS),
    ('"angleRate" "ALL"', HINGE_OUTPUTS),  # anywhere in the array
    ('"NONE"', ()),
    ("", ()),  # empty is NONE
    ('"angle" "body2AnchorPoint"', ("angle", "body2AnchorPoint")),
])
def test_each_rule_selects_its_outputs_without_a_word(tmp_path, value, outputs):
    assert _said(_pendulum(tmp_path, value)) == ([], [], outputs)


@pytest.mark.parametrize("value, ignored", [
    ('"NONE" "angle"', "'angle'"),
    ('"angle" "speed" "NONE"', "'angle', 'speed'"),  # not a name, but ignored: no error either
])
def test_values_beside_none_are_ignored_with_a_warning_not_an_error(tmp_path, value, ignored):
    errors, warnings, outputs = _said(_pendulum(tmp_path, value))
    assert errors == [] and outputs == ()
    assert warnings == [f"{ignored} beside NONE: ignored, as 37.3.3 says of values in addition to NONE; "
                        "the joint reports no outputs"]


@pytest.mark.parametrize("value", ['"angle" "speed"', '"ALL" "speed"'])
def test_an_unknown_name_without_none_is_still_an_error(tmp_path, value):
    errors, _, _ = _said(_pendulum(tmp_path, value))
    assert errors == ["'speed' is not an output of SingleAxisHingeJoint; allowed: ALL, NONE, angle, angleRate, "
                      "body1AnchorPoint, body2AnchorPoint"]


BOTH = ("holds both ALL and NONE, and 37.3.3 gives both: ALL anywhere updates all fields, NONE updates none; "
        "a run updates every output (ALL), and an implementation that updates none follows the clause too")


def test_all_beside_none_reads_as_all_and_check_says_the_clause_gives_both(tmp_path, capsys):
    path = _pendulum(tmp_path, '"NONE" "ALL"')
    assert _said(path) == ([], [BOTH], HINGE_OUTPUTS)
    assert cli_main(["check", path]) == 0
    assert f"{path}:25:11: warning: SingleAxisHingeJoint Pivot.forceOutput: {BOTH}" in capsys.readouterr().out.splitlines()


@needs_ode
def test_validate_holds_neither_reading_of_all_beside_none_against_a_trace(tmp_path, capsys):
    """ODE's trace has the hinge's outputs (x3drbp's reading, ALL); the same trace without them is
    a browser that reads NONE. Each agrees with ODE's run: neither reading is a fault."""
    path = _pendulum(tmp_path, '"ALL" "NONE"')
    full = tmp_path / "all.csv"
    assert cli_main(["run", path, "--backend", "ode", "--duration", "0.25", "--trace", str(full)]) == 0
    lines = full.read_text().splitlines()
    assert {ln.split(",")[2] for ln in lines if ",Pivot," in ln} == set(HINGE_OUTPUTS)
    none = tmp_path / "none.csv"
    none.write_text("\n".join(ln for ln in lines if ",Pivot," not in ln) + "\n")
    capsys.readouterr()
    for trace in (full, none):
        assert cli_main(["validate", path, "--trace", str(trace), "--against", "ode"]) == 0, trace
        assert "| ode | agrees |" in capsys.readouterr().out
