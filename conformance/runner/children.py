"""One `x3drbp run` in a child process with a time limit, and the verdict of how it ended;
and every child process the suite starts, kept so that none outlives an interrupted parent.

An engine's segfault or endless loop is then a verdict, not a lost suite: a child that
died by a signal is crashed, one past its time limit is timed out (its whole process
group killed), exit 3 is unsupported with the backend's own reason.

A run is forked by the command's warm fork server where it can (fork_server.py: no
interpreter start-up or imports per run), and is still a process, a session and a verdict
of its own; else, as every other child, it starts afresh.

Every child (a run, the backend probe, the X_ITE browser) starts through `call`, in a session
of its own: the terminal's Ctrl-C reaches the parent only, and the child's process group is
the child and whatever it starts. A command wrapped in `interruptible` answers SIGINT and
SIGTERM by stopping them all (`stop`: each group SIGTERM, then SIGKILL), and exits
128 + the signal with one line.

A run made before with the same scene bytes, engine version, x3drbp source and options is
read back from the run cache (cache.py: its trace, timing and exit status) rather than run.

A run's notes of what its backend approximates (`SCENE: note: BACKEND approximates ...`, on
its stderr) are said by the command that ran it, once each, not by every child: inside
`notes_shown` run_child hands them on, and they are printed when the block ends; outside it
the child is told -q and says none.
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import os
import signal
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Collection, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, wait
from dataclasses import dataclass, field
from typing import TextIO

from conformance.results import BLEW_UP, CRASHED, ERROR, TIMED_OUT, UNSUPPORTED, Settings
from conformance.runner import cache, fork_server
from conformance.runner.fork_server import GRACE, WarmChild, kill_group

DEFAULT_TIMEOUT = 60.0
EXIT_UNSUPPORTED = 3  # x3drbp.run
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SIGNALS = (signal.SIGINT, signal.SIGTERM)
SLICE = 0.2  # s: the longest a wait on a child goes without running the handler of a signal (_communicate)
QUIET, DEFAULT, VERBOSE = -1, 0, 1  # how much a command says of its runs' notes (options.verbosity)

_live: set[subprocess.Popen] = set()  # children running now (add, discard and copy are atomic under the GIL)
_signal: int | None = None  # the signal that stopped this process's children: none starts after it
_deferring = False  # the main thread is starting a child: the handler must not raise before it is in _live
_handling = False  # an `interruptible` command has its handlers set


class Interrupted(BaseException):
    """SIGINT or SIGTERM reached this process and its children are stopped: unwind (a
    BaseException, as KeyboardInterrupt, so that no `except Exception` keeps going) and exit."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum

    @property
    def status(self) -> int:
        """The shell's convention: 128 + the signal (130 for SIGINT, 143 for SIGTERM)."""
        return 128 + self.signum


class Dropped(Exception):
    """The child was ended because nobody wants what it gives any more (droppable)."""


_dropping = threading.local()  # inside droppable(): the event that ends the child this thread waits on


@contextlib.contextmanager
def droppable(event: threading.Event) -> Iterator[None]:
    """A child this thread waits on in the block is ended (its group killed, Dropped raised)
    once `event` is set, within SLICE s: a run started ahead of being asked for (advise's
    further timings, sweep.Pool) that turned out not to be."""
    previous = getattr(_dropping, "event", None)
    _dropping.event = event
    try:
        yield
    finally:
        _dropping.event = previous


@dataclass
class Outcome:
    """What one child run came to: None verdict when it wrote its trace."""
    verdict: str | None
    reason: str = ""


@dataclass
class Ended:
    """How a child ended: its exit status (None: killed past its time limit) and what it printed."""
    returncode: int | None
    stdout: str
    stderr: str


# the lines that join two tracebacks of one error
_CHAINED = ("During handling of the above exception, another exception occurred:",
            "The above exception was the direct cause of the following exception:")


