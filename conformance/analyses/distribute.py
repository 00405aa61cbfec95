"""Where independent jobs run: a local pool of threads, or a Dask cluster.

Both are concurrent.futures executors (Dask's through Client.get_executor), so a caller
submits module-level functions and gets futures either way; jobs must be picklable and
return plain data (for Dask). Dask is imported only when a scheduler is named.

Locally a job's work is its `x3drbp run` child (forked by the command's fork server,
conformance/runner/fork_server.py) and a little reading of what it wrote: threads waiting
on their children do it without a second interpreter per worker, and an interrupt stops
their children as it stops any (children.interruptible), after which no job starts one.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from concurrent.futures import Executor, ThreadPoolExecutor
from contextlib import contextmanager


@contextmanager
def executor(scheduler: str | None, workers: int | None = None) -> Iterator[Executor]:
    """An executor for the duration of the block: with `scheduler` (a Dask scheduler's address,
    tcp://host:8786) the cluster's workers, as many as it has; else `workers` local threads
    (default: the number of CPUs). Jobs not yet started when the block raises are cancelled."""
    if scheduler is None:
        pool = ThreadPoolExecutor(max_workers=max(1, workers or os.cpu_count() or 1))
        try:
            yield pool
        finally:
            pool.shutdown(wait=True, cancel_futures=True)
        return
    from distributed import Client
    with Client(scheduler) as client:
        # pure=False: two equal jobs are two runs (each measures its own wall time)
        yield client.get_executor(pure=False)
