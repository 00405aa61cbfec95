"""Every backend's declared table speaks x3d_core.semantics.analysis's feature names, and nothing else:
a misspelt name would leave the real feature undeclared, and so refused."""

from __future__ import annotations

import pytest

from backends import base
from x3d_core.model.schema import node_type
from x3d_core.semantics.applied import CANONICAL

# names analysis derives beyond TYPE and TYPE.field
DERIVED = {"inertia.offDiagonal", "limits"}
PREFIXED = {"massDensityModel": ("Box", "Sphere", "Cone"), "appliedParameters": CANONICAL,
            "set_contacts": ("fromSensor", "fromOtherCollider"), "collider": ("watchedOnly",)}

BACKENDS = [b for b in base.available().values() if not isinstance(b, str)]


def is_feature_name(name: str) -> bool:
    kind, _, rest = name.partition(".")
    spec = node_type(kind)
    if spec is None:
        return False
    if not rest or rest in DERIVED or rest in spec.fields:
        return True
    head, _, tail = rest.partition(".")
    if head == "geometry" and kind == "CollidableShape":
        return node_type(tail) is not None and node_type(tail).is_a("X3DGeometryNode")
    return head in PREFIXED and tail in PREFIXED[head]


def test_the_evaluators_table_uses_feature_names():
    assert [n for n in base.EVALUATOR if not is_feature_name(n)] == []


@pytest.mark.parametrize("backend", BACKENDS, ids=lambda b: b.name)
def test_declared_names_are_feature_names(backend):
    assert [n for n in backend.declared if not is_feature_name(n)] == []
