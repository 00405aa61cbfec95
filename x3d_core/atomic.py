"""Write a file whole or not at all: to a temporary name in the same folder, then renamed.

Every output file of x3drbp (traces, matrices, comparison and sweep JSON, reports) goes
through here, so a run killed half-way leaves the previous file or none, never a torn one.
"""

from __future__ import annotations

import json
import os
import tempfile
from typing import Any


def write_bytes(path: str, data: bytes) -> None:
    """path holds data once this returns; until then it holds what it held before."""
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=f".{os.path.basename(path)}-", suffix=".tmp", dir=folder)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def write_text(path: str, text: str) -> None:
    """text as UTF-8, line breaks as given, written atomically."""
    write_bytes(path, text.encode("utf-8"))


def write_json(path: str, data: Any, indent: int | None = 1) -> None:
    """data as JSON with a final line break, written atomically."""
    write_text(path, json.dumps(data, indent=indent) + ("\n" if indent is not None else ""))
