"""A warm fork server for the `x3drbp run` children a command starts by the hundred.

A fresh `python -m x3drbp run` spends about 0.45 s importing numpy, lxml, x3d_core and
its engine before its first step; a sweep starts 300 of them. The server imports all that
once (engines the first time a run of theirs ends well, so that one whose import crashes
crashes a run, not the server) and forks one child per run. Each run stays a process of
its own, so a crash or a hang is still one verdict:

- the child calls setsid() before the server names its pid: the command kills its group,
  as it kills a fresh child's (children._end), and a terminal's Ctrl-C never reaches it;
- its stderr is a pipe the command made and sent over the socket (SCM_RIGHTS), its stdin and
  stdout /dev/null, as children.call gives a run; its exit status comes back as the wait
  status the server reaped, so a signal death reads as Popen's negative return code;
- a command that goes away (its connection closed before the run ended, or the server's
  stdin at EOF: the command is gone) has that run's group, or every group, SIGKILLed;
  SIGTERM to the server ends its runs as children._end does (SIGTERM, GRACE s, SIGKILL);
- every wait on the server is bounded: it names a run within ANSWER_WAIT s, and says how a
  run ended within STATUS_WAIT s of its end (which the command sees itself, on a pidfd of
  the run). A server past either (stopped, say) is stuck: the command SIGKILLs it, its runs
  in flight end as Gone and are run again in fresh children, and the next run starts a new
  server; none comes back as "timed out" for the server's silence.

This module is the command's side (x3drbp/run_server.py is the server's), used by
children.run_child where the server can serve: on Linux (pidfd), when the children would
run this very interpreter (a test that points sys.executable at a stand-in gets fresh
children), and unless X3DRBP_FORK_SERVER=0. A server that cannot start, or dies, is
replaced; after MAX_FAILURES the process runs fresh children: slower, never a lost run.

Protocol, one connection per run: the command sends one JSON line {"argv": [...],
"backend": NAME} with its stderr pipe's write end; the server answers "PID\\n" once the child
has its own session, then "WAITSTATUS\\n" once it has reaped it ("-1\\n" where it could not fork).
"""

from __future__ import annotations

import atexit
import json
import math
import os
import select
import shutil
import socket
import subprocess
import sys
import tempfile
import threading
import time

GRACE = 2.0  # s a child has to end on SIGTERM (X_ITE's node closes its browser) before SIGKILL, here or in the server
READY = b"x3drbp-fork-server ready\n"
NO_FORK = -1  # the status answered where fork() failed
SLICE = 0.2  # s: the longest wait for the server's start without looking at the clock
READY_WAIT = 60.0  # s for a server to import what it preloads (a loaded 2-core machine: a few s)
ANSWER_WAIT = 10.0  # s for a server to fork a run and name it (milliseconds when it is well)
STATUS_WAIT = 10.0  # s for a server to say how a run that has ended ended (it reaps at once when well)
MAX_FAILURES = 2  # servers that could not start or died unasked, after which a command runs fresh children


def kill_group(pgid: int, signum: int) -> None:
    """signum to a process group (a child's: it and what it started); nothing if it is gone."""
    try:
        os.killpg(pgid, signum)
    except (ProcessLookupError, PermissionError):
        pass


def _this_interpreter() -> str | None:
    try:
        return os.readlink("/proc/self/exe")
    except OSError:
        return None


_THIS = _this_interpreter()  # the binary this process runs: children of another (a test's stand-in) start fresh
_lock = threading.Lock()
_server: Server | None = None
_failures = 0


class Gone(Exception):
    """The server could not take the run, or ended before it said how the run ended: run it fresh."""


def usable() -> bool:
    """Whether a run can go to the server: Linux's pidfd and SCM_RIGHTS, this very interpreter
    as the children's, and not turned off (X3DRBP_FORK_SERVER=0)."""
    return (_THIS is not None and os.path.realpath(sys.executable) == _THIS
            and os.environ.get("X3DRBP_FORK_SERVER", "1") != "0"
            and hasattr(os, "pidfd_open") and hasattr(socket, "send_fds"))


