"""Every spec basis of the cases quotes clause 37 as a reader can find it: the edition, then
"37.x.y Name: " (a subclause as the clause's text numbers and names it: a 37.2 concept, an
abstract type, a node), then whole sentences of that subclause, verbatim and uncut.

The bases are the module-level Basis constants of each case package and of closed_forms.py,
where the measures' quotes are defined (an expectation only picks them). The clause's text, the
one this project judges by, is ../shared/reference/clause37-rigid-body-physics.txt (from the
project root): it ships with the project's shared folder, not with x3drbp, so the tests that
read it skip where it is absent. conformance/clause_text.py cuts it into subclauses and
sentences, the cut docs/clause-coverage.md's statements are made by too.
"""

from __future__ import annotations

import functools
import importlib
import re
import types

import pytest

from conformance import clause_text
from conformance.cases import CASES
from conformance.clause_text import STOP, quoted
from conformance.results import EDITION, SPEC, Basis
from x3d_core.model import schema

# the subclauses of clause 37 (number, name) as its text heads them: 37.2's concepts, 37.3's
# abstract types (the text prints 37.3.1 twice, the second for X3DNBodyCollisionSpaceNode) and
# 37.4's nodes, alphabetical (37.4.1 BallJoint ... 37.4.14 UniversalJoint)
CONCEPTS = (("37.2.1", "Overview"), ("37.2.2", "Integration with X3D"), ("37.2.2.1", "Event model evaluation"),
            ("37.2.2.2", "Transformation hierarchy"), ("37.2.3", "Bodies"), ("37.2.4", "Joints"),
            ("37.2.4.1", "What a joint describes"), ("37.2.4.2", "Range of motion limits"),
            ("37.2.5", "Coordinate systems"), ("37.2.5.1", "Initial coordinate system"),
            ("37.2.5.2", "Breaking joints"), ("37.2.5.3", "Collision contact description"))
ABSTRACT = (("37.3.1", "X3DNBodyCollidableNode"), ("37.3.1", "X3DNBodyCollisionSpaceNode"),
            ("37.3.3", "X3DRigidJointNode"))
NODES = sorted(n for n, t in schema.NODE_TYPES.items() if t.component.startswith("RigidBodyPhysics") and not t.abstract)
CLAUSES = frozenset(CONCEPTS + ABSTRACT + tuple((f"37.4.{i}", name) for i, name in enumerate(NODES, 1)))


def _modules() -> list[types.ModuleType]:
    return [importlib.import_module("conformance.cases.closed_forms"),
            *(importlib.import_module(f"conformance.cases.{c.name}") for c in CASES)]


def _spec_bases() -> list[tuple[str, Basis]]:
    """Every spec quote of the cases: each basis's text, and each of its `also` quotes as a basis of its own."""
    found = [(f"{m.__name__.rsplit('.', 1)[-1]}.{name}", value) for m in _modules()
             for name, value in vars(m).items() if isinstance(value, Basis) and value.kind == SPEC]
    return [(where if k == 0 else f"{where}.also[{k - 1}]", Basis(SPEC, quote, basis.source))
            for where, basis in found for k, quote in enumerate(basis.quotes)]


SPEC_BASES = _spec_bases()


@functools.cache
def _subclauses() -> dict[tuple[str, str], tuple[str, ...]]:
    """The text's subclauses, (number, name) -> its paragraphs, whitespace-normalised: each up to
    the next heading of any level, so a quote is held to the subclause its head names."""
    text = clause_text.read()
    if text is None:
        pytest.skip(f"clause 37's text is not at {clause_text.TEXT} (it ships with the project's shared folder, "
                    "not with x3drbp)")
    return {sub.key: sub.paragraphs for sub in clause_text.subclauses(text)}


def test_the_abstract_types_are_the_schema_s():
    names = [name for _, name in ABSTRACT]
    assert all(schema.NODE_TYPES[n].abstract for n in names) and names == sorted(names)


def test_the_clauses_are_the_text_s():
    """CLAUSES numbers and names 37.2 to 37.4 as the text heads them, none missed."""
    assert CLAUSES == {k for k in _subclauses() if re.match(r"37\.[234]\.", k[0])}


def test_whole_sentences_are_whole():
    """The check that holds each quote: a run of sentences passes, a cut one does not; a numbered
    list is part of the sentence whose colon introduces it."""
    paragraphs = ["One is here. Two (e. g., this one) is there.", "body1 starts a paragraph.", "It has these:",
                  "1. one, and 2. two."]
    whole = ("One is  here.", "Two (e. g., this one) is there.", "Two (e. g., this one) is there. body1 starts a "
             "paragraph.", "It has these: 1. one, and 2. two.")
    cut = ("One is", "Two (e.", "g., this one) is there.", "is here.", "is there. body1 starts a paragraph.",
           "1. one, and 2. two.")
    assert all(quoted(q, paragraphs) is not None for q in whole)
    assert not any(quoted(q, paragraphs) is not None for q in cut)


def test_the_cases_quote_the_clause():
    assert len(SPEC_BASES) > 20  # the scan finds the constants (an import change would empty it)


@pytest.mark.parametrize("where, basis", SPEC_BASES, ids=[w for w, _ in SPEC_BASES])
def test_spec_basis_names_its_clause_and_edition(where: str, basis: Basis):
    assert basis.source == EDITION, f"{where}: not the clause text's edition ({basis.source!r})"
    head = clause_text.HEAD.match(basis.text)
    assert head, f"{where}: does not start '37.x.y Name: ': {basis.text[:60]!r}"
    assert head.groups() in CLAUSES, f"{where}: {' '.join(head.groups())} is no subclause of the text"
    assert "..." not in basis.text and "\u2026" not in basis.text, f"{where}: cut with an ellipsis"
    assert STOP.search(basis.text.rstrip()), f"{where}: does not end a sentence"


@pytest.mark.parametrize("where, basis", SPEC_BASES, ids=[w for w, _ in SPEC_BASES])
def test_spec_basis_quotes_its_subclause_verbatim(where: str, basis: Basis):
    split = clause_text.split_basis(basis.text)
    assert split, f"{where}: does not start '37.x.y Name: ': {basis.text[:60]!r}"
    (number, name), quote = split
    paragraphs = _subclauses().get((number, name))
    assert paragraphs is not None, f"{where}: the text has no subclause {number} {name}"
    assert quoted(quote, paragraphs) is not None, \
        f"{where}: not whole sentences of {number} {name} as the text has them: {quote!r}"
