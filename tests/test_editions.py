"""A file's X3D version selects the edition of clause 37's node types: 3.x the clause's own
signatures (x3d_core/model/clause37_nodes.py, generated from the text), 4.x the UOM's. The model keys
each field by its X3D 4.0 name and keeps the file's spelling for writers and diagnostics; a
name of the other edition is one warning line, and the field is read as it names."""

from __future__ import annotations

import math
import os
import subprocess
import sys

import numpy as np
import pytest

from backends import base
from conftest import ROOT, SHARED, needs_ode
from x3d_core.encodings.load import load
from x3d_core.encodings.model_diff import differences
from x3d_core.encodings.vrml_writer import write_vrml
from x3d_core.encodings.xml_writer import write_xml
from x3d_core.model import clause37
from x3d_core.model import clause37_nodes
from x3d_core.model import editions
from x3d_core.model import fields as F
from x3d_core.model.schema import Types, node_type
from x3d_core.semantics.analysis import Use, run_uses
from x3d_core.semantics.world import worlds

TEXT = os.path.join(SHARED, "reference", "clause37-rigid-body-physics.txt")
BODIES = "<RigidBody DEF='A' fixed='true'/><RigidBody DEF='B' position='0 -1 0'/>"
ENDS = "<RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/>"


@pytest.fixture(scope="module")
def text() -> str:
    if not os.path.exists(TEXT):
        pytest.skip(f"clause 37's text is not at {TEXT} (it ships with the project's shared reference folder, "
                    "not with x3drbp)")
    with open(TEXT, encoding="utf-8") as f:
        return f.read()


def xml(tmp_path, version: str, scene: str, name: str = "s.x3d") -> str:
    p = tmp_path / name
    p.write_text(f"<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='{version}'><Scene>\n"
                 f"{scene}\n</Scene></X3D>\n")
    return str(p)


def hinge2(fields: str) -> str:
    return (f"<RigidBodyCollection>{BODIES}<DoubleAxisHingeJoint DEF='H' axis1='0 1 0' axis2='1 0 0' "
            f"minAngle1='-0.1' maxAngle1='0.1' {fields}>{ENDS}</DoubleAxisHingeJoint></RigidBodyCollection>")


# -- the table ---------------------------------------------------------------------------

def test_the_committed_table_is_what_the_text_yields(text):
    """x3d_core/model/clause37_nodes.py is the generator's output for the text (stale after either
    changes: regenerate with python -m x3d_core.model.clause37)."""
    with open(clause37_nodes.__file__, encoding="utf-8") as f:
        assert f.read() == clause37.generate(text), "x3d_core/model/clause37_nodes.py is stale: run python -m x3d_core.model.clause37"


def test_the_text_gives_fourteen_nodes_and_three_abstract_types(text):
    sigs = clause37.signatures(text)
    assert sum(s.abstract for s in sigs) == 3 and sum(not s.abstract for s in sigs) == 14
    rows = {(s.name, r.name): r for s in sigs for r in s.rows}
    assert rows["RigidBody", "inertia"].default.tolist() == [1, 0, 0, 0, 1, 0, 0, 0, 1]  # over three lines
    assert rows["SingleAxisHingeJoint", "maxAngle"].default == math.pi  # π, to the last bit
    assert str(rows["DoubleAxisHingeJoint", "minAngle1"].range) == "[-pi,pi]"
    assert str(rows["RigidBodyCollection", "maxCorrectionSpeed"].range) == "[0,inf) or -1"
    assert str(rows["CollidableShape", "bboxSize"].range) == "[0,inf) or -1 -1 -1"
    assert rows["CollisionSpace", "collidables"].accepts == ("X3DNBodyCollisionSpaceNode", "X3DNBodyCollidableNode")
    assert rows["MotorJoint", "enabledAxes"].range.hi == 3  # a tab inside the row
    assert rows["RigidBodyCollection", "set_contacts"].access == "inputOnly"


def test_a_row_the_reader_cannot_take_names_the_file_line_and_field():
    bad = "Thing : X3DNode {\n  SFFloat [in,out] speed 0 [0,1] sideways\n}\n"
    with pytest.raises(clause37.TextError, match=r"^t\.txt:2: Thing\.speed: cannot read 'sideways'$"):
        clause37.signatures(bad, "t.txt")