class WarmChild:
    """A run forked by the server, with what children.call needs of a subprocess.Popen: pid
    (its group's), communicate(timeout) raising TimeoutExpired, returncode, wait()."""

    def __init__(self, server: Server, conn: socket.socket, err: int, pid: int, status: bytes = b""):
        self.pid, self.returncode = pid, None
        self._server, self._conn, self._err = server, conn, err
        self._said, self._status = bytearray(), bytearray(status)
        try:  # readable once the run has ended, whoever reaps it (the command is not its parent)
            self._pidfd = os.pidfd_open(pid)
        except ProcessLookupError:  # ended and reaped already: its status is on its way
            self._pidfd = -1
        self._ended: float | None = None if self._pidfd >= 0 else time.monotonic()

    def running(self) -> bool:
        """Not ended (a zombie counts as ended: the server may not have reaped it yet)."""
        if self._ended is None and _readable([self._pidfd], 0):
            self._end_seen()
        return self.returncode is None and self._ended is None

    def _end_seen(self) -> None:
        self._ended = time.monotonic()
        os.close(self._pidfd)
        self._pidfd = -1

    def communicate(self, timeout: float | None = None) -> tuple[None, str]:
        """(None, its stderr) once it has ended and closed it; TimeoutExpired past timeout s
        (not where it ended in time and only the server's word is awaited), Gone where the
        server ended, or gave no word STATUS_WAIT s after the run's end (it is then killed)."""
        deadline = None if timeout is None else time.monotonic() + timeout
        while self.returncode is None:
            told = self._status.endswith(b"\n")
            if told and self._err < 0:
                self.returncode = os.waitstatus_to_exitcode(int(self._status))
                break
            now = time.monotonic()
            waits = []
            if self._ended is None or self._err >= 0:  # the run itself is still at it
                if deadline is not None and now >= deadline:
                    raise subprocess.TimeoutExpired("x3drbp run", timeout or 0.0)
                waits.append(None if deadline is None else deadline - now)
            if self._ended is not None and not told:
                if now >= self._ended + STATUS_WAIT:
                    self._server.give_up()
                    raise Gone(f"the fork server gave no word of a run {STATUS_WAIT:g} s after it ended: stuck")
                waits.append(self._ended + STATUS_WAIT - now)
            fds = ([self._err] if self._err >= 0 else []) + ([] if told else [self._conn.fileno()])
            ready = _readable(fds + ([self._pidfd] if self._pidfd >= 0 else []),
                              None if None in waits else min(waits))
            if self._pidfd in ready:
                self._end_seen()
            if self._err in ready:
                data = os.read(self._err, 1 << 16)
                self._said += data
                if not data:
                    os.close(self._err)
                    self._err = -1
            if not told and self._conn.fileno() in ready:
                data = self._conn.recv(64)
                if not data:
                    raise Gone("the fork server ended during the run")
                self._status += data
        return None, self._said.decode("utf-8", errors="replace")

    def wait(self) -> int | None:
        """Its exit status once it has ended (None: the server ended first, or is stuck)."""
        try:
            self.communicate()
        except Gone:
            pass
        self.close()
        return self.returncode

    def close(self) -> None:
        for fd in (self._err, self._pidfd):
            if fd >= 0:
                os.close(fd)
        self._err = self._pidfd = -1
        self._ended = self._ended or time.monotonic()  # no longer watched: not to be waited on
        self._conn.close()


def _readable(fds: list[int], timeout: float | None) -> list[int]:
    """Those of fds ready to read (or at EOF) within timeout s (None: no limit); poll, not
    select, which refuses a descriptor past 1023."""
    poll = select.poll()
    for fd in fds:
        poll.register(fd, select.POLLIN)
    return [fd for fd, _ in poll.poll(None if timeout is None else max(0, math.ceil(timeout * 1000)))]


