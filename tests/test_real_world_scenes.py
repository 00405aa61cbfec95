"""Files as other tools and new authors write them (issue 16): each class of problem found in
third-party scenes, written here from scratch. A valid file loads; a real mistake is one line
naming file, line and field; a name that would merge two bodies in a trace is made unique."""

from __future__ import annotations

import subprocess
import sys

import pytest

from conftest import ROOT, needs_ode
from x3d_core.encodings.load import load
from x3d_core.model.scene import LoadError
from x3d_core.semantics.world import node_names
from x3d_core.traces.trace import read_trace

XML = """<?xml version="1.0" encoding="UTF-8"?>
<X3D profile='Full' version='4.0'>
  <Scene>
{body}
  </Scene>
</X3D>
"""


def _write(tmp_path, name: str, text: str) -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def x3drbp(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "x3drbp", *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=120)


def _one_error(path: str) -> str:
    """`x3drbp check` on a file with one mistake: exit 1, that one line, no traceback."""
    r = x3drbp("check", path)
    assert r.returncode == 1, r.stdout + r.stderr
    errors = [line for line in (r.stdout + r.stderr).splitlines() if ": error: " in line]
    assert len(errors) == 1 and "Traceback" not in r.stderr, r.stdout + r.stderr
    return errors[0]


# -- loading valid files -------------------------------------------------------------------

@pytest.mark.parametrize("header", ["#X3D V3.3 utf8 Titania V4.7.8", "#X3D V4.0 utf8 X_ITE V8.6.8",
                                    "#VRML V2.0 utf8 exported by some tool"])
def test_text_after_the_classic_vrml_encoding_is_a_comment(tmp_path, header):
    path = _write(tmp_path, "s.x3dv", f"{header}\nDEF World RigidBodyCollection {{\n"
                                      "  bodies DEF Ball RigidBody { position 0 1 0 }\n}\n")
    scene = load(path)
    assert not scene.errors, [str(d) for d in scene.errors]
    assert scene.version == header.split()[1][1:]
    assert scene.roots[0]["bodies"][0].def_name == "Ball"


@pytest.mark.parametrize("key", ["#sourceText", "#sourceCode"])
def test_json_script_source_under_either_key(tmp_path, key):
    path = _write(tmp_path, "s.x3dj", '{ "X3D": { "@profile": "Full", "@version": "4.0", "Scene": { "-children": [\n'
                                      '  { "Script": { "@DEF": "S", "field": [ { "@name": "k", "@type": "SFFloat",\n'
                                      '      "@accessType": "initializeOnly", "@value": 2 } ],\n'
                                      f'    "{key}": [ "ecmascript:", "function initialize() {{ }}" ] }} }} ] }} }} }}\n')
    scene = load(path)
    assert not scene.errors, [str(d) for d in scene.errors]
    assert scene.roots[0]["sourceCode"] == "ecmascript:\nfunction initialize() { }"


# -- author mistakes: one line each ----------------------------------------------------------

def test_a_use_element_with_field_values_is_an_error_naming_them(tmp_path):
    path = _write(tmp_path, "use.x3d", XML.format(body="""    <RigidBodyCollection DEF='World'>
      <RigidBody DEF='Ball' position='0 1 0'/>
    </RigidBodyCollection>
    <RigidBodyCollection>
      <RigidBody USE='Ball' containerField='bodies' mass='3'/>
    </RigidBodyCollection>"""))
    line = _one_error(path)
    assert line.startswith(f"{path}:8:") and "USE Ball" in line and "mass would be ignored" in line


def test_a_json_use_with_field_values_is_an_error_naming_them(tmp_path):
    path = _write(tmp_path, "use.x3dj", '{ "X3D": { "@version": "4.0", "Scene": { "-children": [\n'
                                        '  { "Transform": { "@DEF": "T" } },\n'
                                        '  { "Transform": { "@USE": "T", "@translation": [1, 0, 0] } } ] } } }\n')
    line = _one_error(path)
    assert line.startswith(f"{path}:3:") and "@translation would be ignored" in line


def test_a_misspelt_field_gets_the_nearest_name(tmp_path):
    path = _write(tmp_path, "typo.x3d", XML.format(body="""    <RigidBodyCollection>
      <RigidBody DEF='Ball' mas='2'/>
    </RigidBodyCollection>"""))
    line = _one_error(path)
    assert line.startswith(f"{path}:5:") and line.endswith("RigidBody Ball.mas: RigidBody has no field 'mas'; "
                                                           "did you mean 'mass'?")
    far = _write(tmp_path, "far.x3d", XML.format(body="<RigidBodyCollection><RigidBody quux='2'/></RigidBodyCollection>"))
    assert _one_error(far).endswith("RigidBody has no field 'quux'")  # nothing near: no guess


SHAPED_PROTO = """    <ProtoDeclare name='Shaped'>
      <ProtoInterface><field name='what' type='SFNode' accessType='initializeOnly'/></ProtoInterface>
      <ProtoBody><CollidableShape><IS><connect nodeField='shape' protoField='what'/></IS></CollidableShape></ProtoBody>
    </ProtoDeclare>
    <RigidBodyCollection>
      <RigidBody DEF='Ball' position='0 1 0'>
        <ProtoInstance name='Shaped' containerField='geometry'>
          <fieldValue name='what'>{what}</fieldValue>
        </ProtoInstance>
      </RigidBody>
    </RigidBodyCollection>"""


