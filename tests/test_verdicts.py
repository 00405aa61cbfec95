"""Verdicts split by basis: a spec measure failing violates the spec; convention measures
failing alone leave an implementation conforming, with the readings it differs on named."""

from __future__ import annotations

import pytest

from conformance.results import (CONVENTIONS, FAIL, PASS, Basis, Measure, Result, convention, judge,
                                 spec)

SPEC = spec("37.4.9 RigidBody: bodies fall under gravity")
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
    assert r.meaning() == ("conforms, differs in conventions: Hinge.angle sign (angle of body1 relative to body2 "
                           "(ODE); Xj3D and X_ITE alike, the reverse is as legitimate): error 3 rad > tolerance 1 rad")
    r = Result("c", "b", FAIL, "", _measures(False, False))
    assert r.meaning() == ('violates the spec: Ball.position ("37.4.9 RigidBody: bodies fall under gravity"): '
                           "error 2 m > tolerance 1 m")
    assert Result("c", "b", PASS, "", _measures(True, True)).meaning() == "conforms"
    assert Result("c", "b", "unsupported", "X.y: no").meaning() == "unsupported: X.y: no"


def test_a_basis_says_which_and_why():
    with pytest.raises(ValueError):
        Basis("opinion", "x")
    with pytest.raises(ValueError):
        spec("  ")
    m = Measure("q", 1.0, 2.0, "m", ODE).to_json()
    assert m["basis"] == "convention" and m["basis_text"].startswith("angle of body1")
