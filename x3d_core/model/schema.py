"""Node types and field definitions: node_defs.py's by hand, standard_nodes.py's from the UOM
(X3D 4.0's; editions.py gives a 3.x file clause 37's own)."""

from __future__ import annotations

import copy
import functools
import math
import re
from dataclasses import dataclass, field
from collections.abc import Iterator, Mapping
from typing import Any

import numpy as np

from . import fields as F
from .node_defs import DEFINITIONS

ACCESS_TYPES = ("initializeOnly", "inputOnly", "outputOnly", "inputOutput")


@dataclass(frozen=True)
class Range:
    lo: float
    hi: float
    lo_open: bool
    hi_open: bool
    # the one value also allowed outside the interval, whole (clause 37's "[0,∞) or -1 -1 -1")
    alone: tuple[float, ...] = ()

    def contains(self, numbers: Any) -> bool:
        """Whether every number of a value (a number, or an array) lies in the range."""
        if self.alone and np.array_equal(np.ravel(numbers), self.alone):
            return True
        if isinstance(numbers, (int, float)):
            return (numbers > self.lo if self.lo_open else numbers >= self.lo) and \
                (numbers < self.hi if self.hi_open else numbers <= self.hi)
        return bool(np.all(self.inside(np.asarray(numbers, dtype=np.float64))))

    def inside(self, numbers: np.ndarray) -> np.ndarray:
        """Which of an array's numbers lie in the range."""
        lo_ok = numbers > self.lo if self.lo_open else numbers >= self.lo
        hi_ok = numbers < self.hi if self.hi_open else numbers <= self.hi
        return lo_ok & hi_ok

    def __str__(self) -> str:
        """As a diagnostic says it: [0,inf) or -1."""
        return self._interval() + (f" or {' '.join(map(_num, self.alone))}" if self.alone else "")

    def token(self) -> str:
        """As a definition's line writes it, one word: [0,inf)|-1,-1,-1."""
        return self._interval() + (f"|{','.join(map(_num, self.alone))}" if self.alone else "")

    def _interval(self) -> str:
        return f"{'(' if self.lo_open else '['}{_num(self.lo)},{_num(self.hi)}{')' if self.hi_open else ']'}"


def _num(x: float) -> str:
    """A bound as a definition writes it: inf and pi by name."""
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    if abs(abs(x) - math.pi) < 1e-12:
        return "-pi" if x < 0 else "pi"
    return F._num(x)


@dataclass(frozen=True)
class FieldDef:
    name: str
    type: F.FieldType
    access: str
    default: Any
    range: Range | None = None
    unit: str | None = None
    accepts: tuple[str, ...] = ()

    def default_value(self) -> Any:
        return copy.copy(self.default)

    @property
    def readable(self) -> bool:
        """Whether a file may give the field a value (not inputOnly or outputOnly)."""
        return self.access in ("initializeOnly", "inputOutput")


@dataclass
class NodeType:
    name: str
    abstract: bool
    parents: tuple[str, ...]
    container_field: str = "children"
    component: str = ""
    fields: dict[str, FieldDef] = field(default_factory=dict)  # by X3D 4.0's names, whatever the edition
    # an edition's spelling of a field whose X3D 4.0 name (the key) it spells otherwise: 3.x's stopBounce1
    spellings: dict[str, str] = field(default_factory=dict)
    # X3D 4.0 fields the edition lacks, kept with 4.0's definitions so that a file using one still loads
    absent: frozenset[str] = frozenset()

    def spelled(self, name: str) -> str:
        """A field's name in the type's edition."""
        return self.spellings.get(name, name)

    def named(self, name: str) -> FieldDef | None:
        """The field a name of the type's edition stands for; None for another edition's name
        (editions.foreign says which field that is) or a field the edition lacks."""
        key = self._by_spelling.get(name)
        if key is None and (name in self.spellings or name in self.absent):
            return None
        return self.fields.get(key or name)

    @functools.cached_property
    def _by_spelling(self) -> dict[str, str]:
        return {spelling: name for name, spelling in self.spellings.items()}

    @functools.cached_property
    def ancestors(self) -> frozenset[str]:
        """Every type this one derives from, found on first use (a parent may be read later)."""
        seen: set[str] = set()
        stack = list(self.parents)
        while stack:
            p = stack.pop()
            if p not in seen:
                seen.add(p)
                stack.extend(definition(p).parents)
        return frozenset(seen)

    def is_a(self, type_name: str) -> bool:
        return type_name == self.name or type_name in self.ancestors


# Abstract types that only X3D 4.0's own node types implement: a node of an unknown type
# (an EXTERNPROTO instance, a later version's or a browser's node) can never be one of them.
CLOSED_ABSTRACT = frozenset({"X3DNBodyCollidableNode", "X3DNBodyCollisionSpaceNode",
                             "X3DRigidJointNode", "X3DMetadataObject"})

