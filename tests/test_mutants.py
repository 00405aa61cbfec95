"""The suite kills the mutant engines it should, and the wrapping alone changes nothing.

Each mutant (conformance/mutants/table.py) runs, as a plug-in backend in its own child process,
on the cases its row says kill it; its base runs on them too, live (its pins may be in flux),
and so does the identity mutant, which must give the base's verdict on every one of them. The
full score, over every case, is `python -m conformance.mutants` (docs/mutation-score.md).
"""

from __future__ import annotations

import importlib.metadata

import pytest

from backends import base
from conformance import cases as C
from conformance import coverage
from conformance.results import BLEW_UP, CONVENTION, CONVENTIONS, FAIL, PASS, SPEC, UNSUPPORTED, Result
from conformance.runner import verdicts

from conformance.mutants import report, site
from conformance.mutants.score import REFUSED, Fate, Score, worse
from conformance.mutants.table import BASES, BY_NAME, CONTROLS, MUTANTS

try:
    for b in BASES:
        base.load(b)
    MISSING = ""
except ImportError as e:
    MISSING = str(e)
needs_bases = pytest.mark.skipif(bool(MISSING), reason=f"a base backend is unavailable: {MISSING}")
KILLERS = sorted({c for m in MUTANTS for c in m.kills})


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """The mutants' site, first on the PYTHONPATH the runner's children inherit."""
    folder = site.install(str(tmp_path_factory.mktemp("mutants")))
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("PYTHONPATH", site.on_path(folder))
        mp.syspath_prepend(folder)
        base._registry.cache_clear()
        yield folder
    base._registry.cache_clear()


@pytest.fixture(scope="module")
def verdict(installed) -> dict[tuple[str, str], str]:
    """(case, backend) -> verdict: each base and identity mutant on every killing case, each
    mutant on its own; run together, in parallel."""
    pairs = [(c, b) for c in KILLERS for b in (*BASES, *(m.backend for m in CONTROLS))]
    pairs += [(c, m.backend) for m in MUTANTS for c in m.kills]
    results = verdicts.run_many([(lambda c=c, b=b: verdicts.run_pair(C.BY_NAME[c], b)) for c, b in pairs], 2)
    return {(r.case, r.backend): r.verdict for r in results}


def test_a_verdict_worse_than_the_base_kills():
    assert worse(FAIL, PASS) and worse(CONVENTIONS, PASS) and worse(FAIL, CONVENTIONS)
    assert worse(BLEW_UP, PASS) and worse(UNSUPPORTED, CONVENTIONS)  # the base ran: a refusal is a change
    assert not worse(PASS, PASS) and not worse(CONVENTIONS, CONVENTIONS) and not worse(PASS, CONVENTIONS)
    assert not worse(BLEW_UP, FAIL) and not worse(FAIL, UNSUPPORTED)  # where the base fails or never ran: nothing


def test_a_kill_says_whether_a_spec_measure_turned_or_a_convention_alone():
    """A kill to fail turns a sentence of the clause; one to conventions alone only a reading where it is
    silent; one that only stops the run (a refusal, a crash) neither. The report counts each."""
    mutant = MUTANTS[0]

    def fate(*verdicts: str) -> Fate:
        return Fate(mutant, [(Result(f"case{k}", mutant.backend, v), PASS) for k, v in enumerate(verdicts)])
    spec_kill, convention_kill = fate(CONVENTIONS, FAIL, PASS), fate(CONVENTIONS, PASS)
    refused, survivor = fate(UNSUPPORTED, CONVENTIONS), fate(PASS)
    assert [f.turned for f in (spec_kill, convention_kill, refused, survivor)] == [SPEC, CONVENTION, REFUSED, None]
    score = Score([spec_kill, convention_kill, refused, survivor], [], {}, 1.0)
    head = report.markdown(score, 3).splitlines()[0]
    assert ("3 of 4 mutants killed (75%)**, 1 by a spec measure, 1 by a convention alone, 1 by a refusal or crash "
            "alone") in head
    assert report.to_json(score, [])["by_convention"] == 1


def test_every_mutant_is_killed_by_its_cases_or_names_its_gap():
    assert len(MUTANTS) >= 30 and len(BY_NAME) == len(MUTANTS) + len(CONTROLS)
    for m in MUTANTS:
        assert bool(m.kills) != bool(m.gap), m.name
        assert set(m.kills) <= set(C.BY_NAME), m.name
        assert m.world is not None or m.relay is not None, m.name
        assert m.bug and m.models and m.base in base.IN_TREE, m.name
        assert not m.fields or coverage.credited(m), f"{m.name}: none of its kills sets {m.fields}"


def test_the_site_declares_every_mutant_as_a_backend(installed):
    assert site.GROUP == base.GROUP
    found = {ep.name: ep.value for ep in importlib.metadata.entry_points(group=base.GROUP)
             if ep.dist is not None and ep.dist.name == "x3drbp-mutants"}
    assert found == {m.backend: f"conformance.mutants.plugin:{m.attribute}" for m in BY_NAME.values()}
    assert set(found) <= set(base.engines())


@needs_bases
def test_a_mutant_backend_declares_what_its_base_does(installed):
    identity, real = base.load(CONTROLS[0].backend), base.load(CONTROLS[0].base)
    assert identity.table() == real.table() and identity.name == CONTROLS[0].backend
    assert identity.version().startswith(f"{CONTROLS[0].base} {real.version()}")


@needs_bases
@pytest.mark.parametrize("control", CONTROLS, ids=lambda m: m.name)
def test_the_identity_mutant_changes_no_verdict(verdict, control):
    changed = {c: (verdict[(c, control.base)], verdict[(c, control.backend)]) for c in KILLERS
               if verdict[(c, control.backend)] != verdict[(c, control.base)]}
    assert not changed


@needs_bases
@pytest.mark.parametrize("mutant", [m for m in MUTANTS if m.kills], ids=lambda m: m.name)
def test_the_mutant_is_killed(verdict, mutant):
    spared = {c: (verdict[(c, mutant.base)], verdict[(c, mutant.backend)]) for c in mutant.kills
              if not worse(verdict[(c, mutant.backend)], verdict[(c, mutant.base)])}
    assert not spared, f"{mutant.name} ({mutant.bug}) survives (base, mutant verdicts): {spared}"
    # a kill by conventions alone says why the clause cannot judge the bug; a mutant that says so is never a fail
    got = {verdict[(c, mutant.backend)] for c in mutant.kills}
    if FAIL in got:
        assert not mutant.silent, f"{mutant.name}: killed by a spec measure, yet its row says the clause is silent"
    elif got == {CONVENTIONS}:
        assert mutant.silent, f"{mutant.name}: killed by conventions alone: its row must say why the clause is silent"
    # the kills that cover its fields (docs/field-coverage.md) must each turn a spec measure
    unturned = {c: verdict[(c, mutant.backend)] for c in coverage.credited(mutant)
                if verdict[(c, mutant.backend)] != FAIL}
    assert not unturned, f"{mutant.name} covers {mutant.fields} by these kills, which must FAIL: {unturned}"
