"""The event trace in NumPy's .npz: the same rows as the CSV (x3d_core.traces.trace), held as the
arrays a TraceView reads, for a run whose trace is read back by a program, not a person.

The CSV is the contract with other implementations; this is the binary form of what
read_view makes of it: writing formats no number and reading parses none (a 5 s run of a
20-body scene writes 0.1 s of CSV text, and its reader parses it back), and it is what
every run a command starts hands back. `x3drbp run --trace OUT.npz` writes it by choice.

Layout (format FORMAT, every array plain: np.load reads it with allow_pickle=False):
- keys (n, 2) str: each numeric output's node and field, in the order of its first row;
  lengths (n,), widths (n,); t: every output's times, one after another; v: their values,
  each output's (length, width) rows flattened, one after another;
- text_keys (m, 2), text_lengths (m,), text_t, text_v: the outputs kept as text (SFBool,
  SFNode names, MFString), their values as written in the CSV;
- times: every row's time, sorted, each once; count: the number of rows.
"""

from __future__ import annotations

import math
import os
import zipfile
from typing import BinaryIO

import numpy as np
from numpy.lib import format as npy

from x3d_core.files import atomic
from x3d_core.files.inputs import InputRefused, open_regular

from .trace_view import TRACE_LIMIT, TraceView

FORMAT = "x3drbp-trace-npz-1"
ZIP_MAGIC = b"PK\x03\x04"
_NAMES = ("format", "keys", "lengths", "widths", "t", "v", "text_keys", "text_lengths", "text_t", "text_v",
          "times", "count")
# each array's kind of values (numpy's dtype.kind: f floats, i and u integers, U text) and dimensions
_SPEC = {"format": ("U", 0), "keys": ("U", 2), "lengths": ("iu", 1), "widths": ("iu", 1), "t": ("f", 1),
         "v": ("f", 1), "text_keys": ("U", 2), "text_lengths": ("iu", 1), "text_t": ("f", 1), "text_v": ("U", 1),
         "times": ("f", 1), "count": ("iu", 0)}
_WORDS = {"U": "text", "iu": "integers", "f": "real numbers"}
_HEADERS = {(1, 0): npy.read_array_header_1_0, (2, 0): npy.read_array_header_2_0}
# outputs (each held as a few Python objects, ~450 bytes: 10^6 of them ~0.5 GB); a run of
# 10^5 bodies records 4 x 10^5
MAX_OUTPUTS = 10**6
MAX_DIRECTORY = 1 << 16  # bytes of the zip's directory: write_npz's 12 members take under 1 KB
_END_MAGIC, _END_SIZE, _END_SPAN = b"PK\x05\x06", 22, 22 + 0xFFFF  # the end record, after it a comment of < 64 KiB
_ZIP64_MAGIC, _LOCATOR_SIZE = b"PK\x06\x07", 20  # a Zip64 locator, just before the end record


def _keys(keys: list[tuple[str, str]]) -> np.ndarray:
    return np.array(keys, dtype=str).reshape(len(keys), 2)


def arrays(view: TraceView) -> dict[str, np.ndarray]:
    """The view as the file's arrays."""
    keys = view.keys()
    series = [view.series(*k) for k in keys]
    texts = [view.text(*k) for k in view.text_keys()]
    return {
        "format": np.array(FORMAT),
        "keys": _keys(keys),
        "lengths": np.array([len(t) for t, _ in series], dtype=np.int64),
        "widths": np.array([v.shape[1] if v.ndim > 1 else 1 for _, v in series], dtype=np.int64),
        "t": np.concatenate([t for t, _ in series]) if series else np.empty(0),
        "v": np.concatenate([v.ravel() for _, v in series]) if series else np.empty(0),
        "text_keys": _keys(view.text_keys()),
        "text_lengths": np.array([len(t) for t, _ in texts], dtype=np.int64),
        "text_t": np.concatenate([t for t, _ in texts]) if texts else np.empty(0),
        "text_v": np.array([s for _, values in texts for s in values], dtype=str),
        "times": view.times(),
        "count": np.array(len(view), dtype=np.int64),
    }


def write_npz(view: TraceView, path: str) -> None:
    """The view to path, whole or not at all (uncompressed: a run's trace is read back at once)."""
    with atomic.replacing(path) as tmp, open(tmp, "wb") as f:
        np.savez(f, **arrays(view))


class _NotTrace(Exception):
    """What makes a file no trace of this format, in words."""


class NotTrace(ValueError):
    """A file read_npz does not read as a trace: its path, and the reason in words."""

    def __init__(self, path: str, reason: str):
        super().__init__(f"{path}: {reason}")
        self.path, self.reason = path, reason


def read_npz(path: str) -> TraceView:
    """A trace written by write_npz; NotTrace naming the file where it is not one."""
    try:
        return _view(_arrays(path))
    except (_NotTrace, InputRefused) as e:
        raise NotTrace(path, str(e)) from None
    except (zipfile.BadZipFile, EOFError, ValueError) as e:  # numpy's and the zip module's words
        raise NotTrace(path, f"not an x3drbp trace: {e}") from None


