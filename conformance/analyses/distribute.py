"""Where independent jobs run: a local process pool, or a Dask cluster.

Both are concurrent.futures executors (Dask's through Client.get_executor), so a caller
submits module-level functions and gets futures either way; jobs must be picklable and
return plain data. Dask is imported only when a scheduler is named.
"""

from __future__ import annotations

import multiprocessing
import os
from collections.abc import Iterator
from concurrent.futures import Executor, ProcessPoolExecutor
from contextlib import contextmanager


@contextmanager
def executor(scheduler: str | None, workers: int | None = None) -> Iterator[Executor]:
    """An executor for the duration of the block: with `scheduler` (a Dask scheduler's address,
    tcp://host:8786) the cluster's workers, as many as it has; else a pool of `workers` local
    processes (default: the number of CPUs). The local pool spawns fresh interpreters rather than
    forking, so a caller's threads (a progress bar's, Dask's) are never copied mid-flight."""
    if scheduler is None:
        context = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(max_workers=max(1, workers or os.cpu_count() or 1), mp_context=context) as pool:
            yield pool
        return
    from distributed import Client
    with Client(scheduler) as client:
        # pure=False: two equal jobs are two runs (each measures its own wall time)
        yield client.get_executor(pure=False)
