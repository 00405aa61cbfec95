"""Reading a small data file a command is given (a conformance matrix.json, BACKEND.toml pins,
the conformance matrix page): every problem one line, `FILE:LINE: why`, never a traceback.

The file comes through x3d_core.files.inputs (a named pipe or a device is refused before a byte is
read, a file over its limit from fstat) and is read as UTF-8. json and tomllib recurse once
per level of arrays and objects (inline tables): past the interpreter's recursion limit
(~1,000 frames; x3drbp's own files nest 2 to 5 levels) that is a RecursionError, once a
traceback, now the line where the file goes deepest, found only then (a good file pays
nothing for it), as the scene loaders do.
"""

from __future__ import annotations

import json
import re
import tomllib
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from .inputs import InputRefused, read_regular

DOCUMENT_LIMIT = 16 << 20  # bytes: a matrix.json of every case on every backend is under 1 MiB

# what hides brackets from the depth count: strings (and TOML's comments), JSON's within a line
# (one with a line break is malformed anyway); possessive: an unclosed quote costs one failed try
_JSON_HIDDEN = re.compile(r'"(?:[^"\\\n]|\\.)*+"')
_TOML_HIDDEN = re.compile(r'"""(?:[^"\\]|\\.|"{1,2}(?!"))*+"{3,5}|\'\'\'(?:[^\']|\'{1,2}(?!\'))*+\'{3,5}'
                          r'|"(?:[^"\\\n]|\\.)*+"|\'[^\'\n]*+\'|#[^\n]*+', re.S)
_TOML_WHERE = re.compile(r"\s*\((?:at line (\d+), column \d+|at end of document)\)$")


class BadDocument(ValueError):
    """A data file that cannot be read as one: its path, the line (None: the whole file), why."""

    def __init__(self, path: str, line: int | None, message: str):
        super().__init__(f"{path}:{line}: {message}" if line else f"{path}: {message}")
        self.path, self.line, self.message = path, line, message


def read_text(path: str, limit: int = DOCUMENT_LIMIT) -> str:
    """The file's text (UTF-8, a BOM dropped), a regular file of at most `limit` bytes."""
    try:
        data = read_regular(path, limit)
    except InputRefused as e:
        raise BadDocument(path, None, str(e)) from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as e:
        raise BadDocument(path, data.count(b"\n", 0, e.start) + 1, f"not UTF-8 text ({e.reason})") from None


def _line_breaks(m: re.Match) -> str:
    """What is left of a TOML string or comment: its line breaks (a multi-line string's)."""
    return "\n" * m.group().count("\n")


def _too_deep(path: str, text: str, hidden: re.Pattern, left: str | Callable[[re.Match], str]) -> BadDocument:
    """Where a file nested past what its parser recurses into goes deepest, and how deep:
    strings and comments replaced by `left` (what keeps a line a line of the file: nothing for
    JSON's strings, which lie within a line), then each bracket counted in bulk."""
    bare = hidden.sub(left, text).encode("utf-8")
    codes = np.frombuffer(bare, dtype=np.uint8)
    step = ((codes == ord("[")) | (codes == ord("{"))).astype(np.int32) - ((codes == ord("]")) | (codes == ord("}")))
    depth = np.cumsum(step, dtype=np.int32)
    deepest = int(np.argmax(depth))
    return BadDocument(path, bare.count(b"\n", 0, deepest) + 1,
                       f"nested {int(depth[deepest])} levels deep (arrays and objects), deeper than can be read")


def read_json(path: str, limit: int = DOCUMENT_LIMIT) -> Any:
    """The JSON value of a file (see read_text)."""
    text = read_text(path, limit)
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        raise BadDocument(path, e.lineno, f"malformed JSON: {e.msg}") from None
    except RecursionError:
        raise _too_deep(path, text, _JSON_HIDDEN, "") from None


@dataclass(frozen=True)
class Toml:
    """A TOML file read: its tables, and where in its text a table or key stands."""
    path: str
    text: str
    data: dict[str, Any]

    def line(self, table: str, key: str | None = None) -> int | None:
        """The line of `[table]` (a bare or quoted name), or of `key = ` within it; None where
        the text has no such header (a dotted or inline table)."""
        name = f"(?:{re.escape(table)}|\"{re.escape(table)}\"|'{re.escape(table)}')"
        head = re.search(rf"^[ \t]*\[[ \t]*{name}[ \t]*\]", self.text, re.M)
        if head is None:
            return None
        start = self.text.count("\n", 0, head.start()) + 1
        if key is None:
            return start
        end = re.compile(r"^[ \t]*\[", re.M).search(self.text, head.end())
        found = re.compile(rf"^[ \t]*{re.escape(key)}[ \t]*=", re.M).search(
            self.text, head.end(), end.start() if end else len(self.text))
        return start if found is None else self.text.count("\n", 0, found.start()) + 1

    def error(self, table: str, key: str | None, message: str) -> BadDocument:
        """`message` about a table's key, at its line."""
        return BadDocument(self.path, self.line(table, key), message)


def read_toml(path: str, limit: int = DOCUMENT_LIMIT) -> Toml:
    """The TOML of a file (see read_text): a key given twice, or any other syntax error, is a
    BadDocument at its line."""
    text = read_text(path, limit)
    try:
        return Toml(path, text, tomllib.loads(text))
    except RecursionError:
        raise _too_deep(path, text, _TOML_HIDDEN, _line_breaks) from None
    except tomllib.TOMLDecodeError as e:
        message = str(e)
        where = _TOML_WHERE.search(message)
        line = (int(where.group(1)) if where.group(1) else text.count("\n") + 1) if where else None
        said = message[:where.start()] if where else message
        if said == "Cannot overwrite a value":
            said += " (a key given twice)"
        raise BadDocument(path, line, f"malformed TOML: {said}") from None
