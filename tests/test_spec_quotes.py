"""Every spec basis of the cases quotes clause 37 as a reader can find it: the edition, then
"37.x.y Name: " (a clause-37 node, or a 37.2 concept), then whole sentences, uncut.

The bases are the module-level Basis constants of each case package and of closed_forms.py,
where the measures' quotes are defined (an expectation only picks them).
"""

from __future__ import annotations

import importlib
import re
import types

import pytest

from conformance.cases import CASES
from conformance.results import EDITIONS, SPEC, Basis
from x3d_core import schema

# ISO/IEC 19775-1 clause 37: 37.2's concepts (Table 37.1), 37.3's abstract types and 37.4's
# nodes, one subclause each in alphabetical order (37.3.1 X3DNBodyCollidableNode ...,
# 37.4.1 BallJoint ... 37.4.14 UniversalJoint)
CONCEPTS = {"37.2.1": "Overview", "37.2.2": "Bodies", "37.2.3": "Joints", "37.2.4": "Coordinate systems"}
ABSTRACT = ("X3DNBodyCollidableNode", "X3DNBodyCollisionSpaceNode", "X3DRigidJointNode")  # schema's, sorted
NODES = sorted(n for n, t in schema.NODE_TYPES.items() if t.component.startswith("RigidBodyPhysics") and not t.abstract)
CLAUSES = (CONCEPTS | {f"37.3.{i}": name for i, name in enumerate(ABSTRACT, 1)}
           | {f"37.4.{i}": name for i, name in enumerate(NODES, 1)})
HEAD = re.compile(r"^(37(?:\.\d+)+) ([A-Za-z][A-Za-z0-9 ]*?): \S")


def _modules() -> list[types.ModuleType]:
    return [importlib.import_module("conformance.cases.closed_forms"),
            *(importlib.import_module(f"conformance.cases.{c.name}") for c in CASES)]


def _spec_bases() -> list[tuple[str, Basis]]:
    return [(f"{m.__name__.rsplit('.', 1)[-1]}.{name}", value) for m in _modules()
            for name, value in vars(m).items() if isinstance(value, Basis) and value.kind == SPEC]


SPEC_BASES = _spec_bases()


def test_the_abstract_types_are_the_schema_s():
    assert all(schema.NODE_TYPES[n].abstract for n in ABSTRACT) and list(ABSTRACT) == sorted(ABSTRACT)


def test_the_cases_quote_the_clause():
    assert len(SPEC_BASES) > 20  # the scan finds the constants (an import change would empty it)


@pytest.mark.parametrize("where, basis", SPEC_BASES, ids=[w for w, _ in SPEC_BASES])
def test_spec_basis_names_its_clause_and_edition(where: str, basis: Basis):
    assert basis.source in EDITIONS, f"{where}: no edition ({basis.source!r})"
    head = HEAD.match(basis.text)
    assert head, f"{where}: does not start '37.x.y Name: ': {basis.text[:60]!r}"
    number, name = head.groups()
    assert CLAUSES.get(number) == name, f"{where}: {number} is {CLAUSES.get(number)!r}, not {name!r}"
    assert "..." not in basis.text and "\u2026" not in basis.text, f"{where}: cut with an ellipsis"
    assert basis.text.rstrip().endswith((".", ")")), f"{where}: does not end a sentence"
