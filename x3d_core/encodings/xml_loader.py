"""X3D XML encoding (.x3d), read with lxml: no DTD, no entity expansion, no network."""

from __future__ import annotations

import bisect
import re
from array import array

from lxml import etree

from x3d_core.files.paths import quoted
from x3d_core.model import fields as F
from x3d_core.model.scene import Location, Node, Scene

from .build import Builder
from .line_index import LineIndex

_PARSER_OPTIONS = dict(resolve_entities=False, no_network=True, load_dtd=False, dtd_validation=False,
                       huge_tree=True, remove_comments=True, remove_pis=True)
_IGNORED_ATTRIBUTES = frozenset({"DEF", "USE", "containerField", "class", "id", "style"})
_ENTITY_DECL = re.compile(rb"<!ENTITY", re.I)
_ELEMENT_START = re.compile(rb"<[A-Za-z]")
_TAG_LINES = 50  # how far back a start tag may begin before the line lxml reports
_GUESSES = 256  # start tags looked at when only the line of an element is known
# What can hold a '<' that starts no element (comments, CDATA, processing instructions, the
# DOCTYPE), else an element's '<' and the first letter of its name: a match of 2 bytes
_MARKUP = re.compile(rb"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>|<!DOCTYPE(?:[^\[>]++|\[.*?\])*+>|<[A-Za-z_:]",
                     re.S)
_TAG_NAME = re.compile(rb"<[^\s/>]+")
_AFTER_NAME = frozenset((b" ", b"\t", b"\r", b"\n", b"/", b">"))
_ATTRIBUTE = re.compile(rb"\s+([^\s=/>]+)\s*=\s*(?:\"[^\"]*+\"|'[^']*+')")
_START_TAG = re.compile(rb"<[^\s/>]+(?:\s+[^\s=/>]+\s*=\s*(?:\"[^\"]*+\"|'[^']*+'))*+\s*+/?>")


