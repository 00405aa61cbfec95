"""The event trace in NumPy's .npz: the same rows as the CSV (x3d_core.trace), held as the
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

import zipfile

import numpy as np

from . import atomic
from .inputs import open_regular
from .trace_view import TRACE_LIMIT, TraceView

FORMAT = "x3drbp-trace-npz-1"
ZIP_MAGIC = b"PK\x03\x04"
_NAMES = ("format", "keys", "lengths", "widths", "t", "v", "text_keys", "text_lengths", "text_t", "text_v",
          "times", "count")


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


def read_npz(path: str) -> TraceView:
    """A trace written by write_npz; ValueError naming the file where it is not one."""
    try:
        return _view(_arrays(path))
    except _NotTrace as e:
        raise ValueError(f"{path}: {e}") from None
    except (zipfile.BadZipFile, EOFError, ValueError) as e:  # numpy's and the zip module's words
        raise ValueError(f"{path}: not an x3drbp trace: {e}") from None


def _arrays(path: str) -> dict[str, np.ndarray]:
    with open_regular(path, TRACE_LIMIT) as f:
        if f.read(4) != ZIP_MAGIC:  # np.load would take anything else for a pickle or an .npy
            raise _NotTrace("not an x3drbp trace: not an .npz (zip) file")
        f.seek(0)
        with np.load(f, allow_pickle=False) as npz:
            missing = [n for n in _NAMES if n not in npz.files]
            if missing or str(npz["format"]) != FORMAT:
                raise _NotTrace(f"not an x3drbp trace ({FORMAT}): "
                                + (f"no {', '.join(missing)}" if missing else f"format {str(npz['format'])!r}"))
            return {n: npz[n] for n in _NAMES}


def _view(a: dict[str, np.ndarray]) -> TraceView:
    lengths, widths = a["lengths"], a["widths"]
    if len(lengths) != len(a["keys"]) or len(widths) != len(lengths) or lengths.sum() != len(a["t"]) \
            or (lengths * widths).sum() != len(a["v"]) or a["text_lengths"].sum() != len(a["text_t"]) \
            or len(a["text_t"]) != len(a["text_v"]) or len(a["text_lengths"]) != len(a["text_keys"]):
        raise _NotTrace("the trace's arrays disagree on their lengths")
    series = {}
    t_ends, v_ends = np.cumsum(lengths), np.cumsum(lengths * widths)
    for (node, fld), n, w, t_end, v_end in zip(a["keys"].tolist(), lengths.tolist(), widths.tolist(),
                                               t_ends.tolist(), v_ends.tolist()):
        series[(node, fld)] = (a["t"][t_end - n:t_end], a["v"][v_end - n * w:v_end].reshape(n, w))
    texts = {}
    end = 0
    for (node, fld), n in zip(a["text_keys"].tolist(), a["text_lengths"].tolist()):
        texts[(node, fld)] = (a["text_t"][end:end + n], a["text_v"][end:end + n].tolist())
        end += n
    return TraceView.of(series, texts, a["times"], int(a["count"]))
