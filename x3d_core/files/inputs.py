"""Reading an input file whole: a regular file of bounded size, or a one-line reason.

A named pipe would block a reader forever, /dev/zero would fill its memory, a folder or a
socket cannot be read as text: every file x3drbp reads (scenes, traces, the data files of
x3d_core.files.documents) comes through here, which looks at what the path is before reading a
byte of it; a folder of inputs, through require_folder.
"""

from __future__ import annotations

import os
import stat
from typing import BinaryIO


class InputRefused(Exception):
    """The path is not something x3drbp reads; the message says why in a few words."""


_KINDS = ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a named pipe"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"))


def kind(mode: int) -> str:
    """What a non-regular file is, in words."""
    return next((words for test, words in _KINDS if test(mode)), "not a regular file")


def open_regular(path: str, limit: int) -> BinaryIO:
    """The regular file at path (a symbolic link is followed) opened for binary reading, once
    it is known to hold at most `limit` bytes; InputRefused naming what else it is, that it is
    larger, or why it cannot be opened. For readers that stream (a long trace)."""
    try:
        # O_NONBLOCK: opening a named pipe must not wait for a writer before fstat can refuse it
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as e:
        raise InputRefused(f"cannot read file: {e.strerror}") from None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise InputRefused(f"{kind(st.st_mode)}, not a regular file")
        if st.st_size > limit:
            raise InputRefused(f"file is {st.st_size} bytes; x3drbp reads at most {limit}")
        os.set_blocking(fd, True)
        return os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise


def read_regular(path: str, limit: int) -> bytes:
    """The bytes of the regular file at path, at most `limit` of them (see open_regular)."""
    with open_regular(path, limit) as f:
        try:
            # as many bytes as fstat says and one more (read(n) allocates n at once: reading
            # limit + 1 cost every load a 200 MiB buffer); a file that grew meanwhile is read
            # on, up to the limit and one more
            want = min(os.fstat(f.fileno()).st_size, limit) + 1
            data = f.read(want)
            if len(data) == want <= limit:
                data += f.read(limit + 1 - want)
        except OSError as e:
            raise InputRefused(f"cannot read file: {e.strerror}") from None
    if len(data) > limit:
        raise InputRefused(f"file grew past {limit} bytes while read; x3drbp reads at most {limit}")
    return data


def require_folder(path: str) -> None:
    """InputRefused unless path is a folder (a symbolic link to one is): a folder of inputs
    that is missing must be said, not read as one holding nothing."""
    try:
        st = os.stat(path)
    except OSError as e:
        raise InputRefused(f"cannot read folder: {e.strerror}") from None
    if not stat.S_ISDIR(st.st_mode):
        raise InputRefused(f"{'a regular file' if stat.S_ISREG(st.st_mode) else kind(st.st_mode)}, not a folder")
