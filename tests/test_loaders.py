"""What the loaders make of a file: sharing, routes, units, PROTOs, spellings, diagnostics."""

from __future__ import annotations

import math

import numpy as np
import pytest

from x3d_core.encodings.load import load
from x3d_core.encodings.model_diff import differences
from x3d_core.model.scene import LoadError
from x3d_core.semantics.analysis import features
from x3d_core.semantics.applied import applied
from x3d_core.semantics.evaluator import RunSettings, run
from x3d_core.semantics.world import worlds
from conftest import needs_ode

XML_HEAD = "<?xml version='1.0' encoding='UTF-8'?>\n<X3D profile='Full' version='{v}'>\n"


def xml(tmp_path, body, head="", version="4.0", name="s.x3d"):
    p = tmp_path / name
    p.write_text(XML_HEAD.format(v=version) + f"<head>{head}</head>\n<Scene>\n{body}\n</Scene>\n</X3D>\n")
    return load(str(p))


def vrml(tmp_path, body, header="#X3D V4.0 utf8", name="s.x3dv"):
    p = tmp_path / name
    p.write_text(f"{header}\nPROFILE Full\n{body}\n")
    return load(str(p))


PAIR_XML = """
<Group><CollidableShape DEF='S'><Shape containerField='shape'><Box size='1 2 3'/></Shape></CollidableShape></Group>
<RigidBodyCollection DEF='C'>
  <RigidBody DEF='A' mass='2' position='0 1 0'><CollidableShape USE='S' containerField='geometry'/></RigidBody>
  <RigidBody DEF='B'/>
  <BallJoint DEF='J' anchorPoint='0 0.5 0'>
    <RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/>
  </BallJoint>
</RigidBodyCollection>
<ROUTE fromNode='A' fromField='position_changed' toNode='B' toField='set_position'/>
"""
PAIR_VRML = """
Group { children [ DEF S CollidableShape { shape Shape { geometry Box { size 1 2 3 } } } ] }
DEF C RigidBodyCollection {
  bodies [ DEF A RigidBody { mass 2 position 0 1 0 geometry USE S } DEF B RigidBody { } ]
  joints [ DEF J BallJoint { anchorPoint 0 0.5 0 body1 USE A body2 USE B } ]
}
ROUTE A.position_changed TO B.set_position
"""


def test_xml_and_vrml_give_the_same_model(tmp_path):
    a, b = xml(tmp_path, PAIR_XML), vrml(tmp_path, PAIR_VRML)
    assert not a.diagnostics and not b.diagnostics
    assert differences(a, b) == []


def test_differences_notices_a_changed_value(tmp_path):
    a = xml(tmp_path, PAIR_XML)
    b = vrml(tmp_path, PAIR_VRML.replace("mass 2", "mass 3"))
    assert any("mass" in d for d in differences(a, b))


def test_use_is_the_same_object_and_routes_are_kept(tmp_path):
    s = xml(tmp_path, PAIR_XML)
    coll = s.of_type("RigidBodyCollection")[0]
    a, b = coll["bodies"]
    joint = coll["joints"][0]
    assert joint["body1"] is a and joint["body2"] is b
    shape = s.roots[0]["children"][0]
    assert a["geometry"][0] is shape
    assert [(r.from_node, r.from_field, r.to_node, r.to_field) for r in s.routes] == \
        [(a, "position_changed", b, "set_position")]
    assert shape["shape"]["geometry"]["size"].tolist() == [1, 2, 3]


def test_unset_fields_read_their_x3d4_defaults(tmp_path):
    s = xml(tmp_path, PAIR_XML)
    b = s.of_type("RigidBody")[1]
    assert b["mass"] == 1.0 and b["useGlobalGravity"] is True
    assert b["inertia"].tolist() == [1, 0, 0, 0, 1, 0, 0, 0, 1]
    assert s.of_type("RigidBodyCollection")[0]["gravity"].tolist() == [0, -9.8, 0]


