"""The scene model: nodes, routes and diagnostics, the same whatever the encoding."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Iterator, NamedTuple

from x3d_core.files.paths import printable, shown

from .fields import FieldType
from .schema import NodeType


class Location(NamedTuple):
    file: str
    line: int
    col: int = 0  # 0: not yet known (XML), found when a diagnostic needs it

    def __str__(self) -> str:
        return f"{shown(self.file)}:{self.line}:{self.col}"


@dataclass(frozen=True)
class Diagnostic:
    severity: str  # "error" | "warning"
    loc: Location
    subject: str  # "NodeType DEF.field", or "" for the file as a whole
    message: str

    def __str__(self) -> str:
        subject = f"{self.subject}: " if self.subject else ""
        return f"{self.loc}: {self.severity}: {printable(subject + self.message)}"


class LoadError(Exception):
    """A file that cannot be read at all; carries the one diagnostic that says why."""

    def __init__(self, diagnostic: Diagnostic, earlier: list[Diagnostic] | None = None):
        super().__init__(str(diagnostic))
        self.diagnostic = diagnostic
        self.earlier = earlier or []  # what was found before reading had to stop

    @property
    def diagnostics(self) -> list[Diagnostic]:
        return [*self.earlier, self.diagnostic]


@dataclass
class FieldDecl:
    """A field declared by a file (Script interface, PROTO interface)."""
    name: str
    type: FieldType
    access: str
    value: Any
    loc: Location


class Node:
    """One X3D node. Typed nodes hold typed values for the fields the file gave; a node
    of a type x3drbp does not model (spec None) holds its fields as text and its child
    nodes under their field names, so that real scenes load and write back."""

    __slots__ = ("type_name", "spec", "values", "def_name", "loc", "field_locs", "interface", "spellings")

    def __init__(self, type_name: str, spec: NodeType | None, loc: Location, def_name: str | None = None):
        self.type_name = type_name
        self.spec = spec
        self.values: dict[str, Any] = {}
        self.def_name = def_name
        self.loc = loc
        self.field_locs: dict[str, Location] = {}
        self.interface: list[FieldDecl] = _NO_FIELDS  # fields a Script (or unknown node) declares
        # X3D 4.0's name -> the file's, where the file spelt a field otherwise than its edition does
        self.spellings: dict[str, str] = _NO_SPELLINGS

    def get(self, name: str) -> Any:
        """The field's value (by its X3D 4.0 name): as given in the file, else its edition's default."""
        v = self.values.get(name, _MISSING)
        if v is not _MISSING:
            return v
        if self.spec is not None:
            return self.spec.fields[name].default_value()
        return None

    __getitem__ = get

    def spelling(self, name: str) -> str:
        """How the file names a field the model keys by its X3D 4.0 name (its edition's name
        where the file gave the field no value): what writers and diagnostics say."""
        spelt = self.spellings.get(name)
        if spelt is not None:
            return spelt
        return self.spec.spelled(name) if self.spec is not None else name

    @property
    def declares_fields(self) -> bool:
        """Whether the file may declare fields on this node, or give its source as the
        element's text (a Script, a shader, or a node x3drbp does not model). A ShaderPart
        only has source: the loaders ask this one question for both."""
        return self.spec is None or "sourceCode" in self.spec.fields or self.spec.is_a("X3DProgrammableShaderObject")

    @property
    def label(self) -> str:
        """How diagnostics name the node: 'RigidBody BALL', or the type alone."""
        return f"{self.type_name} {self.def_name}" if self.def_name else self.type_name

    def children(self) -> Iterator[Node]:
        """Every node directly held in a field of this one (in field order)."""
        for v in self.values.values():
            if isinstance(v, Node):
                yield v
            elif isinstance(v, list):
                for x in v:
                    if isinstance(x, Node):
                        yield x
        for decl in self.interface:
            v = decl.value
            if isinstance(v, Node):
                yield v
            elif isinstance(v, list):
                yield from (x for x in v if isinstance(x, Node))

    def __repr__(self) -> str:
        return f"<{self.label} at {self.loc}>"


_MISSING = object()
_NO_FIELDS: list[FieldDecl] = []  # shared and never appended to: declare() gives a node its own list
_NO_SPELLINGS: dict[str, str] = {}  # shared and never written to: the Builder gives a node its own dict


@dataclass
class Route:
    from_node: Node
    from_field: str
    to_node: Node
    to_field: str
    loc: Location


@dataclass
class Scene:
    path: str
    encoding: str  # "xml" | "vrml" | "json"
    version: str = "4.0"
    profile: str = "Full"
    components: list[tuple[str, int]] = field(default_factory=list)
    units: dict[str, tuple[str, float]] = field(default_factory=dict)  # category -> (name, to SI)
    meta: list[tuple[str, str]] = field(default_factory=list)
    roots: list[Node] = field(default_factory=list)
    routes: list[Route] = field(default_factory=list)
    protos: list[str] = field(default_factory=list)  # names of the PROTOs expanded in place
    diagnostics: list[Diagnostic] = field(default_factory=list)
    # where the encoding's parser knows less than a line and column (lxml), the loader
    # leaves a way to find the exact place of a later diagnostic
    locate: Callable[[Location, str], Location] = field(default=lambda loc, subject: loc, repr=False,
                                                       compare=False)

    def nodes(self) -> Iterator[Node]:
        """Every distinct node once, depth first in file order (a USEd node at its DEF)."""
        seen: set[int] = set()
        stack = list(reversed(self.roots))
        while stack:
            n = stack.pop()
            if id(n) in seen:
                continue
            seen.add(id(n))
            yield n
            stack.extend(reversed(list(n.children())))

    def of_type(self, type_name: str) -> list[Node]:
        """Nodes of a type or of an abstract type (e.g. 'X3DRigidJointNode')."""
        return [n for n in self.nodes() if n.spec is not None and n.spec.is_a(type_name)]

    @property
    def errors(self) -> list[Diagnostic]:
        return [d for d in self.diagnostics if d.severity == "error"]

    @property
    def warnings(self) -> list[Diagnostic]:
        return [d for d in self.diagnostics if d.severity == "warning"]
