"""The node definitions against the X3D Unified Object Model 4.0 itself."""

from __future__ import annotations

import os

import numpy as np
import pytest
from lxml import etree

from conftest import UOM
from x3d_core import fields as F
from x3d_core.schema import NODE_TYPES

RBP = ["RigidBodyCollection", "RigidBody", "BallJoint", "SingleAxisHingeJoint", "DoubleAxisHingeJoint",
       "SliderJoint", "UniversalJoint", "MotorJoint", "CollisionCollection", "CollisionSpace", "CollisionSensor",
       "CollidableShape", "CollidableOffset", "Contact",
       "X3DRigidJointNode", "X3DNBodyCollidableNode", "X3DNBodyCollisionSpaceNode"]
# Attributes of every XML element, not fields of a node; 'field' is Script's <field> element
NOT_FIELDS = {"DEF", "USE", "class", "id", "style", "IS", "field"}
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
    return {f.get("name"): f for f in el[0].find("InterfaceDefinition").findall("field")
            if f.get("name") not in NOT_FIELDS}


def uom_default(f, ftype):
    text = f.get("default")
    if text is None or ftype.kind == "node":
        return F.empty(ftype)
    return F.parse_xml(ftype, text)


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
