"""The X3D JSON loader: the same model as the XML encoding, and diagnostics at the right line."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from x3d_core.encodings.build import RawValue
from x3d_core.encodings.load import load
from x3d_core.model.scene import LoadError, Node, Scene

PENDULUM_XML = """<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Immersive" version="4.0">
  <head>
    <component name="xj3d_RigidBodyPhysics" level="2"/>
    <unit category="angle" name="degree" conversionFactor="0.0174532925199433"/>
    <meta name="title" content="pendulum"/>
  </head>
  <Scene>
    <Transform DEF="T" translation="0 1 0" rotation="0 0 1 90">
      <Shape DEF="S"><Box size="1 2 3"/></Shape>
    </Transform>
    <RigidBodyCollection DEF="RBC" gravity="0 -9.81 0" iterations="20" preferAccuracy="true">
      <RigidBody DEF="B1" mass="2" position="0 1 0" forces="1 0 0 0 2 0" containerField="bodies">
        <CollidableShape DEF="CS1" containerField="geometry"><Shape USE="S" containerField="shape"/></CollidableShape>
      </RigidBody>
      <RigidBody DEF="B2" fixed="true" containerField="bodies"/>
      <SingleAxisHingeJoint DEF="J" axis="0 0 1" maxAngle="90" minAngle="-45" anchorPoint="0 2 0"
                            forceOutput='"ALL"' containerField="joints">
        <RigidBody USE="B1" containerField="body1"/>
        <RigidBody USE="B2" containerField="body2"/>
      </SingleAxisHingeJoint>
      <CollisionCollection DEF="CC" containerField="collider">
        <CollidableShape USE="CS1" containerField="collidables"/>
      </CollisionCollection>
    </RigidBodyCollection>
    <Script DEF="SC"><![CDATA[
ecmascript:
function initialize() { }
]]><field name="speed" type="SFFloat" accessType="initializeOnly" value="2.5"/></Script>
    <ROUTE fromNode="B1" fromField="position" toNode="T" toField="set_translation"/>
  </Scene>
</X3D>
"""

PENDULUM_JSON = """{ "X3D": {
  "encoding": "UTF-8", "@profile": "Immersive", "@version": "4.0",
  "head": {
    "component": [ { "@name": "xj3d_RigidBodyPhysics", "@level": 2 } ],
    "unit": [ { "@category": "angle", "@name": "degree", "@conversionFactor": 0.0174532925199433 } ],
    "meta": [ { "@name": "title", "@content": "pendulum" } ]
  },
  "Scene": { "-children": [
    { "#comment": "a { brace and a \\"quoted } string\\" must not move positions" },
    { "Transform": { "@DEF": "T", "@translation": [0, 1, 0], "@rotation": [0, 0, 1, 90],
        "-children": [
          { "Shape": { "@DEF": "S",
              "-geometry": { "Box": { "@size": [1, 2, 3] } } } } ] } },
    { "RigidBodyCollection": { "@DEF": "RBC", "@gravity": [0, -9.81, 0], "@iterations": 20,
        "@preferAccuracy": true,
        "-bodies": [
          { "RigidBody": { "@DEF": "B1", "@mass": 2, "@position": [0, 1, 0], "@forces": [1, 0, 0, 0, 2, 0],
              "-geometry": [
                { "CollidableShape": { "@DEF": "CS1",
                    "-shape": { "Shape": { "@USE": "S" } } } } ] } },
          { "RigidBody": { "@DEF": "B2", "@fixed": true } } ],
        "-joints": [
          { "SingleAxisHingeJoint": { "@DEF": "J", "@axis": [0, 0, 1], "@maxAngle": 90, "@minAngle": -45,
              "@anchorPoint": [0, 2, 0], "@forceOutput": ["ALL"],
              "-body1": { "RigidBody": { "@USE": "B1" } },
              "-body2": { "RigidBody": { "@USE": "B2" } } } } ],
        "-collider": { "CollisionCollection": { "@DEF": "CC",
            "-collidables": [ { "CollidableShape": { "@USE": "CS1" } } ] } } } },
    { "Script": { "@DEF": "SC",
        "field": [ { "@name": "speed", "@type": "SFFloat", "@accessType": "initializeOnly", "@value": 2.5 } ],
        "#sourceCode": [ "ecmascript:", "function initialize() { }" ] } },
    { "ROUTE": { "@fromNode": "B1", "@fromField": "position", "@toNode": "T", "@toField": "set_translation" } }
  ] }
} }
"""

PROTO_XML = """<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Immersive" version="4.0">
  <head><component name="RigidBodyPhysics" level="2"/></head>
  <Scene>
    <ProtoDeclare name="Ball">
      <ProtoInterface>
        <field name="m" type="SFFloat" accessType="initializeOnly" value="1"/>
        <field name="geom" type="MFNode" accessType="initializeOnly"/>
      </ProtoInterface>
      <ProtoBody>
        <RigidBody DEF="BODY" position="0 5 0">
          <IS>
            <connect nodeField="mass" protoField="m"/>
            <connect nodeField="geometry" protoField="geom"/>
          </IS>
        </RigidBody>
      </ProtoBody>
    </ProtoDeclare>
    <RigidBodyCollection DEF="RBC">
      <ProtoInstance name="Ball" DEF="P1" containerField="bodies">
        <fieldValue name="m" value="5"/>
        <fieldValue name="geom"><CollidableShape DEF="G"><Shape containerField="shape"><Sphere/></Shape></CollidableShape></fieldValue>
      </ProtoInstance>
      <ProtoInstance name="Ball" DEF="P2" containerField="bodies"/>
    </RigidBodyCollection>
  </Scene>