def test_every_field_of_the_text_is_one_x3d4_field():
    """Each signature row is a field X3D 4.0 has, under its name or the one RENAMED or
    MISPRINTS gives; every 4.0 field the text lacks is absent from the 3.x edition, save
    what the prose defines."""
    for name in editions.RENAMED.keys() | editions.MISPRINTS.keys():
        assert node_type(name) is not None
    for t in Types(clause37_nodes.DEFINITIONS).values():
        if t.abstract:
            continue
        four, three = node_type(t.name), editions.node_type(t.name, "3.3")
        canonical = editions.RENAMED.get(t.name, {}) | editions.MISPRINTS.get(t.name, {})
        keys = {canonical.get(f, f) for f in t.fields}
        assert keys <= set(four.fields), (t.name, keys - set(four.fields))
        assert list(three.fields) == list(four.fields)  # 4.0's keys and order, whatever the edition
        assert three.absent == set(four.fields) - keys - editions.DEFINED_IN_PROSE.get(t.name, set())
        for f, fd in three.fields.items():
            assert fd.unit == four.fields[f].unit, (t.name, f)  # UNIT categories stay node_defs.py's
    for name, renamed in editions.RENAMED.items():
        assert not set(renamed) & set(node_type(name).fields)  # a 3.x name is no 4.0 name of that node


def test_every_slip_decision_is_in_the_docs():
    with open(os.path.join(ROOT, "docs", "spec-loose-ends.md"), encoding="utf-8") as f:
        docs = f.read()
    assert "x3d_core/model/editions.py" in docs
    for slip in editions.SLIPS:
        assert f"`{slip.where}`" in docs, slip.where


# -- defaults and ranges by version -------------------------------------------------------

AXES = ("<SingleAxisHingeJoint/><DoubleAxisHingeJoint/><UniversalJoint/><MotorJoint/><SliderJoint/>"
        "<RigidBody/><RigidBodyCollection/>")


V3_DEFAULTS = {"axis": [0, 0, 0], "axis1": [0, 0, 0], "axis2": [0, 0, 0], "motor1Axis": [0, 0, 0],
               "motor2Axis": [0, 0, 0], "motor3Axis": [0, 0, 0], "slider": [0, 1, 0], "finiteRotationAxis": [0, 0, 0],
               "maxAngle": math.pi, "disableTime": "SFFloat"}
UOM_DEFAULTS = {"axis": [0, 1, 0], "axis1": [1, 0, 0], "axis2": [0, 1, 0], "motor1Axis": [1, 0, 0],
                "motor2Axis": [0, 1, 0], "motor3Axis": [0, 0, 1], "slider": [0, 1, 0], "finiteRotationAxis": [0, 1, 0],
                "maxAngle": 3.141592653, "disableTime": "SFTime"}


def test_a_files_version_selects_its_editions_defaults(tmp_path):
    """The clause's V3 defaults for a 3.x file (any version below 4), the UOM's for a 4.x one."""
    for version, expected in (("3.0", V3_DEFAULTS), ("3.3", V3_DEFAULTS), ("4.0", UOM_DEFAULTS),
                              ("4.1", UOM_DEFAULTS)):
        s = load(xml(tmp_path, version, AXES), check=False)
        hinge, hinge2_, universal, motor, slider, body, collection = s.roots
        got = {"axis": hinge["axis"], "axis1": hinge2_["axis1"], "axis2": hinge2_["axis2"],
               **{f"motor{k}Axis": motor[f"motor{k}Axis"] for k in (1, 2, 3)}, "slider": slider["axis"],
               "finiteRotationAxis": body["finiteRotationAxis"], "maxAngle": hinge["maxAngle"],
               "disableTime": body.spec.fields["disableTime"].type.name}
        assert {k: v.tolist() if isinstance(v, np.ndarray) else v for k, v in got.items()} == expected, version
        assert universal["axis1"].tolist() == expected["axis1"] and universal["axis2"].tolist() == expected["axis2"]
        assert collection.spec.fields["disableTime"].type.name == expected["disableTime"]
        assert not any(n.values for n in s.roots), version  # defaults, not values the loader wrote in


def test_a_files_version_selects_its_editions_ranges(tmp_path):
    """The text's ranges for a 3.x file (SliderJoint's stops [0,inf), maxCorrectionSpeed
    '[0,inf) or -1'), the UOM's for a 4.x one (none, and [-1,inf): model.md says why)."""
    for version, node, field, value, error in (
            ("3.3", "SliderJoint", "minSeparation", "-0.5", "-0.5 is out of range; allowed [0,inf)"),
            ("4.0", "SliderJoint", "minSeparation", "-0.5", None),
            ("3.3", "RigidBodyCollection", "maxCorrectionSpeed", "-1", None),
            ("3.3", "RigidBodyCollection", "maxCorrectionSpeed", "-0.5", "-0.5 is out of range; allowed [0,inf) or -1"),
            ("4.0", "RigidBodyCollection", "maxCorrectionSpeed", "-0.5", None)):
        s = load(xml(tmp_path, version, f"<{node} {field}='{value}'/>"), check=False)
        assert [e.message for e in s.errors] == ([error] if error else []), (version, field, value)