def test_units_turn_degrees_and_lengths_into_si(tmp_path):
    head = ("<unit category='angle' name='degree' conversionFactor='0.017453292519943295'/>"
            "<unit category='length' name='cm' conversionFactor='0.01'/>"
            "<unit category='mass' name='g' conversionFactor='0.001'/>")
    body = ("<RigidBodyCollection gravity='0 -981 0'><RigidBody DEF='A' mass='500' position='0 100 0' "
            "orientation='0 1 0 90' angularVelocity='0 360 0' inertia='1 0 0 0 1 0 0 0 1'/>"
            "<SingleAxisHingeJoint DEF='H' maxAngle='90' minAngle='-45'/></RigidBodyCollection>")
    s = xml(tmp_path, body, head)
    a = s.of_type("RigidBody")[0]
    assert a["mass"] == pytest.approx(0.5)
    assert a["position"].tolist() == pytest.approx([0, 1, 0])
    assert a["orientation"][3] == pytest.approx(math.pi / 2)
    assert a["angularVelocity"][1] == pytest.approx(2 * math.pi)
    assert a["inertia"][0] == pytest.approx(1e-7)  # g cm^2 -> kg m^2
    assert s.of_type("RigidBodyCollection")[0]["gravity"][1] == pytest.approx(-9.81)
    h = s.of_type("SingleAxisHingeJoint")[0]
    assert (h["minAngle"], h["maxAngle"]) == pytest.approx((-math.pi / 4, math.pi / 2))


def test_units_apply_in_classic_vrml_too(tmp_path):
    s = vrml(tmp_path, "UNIT angle degree 0.017453292519943295\nRigidBody { orientation 1 0 0 180 }")
    assert s.roots[0]["orientation"][3] == pytest.approx(math.pi)


def test_xj3d_component_and_prestandard_names(tmp_path):
    s = vrml(tmp_path, "COMPONENT xj3d_RigidBodyPhysics:2\n"
                       "DEF H DoubleAxisHingeJoint { mustOutput [ \"hinge1Angle\" ] }\n"
                       "DEF CC CollisionCollection { }\nCollisionSensor { collidables USE CC }",
             header="#X3D V3.0 utf8")
    assert s.components == [("RigidBodyPhysics", 2)]
    assert s.roots[0]["forceOutput"] == ["hinge1Angle"]
    assert s.roots[2]["collider"] is s.roots[1]
    assert not s.errors


def test_x3d3_joint_axes_default_to_zero(tmp_path):
    s3 = vrml(tmp_path, "SingleAxisHingeJoint { }", header="#X3D V3.3 utf8", name="a.x3dv")
    s4 = vrml(tmp_path, "SingleAxisHingeJoint { }", name="b.x3dv")
    assert s3.roots[0]["axis"].tolist() == [0, 0, 0]
    assert s4.roots[0]["axis"].tolist() == [0, 1, 0]
    assert any("defines no direction" in str(w) for w in s3.warnings)


def test_applied_parameters_read_both_spellings(tmp_path):
    s = xml(tmp_path, "<CollisionCollection appliedParameters='\"FRICTION_COEFFICIENT-2\" \"SPEED_1\" \"SLIP-2\"'/>"
                      "<Contact appliedParameters='\"FRICTION_COEFFICIENT_2\" \"USER_FRICTION\"'/>")
    assert not s.errors
    assert applied(s.roots[0]["appliedParameters"]) == {"FRICTION_COEFFICIENT-2", "SPEED-1", "SLIP-2"}
    assert applied(s.roots[1]["appliedParameters"]) == {"FRICTION_COEFFICIENT-2", "USER_FRICTION"}
    assert "CollisionCollection.appliedParameters.SPEED-1" in features(s)


def test_vrml_proto_expands_with_values_defaults_and_sharing(tmp_path):
    s = vrml(tmp_path, """
PROTO Ball [ inputOutput SFFloat mass 2 initializeOnly SFVec3f at 0 0 0 ] {
  DEF Body RigidBody { mass IS mass position IS at geometry DEF G CollidableShape { } }
}
RigidBodyCollection { bodies [ DEF B1 Ball { at 1 2 3 } DEF B2 Ball { mass 5 } ] }
ROUTE B1.position_changed TO B2.set_position
""")
    assert not s.diagnostics, [str(d) for d in s.diagnostics]
    b1, b2 = s.roots[0]["bodies"]
    assert (b1.type_name, b1.def_name, b1["mass"], b1["position"].tolist()) == ("RigidBody", "B1", 2, [1, 2, 3])
    assert (b2["mass"], b2["position"].tolist()) == (5, [0, 0, 0])
    assert b1["geometry"][0] is not b2["geometry"][0]  # each instance has its own copy
    assert s.protos == ["Ball"] and s.routes[0].to_node is b2