</X3D>
"""

PROTO_JSON = """{ "X3D": { "@profile": "Immersive", "@version": "4.0",
  "head": { "component": [ { "@name": "RigidBodyPhysics", "@level": 2 } ] },
  "Scene": { "-children": [
    { "ProtoDeclare": { "@name": "Ball",
        "ProtoInterface": { "field": [
          { "@name": "m", "@type": "SFFloat", "@accessType": "initializeOnly", "@value": 1 },
          { "@name": "geom", "@type": "MFNode", "@accessType": "initializeOnly" } ] },
        "ProtoBody": { "-children": [
          { "RigidBody": { "@DEF": "BODY", "@position": [0, 5, 0],
              "IS": { "connect": [ { "@nodeField": "mass", "@protoField": "m" },
                                   { "@nodeField": "geometry", "@protoField": "geom" } ] } } } ] } } },
    { "RigidBodyCollection": { "@DEF": "RBC", "-bodies": [
        { "ProtoInstance": { "@name": "Ball", "@DEF": "P1", "fieldValue": [
            { "@name": "m", "@value": 5 },
            { "@name": "geom", "-children": [
                { "CollidableShape": { "@DEF": "G",
                    "-shape": { "Shape": { "-geometry": { "Sphere": {} } } } } } ] } ] } },
        { "ProtoInstance": { "@name": "Ball", "@DEF": "P2" } } ] } }
  ] } } }
