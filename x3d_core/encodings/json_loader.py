"""X3D JSON encoding (.x3dj, ISO/IEC 19776-5), read with the json module.

json.loads gives no positions, so a regex pass over the text first finds where every
object and every key starts; object_pairs_hook, called as each object closes, attaches
those positions to the object, and a diagnostic names the line of the key it is about.
"""

from __future__ import annotations

import itertools
import json
import re
from array import array
from typing import Any, Callable, Iterator

import numpy as np

from x3d_core.files.paths import clipped, quoted
from x3d_core.model import fields as F
from x3d_core.model.scene import FieldDecl, LoadError, Location, Node, Scene

from .build import Builder
from .line_index import LineIndex
from .xml_loader import _IGNORED_ATTRIBUTES

# A string (as a whole, so braces inside it are not structure), or a structural character
_TOKEN = re.compile(r'("[^"\\]*(?:\\.[^"\\]*)*")|([{\[])|([}\]])|(:)')
# A \uD800-\uDFFF escape (maybe); then each escape: a surrogate pair as one (groups 1 and 2),
# a lone high half (group 1 alone), a lone low half (group 3)
_MAYBE_SURROGATE = re.compile(r"\\u[dD][89a-fA-F]")
_ESCAPE = re.compile(r"\\(?:u([dD][89abAB][0-9a-fA-F]{2})(\\u[dD][c-fC-F][0-9a-fA-F]{2})?"
                     r"|u([dD][c-fC-F][0-9a-fA-F]{2})|.)", re.S)
_COLON = re.compile(r"\s*:")
_STATEMENTS = frozenset({"ROUTE", "ProtoDeclare", "ExternProtoDeclare", "IMPORT", "EXPORT"})


# where X3D JSON puts a Script's source: X3dToJson and X_ITE write "#sourceText", older tools "#sourceCode"
_SOURCE_KEYS = ("#sourceText", "#sourceCode")

class _Obj(dict):
    """A JSON object that knows where it and each of its keys start in the text: n is its
    place in _Positions' tables (which keep the offsets in bulk, not per object)."""

    __slots__ = ("n", "key_at")

    def __init__(self, pairs: list[tuple[str, Any]], n: int):
        super().__init__(pairs)
        self.n = n
        self.key_at: dict[str, int] | None = None  # key -> offset, made when first asked


class _Positions:
    """Object and key offsets, listed in the order the objects close: the order in which
    json calls object_pairs_hook. Valid JSON tokenizes the same for both, and json stops
    at the first error, so the two orders agree for every object json builds.

    Kept in flat arrays (8 bytes an offset): tuples and lists per object cost ~300 bytes
    an object, 700 MiB for a file of 10^6 small objects."""

    def __init__(self, text: str):
        self.duplicates: list[tuple[int, str]] = []  # (offset, key) of each key given twice
        self.depth_max = 0
        self.deepest = 0  # offset where the nesting is deepest, for "nesting too deep"
        opened = array("q")  # each object's offset, in opening order
        closed = array("q")  # objects (by opening number) in closing order
        keys, owners = array("q"), array("q")  # each key's offset and its object's opening number
        stack: list[int] = []  # open objects by opening number; -1: an array
        last_string = 0
        for m in _TOKEN.finditer(text):
            kind = m.lastindex
            if kind == 1:
                last_string = m.start()
            elif kind == 2:
                if text[m.start()] == "{":
                    stack.append(len(opened))
                    opened.append(m.start())
                else:
                    stack.append(-1)
                if len(stack) > self.depth_max:
                    self.depth_max, self.deepest = len(stack), m.start()
            elif kind == 3:
                if stack and (top := stack.pop()) >= 0:
                    closed.append(top)
            elif stack and stack[-1] >= 0:
                keys.append(last_string)
                owners.append(stack[-1])
        # in closing order, in bulk: where each object starts, and its keys one object after another
        order = np.frombuffer(closed, dtype=np.int64) if closed else np.zeros(0, np.int64)
        rank = np.full(len(opened), -1, dtype=np.int64)
        rank[order] = np.arange(len(order))
        key_rank = rank[np.frombuffer(owners, dtype=np.int64)] if owners else np.zeros(0, np.int64)
        kept = key_rank >= 0  # keys of objects never closed (malformed JSON, which json refuses) go
        key_rank = key_rank[kept]
        by_object = np.argsort(key_rank, kind="stable")
        self.starts = _array(np.frombuffer(opened, dtype=np.int64)[order] if opened else order)
        self.keys = _array((np.frombuffer(keys, dtype=np.int64)[kept] if keys else key_rank)[by_object])
        self.first_key = _array(np.concatenate([[0], np.cumsum(np.bincount(key_rank, minlength=len(order)))]))

    def hook(self) -> Callable[[list[tuple[str, Any]]], _Obj]:
        """An object_pairs_hook that builds _Obj with positions and records duplicate keys."""
        count = itertools.count()

        def make(pairs: list[tuple[str, Any]]) -> _Obj:
            obj = _Obj(pairs, next(count))
            if len(obj) < len(pairs):  # a key given twice: its last offset, as its last value is kept
                offsets = self.key_offsets(obj.n)
                obj.key_at = {k: at for (k, _), at in zip(pairs, offsets)}
                seen: set[str] = set()
                for (k, _), at in zip(pairs, offsets):
                    if k in seen:
                        self.duplicates.append((at, k))
                    seen.add(k)
            return obj
        return make

    def key_offsets(self, n: int) -> array:
        return self.keys[self.first_key[n]:self.first_key[n + 1]]

    def start(self, obj: _Obj) -> int:
        return self.starts[obj.n]

    def key(self, obj: _Obj, key: str) -> int:
        """Where a key of an object starts (the object's start if it has no such key)."""
        if obj.key_at is None:
            if key not in obj:
                return self.starts[obj.n]
            obj.key_at = dict(zip(obj, self.key_offsets(obj.n)))
        return obj.key_at.get(key, self.starts[obj.n])