def test_xml_proto_expands(tmp_path):
    s = xml(tmp_path, """
<ProtoDeclare name='Link'>
  <ProtoInterface><field name='m' type='SFFloat' accessType='inputOutput' value='3'/></ProtoInterface>
  <ProtoBody><RigidBody><IS><connect nodeField='mass' protoField='m'/></IS></RigidBody></ProtoBody>
</ProtoDeclare>
<RigidBodyCollection>
  <ProtoInstance name='Link' DEF='L1' containerField='bodies'><fieldValue name='m' value='7'/></ProtoInstance>
  <ProtoInstance name='Link' containerField='bodies'/>
</RigidBodyCollection>""")
    assert not s.errors, [str(e) for e in s.errors]
    l1, l2 = s.roots[0]["bodies"]
    assert (l1.def_name, l1["mass"], l2["mass"]) == ("L1", 7, 3)


# A PROTO whose body's first root is a Transform and whose second is the RigidBodyCollection
# (X_ITE's BallJoint example is built so): the body's position IS the instance's start, its
# CollidableShape USEs the first root's Shape, a ROUTE joins the two roots. Drop A stands at
# the top of the scene, Drop B in a Group, and Again's body is one more Drop instance.
MANY_ROOTS_VRML = """
PROTO Drop [ initializeOnly SFVec3f start 0 0 0 ] {
  DEF Ball Transform { children DEF Look Shape { geometry Sphere { radius 0.1 } } }
  RigidBodyCollection { gravity 0 -9.81 0
    bodies DEF Body RigidBody { position IS start geometry CollidableShape { shape USE Look } } }
  ROUTE Body.position_changed TO Ball.set_translation
}
PROTO Again [ ] { Drop { start 6 30 0 } }
DEF A Drop { start 0 10 0 }
Group { children [ DEF B Drop { start 3 20 0 } ] }
Again { }
"""
MANY_ROOTS_XML = """
<ProtoDeclare name='Drop'>
  <ProtoInterface><field name='start' type='SFVec3f' accessType='initializeOnly' value='0 0 0'/></ProtoInterface>
  <ProtoBody>
    <Transform DEF='Ball'><Shape DEF='Look'><Sphere radius='0.1'/></Shape></Transform>
    <RigidBodyCollection gravity='0 -9.81 0'>
      <RigidBody DEF='Body' containerField='bodies'>
        <IS><connect nodeField='position' protoField='start'/></IS>
        <CollidableShape containerField='geometry'><Shape USE='Look' containerField='shape'/></CollidableShape>
      </RigidBody>
    </RigidBodyCollection>
    <ROUTE fromNode='Body' fromField='position_changed' toNode='Ball' toField='set_translation'/>
  </ProtoBody>
</ProtoDeclare>
<ProtoDeclare name='Again'><ProtoBody>
  <ProtoInstance name='Drop'><fieldValue name='start' value='6 30 0'/></ProtoInstance>
</ProtoBody></ProtoDeclare>
<ProtoInstance name='Drop' DEF='A'><fieldValue name='start' value='0 10 0'/></ProtoInstance>
<Group><ProtoInstance name='Drop' DEF='B'><fieldValue name='start' value='3 20 0'/></ProtoInstance></Group>
<ProtoInstance name='Again'/>
"""
MANY_ROOTS_JSON = """{ "X3D": { "@profile": "Full", "@version": "4.0", "Scene": { "-children": [
  { "ProtoDeclare": { "@name": "Drop",
      "ProtoInterface": { "field": [
        { "@name": "start", "@type": "SFVec3f", "@accessType": "initializeOnly", "@value": [0, 0, 0] } ] },
      "ProtoBody": { "-children": [
        { "Transform": { "@DEF": "Ball", "-children": [
            { "Shape": { "@DEF": "Look", "-geometry": { "Sphere": { "@radius": 0.1 } } } } ] } },
        { "RigidBodyCollection": { "@gravity": [0, -9.81, 0], "-bodies": [
            { "RigidBody": { "@DEF": "Body",
                "IS": { "connect": [ { "@nodeField": "position", "@protoField": "start" } ] },
                "-geometry": [ { "CollidableShape": { "-shape": { "Shape": { "@USE": "Look" } } } } ] } } ] } },
        { "ROUTE": { "@fromNode": "Body", "@fromField": "position_changed",
                     "@toNode": "Ball", "@toField": "set_translation" } } ] } } },
  { "ProtoDeclare": { "@name": "Again", "ProtoBody": { "-children": [
      { "ProtoInstance": { "@name": "Drop", "fieldValue": [ { "@name": "start", "@value": [6, 30, 0] } ] } } ] } } },
  { "ProtoInstance": { "@name": "Drop", "@DEF": "A", "fieldValue": [ { "@name": "start", "@value": [0, 10, 0] } ] } },
  { "Group": { "-children": [
      { "ProtoInstance": { "@name": "Drop", "@DEF": "B",
          "fieldValue": [ { "@name": "start", "@value": [3, 20, 0] } ] } } ] } },
  { "ProtoInstance": { "@name": "Again" } } ] } } }
"""
STARTS = [[0, 10, 0], [3, 20, 0], [6, 30, 0]]


