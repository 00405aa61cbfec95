"""Write a file whole or not at all: to a temporary name in the same folder, then renamed.

Every output file of x3drbp (traces, matrices, comparison and sweep JSON, reports, rerun
recordings) goes through here, so a run killed half-way leaves the previous file or none,
never a torn one. The one exception is `x3drbp report`'s step logs (DIR/logs/*.log,
x3drbp/report.py): they are written as the step runs, to be read while it does
and to keep what a killed step said.

What the path names decides how it is written:

- a symbolic link is written through: its target is replaced (atomically, beside the
  target), the link stays a link;
- a regular file, or nothing yet: a temporary file in the same folder, renamed over it;
  the new file has the old one's permission bits (and owner, where we may set it), a new
  one the usual 0666 less the umask;
- a character device or a named pipe (/dev/null, /dev/stdout, a pipe a reader waits on)
  is written straight into, never renamed over: `--trace /dev/null` discards;
- anything else (a folder, a block device, a socket) is refused.

Every failure is a CannotWrite naming the path as given and why, in words (the commands
print it as one line, `x3drbp COMMAND: cannot write PATH: REASON`, and exit 1); the
temporary file is gone by then. A temporary file is named `.x3drbp-PID-NAME-XXXXXXXX.tmp`:
one left behind by a killed process (its pid gone, or untouched for an hour) is removed by
the next write to the same folder.

A command that fills a folder with many files (`conformance --out DIR`) holds it for its
life (`holding`), so that a second command into it is refused at once rather than removing
or overwriting the first's files under it.
"""

from __future__ import annotations

import contextlib
import errno
import fcntl
import json
import os
import stat
import tempfile
import time
from collections.abc import Iterator
from typing import Any

PREFIX = ".x3drbp-"
SUFFIX = ".tmp"
LOCK = ".x3drbp.lock"  # in a folder a command holds (holding): the holder's pid
STALE_S = 3600.0  # a temporary file nobody wrote for this long is a killed writer's
DEAD_GRACE_S = 60.0  # ... and one whose pid is gone, once untouched this long (a pid of another pid namespace)


class CannotWrite(OSError):
    """An output that could not be written: `path` as the user gave it, `reason` in words."""

    def __init__(self, path: str, reason: str, errno: int | None = None):
        super().__init__(errno, reason)
        self.path, self.reason = path, reason

    def __str__(self) -> str:
        return f"cannot write {self.path}: {self.reason}"

    def __reduce__(self):  # pickled across processes (dask workers) whole
        return type(self), (self.path, self.reason, self.errno)


class InUse(OSError):
    """A folder another process holds (`holding`): `pid`, the holder's, None where it has not
    written it yet."""

    def __init__(self, path: str, pid: int | None):
        super().__init__(errno.EBUSY, "in use by another x3drbp command")
        self.path, self.pid = path, pid


def _reason(e: BaseException) -> str:
    if isinstance(e, CannotWrite):
        return e.reason
    if isinstance(e, OSError):
        return e.strerror or str(e) or type(e).__name__
    return str(e) or type(e).__name__


def _failed(path: str, e: OSError) -> CannotWrite:
    return e if isinstance(e, CannotWrite) else CannotWrite(path, _reason(e), e.errno)


_umask: int | None = None


def umask() -> int:
    """The process's umask, read once: from /proc (which changes nothing), else by setting
    it to 0 and back at once (the only portable way to read it)."""
    global _umask
    if _umask is None:
        try:
            with open("/proc/self/status", encoding="ascii") as f:
                _umask = next(int(line.split()[1], 8) for line in f if line.startswith("Umask:"))
        except (OSError, StopIteration, ValueError, IndexError):
            old = os.umask(0)
            os.umask(old)
            _umask = old
    return _umask


def new_file_mode() -> int:
    """What open() gives a file it creates: 0666 less the umask."""
    return 0o666 & ~umask()


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:  # EPERM: someone else's, alive
        return True
    return True