def _array(values: np.ndarray) -> array:
    """Offsets as an array of Python ints (numpy's integers would leak into Locations)."""
    out = array("q")
    out.frombytes(np.ascontiguousarray(values, dtype=np.int64).tobytes())
    return out


def load_json(path: str, source: bytes, scene: Scene) -> None:
    b = Builder(scene)
    try:
        text = source.decode("utf-8-sig")  # X3D JSON is UTF-8 (RFC 8259)
    except UnicodeDecodeError as e:
        line = source.count(b"\n", 0, e.start) + 1
        col = e.start - (source.rfind(b"\n", 0, e.start) + 1) + 1
        raise b.fatal(Location(path, line, col), f"not UTF-8 text, so not X3D JSON ({e.reason})") from None
    text = _refuse_lone_surrogates(b, path, text)
    positions = _Positions(text)
    reader = _Reader(b, path, text, positions)
    try:
        doc = json.loads(text, object_pairs_hook=positions.hook())
    except json.JSONDecodeError as e:
        raise b.fatal(Location(path, e.lineno, e.colno), f"malformed JSON: {e.msg}") from None
    except RecursionError:
        raise reader.too_deep(positions) from None
    if not isinstance(doc, _Obj) or not isinstance(doc.get("X3D"), _Obj):
        at = reader.key(doc, "X3D") if isinstance(doc, _Obj) and "X3D" in doc else Location(path, 1, 1)
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
            scene.roots = b.beside(reader.statements(scene_obj, "-children", "Scene"))
        elif scene_obj is not None:
            b.error(reader.key(x3d, "Scene"), "Scene", "Scene must be a JSON object")
    except RecursionError:
        raise reader.too_deep(positions) from None
    b.finish()