# -- the clause's own names in a 3.x file --------------------------------------------------

V3_HINGE2 = "stopBounce1='0.5' stopErrorCorrection1='0.3' stopConstantForceMix1='0.01'"


@pytest.mark.parametrize("version", ["3.0", "3.3"])
def test_a_3x_file_written_to_the_clause_loads_and_its_values_reach_the_joint(tmp_path, version):
    s = load(xml(tmp_path, version, hinge2(V3_HINGE2) +
                 "<RigidBodyCollection><RigidBody DEF='C' fixed='true'/><RigidBody DEF='D'/><UniversalJoint DEF='U' "
                 "axis1='1 0 0' axis2='0 1 0' stopBounce1='0.25'><RigidBody USE='C' containerField='body1'/>"
                 "<RigidBody USE='D' containerField='body2'/></UniversalJoint></RigidBodyCollection>"))
    assert not s.diagnostics, [str(d) for d in s.diagnostics]
    h, u = s.roots[0]["joints"][0], s.roots[1]["joints"][0]
    assert (h["stop1Bounce"], h["stop1ErrorCorrection"], h["stop1ConstantForceMix"], u["stop1Bounce"]) == \
        (0.5, 0.3, 0.01, 0.25)  # the canonical (X3D 4.0) key the evaluator and backends read
    params = [w.joints[0].params for w in worlds(s)]
    assert (params[0]["stop1Bounce"], params[0]["stop1ErrorCorrection"], params[1]["stop1Bounce"]) == (0.5, 0.3, 0.25)


