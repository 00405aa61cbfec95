"""Reads a trace written by someone else and says, line by line, what is wrong with it.

`x3drbp validate` judges a browser's trace only once it reads as the trace contract says
(docs/implementers.md; docs/commands/run.md): a problem here is the file's, not the
physics', so it is reported with its line and stops the validation (exit 2). Checked:

- the header `time,node,field,value` (a UTF-8 BOM before it read as nothing; lines may end
  in LF, CRLF or a lone CR), and four columns on every row;
- time: a finite number in X3D's grammar (x3d_core.model.fields.number: float() read `1_0` as 10),
  never less than the row before's, the first 0 (within
  START_TOLERANCE: the initial state is a frame);
- node: a name of the scene (its DEF, else x3drbp's TYPE_k: x3d_core.semantics.world.node_names);
- field: an output of that node's type (outputOnly or inputOutput), or `F[i]` / `F[i].SUB`
  for an MFNode output F (a CollisionSensor's intersections[i], contacts[i].depth), SUB a
  field of the node type F holds;
- value: reads as the field's type in X3D XML attribute encoding (x3d_core.model.fields), a node
  name of the scene for SFNode values, rotations with an axis of length 1 within
  AXIS_TOLERANCE;
- every RigidBody of an enabled collection has its position, orientation, linearVelocity
  and angularVelocity rows (what comparisons and expectations read).

The file is read through x3d_core.files.inputs (a named pipe or a device is refused at once, a
file over x3d_core.traces.trace.TRACE_LIMIT too) a chunk at a time, into arrays (a TraceView): a
chunk of plain rows (no quotes, SF number fields written with single spaces) is checked in
bulk, one output at a time; any chunk where that finds something, or cannot decide, is
checked again row by row, which says what is wrong and where. So a trace of 10^7 rows
holds its numbers, not an object per row, and its problems read as they always did. After
MAX_PROBLEMS problems the reading stops.

x3drbp's own .npz (a name ending .npz, as read_view tells the forms apart) is read by
x3d_core.traces.trace_npz, which bounds what it unpacks and refuses times that are not finite; the
same checks then run on each output's arrays, a problem naming the output (the file has no
lines), and its times each never decrease.
"""

from __future__ import annotations

import csv
import gc
import io
import math
import re
import warnings
from dataclasses import dataclass
from itertools import repeat
from operator import itemgetter

import numpy as np

from x3d_core.files.inputs import InputRefused, open_regular
from x3d_core.files.paths import quoted
from x3d_core.model import fields as F
from x3d_core.model import schema
from x3d_core.model.scene import Scene
from x3d_core.traces.trace import (HEADER, TRACE_LIMIT, TraceView, ViewBuilder, chunks, header_problem, line_reader,
                            read_header)
from x3d_core.semantics.world import node_names, worlds
from x3d_core.traces.trace_npz import NotTrace, read_npz

# |axis| - 1: a browser writing single-precision floats with 6 digits is within 1e-6;
# 1e-3 still turns a 1 m body's end by under a millimetre
AXIS_TOLERANCE = 1e-3
BODY_FIELDS = ("position", "orientation", "linearVelocity", "angularVelocity")
_INDEXED = re.compile(r"^(\w+)\[(\d+)\](?:\.(\w+))?$")
_NULL = ("", "NULL")  # an SFNode output holding no node
MAX_PROBLEMS = 1000  # then the reading stops, saying so
# the first row's time, from 0: the initial state is a frame (a browser's float32 clock starts at 0 exactly)
START_TOLERANCE = 1e-6  # s
# a number in X3D's grammar, as the bulk check takes it (anything else goes row by row)
_NUMBER = F.NUMBER


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
            return f"{spec.name} has no output field {quoted(name)}"
        if m is None:
            return fd.type
        if fd.type.name != "MFNode":
            return f"{spec.name}.{name} is {fd.type.name}, not indexed (only MFNode outputs are)"
        if m.group(3) is None:
            return F.FIELD_TYPES["SFNode"]
        held = schema.node_type(fd.accepts[0]) if fd.accepts else None
        sub = held.fields.get(m.group(3)) if held is not None else None
        if sub is None:
            return (f"{spec.name}.{name} holds {held.name if held else 'nodes'}, which have no field "
                    f"{quoted(m.group(3))}")
        return sub.type


