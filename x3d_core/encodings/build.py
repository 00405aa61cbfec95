"""What every loader shares: typing field values, DEF/USE, containment, PROTO expansion.

A loader only tokenizes its encoding and calls a Builder, so each rule of the model
(which field a child goes to, what a USE cycle is, which values are in range, how
UNITs apply) is written once for the three encodings.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from collections.abc import Iterator
from typing import Any, Callable

import numpy as np

from x3d_core.files.paths import quoted
from x3d_core.model import fields as F
from x3d_core.model import editions
from x3d_core.model import schema
from x3d_core.model.scene import Diagnostic, FieldDecl, LoadError, Location, Node, Route, Scene
from x3d_core.model.units import BASE_CATEGORIES, factor

Parser = Callable[[F.FieldType, Any], Any]


@dataclass(frozen=True)
class RawValue:
    """A field of a node type x3drbp does not model, kept as the file wrote it."""
    encoding: str  # "xml" | "vrml" | "json"
    data: Any  # attribute text, ClassicVRML text, or the JSON value


@dataclass
class ProtoDecl:
    name: str
    interface: dict[str, FieldDecl]
    body: list[Node] = field(default_factory=list)
    links: list[tuple[Node, str, str]] = field(default_factory=list)  # (body node, its field, interface field)
    routes: list[Route] = field(default_factory=list)


# Node type and field names (X3D's are XML names: they must also be writable as such)
NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_\-]*")

# Field names of Xj3D's pre-standard component (COMPONENT xj3d_RigidBodyPhysics) that
# the standard renamed
PRESTANDARD_NAMES = {("*", "mustOutput"): "forceOutput", ("CollisionSensor", "collidables"): "collider"}

# PROTO expansion copies a body per instance, and a body may itself instantiate PROTOs: a
# PROTO nested 20 deep whose body instantiates the one before twice is a 1 KB file that
# expands to 2^21 nodes (103 s and 2.6 GiB before these bounds), and a body node holding a
# 30,000-point array doubled 12 times is a 290 KB file that wants 2.9 GB of copies. A load
# copies at most this many nodes, and this many bytes of array values, by expansion, then
# stops with an error at the instance that passes either. An expanded node costs ~0.5 KB
# and ~10 us through load and validation: a scene near the bound loads in ~3 s and ~150 MiB,
# one past it is refused in ~1 s (10^6 took 16 s to load and 5 s to refuse). The corpus,
# scenes/ and the conformance cases expand at most 5 nodes; the largest has about 100.
MAX_EXPANDED_NODES = 250_000
MAX_EXPANDED_BYTES = 256 * 1024 * 1024


class _ExpansionTooLarge(Exception):
    """A PROTO copy that would pass a bound (raised by _copy, caught by instantiate)."""


class _Budget:
    """What PROTO expansion may still copy in this load."""
    __slots__ = ("nodes", "bytes")

    def __init__(self) -> None:
        self.nodes = MAX_EXPANDED_NODES
        self.bytes = MAX_EXPANDED_BYTES


# Node types that only present a scene: a value out of range there cannot change the
# physics, so it is a warning, not an error.
PRESENTATION = frozenset({"Appearance", "Material", "Background", "Viewpoint", "NavigationInfo",
                          "DirectionalLight", "WorldInfo", "TimeSensor", "PositionInterpolator",
                          "OrientationInterpolator", "Color", "Normal", "TextureCoordinate"})


def _base_names(name: str) -> Iterator[str]:
    """The inputOutput field an event name may stand for: X3D routes to an inputOutput FOO
    as set_FOO and from it as FOO_changed."""
    for prefix, suffix in (("set_", ""), ("", "_changed")):
        if name.startswith(prefix) and name.endswith(suffix):
            yield name[len(prefix):len(name) - len(suffix)]


def _base_field(spec: schema.NodeType, name: str) -> schema.FieldDef | None:
    """The field a name of the type's edition stands for: its own, or an event name of it."""
    fd = spec.named(name)
    if fd is not None:
        return fd
    fds = (spec.named(base) for base in _base_names(name))
    return next((fd for fd in fds if fd is not None and fd.access == "inputOutput"), None)