def clean_stale(folder: str, now: float | None = None) -> list[str]:
    """Removes the temporary files killed writers left in folder; returns their names."""
    now = time.time() if now is None else now
    removed = []
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return removed
    for e in entries:
        if not (e.name.startswith(PREFIX) and e.name.endswith(SUFFIX)):
            continue
        try:
            st = e.stat(follow_symlinks=False)
            if not stat.S_ISREG(st.st_mode):
                continue
            age = now - st.st_mtime
            pid_text = e.name[len(PREFIX):].split("-", 1)[0]
            dead = pid_text.isdigit() and int(pid_text) != os.getpid() and not _pid_alive(int(pid_text))
            if age > STALE_S or (dead and age > DEAD_GRACE_S):
                os.unlink(e.path)
                removed.append(e.name)
        except OSError:
            continue
    return removed


def _resolve(path: str) -> tuple[str, os.stat_result | None]:
    """Where path's bytes go (a symbolic link followed to its target) and what is there now."""
    if not path:
        raise CannotWrite(path, "empty path")
    try:
        st = os.stat(path)  # through links, /proc's magic ones too (/dev/stdout on a pipe)
    except FileNotFoundError:
        st = None
    except OSError as e:
        raise _failed(path, e) from None
    if st is not None and (stat.S_ISCHR(st.st_mode) or stat.S_ISFIFO(st.st_mode)):
        return path, st  # opened by the name given: a pipe's /proc link has no path to resolve to
    real = os.path.realpath(path)
    if st is None:
        folder = os.path.dirname(real)
        try:
            fst = os.stat(folder)
        except OSError as e:
            raise CannotWrite(path, f"folder {folder}: {_reason(e)}", e.errno) from None
        if not stat.S_ISDIR(fst.st_mode):
            raise CannotWrite(path, f"{folder} is not a folder")
        return real, None
    if stat.S_ISDIR(st.st_mode):
        raise CannotWrite(path, "it is a folder")
    if not stat.S_ISREG(st.st_mode):  # a character device or a named pipe returned above
        raise CannotWrite(path, "not a regular file, a character device or a named pipe")
    return real, st


def _regular(st: os.stat_result | None) -> bool:
    return st is None or stat.S_ISREG(st.st_mode)


def _take_over(fd: int, st: os.stat_result | None) -> None:
    """The new file gets the permission bits (and owner, where allowed) of the one it replaces,
    or a new file's usual mode."""
    os.fchmod(fd, stat.S_IMODE(st.st_mode) if st is not None else new_file_mode())
    if st is not None and (st.st_uid, st.st_gid) != (os.geteuid(), os.getegid()):
        with contextlib.suppress(OSError):
            os.fchown(fd, st.st_uid, st.st_gid)


def _temporary(folder: str, real: str) -> tuple[int, str]:
    clean_stale(folder)
    name = os.path.basename(real)[:120]  # the temporary name within NAME_MAX however long the output's
    return tempfile.mkstemp(prefix=f"{PREFIX}{os.getpid()}-{name}-", suffix=SUFFIX, dir=folder)


def _into_device(path: str, real: str, chunks: Iterator[bytes]) -> None:
    """Writes straight into a character device or named pipe (never creating a file there)."""
    try:
        fd = os.open(real, os.O_WRONLY | getattr(os, "O_CLOEXEC", 0) | getattr(os, "O_NOCTTY", 0))
    except OSError as e:
        raise _failed(path, e) from None
    try:
        with os.fdopen(fd, "wb") as f:
            for chunk in chunks:
                f.write(chunk)
    except OSError as e:
        raise _failed(path, e) from None


