"""What a Script with directOutput TRUE can change with no ROUTE: the physics nodes its
SFNode/MFNode fields hold, or hold under them (issue 28, item 15), read alike from each
encoding; one that holds none is ignored with a warning that says so."""

from __future__ import annotations

import json

import pytest

from x3d_core.encodings.load import load
from x3d_core.semantics.analysis import SCRIPT_DIRECT_OUTPUT, features, script_reach
from x3d_core.semantics.outcome import outcome_warnings

XML = """<?xml version='1.0' encoding='UTF-8'?>
<X3D profile='Full' version='4.0'><head/><Scene>
<Group DEF='Top'><RigidBodyCollection DEF='World'><RigidBody DEF='Ball' containerField='bodies'/></RigidBodyCollection></Group>
<Script DEF='Mover' directOutput='{direct}'>
<field name='ball' type='SFNode' accessType='initializeOnly'><RigidBody USE='Ball'/></field>
<field name='top' type='MFNode' accessType='inputOutput'><Group USE='Top'/><Shape DEF='Look'/></field>
</Script>
</Scene></X3D>
"""
VRML = """#X3D V4.0 utf8
DEF Top Group { children [ DEF World RigidBodyCollection { bodies DEF Ball RigidBody { } } ] }
DEF Mover Script { directOutput {direct} initializeOnly SFNode ball USE Ball
                   inputOutput MFNode top [ USE Top DEF Look Shape { } ] }
"""


def _json(direct: bool) -> str:
    world = {"RigidBodyCollection": {"@DEF": "World", "-bodies": [{"RigidBody": {"@DEF": "Ball"}}]}}
    script = {"@DEF": "Mover", "@directOutput": direct, "field": [
        {"@name": "ball", "@type": "SFNode", "@accessType": "initializeOnly", "-children": [{"RigidBody": {"@USE": "Ball"}}]},
        {"@name": "top", "@type": "MFNode", "@accessType": "inputOutput",
         "-children": [{"Group": {"@USE": "Top"}}, {"Shape": {"@DEF": "Look"}}]}]}
    children = [{"Group": {"@DEF": "Top", "-children": [world]}}, {"Script": script}]
    return json.dumps({"X3D": {"@profile": "Full", "@version": "4.0", "head": {}, "Scene": {"-children": children}}})


def _scene(tmp_path, encoding: str, direct: bool):
    name, text = {"xml": ("s.x3d", XML.replace("{direct}", str(direct).lower())),
                  "vrml": ("s.x3dv", VRML.replace("{direct}", str(direct).upper())),
                  "json": ("s.x3d.json", _json(direct))}[encoding]
    p = tmp_path / name
    p.write_text(text)
    s = load(str(p))
    assert not s.errors, [str(e) for e in s.errors]
    return s


@pytest.mark.parametrize("encoding", ["xml", "vrml", "json"])
def test_a_direct_output_script_reaches_the_physics_nodes_it_holds_or_holds_under(tmp_path, encoding):
    s = _scene(tmp_path, encoding, True)
    assert [str(r) for r in script_reach(s)] == [
        "Script Mover holds RigidBody Ball in its field ball",
        "Script Mover holds Group Top (holding RigidBodyCollection World) in its field top"]  # not the Shape
    assert SCRIPT_DIRECT_OUTPUT in features(s)


@pytest.mark.parametrize("encoding", ["xml", "vrml", "json"])
def test_a_script_without_direct_output_reaches_nothing(tmp_path, encoding):
    s = _scene(tmp_path, encoding, False)
    assert script_reach(s) == [] and SCRIPT_DIRECT_OUTPUT not in features(s)
    assert not any("directOutput" in w.subject for w in outcome_warnings(s))


def test_a_direct_output_script_holding_no_physics_is_named_as_ignored(tmp_path):
    p = tmp_path / "s.x3dv"
    p.write_text("#X3D V4.0 utf8\nDEF World RigidBodyCollection { bodies DEF Ball RigidBody { } }\n"
                 "DEF Mover Script { directOutput TRUE initializeOnly SFNode look Shape { } }\n")
    s = load(str(p))
    assert script_reach(s) == [] and SCRIPT_DIRECT_OUTPUT not in features(s)
    (w,) = [w for w in outcome_warnings(s) if "directOutput" in w.subject]
    assert w.subject == "Script Mover.directOutput" and "a run goes on without it" in w.message
