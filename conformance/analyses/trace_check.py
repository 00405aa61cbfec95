"""Reads a trace written by someone else and says, line by line, what is wrong with it.

`x3drbp validate` judges a browser's trace only once it reads as the trace contract says
(docs/implementers.md; README's `x3drbp run`): a problem here is the file's, not the
physics', so it is reported with its line and stops the validation (exit 2). Checked:

- the header `time,node,field,value`, and four columns on every row;
- time: a finite number, never less than the row before's;
- node: a name of the scene (its DEF, else x3drbp's TYPE_k: x3d_core.world.node_names);
- field: an output of that node's type (outputOnly or inputOutput), or `F[i]` / `F[i].SUB`
  for an MFNode output F (a CollisionSensor's intersections[i], contacts[i].depth), SUB a
  field of the node type F holds;
- value: reads as the field's type in X3D XML attribute encoding (x3d_core.fields), a node
  name of the scene for SFNode values, rotations with an axis of length 1 within
  AXIS_TOLERANCE;
- every RigidBody of an enabled collection has its position, orientation, linearVelocity
  and angularVelocity rows (what comparisons and expectations read).
"""

from __future__ import annotations

import csv
import math
import re
from dataclasses import dataclass

import numpy as np

from x3d_core import fields as F
from x3d_core import schema
from x3d_core.model import Scene
from x3d_core.trace import HEADER, Row
from x3d_core.world import node_names, worlds

# |axis| - 1: a browser writing single-precision floats with 6 digits is within 1e-6;
# 1e-3 still turns a 1 m body's end by under a millimetre
AXIS_TOLERANCE = 1e-3
BODY_FIELDS = ("position", "orientation", "linearVelocity", "angularVelocity")
_INDEXED = re.compile(r"^(\w+)\[(\d+)\](?:\.(\w+))?$")
_NULL = ("", "NULL")  # an SFNode output holding no node


@dataclass(frozen=True)
class Problem:
    """One thing wrong with a trace; line 0 when it is about the whole file."""
    path: str
    line: int
    message: str

    def __str__(self) -> str:
        return f"{self.path}:{self.line}: {self.message}" if self.line else f"{self.path}: {self.message}"


class _Fields:
    """The output fields a trace row may name, per node of the scene."""

    def __init__(self, scene: Scene):
        names = node_names(scene)
        self.types = {names[id(n)]: n.type_name for n in scene.nodes()}

    def of(self, node: str, fld: str) -> F.FieldType | str:
        """The field's type, or why the node has no such output."""
        spec = schema.node_type(self.types[node])
        if spec is None:
            return f"{node} is a {self.types[node]}, a node type without outputs"
        m = _INDEXED.match(fld)
        name = m.group(1) if m else fld
        fd = spec.fields.get(name)
        if fd is None or fd.access not in ("outputOnly", "inputOutput"):
            return f"{spec.name} has no output field {name!r}"
        if m is None:
            return fd.type
        if fd.type.name != "MFNode":
            return f"{spec.name}.{name} is {fd.type.name}, not indexed (only MFNode outputs are)"
        if m.group(3) is None:
            return F.FIELD_TYPES["SFNode"]
        held = schema.node_type(fd.accepts[0]) if fd.accepts else None
        sub = held.fields.get(m.group(3)) if held is not None else None
        if sub is None:
            return f"{spec.name}.{name} holds {held.name if held else 'nodes'}, which have no field {m.group(3)!r}"
        return sub.type


def _value_problem(ftype: F.FieldType, value: str, names: set[str]) -> str | None:
    if ftype.kind == "node":
        return None if value in names or value in _NULL else f"value {value!r} names no node of the scene"
    try:
        parsed = F.parse_xml(ftype, value)
    except ValueError as e:
        return f"value {value!r} is not {ftype.describe()}: {e}"
    if ftype.rotation:
        axes = np.asarray(parsed, dtype=np.float64).reshape(-1, 4)[:, :3]
        lengths = np.linalg.norm(axes, axis=1)
        bad = np.abs(lengths - 1.0)
        if bad.size and not np.all(bad <= AXIS_TOLERANCE):
            length = float(lengths[np.argmax(bad)])
            return f"rotation {value!r}: the axis has length {length:.6g}, not 1 (within {AXIS_TOLERANCE:g})"
    return None


def check_trace(path: str, scene: Scene) -> tuple[list[Row], list[Problem]]:
    """The trace's rows, and every problem found (no rows when the header is wrong)."""
    fields = _Fields(scene)
    names = set(fields.types)
    problems: list[Problem] = []
    rows: list[Row] = []
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.reader(f)
            header = next(reader, None)
            if header is None or tuple(h.strip() for h in header) != HEADER:
                got = "nothing" if header is None else repr(",".join(header))
                return [], [Problem(path, 1, f"header is {got}, expected {','.join(HEADER)!r}")]
            last = -math.inf
            line = reader.line_num
            for cols in reader:
                where, line = line + 1, reader.line_num
                problem = _row_problem(cols, last, fields, names)
                if problem is not None:
                    problems.append(Problem(path, where, problem))
                    continue
                row = Row(float(cols[0]), *cols[1:])
                last = row.time
                rows.append(row)
    except (OSError, UnicodeDecodeError, csv.Error) as e:
        return [], [Problem(path, 0, f"cannot read: {e}")]
    if not rows and not problems:
        problems.append(Problem(path, 0, "no rows after the header"))
    if not problems:
        problems += _missing(path, rows, scene)
    return rows, problems


def _row_problem(cols: list[str], last: float, fields: _Fields, names: set[str]) -> str | None:
    if len(cols) != 4:
        return f"{len(cols)} columns, expected 4 ({','.join(HEADER)})"
    text, node, fld, value = cols
    try:
        t = float(text)
    except ValueError:
        return f"time {text!r} is not a number"
    if not math.isfinite(t):
        return f"time {text!r} is not finite"
    if t < last:
        return f"time {t:g} is before the previous row's {last:g} (times never decrease)"
    if node not in names:
        return f"node {node!r} is not in the scene (DEF names, or TYPE_k for nodes without one)"
    ftype = fields.of(node, fld)
    if isinstance(ftype, str):
        return f"field {fld!r} of {node}: {ftype}"
    return _value_problem(ftype, value, names)


def _missing(path: str, rows: list[Row], scene: Scene) -> list[Problem]:
    """Every RigidBody field the trace lacks (bodies of enabled collections)."""
    have = {(r.node, r.field) for r in rows}
    return [Problem(path, 0, f"no rows for {b}.{f} (every RigidBody records {', '.join(BODY_FIELDS)})")
            for w in worlds(scene) for b in w.bodies.names for f in BODY_FIELDS if (b, f) not in have]
