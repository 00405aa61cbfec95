"""The contact cases' bases: where the spec is silent (the contact normal's direction, which tangent
is friction direction 1) a trace of the other convention passes the spec measures and fails only
convention measures; a trace that breaks the spec fails a spec measure. Real ODE runs, transformed."""

from __future__ import annotations

import pytest

from x3d_core.traces.trace import Row, TraceView, read_trace

import conformance.cases as C
from conformance import results
from conformance.runner import probe, verdicts

MINE = ("bounce_apex", "incline", "anisotropic_friction", "conveyor", "resting_penetration", "box_stack",
        "collision_filtering", "routed_contacts", "sensor_geometry", "newtons_cradle", "contact_unapplied",
        "collidable_layout")
CASES = {c.name: c for c in C.CASES if c.name in MINE}

_ODE = probe.backend_table().get("ode")
pytestmark = pytest.mark.skipif(_ODE is None or not _ODE.usable, reason="ODE is not installed")


@pytest.fixture(scope="module")
def ode_runs(tmp_path_factory):
    """Each case's result on ODE and its trace's rows."""
    folder = str(tmp_path_factory.mktemp("ode"))
    found = verdicts.run_many([lambda c=c: verdicts.run_pair(c, "ode", keep=folder) for c in CASES.values()])
    return {c.name: (r, read_trace(f"{folder}/{c.name}-ode.csv")) for c, r in zip(CASES.values(), found)}


def _vec(text: str) -> list[float]:
    return [float(x) for x in text.split()]


def _text(v) -> str:
    return " ".join(repr(float(x)) for x in v)


def _edit(rows: list[Row], node: str, suffix: str, f) -> list[Row]:
    """The rows with node's fields ending in suffix mapped by f (on their vectors)."""
    return [Row(r.time, r.node, r.field, _text(f(_vec(r.value)))) if r.node == node and r.field.endswith(suffix)
            else r for r in rows]


def _judge(case: str, rows: list[Row]) -> tuple[str, list[results.Measure]]:
    c = CASES[case]
    measures = c.expect([TraceView(rows)], c.runs)
    return results.judge(measures), measures


def _failing(measures, kind):
    return [m.quantity for m in measures if not m.ok and (m.basis.kind == kind)]


def test_every_measure_of_the_contact_cases_has_a_basis(ode_runs):
    for name, (r, rows) in ode_runs.items():
        assert r.verdict in results.JUDGED, (name, r.verdict, r.reason)
        measures = CASES[name].expect([TraceView(rows)], CASES[name].runs)
        assert measures, name
        for m in measures:
            assert m.basis is not None and m.basis.text.strip(), (name, m.quantity)
            if m.basis.kind == results.SPEC:
                assert m.basis.text.startswith("37."), (name, m.quantity, m.basis.text)


def test_contact_normal_towards_geometry1_breaks_the_clause_s_direction(ode_runs):
    """37.2.5.3: "a unit vector describing the surface normal from body 1 to body 2" (Xj3D's and
    X_ITE's normal, ODE's and Bullet's own, points the other way)."""
    _, rows = ode_runs["sensor_geometry"]
    assert _judge("sensor_geometry", rows)[0] == results.PASS
    verdict, measures = _judge("sensor_geometry", _edit(rows, "Sensor", ".contactNormal", lambda n: [-x for x in n]))
    assert verdict == results.FAIL
    assert _failing(measures, results.SPEC) == [
        "contacts whose contactNormal does not point from geometry1 towards geometry2"]
    # a normal off the contact's axis breaks the spec: "a unit vector describing the normal"
    verdict, measures = _judge("sensor_geometry", _edit(rows, "Sensor", ".contactNormal", lambda n: [0.6, 0.8, 0.0]))
    assert verdict == results.FAIL
    assert "contactNormal - (0, 1, 0) or (0, -1, 0), the nearer (worst contact)" in _failing(measures, results.SPEC)


def test_a_disabled_space_that_still_collides_breaks_its_sentence(ode_runs):
    """X3DNBodyCollisionSpaceNode (printed 37.3.1): "The enabled field specifies whether the collision
    space is to be considered during collision processing." OffSpace held at its start, as its disabled
    space's floor would hold it, fails a spec measure (it was the UOM's description: conventions)."""
    _, rows = ode_runs["collidable_layout"]
    assert _judge("collidable_layout", rows)[0] == results.PASS
    start = next(r.value for r in rows if r.node == "OffSpace" and r.field == "position")
    held = [Row(r.time, r.node, r.field, start if r.field == "position" else "0.0 0.0 0.0")
            if r.node == "OffSpace" and r.field in ("position", "linearVelocity") else r for r in rows]
    verdict, measures = _judge("collidable_layout", held)
    assert verdict == results.FAIL
    assert any(q.startswith("OffSpace") for q in _failing(measures, results.SPEC)), _failing(measures, results.SPEC)


