"""docs/field-coverage.md is current, and every field of clause 37's nodes is accounted for:
covered by a case's mutation, judged as an output, given a reason, or named as a gap; the
fields a case is being written for (coverage.PENDING) fail until it lands."""

from __future__ import annotations

import functools
import os

import pytest

from conformance import coverage
from x3d_core.model import uom

pytestmark = pytest.mark.skipif(not os.path.exists(uom.UOM), reason=(
    f"the X3D Unified Object Model is not at {uom.UOM} (it ships with the project's shared folder): "
    "the table is generated from it"))


@functools.cache
def _table() -> tuple[coverage.Row, ...]:
    return tuple(coverage.rows())


def test_the_committed_table_is_current():
    with open(coverage.TABLE, encoding="utf-8") as f:
        committed = f.read()
    assert committed == coverage.render(list(_table())), "run .venv/bin/python -m conformance.coverage"


def test_every_field_is_accounted_for():
    unexplained = [r.key for r in _table() if not coverage.kind(r)]
    assert not unexplained, f"fields with no case, reason or gap entry: {unexplained}"


def test_no_reason_or_gap_outlives_its_coverage():
    stale = [r.key for r in _table() if (r.covered or r.judged) and
             (r.key in coverage.REASONS or r.key in coverage.UNCOVERED)]
    assert not stale, f"covered now: drop them from coverage.REASONS / UNCOVERED: {stale}"


def test_every_entry_names_a_field():
    keys = {r.key for r in _table()}
    unknown = [k for k in [*coverage.REASONS, *coverage.UNCOVERED, *coverage.PENDING]
               if k.count(".") == 1 and k not in keys]
    assert not unknown, f"no such field of a clause-37 node: {unknown}"


def test_nothing_pending():
    waiting = coverage.open_pending(list(_table()))
    assert not waiting, f"still waiting for their case: {waiting}"
