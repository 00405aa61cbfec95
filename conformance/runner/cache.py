"""Runs already made, reused: the result of a child `x3drbp run` (its exit status, what it said
on stderr, and the files it wrote: trace, --timing, --rerun) kept under a key of all it
depended on, so that a second command that asks for the same run (advise and the sweep both
run a scene at a step; `x3drbp report` run again with nothing changed) reads it back instead.

The key is a SHA-256 of:
- the scene file's bytes (x3drbp fetches no Inline and no EXTERNPROTO: a scene reads no other
  file), not its path: the sweep's rewritten copy in a fresh temporary folder is the same run;
- the backend and its engine's version (the probe's, conformance/runner/probe.py);
- x3drbp's own source: every .py file under x3d_core/, backends/, conformance/ and reports/
  and pyproject.toml, by content (an edit of any of them is a new key, committed or not; a
  checkout that leaves the bytes alike keeps it), with the interpreter, Python's and NumPy's
  versions;
- every option of the run, output paths as their suffix alone (.npz or .csv, the trace's form).

Kept: a run that wrote its trace, that the backend refused (unsupported), whose scene blew up,
and one that timed out, with its time limit: it is reused for a limit as short or shorter
(Drake's 50-link chain passes stability's 60 s limit at both steps: a minute of every report,
run again, for the same verdict), a longer limit runs it again. A crash or an error (which a
killed or starved child can give) runs again the next time. A run is deterministic
(tests/test_determinism.py), so the trace read back is the trace a new run would write; its
--timing file is the measured timing of the run that was kept, not of a new one, and so is a
time-out (measured on this machine, perhaps under load: --no-cache measures it again). Two
threads of one command that want the same run (stability's two spinning-wheel cases share a
scene) run it once: the second waits for the first (claimed).

Kept beside the runs, under the same source digest: the answers of the children that import
every engine to say what the backends declare or make of a scene (probe.ask: question), keyed
by the engines' versions and the files they read; and the view of a CSV trace, as .npz, keyed
by the CSV's bytes (read_view: stability parses a 6 MB trace of its 50-link chain in 0.5 s).

Where: $X3DRBP_CACHE, else $XDG_CACHE_HOME/x3drbp/runs (~/.cache/x3drbp/runs); removing the
folder clears it. X3DRBP_CACHE=off, or a command's --no-cache (report passes it to its steps),
runs every run afresh and keeps none. A backend from outside this project (a plug-in: its code
is not in the key) is never cached. Each entry is one file, written whole (x3d_core/files/atomic.py):
two commands sharing the folder never read half an entry, and the later of two writers of one
key wins. An entry that does not read back whole (cut short, edited, of another format) is a
miss and is written again; a folder that cannot be written costs the runs their reuse, never a
result. The files are kept compressed (zlib), and past LIMIT bytes (2 GiB) the least recently
used entries go (prune), looked at once a command keeps a run.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import json
import os
import sys
import tempfile
import threading
import zlib
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

from x3d_core.files import atomic
from x3d_core.traces import trace
from x3d_core.traces.trace_npz import read_npz, write_npz
from x3d_core.traces.trace_view import TraceView

from conformance.results import BLEW_UP, TIMED_OUT, UNSUPPORTED

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # the project's
ENV = "X3DRBP_CACHE"
OFF = ("off", "0", "no", "false")
FORMAT = b"x3drbp-run-cache 2\n"  # an entry's first line; its second is its header (JSON)
OUTPUTS = ("--trace", "--timing", "--rerun")  # x3drbp run's options that name a file it writes
KEPT = (None, UNSUPPORTED, BLEW_UP, TIMED_OUT)  # the outcomes (children.Outcome.verdict) kept
SOURCES = ("x3d_core", "backends", "conformance", "reports")
LEVEL = 3  # zlib's: a 6 MB trace of the 50-link chain to 1.9 MB in 0.1 s, read back in 0.02 s
LIMIT = 2 << 30  # bytes the folder may hold before prune() removes the least recently used entries

_off = False  # inside turned_off(True): a command's --no-cache
_versions: dict[str, str | None] = {}  # backend -> its engine's version (None: unusable), as the probe said
_lock = threading.RLock()  # the probe asked under it learns under it
_pruned = False  # prune() has looked at the folder in this process
_claims: dict[str, list] = {}  # an entry's path -> [the lock of its run in this process, how many want it]


def folder() -> str | None:
    """Where entries are kept; None where the cache is off."""
    value = os.environ.get(ENV, "").strip()
    if _off or value.lower() in OFF:
        return None
    if value:
        return os.path.abspath(os.path.expanduser(value))
    home = os.environ.get("XDG_CACHE_HOME", "")
    if not os.path.isabs(home):  # the XDG rule: a relative path is to be ignored
        home = os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(home, "x3drbp", "runs")


@contextlib.contextmanager
def turned_off(off: bool) -> Iterator[None]:
    """The block's runs neither reused nor kept where `off` (a command's --no-cache); as it was otherwise,
    so that a step of `x3drbp report --no-cache` (a command run inside it) keeps it off."""
    global _off
    previous = _off
    _off = previous or off
    try:
        yield
    finally:
        _off = previous


@functools.cache
def revision(root: str) -> str:
    """The digest of x3drbp's source under root (module docstring), and what runs it."""
    h = hashlib.sha256()
    files = [os.path.join(root, "pyproject.toml")]
    for top in SOURCES:
        for here, dirs, names in os.walk(os.path.join(root, top)):
            dirs[:] = sorted(d for d in dirs if d != "__pycache__")
            files += [os.path.join(here, n) for n in sorted(names) if n.endswith(".py")]
    for path in files:
        h.update(os.path.relpath(path, root).encode() + b"\0")
        with contextlib.suppress(OSError), open(path, "rb") as f:
            h.update(hashlib.sha256(f.read()).digest())
    import numpy  # a dependency of every command that runs children
    h.update(f"{os.path.realpath(sys.executable)}\0{sys.version}\0{numpy.__version__}".encode())
    return h.hexdigest()


