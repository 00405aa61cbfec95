"""Verdicts split by basis: a spec measure failing violates the spec; convention or description
measures failing alone leave an implementation conforming, with the readings it differs on
named; accuracy is graded against its bound apart, and never changes a verdict."""

from __future__ import annotations

import pytest

from conformance.results import (CONVENTIONS, FAIL, PASS, Basis, Measure, Result, accuracy, convention,
                                 description, judge, spec)

SPEC = spec("37.4.10 RigidBody: bodies fall under gravity")
ODE = convention("angle of body1 relative to body2 (ODE); Xj3D and X_ITE alike, the reverse is as legitimate")


def _measures(spec_ok: bool, convention_ok: bool) -> list[Measure]:
    return [Measure("Ball.position", 0.0 if spec_ok else 2.0, 1.0, "m", SPEC),
            Measure("Hinge.angle sign", 0.0 if convention_ok else 3.0, 1.0, "rad", ODE)]


@pytest.mark.parametrize("spec_ok,convention_ok,verdict", [
    (True, True, PASS), (True, False, CONVENTIONS), (False, True, FAIL), (False, False, FAIL)])
def test_only_a_spec_measure_can_fail_a_case(spec_ok, convention_ok, verdict):
    assert judge(_measures(spec_ok, convention_ok)) == verdict


def test_a_measure_without_a_basis_is_held_as_the_spec():
    assert judge([Measure("x", 2.0, 1.0)]) == FAIL


def test_the_verdict_reads_as_people_say_it():
    r = Result("c", "b", CONVENTIONS, "", _measures(True, False))
    assert r.meaning() == ("conforms, differs in conventions: Hinge.angle sign (convention: angle of body1 relative "
                           "to body2 (ODE); Xj3D and X_ITE alike, the reverse is as legitimate): error 3 rad > "
                           "tolerance 1 rad")
    r = Result("c", "b", FAIL, "", _measures(False, False))
    assert r.meaning() == ('violates the spec: Ball.position (V3 pre-3.3, "37.4.10 RigidBody: bodies fall under '
                           'gravity"): error 2 m > tolerance 1 m')
    assert Result("c", "b", PASS, "", _measures(True, True)).meaning() == "conforms"
    assert Result("c", "b", "unsupported", "X.y: no").meaning() == "unsupported: X.y: no"


def test_accuracy_is_graded_apart_and_never_changes_the_verdict():
    graded = Measure("Bob.period", 0.003, 0.2, "s", SPEC, bound=0.001)  # within the spec, 3x the bound
    rigid = Measure("first step", 5e-4, 2e-7, "rad/s", accuracy("rigid joints: exact"))  # 2500x its bound
    r = Result("c", "b", judge([graded, rigid]), "", [graded, rigid])
    assert r.verdict == PASS and not r.failing()
    assert r.accuracy() == pytest.approx(2500) and [m.quantity for m in r.over_bound()] == ["Bob.period", "first step"]
    assert r.meaning() == "conforms; accuracy 2.5e+03x the bound (first step)"
    within = Result("c", "b", PASS, "", [Measure("Bob.period", 5e-4, 0.2, "s", SPEC, bound=0.001)])
    assert within.meaning() == "conforms; accuracy within the bound" and within.to_json()["accuracy"] == 0.5
    assert Result("c", "b", FAIL, "", [Measure("x", 2.0, 1.0, basis=SPEC, bound=0.5)]).accuracy() == 4.0


def test_a_description_is_a_weaker_basis_than_the_clause():
    uom = description("frictionCoefficients used for computing surface drag.")
    assert judge([Measure("slide", 2.0, 1.0, "m", uom)]) == CONVENTIONS
    assert uom.label() == "description (X3DUOM 4.0)" and SPEC.label() == "spec (V3 pre-3.3)"


def test_a_spec_basis_names_its_edition_and_is_not_cut():
    with pytest.raises(ValueError, match="edition"):
        spec("37.4.10 RigidBody: The mass field indicates the mass of the body.", "V3.3")
    with pytest.raises(ValueError, match="uncut"):
        spec("37.4.1 BallJoint: body1AnchorPoint and body2AnchorPoint ... can be used to detect a separation.")
    with pytest.raises(ValueError, match="source"):
        description("used for drag", "a blog")


def test_a_basis_says_which_and_why():
    with pytest.raises(ValueError):
        Basis("opinion", "x")
    with pytest.raises(ValueError):
        spec("  ")
    m = Measure("q", 1.0, 2.0, "m", ODE).to_json()
    assert m["basis"] == "convention" and m["basis_text"].startswith("angle of body1")