def _declared_field(node: Node, name: str) -> FieldDecl | None:
    """A field the node's file declares (a Script's), by its name or an event name of it."""
    by_name = {d.name: d for d in node.interface}
    if name in by_name:
        return by_name[name]
    decls = (by_name.get(base) for base in _base_names(name))
    return next((d for d in decls if d is not None and d.access == "inputOutput"), None)


class Builder:
    def __init__(self, scene: Scene):
        self.scene = scene
        self.scopes: list[dict[str, Node]] = [{}]
        self.protos: dict[str, ProtoDecl] = {}
        self.open: set[int] = set()  # nodes whose definition is still being read
        self.proto_stack: list[ProtoDecl] = []
        self.externs: set[str] = set()
        self.prestandard = False  # the file declares an xj3d_ component
        self.budget = _Budget()  # what PROTO expansion may still copy
        # a PROTO instance's first root -> (it, held so that its id stays its own; the body's other
        # roots; the PROTO's name; the instance's place), until others() places them after it;
        # finish() names those never placed
        self.unplaced: dict[int, tuple[Node, list[Node], str, Location]] = {}

    # -- diagnostics --------------------------------------------------------
    def error(self, loc: Location, subject: str, message: str) -> None:
        self.scene.diagnostics.append(Diagnostic("error", self.resolve(loc, subject), subject, message))

    def warning(self, loc: Location, subject: str, message: str) -> None:
        self.scene.diagnostics.append(Diagnostic("warning", self.resolve(loc, subject), subject, message))

    def resolve(self, loc: Location, subject: str) -> Location:
        """The exact place of a diagnostic; encodings whose parser gives less override it."""
        return loc

    def fatal(self, loc: Location, message: str) -> LoadError:
        return LoadError(Diagnostic("error", loc, "", message))

    # -- nodes --------------------------------------------------------------
    @property
    def defs(self) -> dict[str, Node]:
        return self.scopes[-1]

    def node(self, type_name: str, loc: Location, def_name: str | None = None) -> Node:
        """A new node, entered as being read until done() is called. An EXTERNPROTO's instance
        is kept untyped even where a later X3D version has a node of its name (4.1's Delay):
        the file's declaration wins over the built-in, whose fields it need not have."""
        spec = None if type_name in self.externs else editions.node_type(type_name, self.scene.version)
        if spec is None and not NAME.fullmatch(type_name):
            raise self.fatal(loc, f"{type_name!r} is not a node type name")
        if type_name == "Script":
            self.warning(loc, type_name, f"{type_name} is kept in the model but does not run")
        n = Node(type_name, spec, loc, def_name)
        if def_name:
            if def_name in self.defs:
                self.warning(loc, n.label, f"DEF name {def_name!r} redefined (first at {self.defs[def_name].loc}); "
                                           "later USEs get this node")
            self.defs[def_name] = n
        self.open.add(id(n))
        return n

    def done(self, node: Node) -> None:
        self.open.discard(id(node))

    def use(self, name: str, loc: Location) -> Node | None:
        n = self.defs.get(name)
        if n is None:
            self.error(loc, f"USE {name}", f"USE of undefined name {name!r}; a USE must follow its DEF")
            return None
        if id(n) in self.open:
            self.error(loc, f"USE {name}", f"USE cycle: {n.label} is used inside its own definition")
            return None
        return n

    # -- field values -------------------------------------------------------
    def field_def(self, node: Node, name: str, loc: Location) -> schema.FieldDef | None:
        """The definition of a field a file names on a typed node, with an error if unknown. A
        name of the other X3D edition is read as the field it names, and the node keeps the
        file's spelling for writers and diagnostics."""
        assert node.spec is not None
        fd = _base_field(node.spec, name)
        if fd is None:
            fd = self.other_edition(node, name, loc, f"{node.label}.{name}")
            if fd is not None:
                node.spellings = {**node.spellings, fd.name: name}
        if fd is None and self.prestandard:
            alias = PRESTANDARD_NAMES.get((node.type_name, name)) or PRESTANDARD_NAMES.get(("*", name))
            fd = node.spec.fields.get(alias) if alias else None
            if fd is not None:
                self.warning(loc, f"{node.label}.{name}", f"pre-standard (Xj3D) name read as {alias}")
        if fd is None:
            for decl in node.interface:
                if decl.name == name:
                    return None
            import difflib  # here: only a misspelt field needs it (every `x3drbp run` imported it)
            names = [node.spec.spelled(f) for f in node.spec.fields if f not in node.spec.absent]
            near = difflib.get_close_matches(name, names, n=1, cutoff=0.7)
            hint = f"; did you mean {near[0]!r}?" if near else ""
            self.error(loc, f"{node.label}.{name}", f"{node.type_name} has no field {name!r}{hint}")
        return fd

    def other_edition(self, node: Node, name: str, loc: Location, subject: str) -> schema.FieldDef | None:
        """The field a name of the other X3D edition (or a slip of clause 37's text) stands for,
        with the warning that names the spelling of the file's version: a warning, not an
        error, as x3d_core/model/editions.py says why."""
        found = editions.foreign(node.spec, name, self.scene.version)
        if found is None:
            return None
        self.warning(loc, subject, found.message)
        return found.field

    def set_value(self, node: Node, name: str, raw: Any, loc: Location, parse: Parser, encoding: str) -> None:
        """Give a field its value from the file's text (or JSON value)."""
        if node.spec is None:
            if not NAME.fullmatch(name):
                self.error(loc, f"{node.label}.{name}", f"{name!r} is not a field name")
                return
            node.values[name] = RawValue(encoding, raw)
            node.field_locs[name] = loc
            return
        fd = self.field_def(node, name, loc)
        if fd is not None:
            self.set_field(node, fd, raw, loc, parse)

    def set_field(self, node: Node, fd: schema.FieldDef, raw: Any, loc: Location, parse: Parser) -> None:
        """Give a field the file named (field_def found it) its value from the file's text."""
        subject = f"{node.label}.{node.spelling(fd.name)}"
        if fd.type.kind == "node":
            self.error(loc, subject, f"{fd.type.name} field takes nodes, not a value")
            return
        if not fd.readable:
            self.error(loc, subject, f"{fd.access} field cannot be given a value in a file")
            return
        try:
            value = parse(fd.type, raw)
        except F.FieldError as e:
            self.error(loc, subject, str(e))
            return
        self.store(node, fd, value, loc)

    def store(self, node: Node, fd: schema.FieldDef, value: Any, loc: Location, convert: bool = True) -> None:
        """Keep a typed value: UNITs applied, then checked against the field's range."""
        subject = f"{node.label}.{node.spelling(fd.name)}"
        if convert and self.scene.units:
            with np.errstate(over="ignore", invalid="ignore"):  # said below, in one line
                value = self.to_si(fd, value)
            if not _finite(value):  # the encodings refuse nan and inf, but a UNIT (length 1e300) can make them
                units = ", ".join(f"{c} {u[0]} {F._num(u[1])}" for c, u in self.scene.units.items())
                self.error(loc, subject, "not a finite number once converted to SI units by "
                                         f"the file's UNIT statements ({units})")
                return
        if fd.range is not None and not fd.type.rotation and not fd.range.contains(value):
            numbers = np.asarray(value, dtype=np.float64).ravel()
            if numbers.size:
                bad = numbers[~fd.range.inside(numbers)][0]
                message = f"{F._num(bad)} is out of range; allowed {fd.range}"
                if node.type_name not in PRESENTATION:
                    self.error(loc, subject, message)
                    return
                self.warning(loc, subject, message + " (kept: it does not affect physics)")
        if fd.name in node.values and fd.name in node.field_locs:
            self.error(loc, subject, f"field given twice (first at {node.field_locs[fd.name]})")
            return
        node.values[fd.name] = value
        node.field_locs[fd.name] = loc

    def to_si(self, fd: schema.FieldDef, value: Any) -> Any:
        units = {k: v[1] for k, v in self.scene.units.items()}
        if fd.type.rotation and "angle" in units:
            value = np.array(value, dtype=np.float64)
            value[..., 3] *= units["angle"]
        k = factor(fd.unit, units)
        if k != 1.0:
            value = value * k if not isinstance(value, np.ndarray) else value * k
        return value

    # -- containment --------------------------------------------------------
    def add_child(self, parent: Node, name: str | None, child: Node, loc: Location) -> None:
        """Put a child node into a field of its parent. name None: the child's default
        containerField, or else the one field of the parent that accepts it."""
        if parent.spec is None:
            key = name or (child.spec.container_field if child.spec else "children")
            slot = parent.values.setdefault(key, [])
            if isinstance(slot, list):
                slot.append(child)
            return
        fd = None
        if name is not None:
            fd = self.field_def(parent, name, loc)
            if fd is None:
                return
        else:
            default = child.spec.container_field if child.spec else "children"
            fd = parent.spec.fields.get(default)
            if fd is None or fd.type.kind != "node" or not schema.accepts(fd, child.type_name):
                fits = [f for f in parent.spec.fields.values()
                        if f.type.kind == "node" and f.readable and f.accepts and schema.accepts(f, child.type_name)
                        and not (f.name == "metadata" and child.spec and not child.spec.is_a("X3DMetadataObject"))]
                if len(fits) == 1:
                    inferred, fd = fd, fits[0]
                    if fd.name != "metadata":  # where every browser puts a metadata node
                        self.warning(loc, f"{parent.label}.{fd.name}",
                                     f"a {child.type_name} goes by default into {default!r}, which "
                                     f"{'does not accept it' if inferred is not None else f'{parent.type_name} lacks'}"
                                     f"; taken as {fd.name!r}, the one field that accepts it, which browsers need not "
                                     f"do (X_ITE 15 does not): give containerField='{fd.name}'")
                elif fd is None:
                    self.error(loc, f"{parent.label}.{default}",
                               f"{parent.type_name} has no field {default!r} for a {child.type_name} "
                               f"(give containerField)")
                    return
        subject = f"{parent.label}.{fd.name}"
        if fd.type.kind != "node":
            self.error(loc, subject, f"{fd.type.name} field cannot hold a node ({child.type_name})")
            return
        if not fd.readable:
            self.error(loc, subject, f"{fd.access} field cannot be given a value in a file")
            return
        if not schema.accepts(fd, child.type_name):
            message = f"a {child.type_name} is not allowed here; allowed: {' or '.join(fd.accepts)}"
            if not parent.spec.is_a("X3DMetadataObject"):
                self.error(loc, subject, message)
                return
            # metadata carries no meaning for a browser; editors (Titania) store any node there
            self.warning(loc, subject, message + " (kept: metadata has no effect)")
        if fd.type.multi:
            parent.values.setdefault(fd.name, []).extend([child, *self.others(child, fd)])
            parent.field_locs.setdefault(fd.name, loc)
        elif fd.name in parent.values and parent.values[fd.name] is not None:
            self.error(loc, subject, f"{fd.type.name} field already holds {parent.values[fd.name].label}")
        else:
            parent.values[fd.name] = child
            parent.field_locs[fd.name] = loc

    def set_null(self, node: Node, name: str, loc: Location) -> None:
        """An explicit NULL (or empty MFNode) for a node field."""
        if node.spec is None:
            node.values.setdefault(name, [])
            return
        fd = self.field_def(node, name, loc)
        if fd is None:
            return
        if fd.type.kind != "node":
            self.error(loc, f"{node.label}.{name}", f"NULL is not a value of {fd.type.name}")
            return
        node.values[fd.name] = [] if fd.type.multi else None

    # -- header ---------------------------------------------------------------
    def component(self, name: str, level: int) -> None:
        """Pre-standard files (Xj3D) declare xj3d_RigidBodyPhysics: read as RigidBodyPhysics."""
        if name.startswith("xj3d_"):
            self.prestandard = True
            name = name[5:]
        self.scene.components.append((name, level))

    def unit(self, category: str, name: str, factor_text: str, loc: Location) -> None:
        if category not in BASE_CATEGORIES:
            self.error(loc, "UNIT", f"unknown unit category {category!r}; allowed: {', '.join(BASE_CATEGORIES)}")
            return
        try:
            k = F.number(factor_text)
        except F.FieldError:
            k = -1.0
        if not 0 < k < float("inf"):
            self.error(loc, f"UNIT {category}", f"conversion factor {quoted(factor_text)} must be a positive number "
                                                f"({F.GRAMMAR})")
            return
        self.scene.units[category] = (name, k)

    # -- routes -------------------------------------------------------------
    def route(self, from_name: str, from_field: str, to_name: str, to_field: str, loc: Location) -> None:
        subject = f"ROUTE {from_name}.{from_field} TO {to_name}.{to_field}"
        ends, types = [], []
        for name, fname, direction in ((from_name, from_field, "out"), (to_name, to_field, "in")):
            n = self.defs.get(name)
            if n is None:
                self.error(loc, subject, f"no node named {name!r}")
                return
            if n.spec is not None:
                end = _base_field(n.spec, fname) or self.other_edition(n, fname, loc, subject) or \
                    _declared_field(n, fname)
                if end is None or end.access not in (("inputOutput", "outputOnly") if direction == "out" else
                                                     ("inputOutput", "inputOnly")):
                    what = "output" if direction == "out" else "input"
                    self.error(loc, subject, f"{n.label} has no {what} field {fname!r}")
                    return
                types.append(end.type)
            ends.append(n)
        if len(types) == 2 and types[0] is not types[1]:
            self.error(loc, subject, f"a ROUTE joins fields of one type; this one joins {types[0].name} "
                                     f"to {types[1].name}")
            return
        r = Route(ends[0], from_field, ends[1], to_field, loc)
        (self.proto_stack[-1].routes if self.proto_stack else self.scene.routes).append(r)

    # -- interfaces and PROTOs ----------------------------------------------
    def declare(self, owner: Node | None, name: str, type_name: str, access: str, loc: Location) -> FieldDecl | None:
        ftype = F.FIELD_TYPES.get(type_name)
        if not NAME.fullmatch(name):
            self.error(loc, name, f"{name!r} is not a field name")
            return None
        if ftype is None:
            self.error(loc, name, f"unknown field type {type_name!r}")
            return None
        if access in ("eventIn", "eventOut", "field", "exposedField"):  # VRML97 spellings
            access = {"eventIn": "inputOnly", "eventOut": "outputOnly", "field": "initializeOnly",
                      "exposedField": "inputOutput"}[access]
        if access not in schema.ACCESS_TYPES:
            self.error(loc, name, f"unknown access type {access!r}; allowed: {', '.join(schema.ACCESS_TYPES)}")
            return None
        decl = FieldDecl(name, ftype, access, F.empty(ftype), loc)
        if owner is not None:
            if not owner.interface:
                owner.interface = []
            owner.interface.append(decl)
        return decl

    def decl_value(self, decl: FieldDecl, raw: Any, parse: Parser) -> None:
        try:
            decl.value = parse(decl.type, raw)
        except F.FieldError as e:
            self.error(decl.loc, decl.name, str(e))

    def begin_proto(self, name: str, interface: dict[str, FieldDecl]) -> ProtoDecl:
        p = ProtoDecl(name, interface)
        self.proto_stack.append(p)
        self.scopes.append({})
        return p

    def end_proto(self, p: ProtoDecl, loc: Location) -> None:
        self.scopes.pop()
        self.proto_stack.pop()
        if not p.body:
            self.error(loc, f"PROTO {p.name}", "PROTO body holds no node")
            return
        self.protos[p.name] = p
        self.scene.protos.append(p.name)

    def connect(self, node: Node, node_field: str, proto_field: str, loc: Location) -> None:
        """An IS: the body node's field takes the instance's value of an interface field."""
        if not self.proto_stack:
            self.error(loc, f"{node.label}.{node_field}", "IS outside a PROTO body")
            return
        p = self.proto_stack[-1]
        decl = p.interface.get(proto_field)
        if decl is None:
            self.error(loc, f"{node.label}.{node_field}", f"PROTO {p.name} has no field {proto_field!r}")
            return
        if node.spec is not None:
            fd = self.field_def(node, node_field, loc)
            if fd is None:
                return
            if fd.type is not decl.type:
                self.error(loc, f"{node.label}.{node_field}",
                           f"IS {proto_field} joins {fd.type.name} to {decl.type.name}")
                return
            node_field = fd.name
        p.links.append((node, node_field, proto_field))

    def declare_extern(self, name: str, loc: Location) -> None:
        self.warning(loc, f"EXTERNPROTO {name}", "external PROTOs are never fetched; "
                                                 "their instances are kept as nodes that do not run")
        self.externs.add(name)

    def instantiate(self, name: str, values: dict[str, Any], loc: Location, def_name: str | None) -> Node | None:
        """Expand a PROTO in place: a copy of its body with the instance's field values."""
        p = self.protos.get(name)
        if p is None and name in self.externs:
            n = self.node(name, loc, def_name)
            self.done(n)
            return n
        if p is None:
            self.error(loc, name, f"unknown node type {name!r} (no PROTO of that name is declared before it)")
            return None
        memo: dict[int, Node] = {}
        prefix = def_name or name
        try:
            body = [_copy(n, memo, prefix, self.budget) for n in p.body]
        except _ExpansionTooLarge:
            subject = f"ProtoInstance {name}"
            what = (f"{MAX_EXPANDED_NODES:,} nodes" if self.budget.nodes < 0 else
                    f"{MAX_EXPANDED_BYTES // 2**20} MiB of field values")
            raise LoadError(Diagnostic(
                "error", self.resolve(loc, subject), subject,
                f"PROTO instances expand the scene past {what} (x3drbp expands no further; "
                f"instances inside PROTO bodies multiply)")) from None
        for node, fname, pname in p.links:
            target = memo[id(node)]
            decl = p.interface[pname]
            value = values[pname] if pname in values else decl.value
            if decl.type.kind == "node":
                value = self.proto_nodes(target, fname, pname, value, loc)
            if target.spec is None:
                target.values[fname] = value if decl.type.kind == "node" else \
                    RawValue("vrml", F.format_vrml(decl.type, value))
            elif decl.type.kind == "node":
                target.values[fname] = value
            else:
                target.values.pop(fname, None)
                target.field_locs.pop(fname, None)
                self.store(target, target.spec.fields[fname], value, loc)
        # an instance inside a PROTO body: its routes are the body's, copied with each instance of it
        routes = self.proto_stack[-1].routes if self.proto_stack else self.scene.routes
        for r in p.routes:
            routes.append(Route(memo[id(r.from_node)], r.from_field, memo[id(r.to_node)], r.to_field, loc))
        first = body[0]
        first.def_name = def_name
        if def_name:
            self.defs[def_name] = first
        if len(body) > 1:
            self.unplaced[id(first)] = (first, body[1:], name, loc)
        return first

    def others(self, node: Node, fd: schema.FieldDef | None = None) -> list[Node]:
        """The other roots of the PROTO instance just expanded to `node`, taken (once) to stand
        after it: X3D instantiates every root of a PROTO body, the first giving the instance's
        type. With fd, only if that MFNode field accepts them all; else finish() names them."""
        entry = self.unplaced.get(id(node))
        if entry is None or (fd is not None and not all(schema.accepts(fd, o.type_name) for o in entry[1])):
            return []
        del self.unplaced[id(node)]
        return entry[1]

    def beside(self, nodes: list[Node]) -> list[Node]:
        """Top-level nodes of a scene or PROTO body, each PROTO instance followed by its other roots."""
        return [m for n in nodes for m in (n, *self.others(n))]

    def finish(self) -> None:
        """Say which PROTO instances' other roots found no place (the instance is a field's value,
        or in a field that cannot hold them): they are left out of the scene, so never simulated."""
        for _, others, name, loc in self.unplaced.values():
            self.warning(loc, f"ProtoInstance {name}",
                         f"the other roots of its PROTO body ({', '.join(o.label for o in others)}) are left out "
                         f"of the scene: x3drbp places them after an instance at the top of the scene or of a "
                         f"PROTO body, or in an MFNode field of a known node type that accepts them")
        self.unplaced.clear()


    def proto_nodes(self, target: Node, fname: str, pname: str, value: Any, loc: Location) -> Any:
        """An instance's node value for an IS'd field, checked as a child of that field would be:
        one node (or None) for an SFNode, a list for an MFNode, each of a type the field accepts."""
        nodes = [n for n in (value if isinstance(value, list) else [value]) if n is not None]
        fd = target.spec.fields.get(fname) if target.spec is not None else None
        subject = f"{target.label}.{fname} (IS {pname})"
        if fd is not None:
            bad = [n.type_name for n in nodes if not schema.accepts(fd, n.type_name)]
            if bad:
                self.error(loc, subject, f"a {bad[0]} is not allowed here; allowed: {' or '.join(fd.accepts)}")
                nodes = []
            if not fd.type.multi:
                if len(nodes) > 1:
                    self.error(loc, subject, f"{fd.type.name} field takes one node, given {len(nodes)}")
                return nodes[0] if nodes else None
        return nodes


