"""The warm fork server's process (`python -m x3drbp.run_server SOCKET`): imports
what an `x3drbp run` needs once, then forks one child per run a command asks for, each in a
session of its own running x3drbp's main. conformance/runner/fork_server.py, the command's
side, says why and how; this is the server's side of its protocol.
"""

from __future__ import annotations

import importlib
import json
import os
import selectors
import signal
import socket
import sys
import time
import traceback

import setproctitle

from x3d_core.files.paths import printable

from conformance.runner.fork_server import GRACE, NO_FORK, READY, kill_group

PRELOAD = ("numpy", "lxml.etree", "x3drbp", "x3drbp.run", "x3d_core.traces.trace_npz")


class _Run:
    """A forked child the server has not reaped yet, and the command's connection waiting on it."""

    def __init__(self, pid: int, conn: socket.socket | None, backend: str):
        self.pid, self.conn, self.backend = pid, conn, backend


def _request(conn: socket.socket) -> tuple[dict, int | None]:
    """The command's JSON line and the stderr descriptor sent with it."""
    data, fds, _, _ = socket.recv_fds(conn, 1 << 16, 1)
    while not data.endswith(b"\n"):
        more = conn.recv(1 << 16)
        if not more:
            break
        data += more
    return json.loads(data), (fds[0] if fds else None)


def _child(argv: list[str], err: int, keep_out: list[int]) -> None:
    """In the forked child (in a session of its own): the command's stderr, x3drbp's main; never returns."""
    status = 1
    try:
        for fd in keep_out:
            os.close(fd)
        devnull = os.open(os.devnull, os.O_RDWR)
        os.dup2(devnull, 0)
        os.dup2(devnull, 1)
        os.dup2(err, 2)
        os.close(devnull)
        os.close(err)
        signal.signal(signal.SIGINT, signal.default_int_handler)  # as a fresh interpreter has them
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        signal.signal(signal.SIGCHLD, signal.SIG_DFL)
        # what ps shows of it, as of a fresh child: the server's own command line would hide which run it is
        # (printable: a file name's byte that is not UTF-8 is a surrogate, which setproctitle refuses:
        # that ended every warm run of such a scene with exit 1 and no word before it ran)
        setproctitle.setproctitle(printable(" ".join([sys.executable, "-m", "x3drbp", *argv])))
        from x3drbp import main
        try:
            status = main(argv)
        except SystemExit as e:  # argparse's usage errors
            status = e.code if isinstance(e.code, int) else 1
        except BaseException:  # as the interpreter would say an uncaught exception
            traceback.print_exc()
            status = 1
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):
                pass
    finally:
        os._exit(status)


def _fork(request: dict, err: int, conn: socket.socket, keep_out: list[int]) -> int:
    """A child running the request, started in its own session before this returns its pid."""
    r, w = os.pipe()
    sys.stdout.flush()
    sys.stderr.flush()
    try:
        pid = os.fork()
    except OSError:
        os.close(r)
        os.close(w)
        return NO_FORK
    if pid == 0:
        os.close(r)
        os.setsid()
        os.write(w, b".")
        os.close(w)
        _child(list(request["argv"]), err, keep_out + [conn.fileno()])
    os.close(w)
    os.read(r, 1)  # the child has its session: its group can be signalled as soon as the command knows the pid
    os.close(r)
    return pid


def _end_all(runs: dict[int, _Run], first: int) -> None:
    """`first` to every run's group, SIGKILL to what is left after GRACE s; every one reaped."""
    for run in runs.values():
        kill_group(run.pid, first)
    deadline = time.monotonic() + GRACE
    while runs and time.monotonic() < deadline:
        for fd, run in list(runs.items()):
            if os.waitpid(run.pid, os.WNOHANG)[0]:
                del runs[fd]
        time.sleep(0.02)
    for run in runs.values():
        kill_group(run.pid, signal.SIGKILL)
        os.waitpid(run.pid, 0)


def serve(path: str) -> None:
    """Listen at path until stdin reaches EOF or SIGTERM comes; fork a run per connection."""
    for name in PRELOAD:
        importlib.import_module(name)
    from backends import base
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(path)
    listener.listen(64)
    sel = selectors.DefaultSelector()
    sel.register(listener, selectors.EVENT_READ, "accept")
    sel.register(0, selectors.EVENT_READ, "command")
    runs: dict[int, _Run] = {}  # pidfd -> run
    loaded: set[str] = set()

    def terminate(signum: int, frame: object) -> None:
        raise SystemExit(0)

    signal.signal(signal.SIGTERM, terminate)
    os.write(1, READY)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)  # what an engine prints on import (pybullet's build line) goes nowhere, as a run's stdout
    os.close(devnull)
    try:
        while True:
            for key, _ in sel.select():
                what = key.data
                if what == "command":
                    if not os.read(0, 1 << 12):
                        return
                elif what == "accept":
                    conn, _ = listener.accept()
                    try:
                        request, err = _request(conn)
                    except (OSError, ValueError):
                        conn.close()
                        continue
                    if err is None:
                        conn.close()
                        continue
                    keep_out = [listener.fileno(), sel.fileno(), *runs,
                                *(r.conn.fileno() for r in runs.values() if r.conn)]
                    pid = _fork(request, err, conn, keep_out)
                    os.close(err)
                    if pid == NO_FORK:
                        conn.sendall(b"%d\n%d\n" % (NO_FORK, NO_FORK))
                        conn.close()
                        continue
                    pidfd = os.pidfd_open(pid)
                    runs[pidfd] = run = _Run(pid, conn, str(request.get("backend", "")))
                    sel.register(pidfd, selectors.EVENT_READ, run)
                    sel.register(conn, selectors.EVENT_READ, ("left", pidfd))
                    conn.sendall(b"%d\n" % pid)
                elif isinstance(what, tuple):  # the command closed (or wrote on) a run's connection
                    run = runs[what[1]]
                    sel.unregister(run.conn)
                    run.conn.close()
                    run.conn = None
                    kill_group(run.pid, signal.SIGKILL)  # nobody waits for it any more
                else:
                    run = runs.pop(key.fd)
                    sel.unregister(key.fd)
                    os.close(key.fd)
                    _, status = os.waitpid(run.pid, 0)
                    if run.conn is not None:
                        sel.unregister(run.conn)
                        try:
                            run.conn.sendall(b"%d\n" % status)
                        except OSError:
                            pass
                        run.conn.close()
                    if status == 0 and run.backend and run.backend not in loaded:
                        loaded.add(run.backend)  # its import is known not to crash: later runs start warm
                        try:
                            base.load(run.backend)
                        except Exception:
                            pass
    finally:
        _end_all(runs, signal.SIGTERM)
        try:
            os.unlink(path)
        except OSError:
            pass


if __name__ == "__main__":
    serve(sys.argv[1])
