"""The event trace: CSV rows `time,node,field,value`, the X3D event stream itself.

`value` is the field in X3D XML attribute encoding with every digit (a trace compared
over long runs needs full precision); rotations are axis-angle, angle in [0, pi].
A trace is written whole or not at all: to a temporary name, then renamed.
"""

from __future__ import annotations

import csv
import io
import os
import tempfile
from dataclasses import dataclass
from typing import Any, Callable, NamedTuple

import numpy as np

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


class Trace:
    """Events in the order they happened."""

    def __init__(self) -> None:
        self.blocks: list[_Block] = []

    def add(self, time: float, node: str, field: str, ftype: str, value: Any) -> None:
        self.add_many(time, [node], field, ftype, np.asarray(value, dtype=np.float64)[None])

    def add_many(self, time: float, nodes: list[str], field: str, ftype: str, values: np.ndarray,
                 convert: Callable[[np.ndarray], np.ndarray] | None = None) -> None:
        """The same field of several nodes: values row k (after convert) belongs to nodes[k]."""
        self.blocks.append(_Block(time, nodes, field, F.FIELD_TYPES[ftype], values, convert))

    def add_text(self, time: float, node: str, field: str, value: str) -> None:
        """A value already in its trace text (a node's name for an SFNode output, say)."""
        self.blocks.append(_Block(time, [node], field, None, np.array([value], dtype=object)))

    @property
    def rows(self) -> list[Row]:
        out = []
        for b in self.blocks:
            if b.ftype is None:
                out.append(Row(b.time, b.nodes[0], b.field, b.values[0]))
                continue
            values = b.convert(b.values) if b.convert is not None else b.values
            for node, value in zip(b.nodes, values.tolist()):
                out.append(Row(b.time, node, b.field, F.format_xml(b.ftype, value)))
        return out

    def text(self) -> str:
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(HEADER)
        w.writerows((F._num(r.time), r.node, r.field, r.value) for r in self.rows)
        return buf.getvalue()

    def write(self, path: str) -> None:
        folder = os.path.dirname(os.path.abspath(path))
        fd, tmp = tempfile.mkstemp(prefix=".trace-", suffix=".csv", dir=folder)
        try:
            with os.fdopen(fd, "w", encoding="utf-8", newline="") as f:
                f.write(self.text())
            os.replace(tmp, path)
        except BaseException:
            os.unlink(tmp)
            raise


def read_trace(path: str) -> list[Row]:
    with open(path, newline="", encoding="utf-8") as f:
        r = csv.reader(f)
        header = next(r)
        if tuple(header) != HEADER:
            raise ValueError(f"{path}:1: header is {','.join(header)!r}, expected {','.join(HEADER)!r}")
        return [Row(float(t), n, fld, v) for t, n, fld, v in r]