def _said(stderr: str) -> list[str]:
    """A child's stderr as the lines that say something, stripped: of a traceback (Python's,
    or faulthandler's after a crash) only its last line, the error and its message, is kept;
    its header, its frames and their source lines (indented beneath the header: a verdict's
    reason once read `raise BlewUp(f"...")`), and the lines chaining two, are left out."""
    out, frames = [], False
    for line in stderr.splitlines():
        if line.rstrip().endswith(("(most recent call last):", "(most recent call first):")):
            frames = True
        elif not (frames and line[:1].isspace()) and line.strip():
            frames = False
            if line.strip() not in _CHAINED:
                out.append(line.strip())
    return out


def _tail(text: str, lines: int = 3) -> str:
    return " | ".join(_said(text)[-lines:])


def classify(returncode: int | None, stderr: str, timed_out: bool = False, timeout: float = DEFAULT_TIMEOUT,
             backend: str = "") -> Outcome:
    """The verdict of one child `x3drbp run` from how it ended (None: it succeeded)."""
    if timed_out:
        return Outcome(TIMED_OUT, f"no result within {timeout:g} s")
    if returncode is None:
        return Outcome(ERROR, "the run did not start")
    if returncode < 0:
        try:
            name = signal.Signals(-returncode).name
        except ValueError:
            name = f"signal {-returncode}"
        return Outcome(CRASHED, f"killed by {name}" + (f": {_tail(stderr)}" if stderr.strip() else ""))
    if returncode == 0:
        return Outcome(None)
    if returncode == EXIT_UNSUPPORTED:
        marker = f"unsupported by {backend}: " if backend else "unsupported by "
        reasons = []
        for line in stderr.splitlines():
            if marker in line:
                reasons.append(line.split(marker, 1)[1].strip())
        return Outcome(UNSUPPORTED, "; ".join(reasons) or _tail(stderr) or "the backend refused the scene")
    blew_up = [ln for ln in _said(stderr) if "blew up" in ln]
    if blew_up:
        return Outcome(BLEW_UP, blew_up[-1])
    if "Traceback (most recent call last)" in stderr:
        return Outcome(CRASHED, f"uncaught exception: {_tail(stderr, 1)}")
    return Outcome(ERROR, _tail(stderr) or f"exit status {returncode}")


def _check() -> None:
    """Interrupted if this process was: a child killed by the stop is no result, and none starts after it."""
    if _signal is not None:
        raise Interrupted(_signal)




