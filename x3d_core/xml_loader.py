"""X3D XML encoding (.x3d), read with lxml: no DTD, no entity expansion, no network."""

from __future__ import annotations

import bisect
import re

from lxml import etree

from . import fields as F
from .build import Builder
from .model import Location, Node, Scene

_PARSER_OPTIONS = dict(resolve_entities=False, no_network=True, load_dtd=False, dtd_validation=False,
                       huge_tree=True, remove_comments=True, remove_pis=True)
_IGNORED_ATTRIBUTES = frozenset({"DEF", "USE", "containerField", "class", "id", "style"})
_ENTITY_DECL = re.compile(rb"<!ENTITY", re.I)
_ELEMENT_START = re.compile(rb"<[A-Za-z]")
_TAG_LINES = 50  # how far back a start tag may begin before the line lxml reports


class XmlBuilder(Builder):
    """Locates an attribute in the source for its diagnostic (lxml gives element lines only)."""

    def __init__(self, scene: Scene, source: bytes):
        super().__init__(scene)
        scene.locate = self.resolve
        self.source = source
        self._line_starts: list[int] | None = None

    def _lines(self) -> list[int]:
        if self._line_starts is None:
            starts = [0]
            starts.extend(m.end() for m in re.finditer(rb"\n", self.source))
            self._line_starts = starts
        return self._line_starts

    def resolve(self, loc: Location, subject: str) -> Location:
        """lxml gives the line where an element's start tag ends, nothing more: find the
        tag (named by the subject where it can) and the attribute the diagnostic is about."""
        starts = self._lines()
        if loc.col or loc.line < 1 or loc.line > len(starts):
            return loc
        line_start = starts[loc.line - 1]
        line_end = starts[loc.line] if loc.line < len(starts) else len(self.source)
        window = starts[max(0, loc.line - 1 - _TAG_LINES)]
        tag = subject.split(" ", 1)[0].split(".", 1)[0].encode()
        attribute = subject.rpartition(".")[2].encode() if "." in subject else b""
        candidates = []  # elements whose start tag ends on the reported line, last first
        for m in reversed(list(_ELEMENT_START.finditer(self.source, window, line_end))):
            tag_end = self.source.find(b">", m.start())
            if tag_end < line_start and m.start() < line_start:
                break
            candidates.append((m.start(), tag_end))
        if not candidates:
            return Location(loc.file, loc.line, 1)
        named = [c for c in candidates if self.source.startswith(tag, c[0] + 1)]
        pos, tag_end = (named or candidates)[0]
        if attribute:
            a = re.compile(rb"\s" + re.escape(attribute) + rb"\s*=").search(self.source, pos, tag_end)
            pos = a.start() + 1 if a else pos
        line = bisect.bisect_right(starts, pos)
        return Location(loc.file, line, pos - starts[line - 1] + 1)


def load_xml(path: str, source: bytes, scene: Scene) -> None:
    b = XmlBuilder(scene, source)
    parser = etree.XMLParser(**_PARSER_OPTIONS)
    try:
        root = etree.fromstring(source, parser, base_url=None)
    except etree.XMLSyntaxError as e:
        line, col = (e.position if e.position else (1, 0))
        msg = re.sub(r",? line \d+, column \d+$", "", e.msg or "malformed XML")
        raise b.fatal(Location(path, line or 1, col or 0), f"malformed XML: {msg}") from None
    dtd = root.getroottree().docinfo.internalDTD
    if dtd is not None and any(True for _ in dtd.iterentities()):
        m = _ENTITY_DECL.search(source)
        line = source.count(b"\n", 0, m.start()) + 1 if m else 1
        raise b.fatal(Location(path, line, 1), "entity declarations are not allowed in X3D files "
                                               "(x3drbp never expands entities)")
    if root.tag != "X3D":
        raise b.fatal(Location(path, root.sourceline or 1, 1),
                      f"not an X3D document: the root element is <{root.tag}>, expected <X3D>")
    scene.version = root.get("version", scene.version)
    scene.profile = root.get("profile", scene.profile)
    reader = _Reader(b, path)
    for child in root:
        if child.tag == "head":
            reader.head(child)
        elif child.tag == "Scene":
            for el in child:
                reader.statement(el, None)
    scene.roots = reader.roots


