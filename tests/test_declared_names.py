"""Names a file declares: a Script's inputOutput field routed by its set_ and _changed
names, and a PROTO or EXTERNPROTO named like a node of a later X3D version (issue 28, items
13 and 14), in each encoding."""

from __future__ import annotations

import json

import pytest

from x3d_core.encodings.load import load

XML = """<?xml version='1.0' encoding='UTF-8'?>
<X3D profile='Full' version='4.0'><head/><Scene>
{body}
</Scene></X3D>
"""


def _xml(tmp_path, body: str):
    p = tmp_path / "s.x3d"
    p.write_text(XML.format(body=body))
    return load(str(p))


def _vrml(tmp_path, body: str):
    p = tmp_path / "s.x3dv"
    p.write_text(f"#X3D V4.0 utf8\nPROFILE Full\n{body}\n")
    return load(str(p))


def _json(tmp_path, children: list, protos: list | None = None):
    p = tmp_path / "s.x3d.json"
    statements = [*(protos or []), *children]
    p.write_text(json.dumps({"X3D": {"@profile": "Full", "@version": "4.0", "head": {},
                                     "Scene": {"-children": statements}}}))
    return load(str(p))


# -- item 13: ROUTEs to set_FOO and from FOO_changed of a Script's inputOutput FOO

ROUTES = [("T", "cycleTime", "S", "set_resetTime"), ("S", "resetTime_changed", "T", "set_startTime"),
          ("T", "cycleTime", "S", "resetTime"), ("S", "resetTime", "T", "startTime")]


def _scene_with_routes(tmp_path, encoding: str):
    if encoding == "xml":
        routes = "".join(f"<ROUTE fromNode='{a}' fromField='{af}' toNode='{b}' toField='{bf}'/>"
                         for a, af, b, bf in ROUTES)
        return _xml(tmp_path, "<TimeSensor DEF='T'/><Script DEF='S'>"
                              "<field name='resetTime' type='SFTime' accessType='inputOutput' value='0'/>"
                              "</Script>" + routes)
    if encoding == "vrml":
        routes = "".join(f"ROUTE {a}.{af} TO {b}.{bf}\n" for a, af, b, bf in ROUTES)
        return _vrml(tmp_path, "DEF T TimeSensor { }\nDEF S Script { inputOutput SFTime resetTime 0 }\n" + routes)
    script = {"@DEF": "S", "field": [{"@name": "resetTime", "@type": "SFTime", "@accessType": "inputOutput",
                                      "@value": 0}]}
    routes = [{"ROUTE": {"@fromNode": a, "@fromField": af, "@toNode": b, "@toField": bf}} for a, af, b, bf in ROUTES]
    return _json(tmp_path, [{"TimeSensor": {"@DEF": "T"}}, {"Script": script}, *routes])


@pytest.mark.parametrize("encoding", ["xml", "vrml", "json"])
def test_a_script_s_input_output_field_is_routed_by_its_event_names(tmp_path, encoding):
    s = _scene_with_routes(tmp_path, encoding)
    assert not s.errors, [str(e) for e in s.errors]
    assert [(r.from_field, r.to_field) for r in s.routes] == [(af, bf) for _, af, _, bf in ROUTES]


@pytest.mark.parametrize("route,message", [
    ("ROUTE T.cycleTime TO S.set_go", "Script S has no input field 'set_go'"),  # go is outputOnly
    ("ROUTE S.go_changed TO T.set_startTime", "Script S has no output field 'go_changed'"),
    ("ROUTE S.init_changed TO T.set_startTime", "Script S has no output field 'init_changed'")])  # initializeOnly
def test_only_an_input_output_field_has_event_names(tmp_path, route, message):
    s = _vrml(tmp_path, "DEF T TimeSensor { }\n"
                        "DEF S Script { outputOnly SFTime go initializeOnly SFTime init 0 }\n" + route)
    assert [e.message for e in s.errors] == [message]


# -- item 14: a PROTO or EXTERNPROTO named Delay (a node of X3D 4.1) is the file's, not the built-in

EXTERN_URL = '"delay.x3dv#Delay"'


def _proto_scene(tmp_path, encoding: str, extern: bool):
    if encoding == "vrml":
        declared = (f"EXTERNPROTO Delay [ inputOutput SFFloat a ] {EXTERN_URL}" if extern else
                    "PROTO Delay [ inputOutput SFFloat a 0 ] { Group { } }")
        return _vrml(tmp_path, f"{declared}\nDEF D Delay {{ a 1 }}\n")
    field = {"@name": "a", "@type": "SFFloat", "@accessType": "inputOutput"}
    instance = {"@name": "Delay", "@DEF": "D", "fieldValue": [{"@name": "a", "@value": 1}]}
    if encoding == "json":
        declared = ({"ExternProtoDeclare": {"@name": "Delay", "@url": ["delay.x3dv#Delay"], "field": [field]}}
                    if extern else {"ProtoDeclare": {"@name": "Delay", "ProtoInterface": {"field": [{**field, "@value": 0}]},
                                                     "ProtoBody": {"-children": [{"Group": {}}]}}})
        return _json(tmp_path, [{"ProtoInstance": instance}], [declared])
    declared = ("<ExternProtoDeclare name='Delay' url='\"delay.x3dv#Delay\"'>"
                "<field name='a' type='SFFloat' accessType='inputOutput'/></ExternProtoDeclare>" if extern else
                "<ProtoDeclare name='Delay'><ProtoInterface><field name='a' type='SFFloat' accessType='inputOutput' "
                "value='0'/></ProtoInterface><ProtoBody><Group/></ProtoBody></ProtoDeclare>")
    return _xml(tmp_path, declared + "<ProtoInstance name='Delay' DEF='D'><fieldValue name='a' value='1'/></ProtoInstance>")


@pytest.mark.parametrize("encoding", ["xml", "vrml", "json"])
@pytest.mark.parametrize("extern", [True, False], ids=["EXTERNPROTO", "PROTO"])
def test_a_declared_prototype_wins_over_a_later_versions_node_of_its_name(tmp_path, encoding, extern):
    s = _proto_scene(tmp_path, encoding, extern)
    assert not s.errors, [str(e) for e in s.errors]
    (d,) = s.roots
    if extern:  # kept as a node that does not run, not as X3D 4.1's Delay with its fields and defaults
        assert (d.type_name, d.spec, d.def_name) == ("Delay", None, "D")
    else:  # expanded: the body's first node
        assert (d.type_name, d.def_name) == ("Group", "D")
