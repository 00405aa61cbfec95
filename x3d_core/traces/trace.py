"""The event trace: CSV rows `time,node,field,value`, the X3D event stream itself.

`value` is the field in X3D XML attribute encoding with every digit (a trace compared
over long runs needs full precision); rotations are axis-angle, angle in [0, pi].
A trace is written whole or not at all: to a temporary name, then renamed.

Reading one (read_trace, read_view) goes through x3d_core.files.inputs: a named pipe or a device
is refused, not waited on, and so is a file larger than TRACE_LIMIT bytes. Times and numbers
are read by X3D's grammar (x3d_core.model.fields), a row that is not a ValueError naming its line. A trace is the
contract between x3drbp and other implementations, so its names are written as they are:
a DEF name that starts with =, +, - or @ is not escaped for spreadsheets
(docs/commands/run.md: "Traces and spreadsheets").
"""

from __future__ import annotations

import csv
import io
from typing import Any, BinaryIO, Callable, Iterator, NamedTuple

import numpy as np

from x3d_core.files import atomic
from x3d_core.files.inputs import open_regular
from x3d_core.files.paths import quoted
from x3d_core.model import fields as F

from .trace_npz import read_npz
from .trace_view import TRACE_LIMIT, Row, TraceView, ViewBuilder, numbers

HEADER = ("time", "node", "field", "value")
CHUNK_BYTES = 2 << 20  # read and parsed at a time


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

    def events(self, as_numbers: bool = False) -> Iterator[tuple[float, str, str, Any]]:
        """The rows, values as written; with `as_numbers`, an SF number or vector column's values
        as lists of floats, the numbers its text reads as (Trace.view formats none)."""
        texts = []
        for c in self.columns:
            if as_numbers and c.ftype is not None and c.ftype.numeric and not c.ftype.multi:
                rows = np.asarray(c.values, dtype=np.float64).reshape(1 if c.constant else self.count, -1).tolist()
                texts.append(rows * self.count if c.constant else rows)
            elif c.constant:
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
            yield from _events(b)

    def view(self) -> TraceView:
        """What read_view reads from this trace's CSV, number for number and in the same key
        order, made from the arrays: an SF number or vector field is never formatted, its
        blocks stacked per (field, nodes) and split per node. Tables and the other fields
        go row by row through the CSV reader's own rule (trace_view.numbers)."""
        groups: dict[tuple[str, tuple[str, ...]], tuple[list[int], list[float], list[np.ndarray]]] = {}
        pieces: dict[tuple[str, str], list[tuple[np.ndarray, np.ndarray, np.ndarray]]] = {}  # first-row order
        loose: dict[tuple[str, str], tuple[list[int], list[float], list[list[float]]]] = {}
        texts: dict[tuple[str, str], tuple[list[float], list[str]]] = {}
        times, count = [], 0
        for seq, b in enumerate(self.blocks):
            if isinstance(b, _Block) and b.ftype is not None and b.ftype.numeric and not b.ftype.multi:
                if not b.nodes:
                    continue
                key = (b.field, tuple(b.nodes))
                g = groups.get(key)
                if g is None:
                    g = groups[key] = ([], [], [])
                    for node in b.nodes:
                        pieces.setdefault((node, b.field), [])
                g[0].append(seq)
                g[1].append(b.time)
                g[2].append(b.convert(b.values) if b.convert is not None else b.values)
                times.append(b.time)
                count += len(b.nodes)
                continue
            times.append(b.time)
            for t, node, fld, value in b.events(as_numbers=True) if isinstance(b, _Table) else _events(b):
                count += 1
                read = value if isinstance(value, list) else numbers(value)
                if read is None:  # SFBool, SFNode names, MFString
                    held = texts.setdefault((node, fld), ([], []))
                    held[0].append(t)
                    held[1].append(value)
                    continue
                pieces.setdefault((node, fld), [])
                held = loose.setdefault((node, fld), ([], [], []))
                held[0].append(seq)
                held[1].append(t)
                held[2].append(read)
        for (fld, nodes), (seqs, ts, values) in groups.items():
            stacked = np.stack(values)
            stacked = stacked.reshape(len(ts), len(nodes), -1)  # SFFloat's (k,) rows as (k, 1)
            s, t = np.array(seqs), np.array(ts)
            for j, node in enumerate(nodes):
                pieces[(node, fld)].append((s, t, stacked[:, j, :]))
        for key, (seqs, ts, rows) in loose.items():
            pieces[key].append((np.array(seqs), np.array(ts), np.array(rows, dtype=np.float64)))
        series = {}
        for key, held in pieces.items():
            widths = {v.shape[1:] for _, _, v in held}
            if len(widths) > 1:
                raise ValueError(f"{key[0]}.{key[1]}: rows of {len(widths)} different widths")
            if len(held) == 1:
                series[key] = (held[0][1], np.ascontiguousarray(held[0][2]))
                continue
            order = np.argsort(np.concatenate([s for s, _, _ in held]), kind="stable")
            series[key] = (np.concatenate([t for _, t, _ in held])[order],
                           np.concatenate([v for _, _, v in held])[order])
        every = np.sort(np.array(times, dtype=np.float64))  # np.unique would import numpy.ma: 8 ms of a run's start
        first = np.ones(len(every), dtype=bool)  # each time's first row (none at all: a run that blew up at t = 0)
        first[1:] = every[1:] != every[:-1]
        return TraceView.of(series, {k: (np.array(t), s) for k, (t, s) in texts.items()}, every[first], count)

    @property
    def rows(self) -> list[Row]:
        return [Row(*e) for e in self.events()]

    def text(self) -> str:
        """The CSV, quoted as the csv module quotes (only what holds a comma, quote or
        line break), written without it: a trace can hold millions of rows. A block's time,
        field and node names are formatted once, and an SF float field's numbers row by row
        in one join (_float_rows), not through a call per number."""
        lines = [",".join(HEADER)]
        times: dict[float, str] = {}
        names: dict[str, str] = {}
        for b in self.blocks:
            when = times.get(b.time)
            if when is None:
                when = times[b.time] = F._num(b.time)
            if isinstance(b, _Block) and b.ftype is not None and b.ftype.kind == "float" and not b.ftype.multi:
                field = _quoted(b.field)
                values = b.convert(b.values) if b.convert is not None else b.values
                for node, value in zip(b.nodes, _float_rows(values)):  # numbers hold no comma or quote
                    named = names.get(node)
                    if named is None:
                        named = names[node] = _quoted(node)
                    lines.append(f"{when},{named},{field},{value}")
                continue
            for _, node, field, value in _events(b):
                lines.append(f"{when},{_quoted(node)},{_quoted(field)},{_quoted(value)}")
        lines.append("")
        return "\n".join(lines)

    def write(self, path: str) -> None:
        atomic.write_text(path, self.text())