def many_roots(tmp_path, encoding: str):
    """MANY_ROOTS in one encoding, loaded without errors."""
    if encoding == "xml":
        s = xml(tmp_path, MANY_ROOTS_XML)
    elif encoding == "vrml":
        s = vrml(tmp_path, MANY_ROOTS_VRML)
    else:
        p = tmp_path / "s.x3dj"
        p.write_text(MANY_ROOTS_JSON)
        s = load(str(p))
    assert not s.errors, [str(e) for e in s.errors]
    assert not any("left out" in str(w) for w in s.warnings)
    return s


@pytest.mark.parametrize("encoding", ["xml", "vrml", "json"])
def test_every_root_of_a_proto_body_is_in_the_scene(tmp_path, encoding):
    s = many_roots(tmp_path, encoding)
    roots = [n.type_name for n in s.roots]
    assert roots == ["Transform", "RigidBodyCollection", "Group", "Transform", "RigidBodyCollection"]
    assert [n.type_name for n in s.roots[2]["children"]] == ["Transform", "RigidBodyCollection"]
    assert s.roots[0].def_name == "A" and s.roots[2]["children"][0].def_name == "B"
    ws = worlds(s)
    assert [w.bodies.position[0].tolist() for w in ws] == STARTS  # IS works in the second root
    balls = [s.roots[0], s.roots[2]["children"][0], s.roots[3]]
    for w, ball in zip(ws, balls):  # USE and ROUTE from the second root reach this instance's first root
        assert w.bodies.nodes[0]["geometry"][0]["shape"] is ball["children"][0]
        assert [(r.from_node, r.to_node) for r in s.routes if r.to_node is ball] == [(w.bodies.nodes[0], ball)]
    assert len({id(ball["children"][0]) for ball in balls}) == 3  # no instance shares a node with another


@pytest.mark.parametrize("encoding", ["xml", "vrml", "json"])
@needs_ode
def test_a_collection_in_a_later_proto_root_falls_freely_on_ode(tmp_path, encoding):
    from backends import ode
    ws = worlds(many_roots(tmp_path, encoding))
    dt, t = 1 / 240, 0.5
    trace = run(ws, ode.BACKEND, RunSettings(t, dt, 60))
    end = {r.node: float(r.value.split()[1]) for r in trace.rows if r.field == "position" and r.time == t}
    assert len(end) == len(STARTS)
    for w, start in zip(ws, STARTS):
        # a first-order step drops by g t^2 / 2 plus at most g dt t / 2 (semi-implicit Euler's exact lag)
        assert abs(start[1] - end[w.bodies.names[0]] - 9.81 * t * t / 2) <= 9.81 * dt * t / 2 + 1e-9