@contextlib.contextmanager
def replacing(path: str) -> Iterator[str]:
    """A temporary path for a writer that wants a name (a library that opens the file
    itself): what it wrote there is moved to path when the block ends (renamed over a
    regular file, copied into a device or named pipe), removed if it raises. Until then
    path holds what it held before. An OSError of the block, or of the move, comes out as
    CannotWrite naming path."""
    real, st = _resolve(path)
    regular = _regular(st)
    folder = os.path.dirname(real) if regular else tempfile.gettempdir()
    try:
        fd, tmp = _temporary(folder, real)
    except OSError as e:
        raise _failed(path, e) from None
    try:
        try:
            if regular:
                _take_over(fd, st)
        finally:
            os.close(fd)
        try:
            yield tmp
        except OSError as e:
            raise _failed(path, e) from None
        try:
            if regular:
                # the writer may have made the file anew: the mode again
                os.chmod(tmp, stat.S_IMODE(st.st_mode) if st is not None else new_file_mode())
                os.replace(tmp, real)
            else:
                with open(tmp, "rb") as f:
                    _into_device(path, real, iter(lambda: f.read(1 << 20), b""))
        except OSError as e:
            raise _failed(path, e) from None
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)


def check(path: str) -> None:
    """Raises now the CannotWrite a write to path would raise for what is there: a missing
    folder, a folder, a path under a file, a folder that may not be written. A command checks
    its outputs so before it runs anything: it neither runs for minutes only to fail, nor
    leaves one output written and the next refused."""
    real, st = _resolve(path)
    if _regular(st):
        _writable(path, os.path.dirname(real))


def check_folder(path: str) -> None:
    """check() for an output folder, which a command makes with its parents: the nearest of
    them that exists is a folder that may be written."""
    nearest = os.path.abspath(path)
    while not os.path.exists(nearest) and os.path.dirname(nearest) != nearest:
        nearest = os.path.dirname(nearest)
    if not os.path.isdir(nearest):
        raise CannotWrite(path, "it is a file, not a folder" if nearest == os.path.abspath(path)
                          else f"{nearest} is a file, not a folder")
    _writable(path, nearest)


def _writable(path: str, folder: str) -> None:
    if not os.access(folder, os.W_OK | os.X_OK):  # a read-only file system too, even for root
        raise CannotWrite(path, f"folder {folder} may not be written")


def write_chunks(path: str, chunks: Iterator[bytes]) -> None:
    """path holds the chunks, concatenated, once this returns; until then it holds what it
    held before (a device or named pipe: what was written so far)."""
    real, st = _resolve(path)
    if not _regular(st):
        _into_device(path, real, chunks)
        return
    with replacing(path) as tmp, open(tmp, "wb") as f:
        for chunk in chunks:
            f.write(chunk)


def write_bytes(path: str, data: bytes) -> None:
    """path holds data once this returns; until then it holds what it held before."""
    write_chunks(path, iter((data,)))


def write_text(path: str, text: str) -> None:
    """text as UTF-8, line breaks as given, written atomically."""
    write_bytes(path, text.encode("utf-8"))


def write_json(path: str, data: Any, indent: int | None = 1) -> None:
    """data as JSON with a final line break, written atomically."""
    write_text(path, json.dumps(data, indent=indent) + ("\n" if indent is not None else ""))


@contextlib.contextmanager
def holding(folder: str) -> Iterator[None]:
    """Holds folder (made, with its parents) for the block: an exclusive flock on FOLDER/.x3drbp.lock,
    which then holds this process's pid. InUse at once where another process holds it. The lock
    goes when the process does, however it ends (a kill too), so none is ever stale; the file
    stays, since removing it would let a command that opened it first and one that made it anew
    each hold a file of that name. OSError where the folder or the file cannot be made."""
    os.makedirs(folder, exist_ok=True)
    fd = os.open(os.path.join(folder, LOCK), os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o666)
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            said = os.pread(fd, 32, 0).decode("ascii", "replace").strip()
            raise InUse(folder, int(said) if said.isdigit() else None) from None
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode("ascii"), 0)
        yield
    finally:
        os.close(fd)