"""


def _load(tmp_path: Path, name: str, text: str) -> Scene:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return load(str(path))


def _load_error(tmp_path: Path, text: str) -> LoadError:
    path = tmp_path / "bad.x3dj"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(LoadError) as info:
        load(str(path))
    assert info.value.diagnostic.loc.file == str(path)
    return info.value


def _assert_same_model(a: Scene, b: Scene) -> None:
    """Node for node: types, DEF names, field values, and which nodes are shared."""
    assert (a.version, a.profile, a.components, a.units, a.meta, a.protos) == \
           (b.version, b.profile, b.components, b.units, b.meta, b.protos)
    na, nb = list(a.nodes()), list(b.nodes())
    assert [(n.type_name, n.def_name) for n in na] == [(n.type_name, n.def_name) for n in nb]
    index_a = {id(n): i for i, n in enumerate(na)}
    index_b = {id(n): i for i, n in enumerate(nb)}

    def same(va: object, vb: object) -> None:
        if isinstance(va, Node):
            assert isinstance(vb, Node) and index_a[id(va)] == index_b[id(vb)]
        elif isinstance(va, list) and va and isinstance(va[0], Node):
            assert [index_a[id(x)] for x in va] == [index_b[id(x)] for x in vb]
        elif isinstance(va, (np.ndarray, float, int, bool)):
            np.testing.assert_array_equal(va, vb)
        else:
            assert va == vb

    assert [index_a[id(n)] for n in a.roots] == [index_b[id(n)] for n in b.roots]
    for x, y in zip(na, nb):
        assert sorted(x.values) == sorted(y.values), x.label
        for k in x.values:
            assert not isinstance(x.values[k], RawValue), f"{x.label}.{k} is untyped"
            same(x.values[k], y.values[k])
        assert [(d.name, d.type, d.access) for d in x.interface] == [(d.name, d.type, d.access) for d in y.interface]
        for dx, dy in zip(x.interface, y.interface):
            same(dx.value, dy.value)
    assert [(index_a[id(r.from_node)], r.from_field, index_a[id(r.to_node)], r.to_field) for r in a.routes] == \
           [(index_b[id(r.from_node)], r.from_field, index_b[id(r.to_node)], r.to_field) for r in b.routes]
    assert {(d.severity, d.subject, d.message) for d in a.diagnostics} == \
           {(d.severity, d.subject, d.message) for d in b.diagnostics}


def test_json_scene_loads_to_the_same_model_as_xml(tmp_path: Path) -> None:
    xml = _load(tmp_path, "pendulum.x3d", PENDULUM_XML)
    js = _load(tmp_path, "pendulum.x3dj", PENDULUM_JSON)
    assert js.encoding == "json" and js.errors == []
    _assert_same_model(xml, js)

    assert js.components == [("RigidBodyPhysics", 2)]
    assert js.meta == [("title", "pendulum")]
    (coll,) = js.of_type("RigidBodyCollection")
    b1, b2 = coll["bodies"]
    (joint,) = coll["joints"]
    transform = js.roots[0]
    assert (b1.def_name, b2.def_name, joint.type_name) == ("B1", "B2", "SingleAxisHingeJoint")
    assert joint["body1"] is b1 and joint["body2"] is b2
    assert coll["collider"]["collidables"][0] is b1["geometry"][0]
    assert b1["geometry"][0]["shape"] is transform["children"][0]
    assert b1["mass"] == 2.0 and b2["fixed"] is True and coll["preferAccuracy"] is True
    np.testing.assert_array_equal(b1["forces"], [[1, 0, 0], [0, 2, 0]])
    np.testing.assert_array_equal(coll["gravity"], [0, -9.81, 0])
    assert joint["forceOutput"] == ["ALL"]
    # UNIT angle degree: SFFloat angles and the angle of an SFRotation are read in degrees
    assert joint["maxAngle"] == pytest.approx(math.pi / 2, abs=1e-12)
    assert joint["minAngle"] == pytest.approx(-math.pi / 4, abs=1e-12)
    np.testing.assert_allclose(transform["rotation"], [0, 0, 1, math.pi / 2], atol=1e-12)
    (route,) = js.routes
    assert (route.from_node, route.from_field, route.to_node, route.to_field) == \
           (b1, "position", transform, "set_translation")
    script = js.roots[2]
    assert script["sourceCode"] == "ecmascript:\nfunction initialize() { }"
    assert [(d.name, d.value) for d in script.interface] == [("speed", 2.5)]


def test_node_locations_are_the_lines_of_their_type_keys(tmp_path: Path) -> None:
    js = _load(tmp_path, "pendulum.x3dj", PENDULUM_JSON)
    lines = PENDULUM_JSON.splitlines()
    nodes = list(js.nodes())
    assert len(nodes) == 10
    for n in nodes:
        at = lines[n.loc.line - 1][n.loc.col - 1:]
        assert at.startswith(f'"{n.type_name}"'), (n, at)
    b1 = js.of_type("RigidBody")[0]
    assert b1.loc.line == next(i for i, t in enumerate(lines, 1) if '"@DEF": "B1"' in t)


def test_proto_declared_and_instanced_in_json_expands(tmp_path: Path) -> None:
    js = _load(tmp_path, "ball.x3dj", PROTO_JSON)
    assert js.errors == []
    _assert_same_model(_load(tmp_path, "ball.x3d", PROTO_XML), js)
    assert js.protos == ["Ball"]
    (coll,) = js.of_type("RigidBodyCollection")
    p1, p2 = coll["bodies"]
    assert (p1.type_name, p1.def_name, p2.def_name) == ("RigidBody", "P1", "P2")
    assert p1 is not p2
    assert (p1["mass"], p2["mass"]) == (5.0, 1.0)
    np.testing.assert_array_equal(p2["position"], [0, 5, 0])
    assert [g.def_name for g in p1["geometry"]] == ["G"] and p2["geometry"] == []
    assert p1["geometry"][0]["shape"]["geometry"].type_name == "Sphere"


def test_malformed_json_names_its_line(tmp_path: Path) -> None:
    text = """{ "X3D": {
  "@version": "4.0",
  "Scene": { "-children": [
    { "Group": { "@DEF": "G" } }
    { "Group": {} }
  ] } } }