class _Reader:
    def __init__(self, b: Builder, path: str, text: str, positions: _Positions):
        self.b = b
        self.path = path
        self.lines = LineIndex(text)
        self.positions = positions

    # -- positions and JSON types -------------------------------------------------
    def at(self, offset: int) -> Location:
        return self.lines.location(self.path, offset)

    def start(self, obj: _Obj) -> Location:
        """Where an object starts."""
        return self.at(self.positions.start(obj))

    def key(self, obj: _Obj, key: str) -> Location:
        return self.at(self.positions.key(obj, key))

    def items(self, obj: _Obj) -> Iterator[tuple[str, Any, Location]]:
        """Each key of an object with its value and place (no per-object table made)."""
        if obj.key_at is not None:
            for k, v in obj.items():
                yield k, v, self.at(obj.key_at[k])
            return
        for (k, v), at in zip(obj.items(), self.positions.key_offsets(obj.n)):
            yield k, v, self.at(at)

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
                self.b.error(self.start(entry), subject,
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
            if isinstance(level, str):  # read as XML's attribute ("²".isdigit(), and int("²") raised)
                try:
                    level = F.parse_xml(F.FIELD_TYPES["SFInt32"], level)
                except F.FieldError:
                    pass
            if isinstance(level, bool) or not isinstance(level, int):
                shown = quoted(level) if isinstance(level, str) else clipped(repr(level))
                self.b.error(self.key(c, "@level"), "component", f"level {shown} is not an integer")
                level = 1
            self.b.component(self.string(c, "@name", "component") or "", level)
        for u in self.objects(head, "unit", "UNIT"):
            self.b.unit(self.string(u, "@category", "UNIT") or "", self.string(u, "@name", "UNIT") or "",
                        str(u.get("@conversionFactor", "")), self.start(u))
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
        for key, value, kloc in self.items(body):
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
                           self.string(c, "@protoField", "connect") or "", self.start(c))

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
                              self.string(f, "@accessType", name) or "", self.start(f))
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
            p.body.extend(self.b.beside(self.statements(proto_body, "-children", f"PROTO {name}")))
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
                self.b.error(self.start(fv), subject, f"PROTO {name} has no field {fname!r}")
                continue
            if decl is None:
                continue
            if decl.type.kind == "node":
                kids = self.statements(fv, "-children", subject)
                values[fname] = kids if decl.type.multi else (kids[0] if kids else None)
            elif "@value" not in fv:
                self.b.error(self.start(fv), subject, "fieldValue gives no @value")
            else:
                try:
                    values[fname] = F.parse_json(decl.type, fv["@value"])
                except F.FieldError as e:
                    self.b.error(self.key(fv, "@value"), subject, str(e))
        return self.b.instantiate(name, values, loc, self.string(body, "@DEF", "ProtoInstance"))


def _refuse_lone_surrogates(b: Builder, path: str, text: str) -> str:
    """An error for each \\uD800-\\uDFFF escape that is not half of a surrogate pair: the
    string it is in cannot be UTF-8, as X3D strings are, and fails later on (when a trace or a
    message writes it). Each is read as U+FFFD so that the rest of the file is still checked."""
    if not _MAYBE_SURROGATE.search(text):
        return text
    lone = [m.start() for m in _ESCAPE.finditer(text) if (m.group(1) and not m.group(2)) or m.group(3)]
    if not lone:
        return text
    subjects = _keys_around(text, lone)
    lines = LineIndex(text)
    for at, subject in zip(lone, subjects):
        b.error(lines.location(path, at), subject,
                f"{text[at:at + 6]} is half of a UTF-16 surrogate pair, alone: no Unicode character, so no "
                "UTF-8 string (X3D strings are UTF-8) can hold it")
    parts, last = [], 0
    for at in lone:
        parts += [text[last:at], "\\ufffd"]
        last = at + 6
    parts.append(text[last:])
    return "".join(parts)


def _keys_around(text: str, offsets: list[int]) -> list[str]:
    """For each offset inside a string, the field it belongs to: 'Type.name' for a value (or
    the key itself) of an "@name" or "-name" key of a node object, else the key alone."""
    out: list[str] = []
    todo = iter(offsets)
    want = next(todo)
    containers: list[str] = []  # the key whose value each open object or array is
    last_key = ""
    last_string = None
    for m in _TOKEN.finditer(text):
        kind = m.lastindex
        if kind == 1:
            last_string = m
            while want is not None and m.start() <= want < m.end():
                is_key = _COLON.match(text, m.end()) is not None
                key = _shown(m.group(1)) if is_key else last_key
                node = containers[-1] if containers else ""
                name = key.lstrip("@-")
                out.append(f"{node}.{name}" if node and name != key else key or "JSON")
                want = next(todo, None)
            if want is None:
                break
        elif kind == 2:
            containers.append(last_key)
            last_key = ""
        elif kind == 3:
            last_key = containers.pop() if containers else ""
        elif last_string is not None:
            last_key = _shown(last_string.group(1))
    out += ["JSON"] * (len(offsets) - len(out))
    return out


def _shown(token: str) -> str:
    """A JSON string token's text as a message can print it (a lone surrogate as its escape)."""
    try:
        text = json.loads(token)
    except ValueError:
        text = token[1:-1]
    return text.encode("utf-8", "backslashreplace").decode("utf-8")


def _json_type(v: Any) -> str:
    """How a message names a JSON value's type."""
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "a boolean"
    if isinstance(v, (int, float)):
        return f"the number {v!r}"
    if isinstance(v, str):
        return f"the string {quoted(v)}"
    return "an array" if isinstance(v, list) else "an object"