def learn(versions: dict[str, str | None]) -> None:
    """Engine versions the probe found (None: unusable), so that a key needs no probe of its own."""
    with _lock:
        _versions.update(versions)


_asker: Callable[[str], str | None] | None = None  # the probe's way to a version (probe imports this module)


def asks_versions(ask: Callable[[str], str | None]) -> None:
    """How a version unknown to the command is found: set by the probe, which imports children and
    this module, so that the cache needs no import of it."""
    global _asker
    _asker = ask


def engine_version(backend: str) -> str | None:
    """The backend's engine version (the probe's, asked in a child the first time a command has not
    probed it); None where it is not usable, or no probe is there to ask (the run is then not kept)."""
    with _lock:
        if backend not in _versions:
            if _asker is None:
                return None
            _versions[backend] = _asker(backend)
        return _versions[backend]


def _digest(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


@dataclass
class Entry:
    """One run's place in the cache: its file, and the paths of this run that an entry names
    by placeholder (the scene as given, each output), so that a run kept for one path serves
    another."""
    path: str
    outputs: dict[str, str]  # option (OUTPUTS) -> the file this run writes
    names: dict[str, str]  # placeholder -> the path this run gives

    def reused(self, timeout: float) -> tuple[int | None, str] | None:
        """The kept run's exit status (None: it timed out) and stderr, its files written where
        this run writes them; None where there is no entry that reads back whole, its files
        cannot be written here (the run then says why), or it timed out under a shorter limit."""
        try:
            with open(self.path, "rb") as f:
                data = f.read()
            if not data.startswith(FORMAT):
                return None
            line, _, body = data[len(FORMAT):].partition(b"\n")
            header = json.loads(line)
            files, at = {}, 0
            for option, (size, digest) in header["files"].items():
                stored = body[at:at + size]
                at += size
                if len(stored) != size or _digest(stored) != digest:
                    return None
                files[option] = zlib.decompress(stored)
            if at != len(body) or set(files) - set(self.outputs):
                return None
            returncode, stderr = header["returncode"], str(header["stderr"])
            if returncode is None and not timeout <= float(header["limit"]):
                return None
            returncode = None if returncode is None else int(returncode)
            for option, path in self.outputs.items():
                if option in files:
                    atomic.write_bytes(path, files[option])
                else:  # the run wrote none (a refusal): neither does its reuse
                    with contextlib.suppress(FileNotFoundError):
                        os.unlink(path)
            os.utime(self.path)  # used now: the last to go (prune)
        except (OSError, ValueError, KeyError, TypeError, AttributeError, zlib.error):
            return None
        for placeholder, value in self.names.items():
            stderr = stderr.replace(placeholder, value)
        return returncode, stderr

    def keep(self, returncode: int | None, stderr: str, timeout: float) -> None:
        """The run just made, kept (its files as it wrote them, compressed; None: it timed out,
        after `timeout` s); nothing where the folder cannot be written."""
        for placeholder, value in sorted(self.names.items(), key=lambda kv: -len(kv[1])):
            stderr = stderr.replace(value, placeholder)
        try:
            files = {}
            for option, path in self.outputs.items():
                if os.path.exists(path):
                    with open(path, "rb") as f:
                        files[option] = zlib.compress(f.read(), LEVEL)
            header = {"returncode": returncode, "limit": timeout, "stderr": stderr,
                      "files": {o: [len(d), _digest(d)] for o, d in files.items()}}
            os.makedirs(os.path.dirname(self.path), exist_ok=True)
            atomic.write_chunks(self.path, iter([FORMAT, json.dumps(header).encode() + b"\n", *files.values()]))
        except OSError:
            return
        global _pruned
        with _lock:
            first, _pruned = not _pruned, True
        if first:  # once a process: a look at every entry's size
            prune(os.path.dirname(os.path.dirname(self.path)))


def prune(where: str, limit: int = LIMIT) -> list[str]:
    """Where the folder holds more than `limit` bytes, its least recently used entries removed
    until it holds 3/4 of it; the entries removed. Each edit of x3drbp's source makes every run
    a new one (the runs of a report keep some 100 MB)."""
    found = []
    for here, _, names in os.walk(where):
        for n in names:
            if n.startswith(atomic.PREFIX):  # a writer's file, not yet an entry
                continue
            with contextlib.suppress(OSError):
                st = os.stat(os.path.join(here, n))
                found.append((st.st_mtime, st.st_size, os.path.join(here, n)))
    total, removed = sum(size for _, size, _ in found), []
    for _, size, path in sorted(found) if total > limit else ():
        if total <= limit * 3 // 4:
            break
        with contextlib.suppress(OSError):
            os.unlink(path)
            removed.append(path)
        total -= size
    return removed


def entry(argv: Sequence[str], backend: str, root: str) -> Entry | None:
    """The cache's entry for the child `x3drbp run` argv (`run SCENE --backend NAME ...`, run in
    root); None where the cache is off or the run is not cached (a plug-in backend, an unusable
    one, a scene that cannot be read: the run says why)."""
    where = folder()
    if where is None:
        return None
    from backends.base import IN_TREE  # here: `x3drbp run` imports children, never the cache's key
    if backend not in IN_TREE or len(argv) < 2:
        return None
    scene = argv[1]
    try:
        with open(os.path.join(root, scene), "rb") as f:
            scene_digest = _digest(f.read())
    except OSError:
        return None
    version = engine_version(backend)
    if version is None:
        return None
    outputs, names, words = {}, {"\0scene\0": scene}, ["run", scene_digest]
    args = list(argv[2:])
    for k, word in enumerate(args):
        if k > 0 and args[k - 1] in OUTPUTS:
            outputs[args[k - 1]] = os.path.join(root, word)
            names[f"\0{args[k - 1]}\0"] = word
            words.append(os.path.splitext(word)[1])
        else:
            words.append(word)
    key = _digest(json.dumps({"revision": revision(root), "engine": [backend, version], "argv": words}).encode())
    return Entry(os.path.join(where, key[:2], key), outputs, names)


@contextlib.contextmanager
def claimed(argv: Sequence[str], backend: str, root: str) -> Iterator[Entry | None]:
    """entry()'s, held for the block: another thread of this process that wants the same run
    waits until this one has run it (and kept it), then reuses it rather than run it beside it."""
    kept = entry(argv, backend, root)
    if kept is None:
        yield None
        return
    with _lock:
        claim = _claims.setdefault(kept.path, [threading.Lock(), 0])
        claim[1] += 1
    try:
        with claim[0]:
            yield kept
    finally:
        with _lock:
            claim[1] -= 1
            if not claim[1]:
                del _claims[kept.path]


def question(script: str, args: Sequence[str]) -> Entry | None:
    """The entry of a question a child answers from x3drbp's code, the engines and the files it
    is given alone (probe.ask: the backends' declarations, their judgement of scenes; a child
    importing every engine, 1.2 s of CPU), its answer kept as the entry's stderr; None where the
    cache is off, no engine version is known yet, or a backend is a plug-in (not in the key)."""
    where = folder()
    from backends.base import IN_TREE  # here, as in entry()
    with _lock:
        versions = sorted(_versions.items())
    if where is None or not versions or any(b not in IN_TREE for b, _ in versions):
        return None
    files = []
    for a in args:
        with contextlib.suppress(OSError), open(a, "rb") as f:
            files.append(_digest(f.read()))
    key = _digest(json.dumps(["question", revision(ROOT), versions, script, list(args), files]).encode())
    return Entry(os.path.join(where, key[:2], key), {}, {})


def read_view(path: str) -> TraceView:
    """x3d_core.traces.trace.read_view(path), a CSV trace's view kept as .npz under the CSV's bytes (and
    x3drbp's source): stability reads a kept run's CSV again each report, 0.5 s of parsing for
    each 6 MB of the 50-link chain, where the .npz reads back in milliseconds."""
    where = folder()
    if where is None or not path.endswith(".csv"):
        return trace.read_view(path)
    with open(path, "rb") as f:
        key = _digest(json.dumps(["view", revision(ROOT), _digest(f.read())]).encode())
    with tempfile.TemporaryDirectory(prefix="x3drbp-view-") as tmp:
        npz = os.path.join(tmp, "view.npz")
        kept = Entry(os.path.join(where, key[:2], key), {"--trace": npz}, {})
        if kept.reused(0.0) is not None:
            return read_npz(npz)
        view = trace.read_view(path)
        write_npz(view, npz)
        kept.keep(0, "", 0.0)
        return view