_TOKEN = re.compile(r'"(?:[^"\\]|\\.)*"|[^\s,\[\]]+')
_RANGE = re.compile(r"^([\[(])([^,]+),([^\])|]+)([\])])(?:\|(\S+))?$")


def _bound(text: str) -> float:
    return float(text.replace("pi", repr(math.pi)))


def _field(node: str, line: str) -> FieldDef:
    head, _, default_text = line.partition(" = ")
    parts = head.split()
    name, tname, access = parts[0], parts[1], parts[2]
    ftype = F.FIELD_TYPES[tname]
    if access not in ACCESS_TYPES:
        raise ValueError(f"{node}.{name}: bad access type {access}")
    rng = unit = None
    accepts: tuple[str, ...] = ()
    for p in parts[3:]:
        if m := _RANGE.match(p):
            alone = tuple(map(_bound, m.group(5).split(","))) if m.group(5) else ()
            rng = Range(_bound(m.group(2)), _bound(m.group(3)), m.group(1) == "(", m.group(4) == ")", alone)
        elif p.startswith("u:"):
            unit = p[2:]
        elif p.startswith("<"):
            accepts = tuple(p[1:-1].split("|"))
        else:
            raise ValueError(f"{node}.{name}: cannot read {p!r}")
    if ftype.kind == "node" or not default_text:
        default = F.empty(ftype)
    else:
        default = F.parse_vrml(ftype, _TOKEN.findall(default_text))
    return FieldDef(name, ftype, access, default, rng, unit, accepts)


_HEADER = re.compile(r"^(?:node|abstract) (\w+)", re.M)


def _blocks(text: str) -> dict[str, str]:
    """Each type's definition (its header line and field lines) by type name, unread."""
    heads = [(m.start(), m.group(1)) for m in _HEADER.finditer(text)]
    ends = [start for start, _ in heads[1:]] + [len(text)]
    return {name: text[start:end] for (start, name), end in zip(heads, ends)}


def _read(block: str) -> NodeType:
    """One type from its definition."""
    header, *lines = block.splitlines()
    kind, rest = header.split("#", 1)[0].split(" ", 1)
    comp = header.split("#", 1)[1].strip() if "#" in header else ""
    rest, _, cf = rest.partition("@")
    name, _, parents = rest.partition(":")
    t = NodeType(name.strip(), kind == "abstract", tuple(parents.split()), cf.strip() or "children", comp)
    for raw in lines:
        line = raw.split("#", 1)[0].strip()
        if line:
            fd = _field(t.name, line)
            t.fields[fd.name] = fd
    return t


class Types(Mapping[str, NodeType]):
    """Types by name, each read from its definition on first use (then always the same object):
    a run reads the few its scene uses, where reading node_defs.py's every type at import cost
    each `x3drbp run` 3 ms."""

    def __init__(self, text: str):
        self._blocks = _blocks(text)
        self._read: dict[str, NodeType] = {}

    def __getitem__(self, name: str) -> NodeType:
        t = self._read.get(name)
        if t is None:
            t = self._read[name] = _read(self._blocks[name])
        return t

    def __contains__(self, name: object) -> bool:
        return name in self._blocks

    def __iter__(self) -> Iterator[str]:
        return iter(self._blocks)

    def __len__(self) -> int:
        return len(self._blocks)


# The hand-written types (with ranges and units)
NODE_TYPES: Mapping[str, NodeType] = Types(DEFINITIONS)


@functools.cache
def _standard_blocks() -> dict[str, str]:
    """Every other X3D 4.0 type's definition, generated from the UOM: split on first use."""
    from .standard_nodes import DEFINITIONS as STANDARD  # 100 kB of text a run rarely needs
    return _blocks(STANDARD)


@functools.cache
def _standard(name: str) -> NodeType:
    return _read(_standard_blocks()[name])


def definition(name: str) -> NodeType | None:
    """The type of that name, concrete or abstract: hand-written, else X3D 4.0's from the UOM."""
    t = NODE_TYPES.get(name)
    if t is None and name in _standard_blocks():  # only real names are cached, not a file's typos
        t = _standard(name)
    return t


def standard_names() -> list[str]:
    """The names of the types generated from the UOM (node_defs.py defines none of them)."""
    return list(_standard_blocks())


def node_type(name: str) -> NodeType | None:
    """The type of a concrete node type name; None for an abstract or unknown one."""
    t = definition(name)
    return t if t is not None and not t.abstract else None


def accepts(fd: FieldDef, child_type: str) -> bool:
    """Whether an SFNode/MFNode field may hold a node of the given type name."""
    return not fd.accepts or _accepts(fd.accepts, child_type)


@functools.cache
def _accepts(accepted: tuple[str, ...], child_type: str) -> bool:
    t = node_type(child_type)
    if t is None:  # an unknown (generic) node: refuse only where every accepted type is known
        return not all(a in CLOSED_ABSTRACT or node_type(a) is not None for a in accepted)
    return any(t.is_a(a) for a in accepted)