def _bad_axis(rotations: np.ndarray) -> tuple[int, float] | None:
    """The rotation (of rows of 4 numbers) whose axis length is furthest from 1, and that
    length, where any is further than AXIS_TOLERANCE; else None."""
    lengths = np.linalg.norm(rotations.reshape(-1, 4)[:, :3], axis=1)
    bad = np.abs(lengths - 1.0)
    if not bad.size or np.all(bad <= AXIS_TOLERANCE):
        return None
    worst = int(np.argmax(bad))
    return worst, float(lengths[worst])


def _axis_problem(value: str, length: float) -> str:
    return f"rotation {value}: the axis has length {length:.6g}, not 1 (within {AXIS_TOLERANCE:g})"


def _value_problem(ftype: F.FieldType, value: str, names: set[str]) -> str | None:
    if ftype.kind == "node":
        return None if value in names or value in _NULL else f"value {quoted(value)} names no node of the scene"
    try:
        parsed = F.parse_xml(ftype, value)
    except ValueError as e:
        return f"value {quoted(value)} is not {ftype.describe()}: {e}"
    bad = _bad_axis(np.asarray(parsed, dtype=np.float64)) if ftype.rotation else None
    return None if bad is None else _axis_problem(quoted(value), bad[1])


def check_trace(path: str, scene: Scene) -> tuple[TraceView, list[Problem]]:
    """The trace (a CSV, or x3drbp's .npz where the name ends so, as read_view tells them), as
    a TraceView of its good rows (len() its row count; empty when the header is wrong or the
    file cannot be read), and every problem found."""
    fields = _Fields(scene)
    view, problems = (_check_npz if path.endswith(".npz") else _check_csv)(path, fields)
    if not len(view) and not problems:
        problems.append(Problem(path, 0, "no rows after the header"))
    if not problems:
        problems += _missing(path, set(view.keys()) | set(view.text_keys()), scene)
    return view, problems


def _check_csv(path: str, fields: _Fields) -> tuple[TraceView, list[Problem]]:
    problems: list[Problem] = []
    b = ViewBuilder()
    state = _State(fields, set(fields.types))
    try:
        with open_regular(path, TRACE_LIMIT) as raw:
            f = line_reader(raw)
            header, lines = read_header(f)
            problem = header_problem(header, lenient=True)
            if problem:
                return TraceView(), [Problem(path, 1, problem)]
            for first, text in chunks(f, lines + 1):
                if not _bulk(text, state, b):
                    _row_by_row(path, first, text, state, b, problems)
                    if len(problems) >= MAX_PROBLEMS:
                        problems.append(Problem(path, 0, f"stopped reading after {MAX_PROBLEMS} problems"))
                        break
                b.flush()
    except (InputRefused, OSError, UnicodeDecodeError, csv.Error) as e:
        said = str(e)  # InputRefused's own words may already begin so ('cannot read file: ...')
        return TraceView(), [Problem(path, 0, said if said.startswith("cannot read") else f"cannot read: {said}")]
    except ValueError as e:  # an output whose good rows hold different counts of numbers (an MF output)
        return TraceView(), [Problem(path, 0, f"cannot read as arrays: {e}")]
    try:
        return b.view(), problems
    except ValueError as e:
        return TraceView(), [Problem(path, 0, f"cannot read: {e}")]


def _check_npz(path: str, fields: _Fields) -> tuple[TraceView, list[Problem]]:
    """x3drbp's own trace as arrays (trace_npz): the CSV's checks, each output's rows at once,
    each problem naming its output (the file has no lines)."""
    try:
        view = read_npz(path)
    except NotTrace as e:
        return TraceView(), [Problem(path, 0, e.reason)]
    names = set(fields.types)
    times = view.times()
    problems = [Problem(path, 0, _start_problem(float(times[0])))] if times.size and not _starts(times[0]) else []
    outputs = [(k, *view.series(*k)) for k in view.keys()] + [(k, *view.text(*k)) for k in view.text_keys()]
    for (node, fld), t, values in outputs:
        problem = _output_problem(fields, names, node, fld, t, values)
        if problem is not None:
            problems.append(Problem(path, 0, f"{node}.{fld}: {problem}"))
    return view, problems[:MAX_PROBLEMS]


