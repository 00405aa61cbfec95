"""ClassicVRML encoding (.x3dv): #X3D V3.x/V4.x (and #VRML V2.0) files."""

from __future__ import annotations

import itertools
import re
from array import array
from typing import Any

from x3d_core.files.paths import quoted
from x3d_core.model import fields as F
from x3d_core.model.scene import Location, Node, Scene

from .build import Builder
from .line_index import LineIndex

# the rest of the header line is a comment (Titania and X_ITE write their names there)
_HEADER = re.compile(rb"^\s*#(X3D V[34]\.\d+|VRML V2\.0) [A-Za-z0-9_-]+[^\r\n]*")
# A string may lack its closing quote only at the end of the file: the loader reports it.
# Possessive (*+, ++) throughout: a file ending in a long run of blanks made the regex try
# every way of splitting it (2^n: a hang), and a string of 10^7 characters took 1.3 GiB of
# backtracking state, one entry per character. Whitespace is ClassicVRML's (19776-2: space, tab,
# CR, LF and the comma), not Python's \s: a no-break space or a form feed is part of a token.
_TOKEN = re.compile(r'(?:[ \t\r\n,]+|#[^\n\r]*)*+("(?:[^"\\]++|\\.)*+"?|[\[\]{}]|[^ \t\r\n,"#\[\]{}]+)', re.S)
_CLOSED_STRING = re.compile(r'"(?:[^"\\]++|\\.)*+"', re.S)
# possessive: a name of 10^5 digits and a letter was quadratic (3 minutes)
_NUMBER = re.compile(rf"(?:[+-]?+0[xX][0-9a-fA-F]++|{F.NUMBER})\Z")
_ACCESS = frozenset({"inputOnly", "outputOnly", "initializeOnly", "inputOutput",
                     "eventIn", "eventOut", "field", "exposedField"})
_KEYWORDS = frozenset({"DEF", "USE", "ROUTE", "TO", "PROTO", "EXTERNPROTO", "IS", "NULL", "IMPORT", "EXPORT",
                       "AS", "TRUE", "FALSE"})
# Every token costs ~100 bytes here (its text and offset; its line is counted only when a
# location is asked for): 1.9e6 tokens peak at ~250 MiB (~690 MiB when each kept its match,
# line and column). Larger arrays belong in the XML or JSON encoding, which keep numbers as
# text until parsed in bulk.
MAX_TOKENS = 2_000_000
_END = " end of file"  # after the last token; no real token starts with a space
_NUMBER_START = frozenset("0123456789+-.")
_INTEGER = re.compile(r"[+-]?(?:0[xX][0-9a-fA-F]{1,16}|[0-9]{1,18})\Z")


def load_vrml(path: str, source: bytes, scene: Scene) -> None:
    b = Builder(scene)
    m = _HEADER.match(source)
    if not m:
        first = source.lstrip().split(b"\n", 1)[0][:40].decode("utf-8", "replace")
        raise b.fatal(Location(path, 1, 1), f"unknown header {first!r}; expected '#X3D V3.x utf8', "
                                            "'#X3D V4.x utf8' or '#VRML V2.0 utf8'")
    header = m.group(1).decode()
    scene.version = header.split("V", 1)[1] if header.startswith("X3D") else "2.0"
    try:
        text = source.decode("utf-8")
    except UnicodeDecodeError as e:
        line = source[:e.start].count(b"\n") + 1
        raise b.fatal(Location(path, line, 1), "not UTF-8 text") from None
    _Parser(b, path, text, m.end()).scene()
    b.finish()


def _image_size(token: str) -> int | None:
    """An SFImage width or height token as ClassicVRML reads an SFInt32 (08 is 8, 0x10 is 16),
    0 if negative; None if it is no integer (1.5, a string)."""
    if not _INTEGER.match(token):
        return None
    return max(int(token, 16 if token[1:3].lower() == "0x" or token[:2].lower() == "0x" else 10), 0)