def test_surface_speed_along_the_other_direction_is_a_convention(ode_runs):
    _, rows = ode_runs["conveyor"]
    assert _judge("conveyor", rows)[0] == results.PASS
    for turn in (lambda v: [-v[0], v[1], v[2]], lambda v: [v[2], v[1], -v[0]]):  # +x, or +z
        verdict, measures = _judge("conveyor", _edit(rows, "Parcel", "linearVelocity", turn))
        assert verdict == results.CONVENTIONS
        assert _failing(measures, results.CONVENTION) == [
            "Parcel.linearVelocity along ODE's first friction direction [-1.0, 0.0, 0.0]"]
    # the belt ignored: the parcel never moves
    verdict, measures = _judge("conveyor", _edit(rows, "Parcel", "linearVelocity", lambda v: [0.0, 0.0, 0.0]))
    assert verdict == results.FAIL and _failing(measures, results.SPEC)


def _differs_in(case: str, rows: list[Row]) -> list[str]:
    """The convention measures a trace that conforms fails, sorted."""
    verdict, measures = _judge(case, rows)
    assert verdict == results.CONVENTIONS
    return sorted(_failing(measures, results.CONVENTION))


def test_friction_axes_swapped_or_along_the_motion_is_a_convention(ode_runs):
    _, rows = ode_runs["anisotropic_friction"]
    assert _judge("anisotropic_friction", rows)[0] == results.PASS
    # direction 1 along +z, direction 2 along -x: Along1 (pushed along -x) slows at mu2 g, Along2 at mu1 g
    v1 = {r.time: _vec(r.value) for r in rows if r.node == "Along1" and r.field == "linearVelocity"}
    v2 = {r.time: _vec(r.value) for r in rows if r.node == "Along2" and r.field == "linearVelocity"}
    as_along2 = {"Along2": lambda t: [v1[t][2], v1[t][1], -v1[t][0]]}  # Along1's motion turned onto +z
    swapped = {"Along1": lambda t: [-v2[t][2], v2[t][1], v2[t][0]], **as_along2}

    def moved(how) -> list[Row]:
        return [Row(r.time, r.node, r.field, _text(how[r.node](r.time)))
                if r.node in how and r.field == "linearVelocity" else r for r in rows]
    assert _differs_in("anisotropic_friction", moved(swapped)) == [
        "Along1.linearVelocity (mu1 = 0.2 along ODE's friction direction 1, [-1.0, 0.0, 0.0])",
        "Along2.linearVelocity (mu2 = 0.6 along ODE's friction direction 2, [0.0, 0.0, 1.0])"]
    # direction 1 along the sliding velocity (Bullet's): both boxes slow at mu1 g, Along2 as Along1 does
    assert _differs_in("anisotropic_friction", moved(as_along2)) == [
        "Along2.linearVelocity (mu2 = 0.6 along ODE's friction direction 2, [0.0, 0.0, 1.0])",
        "Along2.linearVelocity, the two boxes one coefficient each (the better assignment)"]
    # a coefficient the scene does not give (X_ITE's 0.5 where it reads none): Along1 slows at 4.9 m/s^2,
    # neither mu1 g (1.96) nor mu2 g (5.89)
    verdict, measures = _judge("anisotropic_friction",
                               moved({"Along1": lambda t: [-max(3.0 - 0.5 * 9.81 * t, 0.0), 0.0, 0.0]}))
    assert verdict == results.FAIL
    assert _failing(measures, results.SPEC) == ["Along1.linearVelocity slows at mu1 g or mu2 g"]
    # friction ignored: both boxes keep their push
    ignored = _edit(_edit(rows, "Along1", "linearVelocity", lambda v: [-3.0, 0.0, 0.0]),
                    "Along2", "linearVelocity", lambda v: [0.0, 0.0, 3.0])
    verdict, measures = _judge("anisotropic_friction", ignored)
    assert verdict == results.FAIL and len(_failing(measures, results.SPEC)) == 2


def test_a_contact_s_applied_parameters_read_in_either_spelling_and_any_order(ode_runs):
    """contact_unapplied: what the clause leaves free (the spelling of a name, the order of an
    MFString) passes; a Contact that carries what was applied, its own default appliedParameters
    or a friction direction where there is no friction breaks a spec sentence."""
    _, rows = ode_runs["contact_unapplied"]
    assert _judge("contact_unapplied", rows)[0] == results.PASS

    def texts(field: str, value: str) -> list[Row]:
        return [Row(r.time, r.node, r.field, value) if r.node == "Sensor" and r.field.endswith(field) else r
                for r in rows]
    for free in ('"FRICTION_COEFFICIENT_2"', '"FRICTION_COEFFICIENT-2" "FRICTION_COEFFICIENT_2"'):
        assert _judge("contact_unapplied", texts(".appliedParameters", free))[0] == results.PASS, free
    for broken, measure in (
            (texts(".appliedParameters", '"BOUNCE"'), "contacts whose appliedParameters are not the collection's"),
            (texts(".appliedParameters", ""), "contacts whose appliedParameters are not the collection's"),
            (texts(".bounce", "0"), "contacts whose parameters are not the collection's"),  # BOUNCE is not applied
            (texts(".surfaceSpeed", "0 0"), "contacts whose parameters are not the collection's"),
            (texts(".frictionDirection", "-1 0 0"), "contacts without friction whose frictionDirection is not 0 0 0")):
        verdict, measures = _judge("contact_unapplied", broken)
        assert verdict == results.FAIL and _failing(measures, results.SPEC) == [measure], measure
