"""X3D JSON encoding (.x3dj, ISO/IEC 19776-5), read with the json module.

json.loads gives no positions, so a regex pass over the text first finds where every
object and every key starts; object_pairs_hook, called as each object closes, attaches
those positions to the object, and a diagnostic names the line of the key it is about.
"""

from __future__ import annotations

import bisect
import json
import re
from typing import Any, Callable

from . import fields as F
from .build import Builder
from .model import FieldDecl, LoadError, Location, Node, Scene
from .xml_loader import _IGNORED_ATTRIBUTES

# A string (as a whole, so braces inside it are not structure), or a structural character
_TOKEN = re.compile(r'("[^"\\]*(?:\\.[^"\\]*)*")|([{\[])|([}\]])|(:)')
_STATEMENTS = frozenset({"ROUTE", "ProtoDeclare", "ExternProtoDeclare", "IMPORT", "EXPORT"})


# where X3D JSON puts a Script's source: X3dToJson and X_ITE write "#sourceText", older tools "#sourceCode"
_SOURCE_KEYS = ("#sourceText", "#sourceCode")

class _Obj(dict):
    """A JSON object that knows where it and each of its keys start in the text."""

    __slots__ = ("start", "key_starts")

    def __init__(self, pairs: list[tuple[str, Any]], start: int, key_starts: dict[str, int]):
        super().__init__(pairs)
        self.start = start
        self.key_starts = key_starts


class _Positions:
    """Object and key offsets, listed in the order the objects close: the order in which
    json calls object_pairs_hook. Valid JSON tokenizes the same for both, and json stops
    at the first error, so the two orders agree for every object json builds."""

    def __init__(self, text: str):
        self.closed: list[tuple[int, list[int]]] = []
        self.duplicates: list[tuple[int, str]] = []  # (offset, key) of each key given twice
        self.depth_max = 0
        self.deepest = 0  # offset where the nesting is deepest, for "nesting too deep"
        stack: list[tuple[int, list[int]] | None] = []  # None: an array
        last_string = 0
        for m in _TOKEN.finditer(text):
            kind = m.lastindex
            if kind == 1:
                last_string = m.start()
            elif kind == 2:
                stack.append((m.start(), []) if text[m.start()] == "{" else None)
                if len(stack) > self.depth_max:
                    self.depth_max, self.deepest = len(stack), m.start()
            elif kind == 3:
                if stack and (top := stack.pop()) is not None:
                    self.closed.append(top)
            elif stack and stack[-1] is not None:
                stack[-1][1].append(last_string)

    def hook(self) -> Callable[[list[tuple[str, Any]]], _Obj]:
        """An object_pairs_hook that builds _Obj with positions and records duplicate keys."""
        order = iter(self.closed)

        def make(pairs: list[tuple[str, Any]]) -> _Obj:
            start, key_offsets = next(order)
            obj = _Obj(pairs, start, dict(zip((k for k, _ in pairs), key_offsets)))
            if len(obj) < len(pairs):
                seen: set[str] = set()
                for (k, _), at in zip(pairs, key_offsets):
                    if k in seen:
                        self.duplicates.append((at, k))
                    seen.add(k)
            return obj
        return make