def test_other_roots_with_no_place_are_named_not_dropped(tmp_path):
    s = xml(tmp_path, """
<ProtoDeclare name='Ball'><ProtoBody>
  <RigidBody/><RigidBodyCollection><RigidBody containerField='bodies'/></RigidBodyCollection>
</ProtoBody></ProtoDeclare>
<RigidBodyCollection><ProtoInstance name='Ball' containerField='bodies'/></RigidBodyCollection>""")
    assert not s.errors, [str(e) for e in s.errors]
    assert [len(c["bodies"]) for c in s.of_type("RigidBodyCollection")] == [1]
    assert any("ProtoInstance Ball: the other roots of its PROTO body (RigidBodyCollection) are left "
               "out" in str(w) for w in s.warnings)


def test_script_and_externproto_are_kept_with_warnings(tmp_path):
    s = vrml(tmp_path, """
EXTERNPROTO Far [ inputOutput SFFloat x ] "http://example.com/far.x3dv#Far"
DEF F Far { x 1 }
DEF S Script { outputOnly SFFloat go url "ecmascript: function go(v) {}" }
ROUTE S.go TO F.x
""")
    assert not s.errors
    assert s.roots[0].type_name == "Far" and s.roots[1]["url"] == ["ecmascript: function go(v) {}"]
    messages = " ".join(str(w) for w in s.warnings)
    assert "never fetched" in messages and "does not run" in messages


def test_default_container_field_falls_back_to_the_one_accepting_field(tmp_path):
    s = xml(tmp_path, "<CollisionCollection><CollidableShape DEF='S'/></CollisionCollection>"
                      "<WorldInfo><MetadataString name='a'/></WorldInfo>")
    assert not s.errors
    assert s.roots[0]["collidables"][0].def_name == "S"
    assert s.roots[1]["metadata"].type_name == "MetadataString"


@pytest.mark.parametrize("body,subject,fragment", [
    ("<RigidBody mass='0'/>", "RigidBody.mass", "0 is out of range; allowed (0,inf)"),
    ("<RigidBody mass='-1'/>", "RigidBody.mass", "out of range"),
    ("<RigidBodyCollection errorCorrection='1.5'/>", "RigidBodyCollection.errorCorrection", "allowed [0,1]"),
    ("<Sphere radius='-2'/>", "Sphere.radius", "out of range"),
    ("<RigidBody DEF='B' fooBar='1'/>", "RigidBody B.fooBar", "has no field 'fooBar'"),
    ("<RigidBody position='1 2'/>", "RigidBody.position", "expected 3 numbers"),
    ("<Group USE='Nope'/>", "USE Nope", "undefined name"),
    ("<Group DEF='A'><Group USE='A'/></Group>", "USE A", "USE cycle"),
    ("<RigidBodyCollection><Box containerField='bodies'/></RigidBodyCollection>",
     "RigidBodyCollection.bodies", "a Box is not allowed here; allowed: RigidBody"),
    ("<SliderJoint forceOutput='\"angle\"'/>", "SliderJoint.forceOutput", "not an output of SliderJoint"),
    ("<CollisionCollection appliedParameters='\"BOUNCY\"'/>", "CollisionCollection.appliedParameters",
     "not an applied parameter"),
])
def test_errors_name_node_field_and_what_is_allowed(tmp_path, body, subject, fragment):
    s = xml(tmp_path, body)
    assert len(s.errors) == 1, [str(e) for e in s.errors]
    e = s.errors[0]
    assert e.subject == subject and fragment in e.message
    assert str(e).startswith(f"{tmp_path / 's.x3d'}:5:")  # the line of the offending element


def test_error_column_points_at_the_attribute(tmp_path):
    s = xml(tmp_path, "<Group/>\n  <RigidBody\n      position='0 0 0'\n      mass='0'/>")
    assert (s.errors[0].loc.line, s.errors[0].loc.col) == (8, 7)


@pytest.mark.parametrize("body,fragment", [
    ("<RigidBodyCollection><RigidBody DEF='A'/><RigidBody DEF='B'/></RigidBodyCollection>"
     "<RigidBodyCollection><BallJoint><RigidBody USE='A' containerField='body1'/>"
     "<RigidBody USE='B' containerField='body2'/></BallJoint></RigidBodyCollection>",
     "is not in the joint's collection"),
    ("<RigidBodyCollection><BallJoint DEF='J'><RigidBody DEF='A' containerField='body1'/></BallJoint>"
     "<RigidBody USE='A'/></RigidBodyCollection><RigidBodyCollection><BallJoint USE='J'/>"
     "<RigidBody USE='A'/></RigidBodyCollection>", "joint is in 2 collections"),
    ("<UniversalJoint axis1='1 0 0' axis2='1 1 0'><RigidBody containerField='body1'/></UniversalJoint>",
     "45 degrees apart, not perpendicular"),
])
def test_undefined_cases_are_warnings(tmp_path, body, fragment):
    s = xml(tmp_path, body)
    assert not s.errors, [str(e) for e in s.errors]
    assert any(fragment in str(w) for w in s.warnings), [str(w) for w in s.warnings]