class Server:
    """A running server (a subprocess.Popen in the caller's `live` set, so that an interrupt
    ends it with the runs), started with the environment `env`: a command whose environment
    changed since gets a new one, its runs seeing what a fresh child would."""

    def __init__(self, proc: subprocess.Popen, folder: str, env: dict[str, str], live: set):
        self.proc, self.folder, self.env, self.live = proc, folder, env, live
        self.path = os.path.join(folder, "socket")
        self.stuck = False

    def start(self, argv: list[str], backend: str) -> WarmChild:
        """A run of `x3drbp ARGV` forked and in its own session; Gone where the server cannot
        take it (given up as stuck where it does not name the run within ANSWER_WAIT s)."""
        conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        conn.settimeout(ANSWER_WAIT)  # connect, send and the answer: a stopped server takes them and says nothing
        r, w = os.pipe()
        try:
            try:
                conn.connect(self.path)
                socket.send_fds(conn, [json.dumps({"argv": argv, "backend": backend}).encode() + b"\n"], [w])
            finally:
                os.close(w)
            answer = b""
            while not answer.endswith(b"\n"):
                more = conn.recv(64)
                if not more:
                    raise Gone("the fork server ended")
                answer += more
            first, _, rest = answer.partition(b"\n")
            if int(first) == NO_FORK:
                raise Gone("the fork server could not fork")
        except (OSError, ValueError, Gone) as e:
            os.close(r)
            conn.close()
            if isinstance(e, TimeoutError):
                self.give_up()
                e = Gone(f"the fork server named no run within {ANSWER_WAIT:g} s: stuck")
            raise Gone(str(e)) from None
        return WarmChild(self, conn, r, int(first), rest)

    def alive(self) -> bool:
        return self.proc.poll() is None

    def give_up(self) -> None:
        """Stuck (stopped, say): SIGKILLed now, so that every run waiting on it ends as Gone
        and is run afresh; server() starts the next one."""
        self.stuck = True
        try:
            self.proc.kill()
        except OSError:
            pass

    def close(self) -> None:
        """Its stdin closed: it ends its runs (none is left: each command waits for its own) and
        exits, SIGKILLed past GRACE s; its folder removed. Replaced servers and, at exit, the last."""
        self.live.discard(self.proc)
        try:
            self.proc.stdin.close()
            self.proc.wait(GRACE)
        except (OSError, subprocess.TimeoutExpired):
            self.proc.kill()
            self.proc.wait()
        shutil.rmtree(self.folder, ignore_errors=True)


def _start(env: dict[str, str], root: str, live: set) -> Server | None:
    """A server ready to fork runs (its process in `live`), or None (it could not start within READY_WAIT s)."""
    folder = tempfile.mkdtemp(prefix="x3drbp-fork-")
    try:
        proc = subprocess.Popen([sys.executable, "-m", "x3drbp.run_server", os.path.join(folder, "socket")],
                                cwd=root,
                                stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                                start_new_session=True)
    except OSError:
        os.rmdir(folder)
        return None
    live.add(proc)
    server = Server(proc, folder, env, live)
    atexit.register(server.close)
    ready = b""
    deadline = time.monotonic() + READY_WAIT
    while not ready.endswith(READY) and time.monotonic() < deadline:
        if _readable([proc.stdout.fileno()], SLICE):
            more = os.read(proc.stdout.fileno(), 256)
            if not more:
                break
            ready += more
    proc.stdout.close()
    if not ready.endswith(READY):
        server.close()
        return None
    return server


def server(root: str, live: set, interrupted: bool) -> Server | None:
    """This process's server for the present environment, started (or replaced) as needed to
    run in `root`, its process kept in `live`; None once MAX_FAILURES servers failed to start,
    died unasked (not `interrupted`: an interrupt's stop ends it) or were given up as stuck."""
    global _server, _failures
    with _lock:
        env = dict(os.environ)
        if _server is not None and (_server.stuck or not _server.alive()):
            if not interrupted:
                _failures += 1
            _server.close()
            _server = None
        if _server is not None and _server.env != env:
            _server.close()
            _server = None
        if _server is None and _failures < MAX_FAILURES:
            _server = _start(env, root, live)
            if _server is None:
                _failures += 1
        return _server