@needs_ode
def test_a_3_3_file_using_stopBounce1_runs_on_ode(tmp_path):
    pytest.importorskip("backends.ode", reason="ODE is not installed")
    path = xml(tmp_path, "3.3", hinge2(V3_HINGE2))
    out = tmp_path / "t.csv"
    r = subprocess.run([sys.executable, "-m", "x3drbp", "run", path, "--backend", "ode", "--duration", "0.25",
                        "--trace", str(out)], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and out.exists(), r.stderr
    assert "0.25,B,position," in out.read_text()


def test_a_diagnostic_and_a_refusal_name_the_field_as_the_file_does(tmp_path):
    s = load(xml(tmp_path, "3.3", hinge2("stopBounce1='1.5'")))
    assert [str(e).split(": ", 2)[2] for e in s.errors] == [
        "DoubleAxisHingeJoint H.stopBounce1: 1.5 is out of range; allowed [0,1]"]
    s = load(xml(tmp_path, "3.3", hinge2("stopBounce1='0.5'")))
    said = [str(u) for u in run_uses(s) if u.feature == "DoubleAxisHingeJoint.stop1Bounce"]
    assert said == ["DoubleAxisHingeJoint.stop1Bounce = 0.5 (stopBounce1 in the file)"]


# -- a name of the other edition: one line, the field read as it names ----------------------

@pytest.mark.parametrize("version,node,given,field,value,line", [
    ("3.3", "DoubleAxisHingeJoint", "stop1Bounce", "stop1Bounce", 0.5,
     "DoubleAxisHingeJoint.stop1Bounce is X3D 4.0's name; in X3D 3.3 this field is stopBounce1 (read as it)"),
    ("3.0", "UniversalJoint", "stop1Bounce", "stop1Bounce", 0.5,
     "UniversalJoint.stop1Bounce is X3D 4.0's name; in X3D 3.0 this field is stopBounce1 (read as it)"),
    ("4.0", "DoubleAxisHingeJoint", "stopErrorCorrection1", "stop1ErrorCorrection", 0.5,
     "DoubleAxisHingeJoint.stopErrorCorrection1 is X3D 3.x's name; in X3D 4.0 this field is stop1ErrorCorrection "
     "(read as it)"),
    ("4.1", "UniversalJoint", "stopBounce1", "stop1Bounce", 0.5,
     "UniversalJoint.stopBounce1 is X3D 3.x's name; in X3D 4.1 this field is stop1Bounce (read as it)"),
    ("3.3", "RigidBody", "visible", "visible", False,
     "RigidBody.visible is X3D 4.0's; X3D 3.3 has no such field (read as X3D 4.0 defines it)"),
    ("3.2", "CollisionCollection", "description", "description", "floor",
     "CollisionCollection.description is X3D 4.0's; X3D 3.2 has no such field (read as X3D 4.0 defines it)"),
    ("3.3", "Contact", "minbounceSpeed", "minBounceSpeed", 0.5,
     "Contact.minbounceSpeed is a slip of clause 37's text; the field is minBounceSpeed (read as it)"),
    ("4.0", "MotorJoint", "motorAxis1", "motor1Axis", [0, 0, 1],
     "MotorJoint.motorAxis1 is a slip of clause 37's text; the field is motor1Axis (read as it)")])
def test_a_name_of_the_other_edition_is_one_line_and_read_as_it_names(tmp_path, version, node, given, field, value,
                                                                     line):
    text = " ".join(map(str, value)) if isinstance(value, list) else str(value).lower()
    s = load(xml(tmp_path, version, f"<{node} DEF='N' {given}='{text}'/>"), check=False)
    assert [(d.severity, d.loc.line, d.subject, d.message) for d in s.diagnostics] == \
        [("warning", 3, f"{node} N.{given}", line)]
    got = s.roots[0][field]
    assert (got.tolist() if isinstance(got, np.ndarray) else got) == value


@pytest.mark.parametrize("header,scene", [
    ("#X3D V3.3 utf8\n", "DEF H DoubleAxisHingeJoint { stop1Bounce 0.5 }\n"),
    ("", '{"X3D": {"@version": "3.3", "Scene": {"-children": [{"DoubleAxisHingeJoint": '
         '{"@DEF": "H", "@stop1Bounce": 0.5}}]}}}\n')], ids=["vrml", "json"])
def test_every_encoding_says_it_once(tmp_path, header, scene):
    p = tmp_path / ("s.x3dv" if header else "s.x3dj")
    p.write_text(header + scene)
    s = load(str(p), check=False)
    assert [d.message for d in s.diagnostics] == [
        "DoubleAxisHingeJoint.stop1Bounce is X3D 4.0's name; in X3D 3.3 this field is stopBounce1 (read as it)"]
    assert s.roots[0]["stop1Bounce"] == 0.5


def test_a_route_may_name_the_other_editions_field(tmp_path):
    s = load(xml(tmp_path, "3.3", hinge2("") + "<ScalarInterpolator DEF='I'/>"
                 "<ROUTE fromNode='I' fromField='value_changed' toNode='H' toField='stop1Bounce'/>"))
    assert [d.message for d in s.diagnostics] == [
        "DoubleAxisHingeJoint.stop1Bounce is X3D 4.0's name; in X3D 3.3 this field is stopBounce1 (read as it)"]
    assert len(s.routes) == 1


# -- writers -----------------------------------------------------------------------------------

@pytest.mark.parametrize("writer,ext", [(write_xml, ".x3d"), (write_vrml, ".x3dv")], ids=["xml", "vrml"])
def test_writers_keep_the_files_own_spelling(tmp_path, writer, ext):
    """The clause's name where the 3.3 file uses it, and the 4.0 name where the file used that
    instead (so the file reads back with the same warning): the model is one, the text the file's."""
    a = load(xml(tmp_path, "3.3", hinge2("stopBounce1='0.5' stop1ErrorCorrection='0.3'")))
    out = tmp_path / f"out{ext}"
    out.write_bytes(writer(a))
    written = out.read_text()
    assert "stopBounce1" in written and "stop1ErrorCorrection" in written
    assert "stop1Bounce" not in written and "stopErrorCorrection1" not in written
    b = load(str(out))
    assert differences(a, b) == []
    assert [d.message for d in b.diagnostics] == [d.message for d in a.diagnostics] == [
        "DoubleAxisHingeJoint.stop1ErrorCorrection is X3D 4.0's name; in X3D 3.3 this field is stopErrorCorrection1 "
        "(read as it)"]


# -- finite rotation about no axis -----------------------------------------------------------------

def test_a_zero_finite_rotation_axis_is_native_on_every_backend():
    """0 0 0 is ODE's full finite rotation, which is the exponential map every other backend
    turns a body by: no backend approximates it (a 3.x wheel's default asks nothing more)."""
    zero = Use("RigidBody.finiteRotationAxis", np.zeros(3), F.FIELD_TYPES["SFVec3f"])
    for name, backend in base.available().items():
        if not isinstance(backend, str):
            assert base.judge(backend, zero).support is base.Support.NATIVE, name
