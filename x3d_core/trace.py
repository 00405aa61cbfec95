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
from typing import Any

from . import fields as F

HEADER = ("time", "node", "field", "value")


@dataclass(frozen=True)
class Row:
    time: float
    node: str
    field: str
    value: str


class Trace:
    """Rows in the order they happened."""

    def __init__(self) -> None:
        self.rows: list[Row] = []

    def add(self, time: float, node: str, field: str, ftype: str, value: Any) -> None:
        self.rows.append(Row(time, node, field, F.format_xml(F.FIELD_TYPES[ftype], value)))

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