def _events(b: _Block | _Table) -> Iterator[tuple[float, str, str, str]]:
    """One block's rows, values as written."""
    if isinstance(b, _Table):
        yield from b.events()
    elif b.ftype is None:
        yield b.time, b.nodes[0], b.field, b.values[0]
    else:
        values = b.convert(b.values) if b.convert is not None else b.values
        ftype, time, field = b.ftype, b.time, b.field
        for node, value in zip(b.nodes, values.tolist()):
            yield time, node, field, F.format_xml(ftype, value)


def _float_rows(values: np.ndarray) -> list[str]:
    """Each row of an SF float field as format_xml writes it (fields._num: repr, a whole
    number without its ".0"), made by string operations on the repr of all the rows at once
    (a list's repr is its floats' reprs): a ".0" followed by a blank or a line break can only
    end a number."""
    if not len(values):
        return []
    text = repr(values.tolist())
    if values.ndim == 1:  # "[a, b]"
        text = text[1:-1].replace(", ", "\n")
    else:  # "[[a, b], [c, d]]"
        text = text[2:-2].replace("], [", "\n").replace(", ", " ")
    return (text + "\n").replace(".0 ", " ").replace(".0\n", "\n")[:-1].split("\n")


def _quoted(text: str) -> str:
    if "," in text or '"' in text or "\n" in text or "\r" in text:
        return '"' + text.replace('"', '""') + '"'
    return text


