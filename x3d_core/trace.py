"""The event trace: CSV rows `time,node,field,value`, the X3D event stream itself.

`value` is the field in X3D XML attribute encoding with every digit (a trace compared
over long runs needs full precision); rotations are axis-angle, angle in [0, pi].
A trace is written whole or not at all: to a temporary name, then renamed.

Reading one (read_trace, read_view) goes through x3d_core.inputs: a named pipe or a device
is refused, not waited on, and so is a file larger than TRACE_LIMIT bytes. A trace is the
contract between x3drbp and other implementations, so its names are written as they are:
a DEF name that starts with =, +, - or @ is not escaped for spreadsheets (README: "Traces
and spreadsheets").
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from collections.abc import Sequence
from typing import Any, Callable, Iterator, NamedTuple

import numpy as np

from . import atomic
from . import fields as F
from .inputs import open_regular

HEADER = ("time", "node", "field", "value")
# the largest trace read: ~1.5e7 rows at full precision, what a validation holds in about a GiB
TRACE_LIMIT = 1 << 30  # bytes
CHUNK_BYTES = 2 << 20  # read and parsed at a time


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


def read_header(f) -> tuple[list[str] | None, int]:
    """The first record of a binary trace file, and the number of lines it took (its
    header); None at an empty file. UnicodeDecodeError, csv.Error as the csv module raises."""
    first = f.readline()
    while first.count(b'"') % 2:
        more = f.readline()
        if not more:
            break
        first += more
    if not first:
        return None, 1
    header = next(csv.reader(io.StringIO(first.decode("utf-8"), newline="")), [])
    return header, first.count(b"\n") or 1


def chunks(f, first_line: int) -> Iterator[tuple[int, str]]:
    """(the number of its first line, its text): the rest of a binary trace file in pieces of
    about CHUNK_BYTES, each whole records (a quoted field's line breaks kept together)."""
    line = first_line
    while True:
        lines = f.readlines(CHUNK_BYTES)
        if not lines:
            return
        data = b"".join(lines)
        while data.count(b'"') % 2:
            more = f.readline()
            if not more:
                break
            data += more
        yield line, data.decode("utf-8")
        line += data.count(b"\n")


def _records(text: str) -> list[list[str]]:
    return list(csv.reader(io.StringIO(text, newline="")))


def header_problem(header: list[str] | None, lenient: bool = False) -> str | None:
    """What is wrong with a trace's first record (read_header's), in words; None when it is
    HEADER (lenient: once each name is stripped of blanks, as validate reads another's trace)."""
    names = None if header is None else tuple(h.strip() for h in header) if lenient else tuple(header)
    if names == HEADER:
        return None
    got = "nothing" if header is None else repr(",".join(header))
    return f"header is {got}, expected {','.join(HEADER)!r}"


def _record_chunks(path: str) -> Iterator[list[list[str]]]:
    """The records of a trace file after its header, a chunk at a time; ValueError naming the
    file at a wrong header."""
    with open_regular(path, TRACE_LIMIT) as f:
        header, lines = read_header(f)
        problem = header_problem(header)
        if problem:
            raise ValueError(f"{path}:1: {problem}")
        for _, text in chunks(f, lines + 1):
            yield _records(text)


def read_trace(path: str) -> list[Row]:
    """Every row (a list of Row objects: for short traces; read_view holds a long one in arrays)."""
    return [Row(float(t), n, fld, v) for records in _record_chunks(path) for t, n, fld, v in records]


def read_view(path: str) -> TraceView:
    """A trace file straight into a TraceView, a chunk at a time: no object per row, so a
    trace of millions of rows costs its arrays (read_trace's rows cost ~200 bytes each)."""
    b = ViewBuilder()
    for records in _record_chunks(path):
        for t, n, fld, v in records:
            b.add_row(float(t), n, fld, v)
        b.flush()
    return b.view()


class ViewBuilder:
    """A TraceView made a piece at a time: whole arrays of one output (add_series), or rows
    one by one (add_row: TraceView's rule, numbers where every token reads as one, else text).
    Each output's arrays grow in place (by a quarter, a copy each time), so a trace of 10^7
    rows peaks near the size of its arrays, not twice it as joining pieces at the end would."""

    GROWTH = 1.25

    def __init__(self) -> None:
        self._series: dict[tuple[str, str], list] = {}  # key: [times, values, rows used]
        self._rows: dict[tuple[str, str], tuple[list[float], list[list[float]]]] = {}
        self._texts: dict[tuple[str, str], tuple[list[float], list[str]]] = {}
        self._times: list[np.ndarray] = []
        self._loose: list[float] = []
        self.count = 0

    def _append(self, key: tuple[str, str], times: np.ndarray, values: np.ndarray) -> None:
        held = self._series.get(key)
        k = len(times)
        if held is None:
            held = self._series[key] = [np.empty(max(k, 16)), np.empty((max(k, 16), *values.shape[1:])), 0]
        t, v, n = held
        if v.shape[1:] != values.shape[1:]:
            raise ValueError(f"{key[0]}.{key[1]}: rows of {values.shape[1:]} numbers after rows of {v.shape[1:]}")
        if n + k > len(t):
            size = max(n + k, int(len(t) * self.GROWTH) + 16)
            grown_t, grown_v = np.empty(size), np.empty((size, *v.shape[1:]))
            grown_t[:n], grown_v[:n] = t[:n], v[:n]
            held[0], held[1] = t, v = grown_t, grown_v
        t[n:n + k], v[n:n + k] = times, values
        held[2] = n + k

    def add_series(self, key: tuple[str, str], times: np.ndarray, values: np.ndarray, counted: bool = False) -> None:
        """values[i] at times[i]; counted: the times already given to add_times."""
        self.flush_key(key)
        self._append(key, times, values)
        if not counted:
            self.add_times(times)
        self.count += len(times)

    def add_times(self, times: np.ndarray) -> None:
        """Times rows have (a chunk's, once for all its outputs)."""
        self._times.append(np.unique(times))

    def add_row(self, time: float, node: str, fld: str, value: str) -> None:
        key = (node, fld)
        self.count += 1
        self._loose.append(time)
        try:
            values = [float(x) for x in value.split()]
        except ValueError:  # SFBool, SFNode names, MFString (CollisionSensor rows): kept as text
            t, s = self._texts.setdefault(key, ([], []))
            t.append(time)
            s.append(value)
            return
        t, v = self._rows.setdefault(key, ([], []))
        t.append(time)
        v.append(values)

    def flush_key(self, key: tuple[str, str]) -> None:
        rows = self._rows.pop(key, None)
        if rows is not None:
            self._append(key, np.array(rows[0]), np.array(rows[1], dtype=np.float64))

    def flush(self) -> None:
        """Rows added one by one made arrays (at the end of each chunk: bounded memory)."""
        for key in list(self._rows):
            self.flush_key(key)
        if self._loose:
            self._times.append(np.unique(np.array(self._loose)))
            self._loose = []

    def view(self) -> TraceView:
        self.flush()
        series = {k: (t[:n], v[:n]) for k, (t, v, n) in self._series.items()}  # views: no copy
        texts = {k: (np.array(t), s) for k, (t, s) in self._texts.items()}
        times = np.unique(np.concatenate(self._times)) if self._times else np.empty(0)
        return TraceView.of(series, texts, times, self.count)


class TraceView:
    """A trace's rows grouped by (node, field): times, and values as float arrays."""

    def __init__(self, rows: Sequence[Row] | TraceView = ()):
        if isinstance(rows, TraceView):  # the same arrays, shared
            self._series, self._text, self._times, self._count = rows._series, rows._text, rows._times, rows._count
            return
        b = ViewBuilder()
        for r in rows:
            b.add_row(r.time, r.node, r.field, r.value)
        v = b.view()
        self._series, self._text, self._times, self._count = v._series, v._text, v._times, v._count

    @classmethod
    def of(cls, series: dict[tuple[str, str], tuple[np.ndarray, np.ndarray]],
           texts: dict[tuple[str, str], tuple[np.ndarray, list[str]]], times: np.ndarray, count: int) -> TraceView:
        """A view of arrays already grouped; times: every row's time, sorted, each once."""
        v = cls.__new__(cls)
        v._series, v._text, v._times, v._count = series, texts, times, count
        return v

    def __len__(self) -> int:
        """The number of rows."""
        return self._count

    def times(self) -> np.ndarray:
        """Every time a row has (text rows too), sorted, each once."""
        return self._times

    def end(self) -> float:
        """The last time of any row (nan without rows)."""
        return float(self._times[-1]) if self._times.size else float("nan")

    def text_keys(self) -> list[tuple[str, str]]:
        return list(self._text)

    def retimed(self, fn: Callable[[np.ndarray], np.ndarray]) -> TraceView:
        """The same rows, each time t moved to fn(t) (fn maps an array of times)."""
        series = {k: (fn(t), v) for k, (t, v) in self._series.items()}
        texts = {k: (fn(t), s) for k, (t, s) in self._text.items()}
        return TraceView.of(series, texts, np.unique(fn(self._times)), self._count)

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