"""
    d = _load_error(tmp_path, text).diagnostic
    assert (d.loc.line, d.loc.col) == (5, 5)
    assert d.message.startswith("malformed JSON: Expecting ','")


@pytest.mark.parametrize("text", ['[1, 2]', '{"x3d": {}}', '{"X3D": [1]}', '"X3D"'])
def test_json_that_is_not_x3d_is_refused(tmp_path: Path, text: str) -> None:
    assert "not an X3D JSON document" in _load_error(tmp_path, text).diagnostic.message


@pytest.mark.parametrize("text", [
    '{"X3D": {"Scene": {"-children": ' + "[" * 10_000 + "]" * 10_000 + "}}}",
    '{"X3D": {"Scene": {"-children": [' + '{"Group": {"-children": [' * 10_000 + "]}}" * 10_000 + "]}}}",
])
def test_deep_nesting_is_a_load_error(tmp_path: Path, text: str) -> None:
    d = _load_error(tmp_path, text).diagnostic
    assert d.message.startswith("nesting too deep")


def test_wrong_typed_value_names_node_field_and_line(tmp_path: Path) -> None:
    text = """{ "X3D": { "Scene": { "-children": [
  { "RigidBodyCollection": { "-bodies": [
    { "RigidBody": { "@DEF": "B",
        "@mass": "heavy" } } ] } } ] } } }
"""
    scene = _load(tmp_path, "heavy.x3dj", text)
    (err,) = scene.errors
    assert err.subject == "RigidBody B.mass"
    assert '"heavy" is not a number' in err.message
    assert (err.loc.line, err.loc.col) == (4, 9)
    assert "mass" not in scene.of_type("RigidBody")[0].values


def test_wrong_json_types_are_errors_not_exceptions(tmp_path: Path) -> None:
    text = """{ "X3D": { "head": { "component": { "@name": "RigidBodyPhysics" } },
  "Scene": { "-children": [
    { "Group": { "-children": 5 } },
    { "Group": {}, "Transform": {} },
    "text",
    { "RigidBodyCollection": { "-bodies": [ "B" ], "-joints": { "BallJoint": 7 } } },
    { "Transform": { "@translation": [0, 1], "bogus": 1, "@DEF": 3 } },
    { "ROUTE": { "@fromNode": ["T"] } },
    { "RigidBody": { "@mass": 1, "@mass": 2 } }
  ] } } }
"""
    scene = _load(tmp_path, "types.x3dj", text)
    found = {(d.loc.line, d.subject, d.message) for d in scene.errors}
    expected = [
        (1, "component", "component must be a JSON array of objects, not an object"),
        (3, "Group.children", "-children must be a node object {\"NodeType\": {...}}, not the number 5"),
        (4, "Scene", "a node entry must have one key, its node type; got Group, Transform"),
        (2, "Scene", "-children[2] must be a node object {\"NodeType\": {...}}, not the string 'text'"),
        (6, "RigidBodyCollection.bodies", "-bodies[0] must be a node object"),
        (6, "BallJoint", "a BallJoint must be a JSON object, not the number 7"),
        (7, "Transform.translation", "expected 3 numbers (SFVec3f), got 2 values"),
        (7, "Transform", "unexpected key 'bogus'"),
        (7, "Transform", "@DEF must be a JSON string"),
        (8, "ROUTE", "@fromNode must be a JSON string"),
        (9, "@mass", "key '@mass' given twice in one object"),
    ]
    for line, subject, message in expected:
        assert any(ln == line and s == subject and m.startswith(message) for ln, s, m in found), \
            (line, subject, message, sorted(found))
    assert scene.of_type("RigidBody")[-1]["mass"] == 2.0
    assert [n.type_name for n in scene.roots] == ["Group", "RigidBodyCollection", "Transform", "RigidBody"]