def test_perpendicular_universal_axes_give_no_warning(tmp_path):
    s = xml(tmp_path, "<UniversalJoint axis1='0.7071 0.7071 0' axis2='0 0 1'>"
                      "<RigidBody containerField='body1'/></UniversalJoint>")
    assert not s.diagnostics


@pytest.mark.parametrize("text,fragment", [
    ("#X3D V9.0 utf8\nGroup {}", "unknown header"),
    ("#X3D V4.0 utf8\nGroup { children [ Group {", "unexpected end of file"),
    ("#X3D V4.0 utf8\nWorldInfo { title \"open }", "unterminated string"),
])
def test_broken_vrml_is_a_load_error_with_a_line(tmp_path, text, fragment):
    p = tmp_path / "b.x3dv"
    p.write_text(text)
    with pytest.raises(LoadError) as e:
        load(str(p))
    d = e.value.diagnostic
    assert fragment in d.message and d.loc.line >= 1 and d.loc.file == str(p)


def test_vrml_comments_commas_and_mf_without_brackets(tmp_path):
    s = vrml(tmp_path, "# comment\nRigidBody { # another\n position 1, 2, 3 forces 0 0 1 }")
    b = s.roots[0]
    assert b["position"].tolist() == [1, 2, 3] and b["forces"].tolist() == [[0, 0, 1]]
    assert np.shape(b["torques"]) == (0, 3)


def test_prestandard_name_on_a_node_without_that_field_is_unknown(tmp_path):
    s = vrml(tmp_path, "COMPONENT xj3d_RigidBodyPhysics:2\nRigidBody { mustOutput [ \"x\" ] }",
             header="#X3D V3.0 utf8")
    assert [e.message for e in s.errors] == ["RigidBody has no field 'mustOutput'"]


@pytest.mark.parametrize("text", ["4phere { }", "Group { children [ Bo' { } ] }"])
def test_node_type_names_must_be_names(tmp_path, text):
    p = tmp_path / "n.x3dv"
    p.write_text("#X3D V4.0 utf8\n" + text)
    with pytest.raises(LoadError, match="is not a node type name"):
        load(str(p))


def test_route_between_fields_of_different_types_is_an_error(tmp_path):
    s = vrml(tmp_path, "DEF A RigidBody { }\nDEF B RigidBody { }\nROUTE A.position_changed TO B.set_orientation")
    assert [e.message for e in s.errors] == ["a ROUTE joins fields of one type; this one joins SFVec3f to SFRotation"]
    assert s.errors[0].loc.line == 5 and not s.routes


def test_errors_found_before_a_fatal_one_are_kept(tmp_path):
    p = tmp_path / "two.x3dv"
    p.write_text("#X3D V4.0 utf8\nRigidBody { mass 0 }\nGroup { children [ ")
    with pytest.raises(LoadError) as e:
        load(str(p))
    assert [(d.loc.line, d.severity) for d in e.value.diagnostics] == [(2, "error"), (3, "error")]
    assert "mass" in e.value.diagnostics[0].subject


@pytest.mark.parametrize("inertia,fragment", [("1 0 0 0 1 0 0 0 3", "principal moments 1, 1, 3"),
                                              ("1 0.5 0 0 1 0 0 0 1", "not symmetric"),
                                              ("1 0 0 0 -1 0 0 0 1", "must be positive")])
def test_inertia_must_be_a_rigid_bodys(tmp_path, inertia, fragment):
    s = xml(tmp_path, f"<RigidBody inertia='{inertia}'/>")
    assert [e.subject for e in s.errors] == ["RigidBody.inertia"] and fragment in s.errors[0].message