def test_a_proto_node_value_is_checked_as_the_field_it_goes_to(tmp_path):
    wrong = _write(tmp_path, "wrong.x3d", XML.format(body=SHAPED_PROTO.format(what="<RigidBody DEF='Wrong'/>")))
    line = _one_error(wrong)
    assert "CollidableShape.shape (IS what): a RigidBody is not allowed here; allowed: Shape" in line
    right = load(_write(tmp_path, "right.x3d", XML.format(
        body=SHAPED_PROTO.format(what="<Shape><Sphere radius='0.1'/></Shape>"))))
    assert not right.errors, [str(d) for d in right.errors]
    (shape,) = right.of_type("CollidableShape")
    assert shape["shape"].type_name == "Shape"  # one node, not a list of one


# -- names in traces -----------------------------------------------------------------------

PAIR_PROTO = """    <ProtoDeclare name='Pair'>
      <ProtoInterface><field name='at' type='SFVec3f' accessType='initializeOnly' value='0 0 0'/></ProtoInterface>
      <ProtoBody>
        <RigidBodyCollection>
          <RigidBody DEF='Body'><IS><connect nodeField='position' protoField='at'/></IS></RigidBody>
        </RigidBodyCollection>
      </ProtoBody>
    </ProtoDeclare>
    <ProtoInstance name='Pair'><fieldValue name='at' value='1 0 0'/></ProtoInstance>
    <ProtoInstance name='Pair'><fieldValue name='at' value='2 0 0'/></ProtoInstance>
    <RigidBodyCollection>
      <RigidBody DEF='RigidBody_1' position='0 1 0'/>
      <RigidBody position='0 2 0'/>
    </RigidBodyCollection>"""


@needs_ode
def test_every_body_gets_its_own_name_in_the_trace_and_the_derived_ones_are_said(tmp_path):
    path = _write(tmp_path, "names.x3d", XML.format(body=PAIR_PROTO))
    scene = load(path)
    names = node_names(scene)
    bodies = [names[id(b)] for b in scene.of_type("RigidBody")]
    assert bodies == ["Pair_Body", "Pair_Body_2", "RigidBody_1", "RigidBody_2"]
    warnings = sorted(str(w) for w in scene.warnings if "in traces" in str(w))
    assert warnings == [f"{path}:16:0: warning: RigidBody: goes by 'RigidBody_2' in traces: RigidBody_k names up to "
                        "it are DEF names",
                        f"{path}:8:0: warning: RigidBody Pair_Body: goes by 'Pair_Body_2' in traces: its DEF "
                        "'Pair_Body' is taken by another node"]
    out = tmp_path / "names.csv"
    r = x3drbp("run", path, "--backend", "ode", "--duration", "0.1", "--trace", str(out))
    assert r.returncode == 0, r.stderr
    rows = [row for row in read_trace(str(out)) if row.field == "position" and row.time == 0]
    assert {row.node: row.value for row in rows} == {
        "Pair_Body": "1 0 0", "Pair_Body_2": "2 0 0", "RigidBody_1": "0 1 0", "RigidBody_2": "0 2 0"}


def test_a_scene_whose_names_are_unique_gets_no_naming_warning(tmp_path):
    path = _write(tmp_path, "plain.x3d", XML.format(body="""    <RigidBodyCollection>
      <RigidBody DEF='A'/><RigidBody/><RigidBody/>
    </RigidBodyCollection>"""))
    scene = load(path)
    assert [names for names in (node_names(scene)[id(b)] for b in scene.of_type("RigidBody"))] == [
        "A", "RigidBody_1", "RigidBody_2"]
    assert not [w for w in scene.warnings if "in traces" in str(w)]


def test_a_file_that_cannot_be_read_is_still_a_load_error(tmp_path):
    path = _write(tmp_path, "bad.x3dv", "#X3D V9.9 utf8 Titania\nGroup {}\n")
    with pytest.raises(LoadError, match="unknown header"):
        load(path)


def test_unquoted_output_names_get_a_hint_to_quote_each(tmp_path):
    joint = """    <RigidBodyCollection>
      <RigidBody DEF='A' position='0 1 0'/><RigidBody DEF='B' fixed='true'/>
      <SingleAxisHingeJoint DEF='H' forceOutput={value}>
        <RigidBody USE='A' containerField='body1'/><RigidBody USE='B' containerField='body2'/>
      </SingleAxisHingeJoint>
    </RigidBodyCollection>"""
    unquoted = _write(tmp_path, "unquoted.x3d", XML.format(body=joint.format(value="'angle angleRate'")))
    assert _one_error(unquoted).endswith("""; quote each name: '"angle" "angleRate"'""")
    wrong = _write(tmp_path, "wrong.x3d", XML.format(body=joint.format(value="'angle speed'")))
    assert "quote each name" not in _one_error(wrong)  # 'speed' is no output: quoting would not help
    quoted = load(_write(tmp_path, "quoted.x3d", XML.format(body=joint.format(value="""'"angle" "angleRate"'"""))))
    assert not quoted.errors and quoted.of_type("SingleAxisHingeJoint")[0]["forceOutput"] == ["angle", "angleRate"]


def test_a_body_listed_twice_in_one_collection_is_not_said_to_be_in_two(tmp_path):
    path = _write(tmp_path, "twice.x3d", XML.format(body="""    <RigidBodyCollection DEF='World'>
      <RigidBody DEF='Ball' position='0 1 0'/>
      <RigidBody USE='Ball'/>
    </RigidBodyCollection>"""))
    assert [str(w) for w in load(path).warnings] == [
        f"{path}:5:7: warning: RigidBody Ball: body is listed 2 times in RigidBodyCollection World's bodies; it is "
        "one body, simulated once"]