def _running(proc: subprocess.Popen | WarmChild) -> bool:
    """Whether the child has not ended, asked without reaping it: Popen.poll answers None while
    another thread's wait on the child holds its lock."""
    if isinstance(proc, WarmChild):
        return proc.running()
    if proc.returncode is not None:
        return False
    try:
        return os.waitid(os.P_PID, proc.pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is None
    except ChildProcessError:  # reaped meanwhile
        return False


def _end(procs: Sequence[subprocess.Popen | WarmChild], first: int = signal.SIGTERM) -> None:
    """`first` to each child's group, SIGKILL to what is left of the groups after GRACE s."""
    for p in procs:
        kill_group(p.pid, first)
    started = time.monotonic()
    while time.monotonic() < started + GRACE and any(map(_running, procs)):
        time.sleep(0.02)
    for p in procs:
        kill_group(p.pid, signal.SIGKILL)  # stragglers, grandchildren included


def stop(signum: int) -> None:
    """Stop every child of this process (the fork server among them), and let none start
    after: SIGTERM first, so that a child can close what it started (X_ITE's browser),
    SIGKILL GRACE s later; a signal after the first SIGKILLs at once."""
    global _signal
    first = signal.SIGTERM if _signal is None else signal.SIGKILL
    if _signal is None:
        _signal = signum
    _end(list(_live.copy()), first)


def handle_signal(signum: int, frame: object) -> None:
    """The handler `interruptible` installs: stop the children, then unwind the command, on
    the first signal only (a second one, even inside this handler, only hastens the stop) and
    not while the main thread starts a child (`call` raises once the child is in _live)."""
    first = _signal is None
    stop(signum)
    if first and not _deferring:
        raise Interrupted(signum)


def _communicate(proc: subprocess.Popen, timeout: float) -> tuple[str, str]:
    """proc.communicate() within `timeout` s (TimeoutExpired past it), in slices of SLICE s:
    the kernel may hand SIGINT or SIGTERM to any thread (a library's, a pool's), and then the
    main thread runs the handler only once it runs Python again, which one long wait on the
    child would put off until the child ends (seen in process pool workers). Dropped once the
    thread's droppable() event is set."""
    deadline = time.monotonic() + timeout
    while True:
        try:
            return proc.communicate(timeout=max(0.0, min(SLICE, deadline - time.monotonic())))
        except subprocess.TimeoutExpired:
            if time.monotonic() >= deadline:
                raise
            dropping = getattr(_dropping, "event", None)
            if dropping is not None and dropping.is_set():
                raise Dropped("nobody wants the run any more") from None


def call(cmd: Sequence[str], timeout: float, stdout: bool = True,
         warm: fork_server.Server | None = None, backend: str = "") -> Ended:
    """`cmd` from the project root in a session of its own, its stderr (and stdout, unless
    `stdout` is False) captured, its group ended (_end) past `timeout` s or when an exception
    leaves this call. With `warm`, cmd (`python -m x3drbp ARGS`, stdout not captured)
    is forked by that fork server, which has imported `backend` if a run of it ended well.
    OSError when it cannot start (fork_server.Gone where the server could not take it);
    Interrupted when this process was interrupted."""
    global _deferring
    _check()
    main = threading.current_thread() is threading.main_thread()  # where signal handlers run
    proc = None
    try:
        if main:
            _deferring = True
        if warm is not None:
            proc = warm.start(list(cmd[3:]), backend)
        else:
            proc = subprocess.Popen(cmd, cwd=ROOT, stdin=subprocess.DEVNULL,
                                    stdout=subprocess.PIPE if stdout else subprocess.DEVNULL,
                                    stderr=subprocess.PIPE, text=True, start_new_session=True)
        _live.add(proc)
        if main:
            _deferring = False
        _check()  # a signal came while it started (or, in another thread, while the stop took its list)
        out, err = _communicate(proc, timeout)
        returncode: int | None = proc.returncode
    except subprocess.TimeoutExpired:
        _end([proc])
        out, err = proc.communicate()
        returncode = None
    except BaseException:
        if proc is not None:
            _end([proc])
            proc.wait()
        _check()  # an interrupt that came while it could not start outranks why
        raise
    finally:
        if main:
            _deferring = False
        _live.discard(proc)
        if isinstance(proc, WarmChild):
            proc.close()
    _check()
    return Ended(returncode, out or "", err or "")


def interruptible(command: Callable[[argparse.Namespace], int]) -> Callable[[argparse.Namespace], int]:
    """An x3drbp command that, on SIGINT or SIGTERM, stops its children (`stop`) and returns
    128 + the signal after one line, no traceback. A signal this process ignores (nohup, a
    shell's background job) stays ignored; a command another runs (report's steps) leaves it
    all to the outer one."""
    @functools.wraps(command)
    def run(args: argparse.Namespace) -> int:
        global _signal, _handling
        if _handling or threading.current_thread() is not threading.main_thread():
            return command(args)
        _signal, _handling, previous = None, True, {}
        try:
            try:
                for s in SIGNALS:
                    if signal.getsignal(s) is not signal.SIG_IGN:
                        previous[s] = signal.signal(s, handle_signal)
                return command(args)
            finally:
                for s, handler in previous.items():
                    signal.signal(s, handler)
                _handling = False
        except Interrupted as e:  # also one that came while the handlers were set or restored
            print(f"x3drbp {args.command}: interrupted", file=sys.stderr)
            return e.status
    return run


@dataclass
class Notes:
    """The notes the runs of one command gave, printed once it has run them: each distinct
    line once (DEFAULT), every run's every line (VERBOSE: the runs were told -v), or none
    (QUIET: the runs were told -q)."""
    verbosity: int
    lines: list[str] = field(default_factory=list)  # as the runs gave them (list.extend is atomic under the GIL)

    def flag(self) -> tuple[str, ...]:
        """What a child `x3drbp run` is told, so that it prints what this command will show."""
        return ("-q",) if self.verbosity <= QUIET else ("-v",) if self.verbosity >= VERBOSE else ()

    def show(self) -> None:
        """On stderr, as the verbosity says (none with QUIET, should a run have said some)."""
        if self.verbosity <= QUIET:
            return
        for line in self.lines if self.verbosity >= VERBOSE else sorted(set(self.lines)):
            print(line, file=sys.stderr)


_notes: Notes | None = None  # the command's, inside notes_shown
# where progress bars go while a command's stderr is not the terminal: x3drbp report sends
# each step's output to its log and the step's bar to the terminal it runs in
BARS: TextIO | None = None


def progress_shown(quiet: bool) -> bool:
    """Whether a command draws a bar of runs done: for a person watching a terminal, never when quiet."""
    return not quiet and (BARS is not None or sys.stderr.isatty())


def wait_all(futures: Collection[Future], progress: bool = False) -> None:
    """Wait for every future in SLICE-long waits (a signal is handled within one), with a bar
    of those done where `progress` (on BARS, else stderr; under x3drbp report it clears itself)."""
    from tqdm import tqdm
    with tqdm(total=len(futures), unit="run", file=BARS or sys.stderr, disable=not progress,
              leave=BARS is None) as bar:
        pending = set(futures)
        while pending:
            done, pending = wait(pending, timeout=SLICE, return_when=FIRST_COMPLETED)
            bar.update(len(done))


@contextlib.contextmanager
def notes_shown(verbosity: int) -> Iterator[None]:
    """The notes of the runs started in the block (from any thread), printed on stderr when
    it ends without an exception (after any progress bar): so that a command running a
    scene on a backend many times says each of its notes once."""
    global _notes
    notes = Notes(verbosity)
    previous, _notes = _notes, notes
    try:
        yield
    finally:
        _notes = previous
    notes.show()


def run_child(scene: str, backend: str, settings: Settings, trace: str,
              timeout: float = DEFAULT_TIMEOUT, extra: Sequence[str] = ()) -> Outcome:
    """`x3drbp run` (with the `extra` options) in its own process (and process group),
    killed after `timeout` seconds. Its notes go to the command's Notes (notes_shown), never
    into the verdict's reason."""
    notes = _notes
    cmd = [sys.executable, "-m", "x3drbp", "run", scene, "--backend", backend, *settings.args(),
           "--trace", trace, *(notes.flag() if notes is not None else ("-q",)), *extra]
    with cache.claimed(cmd[3:], backend, ROOT) as kept:  # None: not cached (conformance/runner/cache.py says when)
        reused = kept.reused(timeout) if kept is not None else None
        try:
            ended = Ended(reused[0], "", reused[1]) if reused is not None else _started(cmd, timeout, backend)
        except OSError as e:
            return Outcome(ERROR, f"could not start {sys.executable}: {e}")
        out = _outcome(ended, scene, backend, trace, timeout, notes)
        if kept is not None and reused is None and out.verdict in cache.KEPT:
            kept.keep(ended.returncode, ended.stderr, timeout)
        return out


def _outcome(ended: Ended, scene: str, backend: str, trace: str, timeout: float, notes: Notes | None) -> Outcome:
    """The verdict of a run that ended so, its notes handed to `notes`."""
    if ended.returncode is None:
        return classify(None, "", timed_out=True, timeout=timeout)
    marker = f"{scene}: note: {backend} approximates "
    said = ended.stderr.splitlines(keepends=True)
    if notes is not None:  # named as from where this command runs (a child runs in ROOT, given the full path)
        shown = os.path.relpath(scene) if os.path.isabs(scene) else scene
        shown = scene if shown.startswith("..") else shown
        notes.lines.extend(shown + line[len(scene):].rstrip("\n") for line in said if line.startswith(marker))
    out = classify(ended.returncode, "".join(line for line in said if not line.startswith(marker)), backend=backend)
    if out.verdict is None and not os.path.exists(trace):
        return Outcome(ERROR, "the run succeeded but wrote no trace")
    return out


def _started(cmd: list[str], timeout: float, backend: str) -> Ended:
    """The run, forked by the command's fork server where it can be, else afresh."""
    warm = fork_server.server(ROOT, _live, _signal is not None) if fork_server.usable() else None
    try:
        return call(cmd, timeout, stdout=False, warm=warm, backend=backend)
    except fork_server.Gone:  # the server could not take it, or ended during it: the run afresh
        return call(cmd, timeout, stdout=False)