class _Parser:
    def __init__(self, b: Builder, path: str, text: str, start: int):
        self.b = b
        self.path = path
        self.text = text
        self.lines = LineIndex(text)
        # each token's text and offset; its line and column are found only when asked for
        self.toks: list[str] = []
        pos = array("q")
        toks_append, pos_append = self.toks.append, pos.append
        for m in itertools.islice(_TOKEN.finditer(text, start), MAX_TOKENS + 1):
            toks_append(m.group(1))
            pos_append(m.start(1))
        if len(self.toks) > MAX_TOKENS:
            raise b.fatal(self.lines.location(path, pos[-1]),
                          f"more than {MAX_TOKENS} tokens (numbers, names, brackets): x3drbp reads no larger "
                          "ClassicVRML file; the XML or JSON encoding holds larger arrays")
        self.ntok = len(self.toks)
        self.toks += [_END, _END]
        pos.append(len(text))
        self.pos = pos
        last = self.toks[self.ntok - 1] if self.ntok else ""
        if last[:1] == '"' and not _CLOSED_STRING.fullmatch(last):
            raise b.fatal(self.loc(self.ntok - 1), "unterminated string")
        self.i = 0
        self.roots: list[Node] = []

    # -- tokens ---------------------------------------------------------------
    def loc(self, i: int | None = None) -> Location:
        i = min(self.i if i is None else i, self.ntok)
        return self.lines.location(self.path, self.pos[i])

    def shown(self, k: int = 0) -> str:
        """The next token as a message shows it."""
        t = self.peek(k)
        return "the end of the file" if t == _END else quoted(t)

    def peek(self, k: int = 0) -> Any:
        return self.toks[self.i + k]

    def next(self) -> str:
        if self.i >= self.ntok:
            raise self.b.fatal(self.loc(), "unexpected end of file")
        t = self.toks[self.i]
        self.i += 1
        return t

    def expect(self, what: str) -> None:
        at = self.i
        t = self.next()
        if t != what:
            raise self.b.fatal(self.loc(at), f"expected '{what}', found {quoted(t)}")

    def ident(self, what: str) -> str:
        at = self.i
        t = self.next()
        if t in "[]{}" or t.startswith('"') or _NUMBER.match(t) or t in _KEYWORDS:
            raise self.b.fatal(self.loc(at), f"expected {what}, found {quoted(t)}")
        return t

    # -- statements -------------------------------------------------------------
    def scene(self) -> None:
        scene = self.b.scene
        while self.peek() in ("PROFILE", "COMPONENT", "UNIT", "META"):
            kw = self.next()
            at = self.loc()
            if kw == "PROFILE":
                scene.profile = self.ident("a profile name")
            elif kw == "COMPONENT":
                name, _, level = self.ident("a component name").partition(":")
                if not level and self.peek() == ":":
                    self.next()
                    level = self.next()
                try:
                    self.b.component(name, F.parse_xml(F.FIELD_TYPES["SFInt32"], level))
                except F.FieldError:
                    self.b.error(at, "COMPONENT", f"level {quoted(level)} is not an integer")
            elif kw == "UNIT":
                category, name, factor = self.next(), self.next(), self.next()
                self.b.unit(category, name, factor, at)
            else:
                scene.meta.append((self.string(), self.string()))
        while self.peek() != _END:
            node = self.statement()
            if node is not None:
                self.roots.extend(self.b.beside([node]))
        scene.roots = self.roots

    def string(self) -> str:
        at = self.i
        t = self.next()
        if not t.startswith('"'):
            raise self.b.fatal(self.loc(at), f"expected a quoted string, found {quoted(t)}")
        return F.parse_vrml(F.FIELD_TYPES["SFString"], [t])

    def statement(self) -> Node | None:
        t = self.peek()
        if t == "ROUTE":
            self.route()
        elif t == "PROTO":
            self.proto()
        elif t == "EXTERNPROTO":
            self.externproto()
        elif t in ("IMPORT", "EXPORT"):
            at = self.loc()
            kw = self.next()
            self.next()
            if self.peek() == "AS":
                self.next()
                self.next()
            self.b.warning(at, kw, f"{kw} is kept out of the model (no Inline is loaded)")
        else:
            return self.node()
        return None

    def route(self) -> None:
        at = self.loc()
        self.next()
        src = self.next()
        self.expect("TO")
        dst = self.next()
        if "." not in src or "." not in dst:
            raise self.b.fatal(at, "ROUTE needs NODE.field TO NODE.field")
        a, _, af = src.partition(".")
        c, _, cf = dst.partition(".")
        self.b.route(a, af, c, cf, at)

    def node(self) -> Node | None:
        at = self.loc()
        t = self.next()
        if t == "USE":
            return self.b.use(self.ident("a DEF name after USE"), at)
        if t == "NULL":
            return None
        def_name = None
        if t == "DEF":
            def_name = self.ident("a name after DEF")
            at = self.loc()
            t = self.next()
        if t in "[]{}" or t.startswith('"') or _NUMBER.match(t) or t in _KEYWORDS:
            raise self.b.fatal(at, f"expected a node, found {quoted(t)}")
        if t in self.b.protos:
            return self.proto_instance(t, def_name, at)
        node = self.b.node(t, at, def_name)
        self.expect("{")
        while self.peek() != "}":
            if self.peek() == _END:
                raise self.b.fatal(self.loc(), f"unexpected end of file inside {node.label} (missing '}}')")
            self.body_item(node)
        self.next()
        self.b.done(node)
        return node

    def body_item(self, node: Node) -> None:
        t = self.peek()
        if t in ("ROUTE", "PROTO", "EXTERNPROTO"):
            self.statement()
            return
        if t in _ACCESS and node.declares_fields:
            self.interface_decl(node)
            return
        at = self.loc()
        name = self.ident(f"a field name in {node.label}")
        if self.peek() == "IS":
            self.next()
            self.b.connect(node, name, self.ident("an interface field name after IS"), at)
            return
        fd = None
        if node.spec is not None:
            fd = self.b.field_def(node, name, at)
            if fd is None:
                decl = next((d for d in node.interface if d.name == name), None)
                if decl is not None:
                    self.decl_value(decl)
                    return
                self.skip_value()
                return
        if fd is not None and fd.type.kind == "node":
            if fd.name in node.field_locs:
                self.b.error(at, f"{node.label}.{node.spelling(fd.name)}",
                             f"field given twice (first at {node.field_locs[fd.name]})")
            self.node_value(node, fd.name, fd.type.multi)
        elif fd is not None:
            self.b.set_field(node, fd, self.value_tokens(fd.type), at, F.parse_vrml)
        else:
            self.generic_value(node, name, at)

    # -- values -----------------------------------------------------------------
    def is_node_start(self) -> bool:
        t = self.peek()
        return t in ("DEF", "USE", "NULL") or (self.peek(1) == "{" and t not in "[]{}" and t[0] != '"')

    def node_value(self, parent: Node, name: str, multi: bool) -> None:
        at = self.loc()
        if self.peek() == "[":
            self.next()
            if self.peek() == "]":
                self.b.set_null(parent, name, at)
            while self.peek() != "]":
                if self.peek() == _END:
                    raise self.b.fatal(self.loc(), f"unexpected end of file in {parent.label}.{name} (missing ']')")
                self.one_node(parent, name)
            self.next()
        else:
            if self.peek() == "NULL":
                self.next()
                self.b.set_null(parent, name, at)
                return
            self.one_node(parent, name)

    def one_node(self, parent: Node, name: str) -> None:
        at = self.loc()
        if not self.is_node_start():
            raise self.b.fatal(at, f"expected a node for {parent.label}.{name}, found {self.shown()}")
        child = self.node()
        if child is not None:
            self.b.add_child(parent, name, child, at)

    def value_tokens(self, ftype: F.FieldType) -> list[str]:
        """The tokens of one non-node value: a bracketed list, or one element."""
        if self.peek() == "[":
            self.next()
            out = []
            while self.peek() != "]":
                t = self.peek()
                if t == _END or t in ("[", "{", "}"):
                    raise self.b.fatal(self.loc(), f"expected ']' to close a {ftype.name} value, found {self.shown()}")
                out.append(self.next())
            self.next()
            return out
        count = ftype.width if ftype.numeric else 1
        if ftype.name == "SFImage":
            # width height components, then width*height pixels; a width or height that is no
            # integer (1.5) reads no pixels, and parsing the value says what is wrong
            head = self.scalars(3)
            w, h = (_image_size(x) for x in head[:2]) if len(head) >= 2 else (0, 0)
            if w is None or h is None:  # the pixels that follow are the value's too
                return head + self.scalars(1 << 62)
            return head + self.scalars(w * h)
        return self.scalars(count)

    def scalars(self, count: int) -> list[str]:
        """Up to count tokens of a value outside brackets: numbers, strings, booleans, and what
        Python would read as a number (1_000, inf, ١٠), so that it is refused as one, not read
        as the next field's name."""
        out = []
        while len(out) < count:
            t = self.peek()
            if not (t[0] in _NUMBER_START or t[0] == '"' or t == "TRUE" or t == "FALSE" or F.reads_as_float(t)):
                break
            out.append(self.next())
        return out

    def skip_value(self) -> None:
        """Step over the value of a field already reported as unknown."""
        if self.is_node_start():
            self.node()
        elif self.peek() == "[":
            depth = 0
            while True:
                t = self.next()
                depth += (t == "[") - (t == "]")
                if depth == 0:
                    break
        else:
            self.scalars(1 << 30)

    def generic_value(self, node: Node, name: str, at: Location) -> None:
        """A field of an unmodelled node type: nodes become children, the rest stays text."""
        if self.is_node_start():
            self.node_value(node, name, True)
            return
        if self.peek() == "[":
            j = self.i + 1
            if self.toks[j] in ("DEF", "USE") or (j < self.ntok and self.toks[j + 1] == "{"):
                self.node_value(node, name, True)
                return
            start = self.pos[self.i]
            self.value_tokens(F.FIELD_TYPES["MFString"])
        else:
            start = self.pos[self.i]
            if not self.scalars(1 << 30):
                raise self.b.fatal(at, f"expected a value for {node.label}.{name}, found {self.shown()}")
        end = self.pos[self.i - 1] + len(self.toks[self.i - 1])
        self.b.set_value(node, name, self.text[start:end], at, F.parse_vrml, "vrml")

    # -- interfaces, PROTOs -----------------------------------------------------
    def interface_decl(self, owner: Node | None, with_value: bool = True):
        at = self.loc()
        access = self.next()
        tname = self.ident("a field type")
        name = self.ident("a field name")
        decl = self.b.declare(owner, name, tname, access, at)
        if decl is None:
            raise self.b.fatal(at, f"cannot read the declaration of {name!r}")
        if with_value and decl.access in ("initializeOnly", "inputOutput"):
            if owner is not None and self.peek() == "IS":
                self.next()
                self.b.connect(owner, name, self.ident("an interface field name after IS"), at)
            else:
                self.decl_value(decl)
        return decl

    def decl_value(self, decl) -> None:
        if decl.type.kind == "node":
            holder = Node("field", None, decl.loc)
            self.node_value(holder, decl.name, decl.type.multi)
            kids = holder.values.get(decl.name, [])
            decl.value = kids if decl.type.multi else (kids[0] if kids else None)
        else:
            self.b.decl_value(decl, self.value_tokens(decl.type), F.parse_vrml)

    def interface(self, with_values: bool) -> dict:
        self.expect("[")
        out = {}
        while self.peek() != "]":
            if self.peek() not in _ACCESS:
                raise self.b.fatal(self.loc(), f"expected a field declaration, found {self.shown()}")
            d = self.interface_decl(None, with_values)
            out[d.name] = d
        self.next()
        return out

    def proto(self) -> None:
        at = self.loc()
        self.next()
        name = self.ident("a PROTO name")
        p = self.b.begin_proto(name, self.interface(True))
        self.expect("{")
        while self.peek() != "}":
            if self.peek() == _END:
                raise self.b.fatal(self.loc(), f"unexpected end of file in PROTO {name} (missing '}}')")
            n = self.statement()
            if n is not None:
                p.body.extend(self.b.beside([n]))
        self.next()
        self.b.end_proto(p, at)

    def externproto(self) -> None:
        at = self.loc()
        self.next()
        name = self.ident("an EXTERNPROTO name")
        self.interface(False)
        if not self.value_tokens(F.FIELD_TYPES["MFString"]):
            raise self.b.fatal(self.loc(), f"expected the URL list of EXTERNPROTO {name}, found {self.shown()}")
        self.b.declare_extern(name, at)

    def proto_instance(self, name: str, def_name: str | None, at: Location) -> Node | None:
        p = self.b.protos[name]
        values: dict[str, Any] = {}
        self.expect("{")
        while self.peek() != "}":
            if self.peek() == _END:
                raise self.b.fatal(self.loc(), f"unexpected end of file in {name} (missing '}}')")
            fat = self.loc()
            fname = self.ident(f"a field name of {name}")
            decl = p.interface.get(fname)
            if decl is None:
                self.b.error(fat, f"{name}.{fname}", f"PROTO {name} has no field {fname!r}")
                self.skip_value()
                continue
            if decl.type.kind == "node":
                holder = Node("field", None, fat)
                self.node_value(holder, fname, True)
                kids = holder.values.get(fname, [])
                values[fname] = kids if decl.type.multi else (kids[0] if kids else None)
            else:
                try:
                    values[fname] = F.parse_vrml(decl.type, self.value_tokens(decl.type))
                except F.FieldError as e:
                    self.b.error(fat, f"{name}.{fname}", str(e))
        self.next()
        return self.b.instantiate(name, values, at, def_name)