class XmlBuilder(Builder):
    """Places an element, and the attribute a diagnostic is about, in the source: lxml gives
    only the line where a start tag ends (the same for every element of a minified file).

    One scan lists every start tag's offset in document order, the order root.iter() gives
    the elements, so an element's start tag is found by its index; a tag's attributes are
    read once, when a diagnostic first asks about one of them."""

    def __init__(self, scene: Scene, source: bytes):
        super().__init__(scene)
        scene.locate = self.resolve
        self.source = source
        self.lines = LineIndex(source)
        self._tags = array("q")  # offset of each element's start tag, in document order
        self._order: dict[etree._Element, int] = {}  # element -> its index in document order
        self._attributes: dict[int, dict[bytes, int]] = {}  # tag offset -> attribute name -> offset
        self._ends: dict[int, int] = {}  # tag offset -> offset of its '>'

    def index(self, root: etree._Element) -> None:
        """Pair the elements of the parsed tree with their start tags. Only the elements of a
        line where two start tags of one name end (a minified file's, one another's children
        of one type) are kept in a table: elsewhere the line and the node type name one tag."""
        self._tags = array("q", (m.start() for m in _MARKUP.finditer(self.source) if m.end() - m.start() == 2))
        order: dict[etree._Element, int] = {}
        line, names, on_line, repeated = -1, set(), [], False
        n = 0
        for n, el in enumerate(root.iter(tag=etree.Element), 1):
            if el.sourceline != line:
                if repeated:
                    order.update(on_line)
                line, repeated = el.sourceline, False
                names.clear()
                on_line.clear()
            repeated = repeated or el.tag in names
            names.add(el.tag)
            on_line.append((el, n - 1))
        if repeated:
            order.update(on_line)
        if n == len(self._tags):
            self._order = order
        else:  # never expected of a file lxml parsed: fall back to the lines lxml gives
            self._tags = array("q")

    def element_loc(self, path: str, el: etree._Element) -> Location:
        """Where an element's start tag begins, if the index pairs it; else the line lxml gives
        (column 0: resolve() finds the tag, and the attribute, when a diagnostic asks)."""
        i = self._order.get(el)
        if i is None:
            return Location(path, el.sourceline or 0, 0)
        return self.lines.location(path, self._tags[i])

    def _tag_attributes(self, tag: int) -> dict[bytes, int]:
        """Each attribute's offset in the start tag at an offset (read once per tag)."""
        found = self._attributes.get(tag)
        if found is None:
            if len(self._attributes) >= 64:
                self._attributes.clear()
            found = {}
            m = _TAG_NAME.match(self.source, tag)
            pos = m.end() if m else tag + 1
            while (a := _ATTRIBUTE.match(self.source, pos)) is not None:
                found.setdefault(a.group(1), a.start(1))
                pos = a.end()
            self._attributes[tag] = found
        return found

    def resolve(self, loc: Location, subject: str) -> Location:
        """The place of a diagnostic about an element (a location at its start tag) or a field
        (the attribute that gives it, where the tag has one)."""
        if loc.line < 1:
            return loc
        attribute = subject.rpartition(".")[2].encode() if "." in subject else b""
        if loc.col:
            start = self.lines.line_start(loc.line)
            tag = None if start is None else start + loc.col - 1
            if tag is None or self.source[tag:tag + 1] != b"<":
                return loc  # already exact
        else:
            tag = self._guess_tag(loc, subject)
            if tag is None:
                return Location(loc.file, loc.line, 1)
        pos = self._tag_attributes(tag).get(attribute, tag) if attribute else tag
        return self.lines.location(loc.file, pos)

    def _guess_tag(self, loc: Location, subject: str) -> int | None:
        """For an element known only by its line (the line where its start tag ends): among
        the start tags that end there, the last of the subject's node type, else the last."""
        line_start = self.lines.line_start(loc.line)
        if line_start is None:
            return None
        line_end = self.lines.line_end(loc.line)
        window = self.lines.line_start(max(1, loc.line - _TAG_LINES)) or 0
        if self._tags:
            hi = bisect.bisect_left(self._tags, line_end)
            starts = self._tags[max(bisect.bisect_left(self._tags, window), hi - _GUESSES):hi]
        else:
            starts = array("q")
            for m in _ELEMENT_START.finditer(self.source, window, line_end):
                starts.append(m.start())
                if len(starts) > 2 * _GUESSES:
                    del starts[:_GUESSES]  # bounded work and memory on a long line
        name = subject.split(" ", 1)[0].split(".", 1)[0].encode()
        last = None
        for c in reversed(starts):
            end = self._tag_end(c)
            if end < line_start:
                break
            if end >= line_end:  # starts on the line but ends on a later one
                continue
            last = c if last is None else last
            if self.source.startswith(name, c + 1) and self.source[c + 1 + len(name):c + 2 + len(name)] in _AFTER_NAME:
                return c
        return last

    def _tag_end(self, tag: int) -> int:
        """The offset of a start tag's '>' (kept: many diagnostics may ask about one long tag)."""
        end = self._ends.get(tag)
        if end is None:
            if len(self._ends) >= 4096:
                self._ends.clear()
            m = _START_TAG.match(self.source, tag)
            end = self._ends[tag] = m.end() - 1 if m else self.source.find(b">", tag)
        return end


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
    b.index(root)
    reader = _Reader(b, path)
    for child in root:
        if child.tag == "head":
            reader.head(child)
        elif child.tag == "Scene":
            for el in child:
                reader.statement(el, None)
    scene.roots = reader.roots
    b.finish()


class _Reader:
    def __init__(self, b: XmlBuilder, path: str):
        self.b = b
        self.path = path
        self.roots: list[Node] = []

    def loc(self, el: etree._Element, attribute: str | None = None) -> Location:
        """Where the element's start tag begins, or the attribute named (if the tag has it)."""
        loc = self.b.element_loc(self.path, el)
        return self.b.resolve(loc, f".{attribute}") if attribute else loc

    def head(self, head: etree._Element) -> None:
        scene = self.b.scene
        for el in head:
            if el.tag == "component":
                try:
                    level = F.parse_xml(F.FIELD_TYPES["SFInt32"], el.get("level", "1"))
                except F.FieldError:
                    self.b.error(self.loc(el, "level"), "component",
                                 f"level {quoted(el.get('level'))} is not an integer")
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
                self.roots.extend(self.b.beside([node]))
            else:
                self.b.add_child(parent, el.get("containerField"), node, self.loc(el))

    def node(self, el: etree._Element) -> Node | None:
        tag = el.tag
        use = el.get("USE")
        if use is not None:
            loc = self.loc(el)
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
                    p.body.extend(self.b.beside([n]))
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