def load_json(path: str, source: bytes, scene: Scene) -> None:
    b = Builder(scene)
    try:
        text = source.decode("utf-8-sig")  # X3D JSON is UTF-8 (RFC 8259)
    except UnicodeDecodeError as e:
        line = source.count(b"\n", 0, e.start) + 1
        col = e.start - (source.rfind(b"\n", 0, e.start) + 1) + 1
        raise b.fatal(Location(path, line, col), f"not UTF-8 text, so not X3D JSON ({e.reason})") from None
    positions = _Positions(text)
    reader = _Reader(b, path, text)
    try:
        doc = json.loads(text, object_pairs_hook=positions.hook())
    except json.JSONDecodeError as e:
        raise b.fatal(Location(path, e.lineno, e.colno), f"malformed JSON: {e.msg}") from None
    except RecursionError:
        raise reader.too_deep(positions) from None
    if not isinstance(doc, _Obj) or not isinstance(doc.get("X3D"), _Obj):
        at = reader.at(doc.key_starts["X3D"]) if isinstance(doc, _Obj) and "X3D" in doc else Location(path, 1, 1)
        raise b.fatal(at, 'not an X3D JSON document: expected an object {"X3D": {...}}')
    for at, key in positions.duplicates:
        b.error(reader.at(at), key, f"key {key!r} given twice in one object; the last one is used")
    x3d = doc["X3D"]
    scene.version = reader.string(x3d, "@version", "X3D") or scene.version
    scene.profile = reader.string(x3d, "@profile", "X3D") or scene.profile
    try:
        if "head" in x3d:
            reader.head(x3d["head"], reader.key(x3d, "head"))
        scene_obj = x3d.get("Scene")
        if isinstance(scene_obj, _Obj):
            scene.roots = reader.statements(scene_obj, "-children", "Scene")
        elif scene_obj is not None:
            b.error(reader.key(x3d, "Scene"), "Scene", "Scene must be a JSON object")
    except RecursionError:
        raise reader.too_deep(positions) from None