def _output_problem(fields: _Fields, names: set[str], node: str, fld: str, t: np.ndarray,
                    values: np.ndarray | list[str]) -> str | None:
    """What is wrong with one output of an .npz trace: its name, its times, its values."""
    ftype = _output_type(fields, names, node, fld)
    if isinstance(ftype, str):
        return ftype
    if t.size > 1 and np.any(np.diff(t) < 0):
        return "its times decrease (times never decrease)"
    if isinstance(values, np.ndarray) and ftype.kind == "float" and not ftype.multi:
        if values.shape[1] != ftype.width:
            return f"rows of {values.shape[1]} numbers, not {ftype.describe()}"
        if not np.isfinite(values).all():
            return "a value that is not a finite number"
        bad = _bad_axis(values) if ftype.rotation else None
        return None if bad is None else _axis_problem(f"at t = {t[bad[0]]:g}", bad[1])
    texts = values if isinstance(values, list) else (" ".join(map(F._num, row)) for row in values.tolist())
    return next((p for p in (_value_problem(ftype, v, names) for v in texts) if p is not None), None)


def _starts(t: float) -> bool:
    """Whether a trace whose first time is t starts at 0, within START_TOLERANCE."""
    return abs(t) <= START_TOLERANCE


def _start_problem(t: float) -> str:
    return (f"the first row is at t = {t:g} s; a trace starts at t = 0, the initial state "
            f"(within {START_TOLERANCE:g} s)")


class _State:
    """What the check carries from chunk to chunk: the last good time, each output's type."""

    def __init__(self, fields: _Fields, names: set[str]):
        self.fields, self.names, self.last = fields, names, -math.inf
        self.types: dict[tuple[str, str], F.FieldType | None] = {}  # None: not an output of the scene

    def ftype(self, key: tuple[str, str]) -> F.FieldType | None:
        if key not in self.types:
            node, fld = key
            t = self.fields.of(node, fld) if node in self.names else None
            self.types[key] = None if isinstance(t, str) else t
        return self.types[key]


def _row_by_row(path: str, first: int, text: str, state: _State, b: ViewBuilder, problems: list[Problem]) -> None:
    """The chunk's rows one at a time: its problems, with their lines, and its good rows."""
    reader = csv.reader(io.StringIO(text, newline=""))
    line = 0
    for cols in reader:
        where, line = first + line, reader.line_num
        problem = _row_problem(cols, state.last, state.fields, state.names)
        if problem is not None:
            problems.append(Problem(path, where, problem))
            if len(problems) >= MAX_PROBLEMS:
                return
            continue
        t = float(cols[0])
        if state.last == -math.inf and not _starts(t):
            problems.append(Problem(path, where, _start_problem(t)))
        state.last = t
        b.add_row(t, *cols[1:])


def _bulk(text: str, state: _State, b: ViewBuilder) -> bool:
    """The chunk checked and added a whole output at a time; False, adding nothing, where
    anything is wrong or not plain (row_by_row then says what)."""
    if '"' in text or "\r" in text:
        return False
    text = text[:-1] if text.endswith("\n") else text
    lines = text.split("\n")
    if set(map(str.count, lines, repeat(",", len(lines)))) != {3}:  # four columns on every row
        return False
    del lines
    enabled = gc.isenabled()
    gc.disable()  # a chunk makes ~10^6 strings, none of them cyclic: no collection to run
    try:
        return _bulk_rows(text.replace("\n", ",").split(","), state, b)
    finally:
        if enabled:
            gc.enable()


