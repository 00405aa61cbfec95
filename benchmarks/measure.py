"""Timing and memory measures the benchmark scripts share."""

from __future__ import annotations

import gc
import subprocess
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