class _Reader:
    def __init__(self, b: XmlBuilder, path: str):
        self.b = b
        self.path = path
        self.roots: list[Node] = []

    def loc(self, el: etree._Element, attribute: str | None = None) -> Location:
        """The element's line; the column is found only if a diagnostic needs it."""
        loc = Location(self.path, el.sourceline or 0, 0)
        return self.b.resolve(loc, f".{attribute}") if attribute else loc

    def head(self, head: etree._Element) -> None:
        scene = self.b.scene
        for el in head:
            if el.tag == "component":
                try:
                    level = int(el.get("level", "1"))
                except ValueError:
                    self.b.error(self.loc(el, "level"), "component", f"level {el.get('level')!r} is not an integer")
                    level = 1
                self.b.component(el.get("name", ""), level)
            elif el.tag == "unit":
                self.unit(el)
            elif el.tag == "meta":
                scene.meta.append((el.get("name", ""), el.get("content", "")))

    def unit(self, el: etree._Element) -> None:
        self.b.unit(el.get("category", ""), el.get("name", ""), el.get("conversionFactor", ""), self.loc(el))

    # -- statements and nodes ---------------------------------------------------
    def statement(self, el: etree._Element, parent: Node | None) -> None:
        tag = el.tag
        if not isinstance(tag, str):
            return
        if tag == "ROUTE":
            self.b.route(el.get("fromNode", ""), el.get("fromField", ""), el.get("toNode", ""),
                         el.get("toField", ""), self.loc(el))
        elif tag == "ProtoDeclare":
            self.proto_declare(el)
        elif tag == "ExternProtoDeclare":
            self.b.declare_extern(el.get("name", ""), self.loc(el))
        elif tag in ("IMPORT", "EXPORT"):
            self.b.warning(self.loc(el), tag, f"{tag} is kept out of the model (no Inline is loaded)")
        elif tag == "IS":
            if parent is not None:
                for c in el:
                    if c.tag == "connect":
                        self.b.connect(parent, c.get("nodeField", ""), c.get("protoField", ""), self.loc(c))
        elif tag in ("field", "fieldValue"):
            self.b.error(self.loc(el), tag, f"<{tag}> is only allowed in a Script, ProtoDeclare or ProtoInstance")
        else:
            node = self.node(el)
            if node is None:
                return
            if parent is None:
                self.roots.append(node)
            else:
                self.b.add_child(parent, el.get("containerField"), node, Location(self.path, el.sourceline or 0))

    def node(self, el: etree._Element) -> Node | None:
        tag = el.tag
        use = el.get("USE")
        if use is not None:
            loc = Location(self.path, el.sourceline or 0)
            n = self.b.use(use, loc)
            if n is not None and tag != "ProtoInstance" and n.type_name != tag:
                self.b.error(loc, f"USE {use}", f"names a {n.type_name}, not a {tag}")
                return None
            given = [a for a in el.attrib if a not in _IGNORED_ATTRIBUTES and not a.startswith("{")]
            given += [c.tag for c in el if isinstance(c.tag, str)]
            if given:
                self.b.error(loc, f"USE {use}", f"a USE takes no field values or children, and {', '.join(given)} "
                                                "would be ignored: set them where the node is DEFined")
            return n
        if tag == "ProtoInstance":
            return self.proto_instance(el)
        loc = self.loc(el)
        node = self.b.node(tag, loc, el.get("DEF"))
        for name, text in el.attrib.items():
            if name in _IGNORED_ATTRIBUTES or name.startswith("{"):
                continue
            self.b.set_value(node, name, text, loc, F.parse_xml, "xml")
        for child in el:
            if child.tag == "field" and node.declares_fields:
                self.interface_field(node, child)
            elif child.tag in ("fieldValue",):
                self.b.error(self.loc(child), child.tag, "<fieldValue> belongs in a ProtoInstance")
            else:
                self.statement(child, node)
        if node.declares_fields:  # a Script's source: CDATA anywhere among its <field>s
            text = ((el.text or "") + "".join(c.tail or "" for c in el)).strip()
            if text:
                self.b.set_value(node, "sourceCode", text, loc, F.parse_xml, "xml")
        self.b.done(node)
        return node

    def interface_field(self, owner: Node | None, el: etree._Element):
        decl = self.b.declare(owner, el.get("name", ""), el.get("type", ""), el.get("accessType", ""), self.loc(el))
        if decl is None:
            return None
        if el.get("value") is not None:
            if decl.type.kind == "node":
                self.b.error(self.loc(el, "value"), decl.name, "a node field's value is given as child nodes")
            else:
                self.b.decl_value(decl, el.get("value"), F.parse_xml)
        kids = [self.node(c) for c in el if isinstance(c.tag, str)]
        kids = [k for k in kids if k is not None]
        if kids:
            decl.value = kids if decl.type.multi else kids[0]
        return decl

    def proto_declare(self, el: etree._Element) -> None:
        name = el.get("name", "")
        interface = {}
        iface = el.find("ProtoInterface")
        if iface is not None:
            for f in iface:
                if f.tag == "field":
                    d = self.interface_field(None, f)
                    if d is not None:
                        interface[d.name] = d
        p = self.b.begin_proto(name, interface)
        body = el.find("ProtoBody")
        if body is not None:
            for c in body:
                if c.tag in ("ROUTE", "ProtoDeclare"):
                    self.statement(c, None)
                    continue
                n = self.node(c) if isinstance(c.tag, str) else None
                if n is not None:
                    p.body.append(n)
        self.b.end_proto(p, self.loc(el))

    def proto_instance(self, el: etree._Element) -> Node | None:
        name = el.get("name", "")
        proto = self.b.protos.get(name)
        values = {}
        for fv in el:
            if fv.tag != "fieldValue":
                continue
            fname = fv.get("name", "")
            decl = proto.interface.get(fname) if proto else None
            if proto is not None and decl is None:
                self.b.error(self.loc(fv), f"ProtoInstance {name}.{fname}", f"PROTO {name} has no field {fname!r}")
                continue
            if decl is None:
                continue
            if decl.type.kind == "node":
                kids = [k for k in (self.node(c) for c in fv if isinstance(c.tag, str)) if k is not None]
                values[fname] = kids if decl.type.multi else (kids[0] if kids else None)
            else:
                try:
                    values[fname] = F.parse_xml(decl.type, fv.get("value", ""))
                except F.FieldError as e:
                    self.b.error(self.loc(fv, "value"), f"ProtoInstance {name}.{fname}", str(e))
        return self.b.instantiate(name, values, self.loc(el), el.get("DEF"))
