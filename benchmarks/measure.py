"""Timing and memory measures the benchmark scripts share."""

from __future__ import annotations

import gc
import io
import os
import subprocess
import sys
import tarfile
import time
import tracemalloc
from typing import Any, Callable


def timed(fn: Callable[[], Any], repeat: int) -> tuple[float, Any]:
    """The best wall time of repeat calls, and the last call's result (so that what was
    timed can be checked without running it again)."""
    times, result = [], None
    for _ in range(repeat):
        result = None
        gc.collect()
        t = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t)
    return min(times), result


def peak_mb(fn: Callable[[], Any]) -> float:
    """Peak Python allocations of one call (tracemalloc: not the engines' own memory)."""
    gc.collect()
    tracemalloc.start()
    fn()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak / 2 ** 20


def process_wall(cmd: list[str], **options: Any) -> float:
    """The wall time of one whole process, start-up to exit, its output discarded
    (CalledProcessError if it fails); options go to subprocess.run (cwd, env)."""
    started = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, **options)
    return time.perf_counter() - started


# Forks and runs a command, its output discarded, and prints its CPU seconds, ru_maxrss (KiB) and
# exit status. Linux keeps in a process's ru_maxrss the resident size of the memory it replaced at
# exec, so a child of a big process (one with numpy loaded, or a compiled pile in memory) reads at
# least that process's size: forked from this bare interpreter (python -S), the floor is its few MB.
_LAUNCH = """import os, sys
pid = os.fork()
if pid == 0:
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    os.dup2(null, 2)
    os.execvp(sys.argv[1], sys.argv[1:])
_, status, usage = os.wait4(pid, 0)
print(usage.ru_utime + usage.ru_stime, usage.ru_maxrss, os.waitstatus_to_exitcode(status))
"""


def process_usage(cmd: list[str], **options: Any) -> tuple[float, float]:
    """The CPU seconds (user + system, the kernel's count of the child: a load beside it barely
    moves it) and the peak resident memory in MB (ru_maxrss, read with wait4 by a bare launcher:
    _LAUNCH) of one whole process, its output discarded (CalledProcessError if it fails); options
    go to subprocess.run (cwd, env)."""
    launched = subprocess.run([sys.executable, "-S", "-c", _LAUNCH, *cmd], check=True, capture_output=True,
                              text=True, **options)
    cpu, rss, status = launched.stdout.split()
    if int(status):
        raise subprocess.CalledProcessError(int(status), cmd)
    return float(cpu), int(rss) / 1024  # Linux counts ru_maxrss in KiB


def process_cpu(cmd: list[str], **options: Any) -> float:
    """process_usage's CPU seconds."""
    return process_usage(cmd, **options)[0]


def compiled_env(folder: str, **extra: str) -> dict[str, str]:
    """This process's environment for timed children, with Python's bytecode cache on, kept under
    folder: as an installed package runs (pip compiles it; a checkout caches on first import),
    where PYTHONDONTWRITEBYTECODE would have every process compile the project's modules it
    imports from source (measured: 85 ms of CPU more for an `x3drbp run` of the car, 25 ms for
    its native script). Time a child only after a first, untimed run with the same environment
    has filled the cache. One OpenBLAS thread on both sides, as `x3drbp` sets for itself
    (x3drbp): numpy's spinning threads cost each process about 0.1 s of CPU, the same on
    both sides, which would flatter every ratio, and a native script could set it as well."""
    env = dict(os.environ, PYTHONPYCACHEPREFIX=os.path.join(folder, "pycache"), OPENBLAS_NUM_THREADS="1", **extra)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def tree_at(rev: str, root: str, folder: str) -> str:
    """The files of revision rev of the git checkout at root (git archive), unpacked under folder:
    a command run there with `python -m` (cwd the tree) runs that revision's x3drbp."""
    data = subprocess.run(["git", "-C", root, "archive", rev], check=True, capture_output=True).stdout
    out = os.path.join(folder, f"tree-{rev}")
    with tarfile.open(fileobj=io.BytesIO(data)) as tar:
        tar.extractall(out, filter="data")
    return out


def command_line(tree: str) -> list[str]:
    """How to start the x3drbp command in a tree, run with the tree as its folder: `python -m
    x3drbp`, or `python -m conformance.cli` in a tree from before the command line had its own
    package (the editable install would otherwise find this tree's x3drbp from that one)."""
    own = os.path.isdir(os.path.join(tree, "x3drbp"))
    return [sys.executable, "-m", "x3drbp" if own else "conformance.cli"]


def packages(tree: str) -> list[str]:
    """The tree's package folders, for its bytecode to be compiled before any run is timed."""
    return [p for p in (os.path.join(tree, d) for d in ("x3d_core", "backends", "conformance", "reports", "x3drbp"))
            if os.path.isdir(p)]

