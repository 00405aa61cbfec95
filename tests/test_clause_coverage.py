"""docs/clause-coverage.md is current, and every statement of clause 37 has a standing: checked by
a case, or given in conformance.clause_coverage as a gap (what would show it), a statement only
input events show, or a reason none can; no entry there names a statement the text lacks, or one a
case now checks.

The statements are made from the clause's text and the field findings from the X3D Unified
Object Model (conformance.coverage): both ship with the project's shared folder, not with x3drbp,
so the tests skip where either is absent.
"""

from __future__ import annotations

import functools
import os

import pytest

from conformance import case_bases, clause_coverage, clause_statements, clause_text
from conformance.cases import BY_NAME, CASES
from conformance.results import SPEC
from x3d_core.model import clause37
from x3d_core.model import uom

pytestmark = pytest.mark.skipif(
    not (os.path.isfile(clause_text.TEXT) and os.path.isfile(uom.UOM)),
    reason=f"clause 37's text ({clause_text.TEXT}) or the X3D Unified Object Model ({uom.UOM}) is not here (they "
           "ship with the project's shared folder, not with x3drbp): the page is generated from both")


@functools.cache
def _clause() -> clause_statements.Clause:
    return clause_statements.read(clause_text.read())


@functools.cache
def _table() -> tuple[clause_coverage.Standing, ...]:
    return tuple(clause_coverage.standings(_clause()))


def test_the_committed_page_is_current():
    with open(clause_coverage.PAGE, encoding="utf-8") as f:
        committed = f.read()
    assert committed == clause_coverage.render(list(_table())), "run .venv/bin/python -m conformance.clause_coverage"


def test_every_statement_has_a_standing():
    none = [s.statement.id for s in _table() if not s.kind]
    assert not none, f"statements neither checked nor in clause_coverage's GAPS, INPUT_EVENTS or REASONS: {none}"


def test_no_entry_outlives_its_check_or_names_no_statement():
    ids = {s.statement.id for s in _table()}
    checked = {s.statement.id for s in _table() if s.kind == clause_coverage.CHECKED}
    entries = [(kind, key) for kind, d in clause_coverage.ENTRIES for key in d]
    assert not [k for _, k in entries if k not in ids], "entries for no statement of the text"
    assert not [k for _, k in entries if k in checked], "checked now: drop these entries"
    keys = [k for _, k in entries]
    assert len(keys) == len(set(keys)), "a statement with two standings"


def test_the_statements_are_the_text_s():
    """Unique ids; every signature row is one; sentences are the prose's, signatures and table
    titles left out; Table 37.3's rows are its twenty."""
    statements = _clause().statements
    ids = [s.id for s in statements]
    assert len(ids) == len(set(ids))
    rows = [s for s in statements if s.row is not None]
    assert len(rows) == sum(len(sig.rows) for sig in clause37.signatures(clause_text.read()))
    prose = [s.text for s in statements if s.row is None]
    assert not [t for t in prose if " : " in t and "{" in t], "a signature read as prose"
    assert not [t for t in prose if clause_statements.TITLE.match(t)], "a table title read as a sentence"
    assert len([s for s in statements if s.id.startswith("Table 37.3/")]) == 20


def test_every_spec_basis_a_case_is_held_to_quotes_statements():
    """A basis matches the listed sentences (or its case would be credited with nothing)."""
    lost = [(c.name, name) for c in CASES for name, b in case_bases.held_to(c).items()
            if b.kind == SPEC and not _clause().quoted(b.text)]
    assert not lost


def test_a_case_is_held_to_the_bases_of_the_helpers_it_calls():
    """free_fall names GRAVITY and calls ballistic, which holds the clock to CLOCK."""
    assert {"closed_forms.GRAVITY", "closed_forms.CLOCK"} <= set(case_bases.held_to(BY_NAME["free_fall"]))
