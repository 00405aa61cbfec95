"""The event trace: CSV rows `time,node,field,value`, the X3D event stream itself.

`value` is the field in X3D XML attribute encoding with every digit (a trace compared
over long runs needs full precision); rotations are axis-angle, angle in [0, pi].
A trace is written whole or not at all: to a temporary name, then renamed.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from collections.abc import Sequence
from typing import Any, Callable, Iterator, NamedTuple

import numpy as np

from . import atomic
from . import fields as F

HEADER = ("time", "node", "field", "value")


@dataclass(frozen=True)
class Row:
    time: float
    node: str
    field: str
    value: str


class _Block(NamedTuple):
    """One field of several nodes at one time, kept as numbers until written: recording
    a frame costs a few array copies, not a string per value."""
    time: float
    nodes: list[str]
    field: str
    ftype: F.FieldType | None  # None: values hold the text itself
    values: np.ndarray  # (len(nodes), width), or (len(nodes),) for SFFloat
    convert: Callable[[np.ndarray], np.ndarray] | None = None  # applied when written (quaternions -> SFRotation)


class Column(NamedTuple):
    """One field of every record of a _Table: a row per record, or one value for all."""
    field: str  # "" for records that are values themselves (intersections[i])
    ftype: F.FieldType | None  # None: values hold the text itself
    values: Any  # (k, ...) array, or the one value every record has where constant
    constant: bool = False


class _Table(NamedTuple):
    """k indexed records of one node at one time, as columns (a CollisionSensor's
    contacts[i].FIELD): a frame with many contacts costs a few array references, and its
    rows are made only when the trace is written."""
    time: float
    node: str
    name: str  # "contacts": rows are named contacts[i].FIELD
    count: int
    columns: list[Column]

    def events(self) -> Iterator[tuple[float, str, str, str]]:
        texts = []
        for c in self.columns:
            if c.constant:
                one = c.values if c.ftype is None else F.format_xml(c.ftype, np.asarray(c.values).tolist())
                texts.append([one] * self.count)
            else:
                texts.append(list(c.values) if c.ftype is None
                             else [F.format_xml(c.ftype, v) for v in np.asarray(c.values).tolist()])
        fields = [f".{c.field}" if c.field else "" for c in self.columns]
        for i in range(self.count):
            for f, t in zip(fields, texts):
                yield self.time, self.node, f"{self.name}[{i}]{f}", t[i]


class Trace:
    """Events in the order they happened."""

    def __init__(self) -> None:
        self.blocks: list[_Block | _Table] = []

    def add(self, time: float, node: str, field: str, ftype: str, value: Any) -> None:
        self.add_many(time, [node], field, ftype, np.asarray(value, dtype=np.float64)[None])

    def add_many(self, time: float, nodes: list[str], field: str, ftype: str, values: np.ndarray,
                 convert: Callable[[np.ndarray], np.ndarray] | None = None) -> None:
        """The same field of several nodes: values row k (after convert) belongs to nodes[k]."""
        self.blocks.append(_Block(time, nodes, field, F.FIELD_TYPES[ftype], values, convert))

    def add_text(self, time: float, node: str, field: str, value: str) -> None:
        """A value already in its trace text (a node's name for an SFNode output, say)."""
        self.blocks.append(_Block(time, [node], field, None, np.array([value], dtype=object)))

    def add_table(self, time: float, node: str, name: str, count: int, columns: list[Column]) -> None:
        """count indexed records of node (rows NAME[i].FIELD, one per record and column)."""
        if count:
            self.blocks.append(_Table(time, node, name, count, columns))

    def blocks_of(self, field: str) -> list[_Block]:
        """The blocks of one field in time order, values still arrays (for bulk readers)."""
        return [b for b in self.blocks if isinstance(b, _Block) and b.field == field]

    def tables_of(self, name: str) -> list[_Table]:
        return [b for b in self.blocks if isinstance(b, _Table) and b.name == name]

    def events(self) -> Iterator[tuple[float, str, str, str]]:
        """(time, node, field, value text) in order: the rows, made only now."""
        for b in self.blocks:
            if isinstance(b, _Table):
                yield from b.events()
            elif b.ftype is None:
                yield b.time, b.nodes[0], b.field, b.values[0]
            else:
                values = b.convert(b.values) if b.convert is not None else b.values
                ftype, time, field = b.ftype, b.time, b.field
                for node, value in zip(b.nodes, values.tolist()):
                    yield time, node, field, F.format_xml(ftype, value)

    @property
    def rows(self) -> list[Row]:
        return [Row(*e) for e in self.events()]

    def text(self) -> str:
        """The CSV, quoted as the csv module quotes (only what holds a comma, quote or
        line break), written without it: a trace can hold millions of rows."""
        lines = [",".join(HEADER)]
        times: dict[float, str] = {}
        for t, node, field, value in self.events():
            when = times.get(t)
            if when is None:
                when = times[t] = F._num(t)
            lines.append(f"{when},{_quoted(node)},{_quoted(field)},{_quoted(value)}")
        lines.append("")
        return "\n".join(lines)

    def write(self, path: str) -> None:
        atomic.write_text(path, self.text())


def _quoted(text: str) -> str:
    if "," in text or '"' in text or "\n" in text or "\r" in text:
        return '"' + text.replace('"', '""') + '"'
    return text


def read_trace(path: str) -> list[Row]:
    with open(path, newline="", encoding="utf-8") as f:
        r = csv.reader(f)
        header = next(r)
        if tuple(header) != HEADER:
            raise ValueError(f"{path}:1: header is {','.join(header)!r}, expected {','.join(HEADER)!r}")
        return [Row(float(t), n, fld, v) for t, n, fld, v in r]


class TraceView:
    """A trace's rows grouped by (node, field): times, and values as float arrays."""

    def __init__(self, rows: Sequence[Row]):
        groups: dict[tuple[str, str], tuple[list[float], list[list[float]]]] = {}
        texts: dict[tuple[str, str], tuple[list[float], list[str]]] = {}
        for r in rows:
            try:
                values = [float(x) for x in r.value.split()]
            except ValueError:  # SFBool, SFNode names, MFString (CollisionSensor rows): kept as text
                t, s = texts.setdefault((r.node, r.field), ([], []))
                t.append(r.time)
                s.append(r.value)
                continue
            t, v = groups.setdefault((r.node, r.field), ([], []))
            t.append(r.time)
            v.append(values)
        self._series = {k: (np.array(t), np.array(v, dtype=np.float64)) for k, (t, v) in groups.items()}
        self._text = {k: (np.array(t), s) for k, (t, s) in texts.items()}

    def text(self, node: str, fld: str) -> tuple[np.ndarray, list[str]]:
        """(times (n,), values as written) of an output that is not numbers: SFBool, SFNode, MFString."""
        try:
            return self._text[(node, fld)]
        except KeyError:
            raise KeyError(f"the trace has no {node}.{fld} text rows") from None

    def keys(self) -> list[tuple[str, str]]:
        return list(self._series)

    def series(self, node: str, fld: str) -> tuple[np.ndarray, np.ndarray]:
        """(times (n,), values (n, width)) of one output."""
        try:
            return self._series[(node, fld)]
        except KeyError:
            raise KeyError(f"the trace has no {node}.{fld} rows") from None

    def at(self, time: float) -> dict[tuple[str, str], np.ndarray]:
        """Every output's value at one frame time (exact match)."""
        out = {}
        for k, (t, v) in self._series.items():
            hit = np.flatnonzero(t == time)
            if hit.size:
                out[k] = v[hit[0]]
        return out

    def bodies(self) -> list[str]:
        """The nodes that have both a position and an orientation: the bodies, in trace order."""
        keys = set(self._series)
        return [n for n, f in self._series if f == "position" and (n, "orientation") in keys]