class _Reader:
    def __init__(self, b: Builder, path: str, text: str):
        self.b = b
        self.path = path
        self.line_starts = [0] + [m.end() for m in re.finditer("\n", text)]

    # -- positions and JSON types -------------------------------------------------
    def at(self, offset: int) -> Location:
        line = bisect.bisect_right(self.line_starts, offset)
        return Location(self.path, line, offset - self.line_starts[line - 1] + 1)

    def key(self, obj: _Obj, key: str) -> Location:
        return self.at(obj.key_starts.get(key, obj.start))

    def too_deep(self, positions: _Positions) -> LoadError:
        return self.b.fatal(self.at(positions.deepest),
                            f"nesting too deep ({positions.depth_max} levels of JSON arrays and objects)")

    def string(self, obj: _Obj, key: str, subject: str) -> str | None:
        """A key's string value; None, with an error if it is there but not a string."""
        v = obj.get(key)
        if v is None or isinstance(v, str):
            return v
        self.b.error(self.key(obj, key), subject, f"{key} must be a JSON string, not {_json_type(v)}")
        return None

    def objects(self, obj: _Obj, key: str, subject: str) -> list[_Obj]:
        """The objects of a key whose value is an array of objects (field, connect, meta...)."""
        v = obj.get(key)
        if v is None:
            return []
        if isinstance(v, list) and all(isinstance(x, _Obj) for x in v):
            return v
        self.b.error(self.key(obj, key), subject, f"{key} must be a JSON array of objects, not {_json_type(v)}")
        return []

    def entries(self, obj: _Obj, key: str, subject: str) -> list[tuple[str, _Obj, Location]]:
        """The node and statement entries under a "-field" key: an array of {"Type": {...}}
        objects, or one such object for an SFNode field. "#comment" entries are skipped."""
        v = obj.get(key, [])
        loc = self.key(obj, key)
        out = []
        many = isinstance(v, list)
        for i, entry in enumerate(v if many else [v]):
            if not isinstance(entry, _Obj):
                self.b.error(loc, subject, f"{key}{f'[{i}]' if many else ''} must be a node object "
                                           f"{{\"NodeType\": {{...}}}}, not {_json_type(entry)}")
                continue
            names = [k for k in entry if k != "#comment"]
            if not names:
                continue
            name = names[0]
            if len(names) > 1:
                self.b.error(self.at(entry.start), subject,
                             f"a node entry must have one key, its node type; got {', '.join(names)}")
            elif not isinstance(entry[name], _Obj):
                self.b.error(self.key(entry, name), name,
                             f"a {name} must be a JSON object, not {_json_type(entry[name])}")
            else:
                out.append((name, entry[name], self.key(entry, name)))
        return out

    # -- head -----------------------------------------------------------------------
    def head(self, head: Any, loc: Location) -> None:
        if not isinstance(head, _Obj):
            self.b.error(loc, "head", f"head must be a JSON object, not {_json_type(head)}")
            return
        scene = self.b.scene
        for c in self.objects(head, "component", "component"):
            level = c.get("@level", 1)
            if isinstance(level, str) and level.strip().isdigit():
                level = int(level)
            if isinstance(level, bool) or not isinstance(level, int):
                self.b.error(self.key(c, "@level"), "component", f"level {level!r} is not an integer")
                level = 1
            self.b.component(self.string(c, "@name", "component") or "", level)
        for u in self.objects(head, "unit", "UNIT"):
            self.b.unit(self.string(u, "@category", "UNIT") or "", self.string(u, "@name", "UNIT") or "",
                        str(u.get("@conversionFactor", "")), self.at(u.start))
        for m in self.objects(head, "meta", "meta"):
            scene.meta.append((self.string(m, "@name", "meta") or "", self.string(m, "@content", "meta") or ""))

    # -- statements and nodes ---------------------------------------------------------
    def statements(self, obj: _Obj, key: str, subject: str) -> list[Node]:
        """Read the entries of a "-field" key: statements take effect, nodes are returned."""
        nodes = []
        for name, body, loc in self.entries(obj, key, subject):
            if name in _STATEMENTS:
                self.statement(name, body, loc)
            else:
                n = self.node(name, body, loc)
                if n is not None:
                    nodes.append(n)
        return nodes

    def statement(self, name: str, body: _Obj, loc: Location) -> None:
        if name == "ROUTE":
            ends = [self.string(body, k, "ROUTE") or "" for k in ("@fromNode", "@fromField", "@toNode", "@toField")]
            self.b.route(*ends, loc)
        elif name == "ProtoDeclare":
            self.proto_declare(body, loc)
        elif name == "ExternProtoDeclare":
            self.b.declare_extern(self.string(body, "@name", name) or "", loc)
        else:
            self.b.warning(loc, name, f"{name} is kept out of the model (no Inline is loaded)")

    def node(self, type_name: str, body: _Obj, loc: Location) -> Node | None:
        use = self.string(body, "@USE", type_name)
        if use is not None:
            n = self.b.use(use, self.key(body, "@USE"))
            if n is not None and type_name != "ProtoInstance" and n.type_name != type_name:
                self.b.error(self.key(body, "@USE"), f"USE {use}", f"names a {n.type_name}, not a {type_name}")
                return None
            given = [k for k in body if k not in ("@USE", "@containerField", "#comment") and
                     k[1:] not in _IGNORED_ATTRIBUTES]
            if given:
                self.b.error(self.key(body, "@USE"), f"USE {use}", f"a USE takes no field values or children, and "
                                                                   f"{', '.join(given)} would be ignored: set them "
                                                                   "where the node is DEFined")
            return n
        if type_name == "ProtoInstance":
            return self.proto_instance(body, loc)
        node = self.b.node(type_name, loc, self.string(body, "@DEF", type_name))
        for key, value in body.items():
            kloc = self.key(body, key)
            if key.startswith("@"):
                if key[1:] not in _IGNORED_ATTRIBUTES:
                    self.b.set_value(node, key[1:], value, kloc, F.parse_json, "json")
            elif key.startswith("-"):
                self.field_nodes(node, body, key, kloc)
            elif key == "field" and node.declares_fields:
                for f in self.objects(body, key, node.label):
                    self.interface_field(node, f)
            elif key == "IS":
                self.connects(node, value, kloc)
            elif key in _SOURCE_KEYS:
                # a Script's source; other nodes' (ShaderPart's) is their text content, which the
                # XML loader leaves aside too
                if node.declares_fields:
                    self.source_code(node, value, kloc)
            elif key in ("field", "fieldValue"):
                self.b.error(kloc, node.label, f"{key} is only allowed in a Script, ProtoDeclare or ProtoInstance")
            elif key != "#comment":
                self.b.error(kloc, node.label, f"unexpected key {key!r} in a {type_name} "
                                               "(attributes are \"@name\", child nodes \"-field\")")
        self.b.done(node)
        return node

    def field_nodes(self, node: Node, body: _Obj, key: str, loc: Location) -> None:
        """The child nodes of a "-field" key go into that field; null empties it."""
        if body[key] is None:
            self.b.set_null(node, key[1:], loc)
            return
        for child in self.statements(body, key, f"{node.label}.{key[1:]}"):
            self.b.add_child(node, key[1:], child, child.loc)

    def connects(self, node: Node, value: Any, loc: Location) -> None:
        if not isinstance(value, _Obj):
            self.b.error(loc, f"{node.label} IS", f"IS must be a JSON object, not {_json_type(value)}")
            return
        for c in self.objects(value, "connect", f"{node.label} IS"):
            self.b.connect(node, self.string(c, "@nodeField", "connect") or "",
                           self.string(c, "@protoField", "connect") or "", self.at(c.start))

    def source_code(self, node: Node, value: Any, loc: Location) -> None:
        """A Script's source, the sourceCode field: one string or an array of lines."""
        if isinstance(value, list) and all(isinstance(s, str) for s in value):
            value = "\n".join(value)
        if not isinstance(value, str):
            self.b.error(loc, f"{node.label}.sourceCode", "#sourceText/#sourceCode must be a string or an array of "
                                                          "strings")
        elif value.strip():
            self.b.set_value(node, "sourceCode", value.strip(), loc, F.parse_json, "json")

    def interface_field(self, owner: Node | None, f: _Obj) -> FieldDecl | None:
        name = self.string(f, "@name", "field") or ""
        decl = self.b.declare(owner, name, self.string(f, "@type", name) or "",
                              self.string(f, "@accessType", name) or "", self.at(f.start))
        if decl is None:
            return None
        if "@value" in f:
            if decl.type.kind == "node":
                self.b.error(self.key(f, "@value"), decl.name, "a node field's value is given as child nodes")
            else:
                self.b.decl_value(decl, f["@value"], F.parse_json)
        kids = self.statements(f, "-children", decl.name)
        if kids:
            decl.value = kids if decl.type.multi else kids[0]
        return decl

    def proto_declare(self, body: _Obj, loc: Location) -> None:
        name = self.string(body, "@name", "ProtoDeclare") or ""
        interface = {}
        iface = body.get("ProtoInterface")
        if isinstance(iface, _Obj):
            for f in self.objects(iface, "field", f"PROTO {name}"):
                d = self.interface_field(None, f)
                if d is not None:
                    interface[d.name] = d
        elif iface is not None:
            self.b.error(self.key(body, "ProtoInterface"), f"PROTO {name}", "ProtoInterface must be a JSON object")
        p = self.b.begin_proto(name, interface)
        proto_body = body.get("ProtoBody")
        if isinstance(proto_body, _Obj):
            p.body.extend(self.statements(proto_body, "-children", f"PROTO {name}"))
        elif proto_body is not None:
            self.b.error(self.key(body, "ProtoBody"), f"PROTO {name}", "ProtoBody must be a JSON object")
        self.b.end_proto(p, loc)

    def proto_instance(self, body: _Obj, loc: Location) -> Node | None:
        name = self.string(body, "@name", "ProtoInstance") or ""
        proto = self.b.protos.get(name)
        values: dict[str, Any] = {}
        for fv in self.objects(body, "fieldValue", f"ProtoInstance {name}"):
            fname = self.string(fv, "@name", f"ProtoInstance {name}") or ""
            subject = f"ProtoInstance {name}.{fname}"
            decl = proto.interface.get(fname) if proto else None
            if proto is not None and decl is None:
                self.b.error(self.at(fv.start), subject, f"PROTO {name} has no field {fname!r}")
                continue
            if decl is None:
                continue
            if decl.type.kind == "node":
                kids = self.statements(fv, "-children", subject)
                values[fname] = kids if decl.type.multi else (kids[0] if kids else None)
            elif "@value" not in fv:
                self.b.error(self.at(fv.start), subject, "fieldValue gives no @value")
            else:
                try:
                    values[fname] = F.parse_json(decl.type, fv["@value"])
                except F.FieldError as e:
                    self.b.error(self.key(fv, "@value"), subject, str(e))
        return self.b.instantiate(name, values, loc, self.string(body, "@DEF", "ProtoInstance"))


def _json_type(v: Any) -> str:
    """How a message names a JSON value's type."""
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "a boolean"
    if isinstance(v, (int, float)):
        return f"the number {v!r}"
    if isinstance(v, str):
        return f"the string {v!r}"
    return "an array" if isinstance(v, list) else "an object"
