"""A trace's rows grouped by output, as arrays: what every reader of a trace works on,
whichever form it was read from (x3d_core.traces.trace's CSV, x3d_core.traces.trace_npz's arrays)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Callable

import numpy as np

from x3d_core.model import fields as F

# the largest trace read: ~1.5e7 rows at full precision, what a validation holds in about a GiB
TRACE_LIMIT = 1 << 30  # bytes


@dataclass(frozen=True)
class Row:
    time: float
    node: str
    field: str
    value: str



def numbers(value: str) -> list[float] | None:
    """A row's value as a view holds it: its numbers where every token reads as one, else
    None (the value is kept as text). Both ways of making a view (ViewBuilder.add_row from
    the CSV, Trace.view from the arrays) read a row by this one rule. A value of no token is
    text (a Contact's empty appliedParameters), not a row of no numbers: no output is that."""
    try:
        return [float(x) for x in value.split()] or None
    except ValueError:
        return None


class ViewBuilder:
    """A TraceView made a piece at a time: whole arrays of one output (add_series), or rows
    one by one (add_row: TraceView's rule, numbers where every token reads as one, else text).
    Each output's arrays grow in place (by a quarter, a copy each time), so a trace of 10^7
    rows peaks near the size of its arrays, not twice it as joining pieces at the end would."""

    GROWTH = 1.25

    def __init__(self, strict: bool = False) -> None:
        # strict: rows read from a file, whose numbers are X3D's: add_row refuses what float()
        # alone read (1_000 as 1000, nan, two numbers apart by a no-break space); rows made in
        # memory (Trace.rows, a test's non-finite value) are read as float() reads them
        self.strict = strict
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
        values = numbers(value)
        if values is not None and self.strict:
            problem = F.numbers_problem(value)
            if problem is not None:
                raise F.FieldError(problem)
        if values is None:  # SFBool, SFNode names, MFString (CollisionSensor rows): kept as text
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
