"""The node definitions against the X3D Unified Object Model 4.0 itself."""

from __future__ import annotations

import os

import numpy as np
import pytest
from lxml import etree

from conftest import UOM
from x3d_core.model import fields as F
from x3d_core.model import standard_nodes
from x3d_core.model.schema import NODE_TYPES, definition, node_type, standard_names
from x3d_core.model.uom import STATEMENTS, field_type, generate, interface_fields, parents
from x3d_core.model.uom import default as uom_default

RBP = ["RigidBodyCollection", "RigidBody", "BallJoint", "SingleAxisHingeJoint", "DoubleAxisHingeJoint",
       "SliderJoint", "UniversalJoint", "MotorJoint", "CollisionCollection", "CollisionSpace", "CollisionSensor",
       "CollidableShape", "CollidableOffset", "Contact",
       "X3DRigidJointNode", "X3DNBodyCollidableNode", "X3DNBodyCollisionSpaceNode"]
# Where x3drbp's range is the spec's and the UOM gives none, or the UOM's rounds pi:
# listed so that any other difference fails.
SPEC_RANGES = {"mass", "errorCorrection", "constantForceMix", "contactSurfaceThickness", "iterations",
               "maxCorrectionSpeed", "disableAngularSpeed", "disableLinearSpeed", "angularDampingFactor",
               "linearDampingFactor", "finiteRotationAxis", "minAngle", "maxAngle", "minAngle1", "maxAngle1",
               "axis1Angle", "axis2Angle", "axis3Angle", "stopBounce", "stop1Bounce", "stop2Bounce", "stop3Bounce",
               "stopErrorCorrection", "stop1ErrorCorrection", "stop2ErrorCorrection", "stop3ErrorCorrection",
               "stop1ConstantForceMix", "suspensionErrorCorrection", "suspensionForce", "size", "xSpacing",
               "zSpacing"}


@pytest.fixture(scope="module")
def uom():
    if not os.path.exists(UOM):
        pytest.skip(f"the X3D Unified Object Model is not at {UOM} (it ships with the project's shared "
                    "reference folder, not with x3drbp)")
    return etree.parse(UOM)


def uom_fields(uom, name):
    el = uom.xpath(f'//ConcreteNode[@name="{name}"] | //AbstractNodeType[@name="{name}"]')
    assert el, f"{name} is not in the UOM"
    return interface_fields(el[0])


@pytest.mark.parametrize("name", RBP)
def test_rigid_body_physics_node_matches_uom(uom, name):
    ours = NODE_TYPES[name]
    theirs = uom_fields(uom, name)
    if ours.abstract:
        assert set(ours.fields) == set(theirs), f"{name}: fields differ"
    else:
        assert set(ours.fields) == set(theirs), \
            f"{name}: missing {set(theirs) - set(ours.fields)}, extra {set(ours.fields) - set(theirs)}"
    for fname, f in theirs.items():
        fd = ours.fields[fname]
        assert fd.type.name == f.get("type"), f"{name}.{fname} type"
        assert fd.access == f.get("accessType"), f"{name}.{fname} access"
        assert F.values_equal(fd.type, fd.default, uom_default(f, fd.type)) or (
            # the UOM writes pi as 3.141592653; x3drbp keeps every digit
            fd.type.name == "SFFloat" and abs(fd.default - uom_default(f, fd.type)) < 1e-9), \
            f"{name}.{fname} default {fd.default!r}"
        accepted = f.get("acceptableNodeTypes")
        if accepted and fd.type.kind == "node":
            assert fd.accepts == tuple(accepted.split("|")), f"{name}.{fname} accepted node types"


def test_every_typed_node_agrees_with_uom(uom):
    """Supporting nodes: every field x3drbp defines exists in the UOM with the same
    type, access, default, and the UOM's range where it states one."""
    for name, t in NODE_TYPES.items():
        if t.abstract and name not in RBP:
            continue
        theirs = uom_fields(uom, name)
        for fname, fd in t.fields.items():
            assert fname in theirs, f"{name}.{fname} is not in the UOM"
            f = theirs[fname]
            assert (fd.type.name, fd.access) == (f.get("type"), f.get("accessType")), f"{name}.{fname}"
            d = uom_default(f, fd.type)
            assert F.values_equal(fd.type, fd.default, d) or np.allclose(fd.default, d, atol=1e-9), \
                f"{name}.{fname} default"
            lo = f.get("minInclusive") or f.get("minExclusive")
            hi = f.get("maxInclusive") or f.get("maxExclusive")
            if (lo is not None or hi is not None) and fname not in SPEC_RANGES:
                assert fd.range is not None, f"{name}.{fname}: the UOM gives a range"
                if lo is not None:
                    assert fd.range.lo == float(lo) and fd.range.lo_open == (f.get("minExclusive") is not None)
                if hi is not None:
                    assert fd.range.hi == float(hi) and fd.range.hi_open == (f.get("maxExclusive") is not None)


def test_component_has_fourteen_concrete_and_three_abstract_types():
    rbp = [t for t in NODE_TYPES.values() if t.name in RBP]
    assert sum(not t.abstract for t in rbp) == 14
    assert sum(t.abstract for t in rbp) == 3


def test_standard_nodes_table_is_what_the_uom_gives(uom):
    """x3d_core/model/standard_nodes.py is the generator's output for this UOM and node_defs.py
    (stale after either changes: regenerate with python -m x3d_core.model.uom)."""
    with open(standard_nodes.__file__, encoding="utf-8") as f:
        assert f.read() == generate(uom), "x3d_core/model/standard_nodes.py is stale: run python -m x3d_core.model.uom"


def test_every_x3d4_type_derives_as_the_uom_says(uom):
    """Every X3D 4.0 type, hand-written or generated, is served with the UOM's parents, and
    every concrete one with its default containerField; nothing else is generated."""
    generated = set()
    for el in uom.iter("AbstractNodeType", "AbstractObjectType", "ConcreteNode"):
        name = el.get("name")
        if name in STATEMENTS:
            continue
        t = definition(name)
        assert t is not None and t.parents == tuple(parents(el)), name
        assert t.abstract == (el.tag != "ConcreteNode"), name
        if not t.abstract:
            assert t.container_field == el.find("InterfaceDefinition/containerField").get("default"), name
        if name not in NODE_TYPES:
            generated.add(name)
    assert generated == set(standard_names())


def test_every_generated_node_type_has_the_uoms_fields(uom):
    """What the table's text reads back as, field by field, against the UOM's own values."""
    for el in uom.iter("ConcreteNode"):
        name = el.get("name")
        if name in NODE_TYPES or name in STATEMENTS:
            continue
        t = node_type(name)
        comp = el.find("InterfaceDefinition/componentInfo")
        assert t.component == f"{comp.get('name')} {comp.get('level')}", name
        theirs = interface_fields(el)
        assert list(t.fields) == list(theirs), name
        for fname, f in theirs.items():
            fd = t.fields[fname]
            assert (fd.type, fd.access, fd.range, fd.unit) == (field_type(f), f.get("accessType"), None, None), \
                f"{name}.{fname}"
            assert F.values_equal(fd.type, fd.default, uom_default(f, fd.type)), f"{name}.{fname} default"
            accepted = f.get("acceptableNodeTypes")
            assert fd.accepts == (tuple(accepted.split("|")) if accepted and fd.type.kind == "node" else ()), \
                f"{name}.{fname} accepted node types"