def _bulk_rows(flat: list[str], state: _State, b: ViewBuilder) -> bool:
    times, values = flat[0::4], flat[3::4]
    parsed_times = dict.fromkeys(times)  # a frame's rows share their time: each read once
    try:
        for text in parsed_times:
            parsed_times[text] = F.number(text)
    except ValueError:
        return False
    t = np.fromiter(map(parsed_times.__getitem__, times), np.float64, len(times))
    if not np.isfinite(t).all() or t[0] < state.last or (t.size > 1 and np.any(np.diff(t) < 0)) \
            or (state.last == -math.inf and not _starts(t[0])):
        return False
    keys = list(zip(flat[1::4], flat[2::4]))
    ids = {k: i for i, k in enumerate(dict.fromkeys(keys))}
    types = [state.ftype(k) for k in ids]
    if any(ft is None for ft in types):
        return False
    gid = np.fromiter(map(ids.__getitem__, keys), np.intp, len(keys))
    del keys
    order = np.argsort(gid, kind="stable")
    bounds = np.concatenate([[0], np.cumsum(np.bincount(gid, minlength=len(ids)))])
    parsed = []
    for i, (key, ftype) in enumerate(zip(ids, types)):
        idx = order[bounds[i]:bounds[i + 1]]
        vals = [values[idx[0]]] if idx.size == 1 else list(itemgetter(*idx.tolist())(values))
        got = _bulk_values(ftype, vals, state.names)
        if got is None:
            return False
        parsed.append((key, t[idx], got, vals))
    b.add_times(t)
    for key, tk, got, vals in parsed:
        if isinstance(got, np.ndarray):
            b.add_series(key, tk, got, counted=True)
        else:
            for time, value in zip(tk.tolist(), vals):
                b.add_row(time, key[0], key[1], value)
    state.last = float(t[-1])
    return True


_PATTERNS: dict[int, re.Pattern] = {}


def _bulk_values(ftype: F.FieldType, vals: list[str], names: set[str]) -> np.ndarray | bool | None:
    """One output's values in a chunk: an (n, width) array where they are SF numbers written
    plainly; True where they are good but are to be added row by row (other types); None
    where any is not good, or the bulk check cannot tell."""
    if ftype.kind == "float" and not ftype.multi:
        w = ftype.width
        pattern = _PATTERNS.get(w)
        if pattern is None:
            one = _NUMBER + f"(?: {_NUMBER})" * (w - 1)
            pattern = _PATTERNS[w] = re.compile(f"{one}(?:\n{one})*+")
        joined = "\n".join(vals)
        if pattern.fullmatch(joined) is None:
            return None
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            try:
                arr = np.fromstring(joined, dtype=np.float64, sep=" ")
            except (ValueError, DeprecationWarning):
                return None
        if arr.size != len(vals) * w or not np.isfinite(arr).all():
            return None
        arr = arr.reshape(len(vals), w)
        return None if ftype.rotation and _bad_axis(arr) is not None else arr
    return True if all(_value_problem(ftype, v, names) is None for v in vals) else None


def _row_problem(cols: list[str], last: float, fields: _Fields, names: set[str]) -> str | None:
    if len(cols) != 4:
        return f"{len(cols)} columns, expected 4 ({','.join(HEADER)})"
    text, node, fld, value = cols
    try:
        t = F.number(text)
    except F.FieldError as e:
        return f"time {e}"
    if not math.isfinite(t):
        return f"time {quoted(text)} is not finite"
    if t < last:
        return f"time {t:g} is before the previous row's {last:g} (times never decrease)"
    ftype = _output_type(fields, names, node, fld)
    return ftype if isinstance(ftype, str) else _value_problem(ftype, value, names)


def _output_type(fields: _Fields, names: set[str], node: str, fld: str) -> F.FieldType | str:
    """The type of an output a row names, or why the scene has no such output."""
    if node not in names:
        return f"node {quoted(node)} is not in the scene (DEF names, or TYPE_k for nodes without one)"
    ftype = fields.of(node, fld)
    return f"field {quoted(fld)} of {node}: {ftype}" if isinstance(ftype, str) else ftype


def _missing(path: str, have: set[tuple[str, str]], scene: Scene) -> list[Problem]:
    """Every RigidBody field the trace lacks (bodies of enabled collections); have: the
    (node, field) pairs it has."""
    return [Problem(path, 0, f"no rows for {b}.{f} (every RigidBody records {', '.join(BODY_FIELDS)})")
            for w in worlds(scene) for b in w.bodies.names for f in BODY_FIELDS if (b, f) not in have]
