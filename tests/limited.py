"""x3drbp in a child process under resource limits, for the tests that prove an input is
refused in bounded memory and CPU time: an unbounded read dies of its limit (a MemoryError,
SIGXCPU) and fails the test, rather than filling the machine.

No wall-clock limit: the machine is shared, and a named pipe a test reads is always fed
(`fed`), so that a reader that does not refuse it reads without end into its limits rather
than blocking forever.
"""

from __future__ import annotations

import contextlib
import os
import re
import resource
import subprocess
import sys
import threading
from collections.abc import Iterator

from conftest import ROOT

MEMORY = 1 << 30  # bytes of address space: numpy, lxml and an engine take ~0.5 GiB of it
CPU_S = 60  # a refusal takes about a second of CPU, python's start-up included
ENV = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")  # no thread stacks of 64 MB each


def _limits(memory: int, cpu_s: int) -> None:
    resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    resource.setrlimit(resource.RLIMIT_CPU, (cpu_s, cpu_s))


def run(argv: list[str], cwd: str = ROOT, memory: int = MEMORY, cpu_s: int = CPU_S) -> subprocess.CompletedProcess:
    """argv in cwd, within `memory` bytes and `cpu_s` CPU seconds (its children too)."""
    return subprocess.run(argv, cwd=cwd, capture_output=True, text=True, errors="replace", env=ENV,
                          preexec_fn=lambda: _limits(memory, cpu_s))


def cpu_of(run_child) -> tuple[subprocess.CompletedProcess, float]:
    """What run_child() returns (it runs and reaps one child) and the CPU seconds, user and
    system, that child and its own children spent: a bound a busy machine does not move, as
    wall time would (three 10 s wall-clock limits failed at load 5-9)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = run_child()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return p, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def x3drbp(*args: str, memory: int = MEMORY) -> subprocess.CompletedProcess:
    """`x3drbp ARGS` from the project root, limited as `run` says."""
    return run([sys.executable, "-m", "x3drbp", *args], memory=memory)


def one_line(p: subprocess.CompletedProcess, status: int, pattern: str) -> str:
    """The one line the command printed (stdout and stderr together), checked to match
    `pattern` (a regular expression, from its start), with exit `status` and no traceback."""
    out = p.stdout + p.stderr
    assert "Traceback" not in out and "MemoryError" not in out, out
    assert p.returncode == status, f"exit {p.returncode}, not {status}:\n{out}"
    printed = [line for line in out.splitlines() if line.strip()]
    assert len(printed) == 1, out
    assert re.match(pattern, printed[0]), (pattern, printed[0])
    return printed[0]


def leftovers(folder: str) -> list[str]:
    """The temporary files of a write that did not finish (x3d_core.files.atomic's names)."""
    return [n for n in os.listdir(folder) if n.startswith(".x3drbp-") and n.endswith(".tmp")]


@contextlib.contextmanager
def fed(path: str, chunk: bytes = b"[" * 65536) -> Iterator[str]:
    """A named pipe at path that a thread keeps writing `chunk` into for as long as the block
    runs: a reader never blocks on it, and one that reads on gets no end of it."""
    os.mkfifo(path)
    fd = os.open(path, os.O_RDWR | os.O_NONBLOCK)  # a writer (and reader) of our own: no open blocks
    done = threading.Event()

    def feed() -> None:
        while not done.is_set():
            try:
                os.write(fd, chunk)
            except BlockingIOError:  # full: nobody is reading
                done.wait(0.01)

    writer = threading.Thread(target=feed, daemon=True)
    writer.start()
    try:
        yield path
    finally:
        done.set()
        writer.join()
        os.close(fd)
