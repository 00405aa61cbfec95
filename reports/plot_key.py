"""A plot's key: a digest of the data it draws, of the code that draws it and of matplotlib's
version, kept in the PNG itself (a tEXt chunk), so that a plot is drawn again only where one of
those changed. A warm `x3drbp report` (nothing changed) drew its 15 divergence plots again:
9 s of CPU for the same bytes. In the file rather than beside it, a key cannot outlive or
miss its picture, and the folders hold what they held.
"""

from __future__ import annotations

import functools
import hashlib
import importlib.metadata
import importlib.util
import json
import struct

import numpy as np

KEYWORD = b"x3drbp-key"  # the tEXt chunk's keyword
_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def digest(data: list, modules: tuple[str, ...]) -> str:
    """SHA-256 of what a plot draws (JSON values and NumPy arrays, in order), the source files of
    the modules that draw it (by name) and matplotlib's version, none of them imported: a plot
    that is not drawn again does not pay for matplotlib's import (0.7 s)."""
    h = hashlib.sha256(_matplotlib().encode())
    for name in modules:
        with open(importlib.util.find_spec(name).origin, "rb") as f:
            h.update(hashlib.sha256(f.read()).digest())
    for part in data:
        if isinstance(part, np.ndarray):
            h.update(f"{part.dtype.str}{part.shape}".encode())
            h.update(np.ascontiguousarray(part).tobytes())
        else:
            h.update(json.dumps(part, sort_keys=True, allow_nan=True).encode())
        h.update(b"\0")
    return h.hexdigest()


@functools.cache
def _matplotlib() -> str:
    """matplotlib's version, from its installed metadata (a look through sys.path: asked once)."""
    return importlib.metadata.version("matplotlib")


def metadata(key: str) -> dict[str, str | None]:
    """savefig's PNG metadata that keeps the key (and no software tag: the same data, the same bytes)."""
    return {"Software": None, KEYWORD.decode(): key}


def drawn(path: str, key: str) -> bool:
    """Whether the PNG at path is whole (its chunks through IEND) and was drawn with this key;
    False where it is missing, cut short or keyed otherwise."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return False
    if not data.startswith(_SIGNATURE):
        return False
    found, at = None, len(_SIGNATURE)
    while at + 12 <= len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        if kind == b"tEXt":
            word, _, text = data[at + 8:at + 8 + length].partition(b"\0")
            found = text if word == KEYWORD else found
        if kind == b"IEND":
            return found == key.encode()
        at += 12 + length
    return False
