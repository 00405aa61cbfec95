"""Write a file whole or not at all: to a temporary name in the same folder, then renamed.

Every output file of x3drbp (traces, matrices, comparison and sweep JSON, reports, rerun
recordings) goes through here, so a run killed half-way leaves the previous file or none,
never a torn one. The one exception is `x3drbp report`'s step logs (DIR/logs/*.log,
conformance/cli/report.py): they are written as the step runs, to be read while it does
and to keep what a killed step said.
"""

from __future__ import annotations

import contextlib
import json
import os
import tempfile
from collections.abc import Iterator
from typing import Any


@contextlib.contextmanager
def replacing(path: str) -> Iterator[str]:
    """A temporary path in path's folder for a writer that wants a name (a library that
    opens the file itself): renamed to path when the block ends, removed if it raises.
    Until then path holds what it held before."""
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=f".{os.path.basename(path)}-", suffix=".tmp", dir=folder)
    os.close(fd)
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_bytes(path: str, data: bytes) -> None:
    """path holds data once this returns; until then it holds what it held before."""
    with replacing(path) as tmp, open(tmp, "wb") as f:
        f.write(data)


def write_text(path: str, text: str) -> None:
    """text as UTF-8, line breaks as given, written atomically."""
    write_bytes(path, text.encode("utf-8"))


def write_json(path: str, data: Any, indent: int | None = 1) -> None:
    """data as JSON with a final line break, written atomically."""
    write_text(path, json.dumps(data, indent=indent) + ("\n" if indent is not None else ""))