def _finite(value: Any) -> bool:
    """Whether a typed value's numbers are all finite (what holds no float is)."""
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, np.ndarray) and value.dtype.kind == "f":
        return bool(np.isfinite(value).all())
    return True


def _copy(node: Node, memo: dict[int, Node], prefix: str, budget: _Budget) -> Node:
    """Deep copy of a PROTO body node; nodes shared by USE in the body stay shared. Each node
    and array copied is taken from the budget: _ExpansionTooLarge once either runs out."""
    done = memo.get(id(node))
    if done is not None:
        return done
    budget.nodes -= 1
    if budget.nodes < 0:
        raise _ExpansionTooLarge
    name = f"{prefix}_{node.def_name}" if node.def_name else None
    c = Node(node.type_name, node.spec, node.loc, name)
    memo[id(node)] = c
    c.interface = node.interface
    c.spellings = node.spellings
    for k, v in node.values.items():
        if isinstance(v, Node):
            v = _copy(v, memo, prefix, budget)
        elif isinstance(v, list) and v and isinstance(v[0], Node):
            v = [_copy(x, memo, prefix, budget) for x in v]
        elif isinstance(v, (np.ndarray, list)):
            budget.bytes -= v.nbytes if isinstance(v, np.ndarray) else 8 * len(v)
            if budget.bytes < 0:
                raise _ExpansionTooLarge
            v = v.copy()
        c.values[k] = v
    c.field_locs = dict(node.field_locs)
    return c