class _CrLines:
    """A trace file whose lines end in a lone CR (classic Mac OS; some spreadsheets export so)
    or a CRLF, read as lines that end in LF: readline and readlines, what read_header and
    chunks call. Without it a CR-only file was one line, its header, and "no rows after the
    header"."""

    def __init__(self, f: BinaryIO):
        self._f, self._held = f, b""

    def _more(self) -> bool:
        data = self._f.read(CHUNK_BYTES)
        if data.endswith(b"\r"):  # a CRLF is not split between two reads
            data += self._f.read(1)
        self._held += data.replace(b"\r\n", b"\n").replace(b"\r", b"\n")
        return bool(data)

    def readline(self) -> bytes:
        while b"\n" not in self._held and self._more():
            pass
        end = self._held.find(b"\n") + 1 or len(self._held)
        line, self._held = self._held[:end], self._held[end:]
        return line

    def readlines(self, hint: int) -> list[bytes]:
        while (len(self._held) < hint or b"\n" not in self._held) and self._more():
            pass
        end = self._held.rfind(b"\n") + 1 or len(self._held)
        lines, self._held = self._held[:end], self._held[end:]
        return lines.splitlines(keepends=True)


def line_reader(f: BinaryIO) -> BinaryIO | _CrLines:
    """f as read_header and chunks read it: as it is, or, where its first line ends in a CR
    (alone, or a CRLF), with each CR or CRLF a line's end (so that a CRLF trace takes
    validate's bulk check, which leaves any chunk holding a CR to the row-by-row one: 4.7
    times the CPU)."""
    head = f.read(1 << 16)
    f.seek(0)
    cr, lf = head.find(b"\r"), head.find(b"\n")
    return _CrLines(f) if 0 <= cr and (lf < 0 or cr < lf) else f


def read_header(f) -> tuple[list[str] | None, int]:
    """The first record of a binary trace file (a UTF-8 BOM before it read as nothing, as every
    other reader of x3drbp's reads one), and the number of lines it took (its header); None at
    an empty file. UnicodeDecodeError, csv.Error as the csv module raises."""
    first = f.readline()
    while first.count(b'"') % 2:
        more = f.readline()
        if not more:
            break
        first += more
    first = first.removeprefix(b"\xef\xbb\xbf")
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
    got = "nothing" if header is None else quoted(",".join(header))
    return f"header is {got}, expected {','.join(HEADER)!r}"


def _record_chunks(path: str) -> Iterator[tuple[int, str, list[list[str]]]]:
    """(its first line, its text, its records): the rest of a trace file after its header, a
    chunk at a time; ValueError naming the file at a wrong header."""
    with open_regular(path, TRACE_LIMIT) as raw:
        f = line_reader(raw)
        header, lines = read_header(f)
        problem = header_problem(header)
        if problem:
            raise ValueError(f"{path}:1: {problem}")
        for first, text in chunks(f, lines + 1):
            yield first, text, _records(text)


def _line(text: str, first: int, k: int) -> int:
    """The line where record k of a chunk (its text, its first line) starts; found only for a
    message, so that reading a good chunk counts none."""
    reader = csv.reader(io.StringIO(text, newline=""))
    line = first
    for i, _ in enumerate(reader):
        if i == k:
            break
        line = first + reader.line_num
    return line


def _time(text: str) -> float:
    """A row's time, a number in X3D's grammar (float() alone read 1_0 as 10 s)."""
    try:
        return F.number(text)
    except F.FieldError as e:
        raise ValueError(f"time {e}") from None


def _rows(path: str, add: Callable[[float, str, str, str], None], flush: Callable[[], None]) -> None:
    """Each row of a CSV trace to add(time, node, field, value), flush() after each chunk; a
    ValueError naming file and line at a row that does not read."""
    for first, text, records in _record_chunks(path):
        k, said, time = 0, None, 0.0
        try:
            for k, (t, n, fld, v) in enumerate(records):
                if t != said:  # a frame's rows share their time: each read once
                    said, time = t, _time(t)
                add(time, n, fld, v)
        except ValueError as e:
            raise ValueError(f"{path}:{_line(text, first, k)}: {e}") from None
        flush()


def read_trace(path: str) -> list[Row]:
    """Every row (a list of Row objects: for short traces; read_view holds a long one in arrays)."""
    rows: list[Row] = []
    _rows(path, lambda t, n, fld, v: rows.append(Row(t, n, fld, v)), lambda: None)
    return rows


def read_view(path: str) -> TraceView:
    """A trace file straight into a TraceView: a CSV a chunk at a time (no object per row, so a
    trace of millions of rows costs its arrays; read_trace's rows cost ~200 bytes each), a
    .npz (x3d_core.traces.trace_npz) as its arrays."""
    if path.endswith(".npz"):
        return read_npz(path)
    b = ViewBuilder(strict=True)
    _rows(path, b.add_row, b.flush)
    return b.view()
