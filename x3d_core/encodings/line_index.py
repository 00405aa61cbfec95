"""Line and column of an offset into a loaded text, computed when a diagnostic asks (every
loader's, so that none keeps a number per line)."""

from __future__ import annotations

import bisect
from array import array

from x3d_core.model.scene import Location


class LineIndex:
    """Line and column of an offset into a text (str or bytes), found when a diagnostic asks.

    Keeps two numbers per block of _BLOCK characters (the newlines before the block, and
    where the last of them is), not one per line: a file of 42 MB of newlines once cost
    2 GiB in a list of line starts. Each question reads at most one block."""

    _BLOCK = 1 << 12

    def __init__(self, text: str | bytes):
        self.text = text
        self._nl = b"\n" if isinstance(text, bytes) else "\n"
        self._before: array | None = None  # newlines before each block
        self._last: array | None = None  # offset of the last newline before each block, -1 if none
        self._cursor = (0, 1, -1)  # an offset, its line, the offset of the last newline before it

    def _blocks(self) -> tuple[array, array]:
        if self._before is None:
            text, nl, size = self.text, self._nl, self._BLOCK
            before, last = array("q", [0]), array("q", [-1])
            for s in range(0, len(text), size):
                before.append(before[-1] + text.count(nl, s, s + size))
                r = text.rfind(nl, s, s + size)
                last.append(r if r >= 0 else last[-1])
            self._before, self._last = before, last
        return self._before, self._last

    def locate(self, offset: int) -> tuple[int, int]:
        """(line, column), both from 1, of an offset (at most len(text))."""
        at, line, nl_before = self._cursor  # the last answer: loaders ask mostly in file order
        if not at <= offset < at + self._BLOCK:
            before, last = self._blocks()
            b = offset // self._BLOCK
            at = b * self._BLOCK
            line, nl_before = before[b] + 1, last[b]
        line += self.text.count(self._nl, at, offset)
        r = self.text.rfind(self._nl, at, offset)
        if r >= 0:
            nl_before = r
        self._cursor = (offset, line, nl_before)
        return line, offset - nl_before

    def line_start(self, line: int) -> int | None:
        """The offset where a line (from 1) starts; None past the last line."""
        if line == 1:
            return 0
        before, _ = self._blocks()
        if line - 1 > before[-1]:
            return None
        b = bisect.bisect_left(before, line - 1) - 1  # the block holding the (line-1)th newline
        s = b * self._BLOCK
        at = s - 1
        for _ in range(line - 1 - before[b]):
            at = self.text.find(self._nl, at + 1)
        return at + 1

    def line_end(self, line: int) -> int:
        """The offset just past a line's newline (the text's end for the last line)."""
        start = self.line_start(line)
        end = self.text.find(self._nl, start) if start is not None else -1
        return len(self.text) if end < 0 else end + 1

    def location(self, path: str, offset: int) -> Location:
        return Location(path, *self.locate(offset))