def _arrays(path: str) -> dict[str, np.ndarray]:
    """The arrays, each checked from the zip's directory and its .npy header before a byte of
    it is unpacked: the sizes they declare (a zip bomb unpacks as much as it declares, zipfile
    reads no further), their kind of numbers (never objects or complex numbers), and that their
    shape fills exactly what they declare (a shape of 10^15 is refused, not allocated)."""
    with open_regular(path, TRACE_LIMIT) as f:
        if f.read(4) != ZIP_MAGIC:  # np.load would take anything else for a pickle or an .npy
            raise _NotTrace("not an x3drbp trace: not an .npz (zip) file")
        _check_directory(f)
        with zipfile.ZipFile(f) as z:
            held = set(z.namelist())
            missing = [n for n in _NAMES if f"{n}.npy" not in held]
            if missing:
                raise _NotTrace(f"not an x3drbp trace ({FORMAT}): no {', '.join(missing)}")
            members = {n: z.getinfo(f"{n}.npy") for n in _NAMES}
            unpacked = sum(m.file_size for m in members.values())
            if unpacked > TRACE_LIMIT:
                raise _NotTrace(f"its arrays unpack to {unpacked} bytes; x3drbp reads at most {TRACE_LIMIT}")
            a = {}
            for n, member in members.items():
                a[n] = _array(z, member, n)
                if n == "format" and str(a[n]) != FORMAT:
                    raise _NotTrace(f"not an x3drbp trace ({FORMAT}): format {str(a[n])!r}")
    for n in ("t", "text_t", "times"):
        if not np.isfinite(a[n]).all():
            raise _NotTrace(f"{n} holds a time that is not a finite number")
    return a


def _check_directory(f: BinaryIO) -> None:
    """Refuses a zip whose directory is larger than MAX_DIRECTORY bytes (zipfile holds an object
    of ~500 bytes per member it lists: a 1 GiB directory would be 10 GB) or is a Zip64 one
    (whose sizes zipfile takes from another record; write_npz never needs one)."""
    f.seek(0, os.SEEK_END)
    size = f.tell()
    f.seek(max(0, size - _END_SPAN))
    tail = f.read()
    end = tail.rfind(_END_MAGIC)
    if end < 0 or len(tail) - end < _END_SIZE:
        raise _NotTrace("not an x3drbp trace: the zip file has no end record")
    if end >= _LOCATOR_SIZE and tail[end - _LOCATOR_SIZE:end - _LOCATOR_SIZE + 4] == _ZIP64_MAGIC:
        raise _NotTrace("not an x3drbp trace: a Zip64 file (write_npz writes none)")
    listed = int.from_bytes(tail[end + 12:end + 16], "little")
    if listed > MAX_DIRECTORY:
        raise _NotTrace(f"its zip directory is {listed} bytes; x3drbp reads at most {MAX_DIRECTORY}")
    f.seek(0)


def _array(z: zipfile.ZipFile, member: zipfile.ZipInfo, name: str) -> np.ndarray:
    """One array, once its .npy header agrees with _SPEC and with the member's declared size."""
    kinds, ndim = _SPEC[name]
    with z.open(member) as m:
        header = _HEADERS.get(npy.read_magic(m))
        if header is None:
            raise _NotTrace(f"{name}: not a .npy array of format 1.0 or 2.0")
        shape, _, dtype = header(m)
        data = member.file_size - m.tell()
    if dtype.hasobject or dtype.kind not in kinds:
        raise _NotTrace(f"{name}: {dtype} values; a trace holds {_WORDS[kinds]} there")
    if len(shape) != ndim or (name.endswith("keys") and shape[1] != 2):
        raise _NotTrace(f"{name}: an array of shape {shape}")
    if name.endswith("keys") and shape[0] > MAX_OUTPUTS:
        raise _NotTrace(f"{name}: {shape[0]} outputs; x3drbp reads at most {MAX_OUTPUTS} of a kind")
    if math.prod(shape) * dtype.itemsize != data:
        raise _NotTrace(f"{name}: its shape {shape} of {dtype} needs {math.prod(shape) * dtype.itemsize} bytes; "
                        f"it holds {data}")
    with z.open(member) as m:
        return npy.read_array(m, allow_pickle=False)


def _view(a: dict[str, np.ndarray]) -> TraceView:
    """The view of the arrays, once they agree (in Python's integers, which do not wrap)."""
    lengths, widths, text_lengths = a["lengths"].tolist(), a["widths"].tolist(), a["text_lengths"].tolist()
    if min(lengths + text_lengths, default=0) < 0 or min(widths, default=1) < 1:
        raise _NotTrace("the trace's arrays give a length below 0 or a width below 1")
    if len(lengths) != len(a["keys"]) or len(widths) != len(lengths) or sum(lengths) != len(a["t"]) \
            or sum(n * w for n, w in zip(lengths, widths)) != len(a["v"]) or sum(text_lengths) != len(a["text_t"]) \
            or len(a["text_t"]) != len(a["text_v"]) or len(text_lengths) != len(a["text_keys"]):
        raise _NotTrace("the trace's arrays disagree on their lengths")
    series = {}
    t_end = v_end = 0
    for (node, fld), n, w in zip(a["keys"].tolist(), lengths, widths):
        series[(node, fld)] = (a["t"][t_end:t_end + n], a["v"][v_end:v_end + n * w].reshape(n, w))
        t_end, v_end = t_end + n, v_end + n * w
    texts = {}
    end = 0
    for (node, fld), n in zip(a["text_keys"].tolist(), text_lengths):
        texts[(node, fld)] = (a["text_t"][end:end + n], a["text_v"][end:end + n].tolist())
        end += n
    return TraceView.of(series, texts, a["times"], int(a["count"]))
