"""Where independent jobs run: a local process pool, or a Dask cluster.

Both are concurrent.futures executors (Dask's through Client.get_executor), so a caller
submits module-level functions and gets futures either way; jobs must be picklable and
return plain data. Dask is imported only when a scheduler is named.

A local pool's worker stops its own children when it gets SIGINT (the terminal's Ctrl-C
reaches the whole foreground group) or SIGTERM (children.stop sends it to the workers of an
interrupted parent), then ends: submit jobs through `guarded` so that a running one unwinds
first (its temporary files removed).
"""

from __future__ import annotations

import multiprocessing
import os
import signal
from collections.abc import Callable, Iterator
from concurrent.futures import Executor, ProcessPoolExecutor
from contextlib import contextmanager
from typing import TypeVar

from conformance.runner import children

T = TypeVar("T")
_busy = False  # this worker is running a job: an interrupt unwinds it rather than ending the worker at once


def _on_signal(signum: int, frame: object) -> None:
    """A pool worker's handler: a running job's children stopped and the job unwound (`guarded`
    then ends the worker); an idle worker, which has no children, ends at once."""
    if _busy:
        children.handle_signal(signum, frame)
        return
    os._exit(128 + signum)


def _start_worker() -> None:
    for s in children.SIGNALS:
        if signal.getsignal(s) is not signal.SIG_IGN:  # as the parent: a background job ignores SIGINT
            signal.signal(s, _on_signal)


def guarded(job: Callable[..., T], *args: object) -> T:
    """job(*args) in a pool worker that ends once an interrupt has unwound the job (the pool
    would otherwise hand it the next one); elsewhere (Dask) just job(*args)."""
    global _busy
    try:
        _busy = True
        return job(*args)
    except children.Interrupted as e:
        os._exit(e.status)
    finally:
        _busy = False


@contextmanager
def executor(scheduler: str | None, workers: int | None = None) -> Iterator[Executor]:
    """An executor for the duration of the block: with `scheduler` (a Dask scheduler's address,
    tcp://host:8786) the cluster's workers, as many as it has; else a pool of `workers` local
    processes (default: the number of CPUs). The local pool spawns fresh interpreters rather than
    forking, so a caller's threads (a progress bar's, Dask's) are never copied mid-flight."""
    if scheduler is None:
        context = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(max_workers=max(1, workers or os.cpu_count() or 1), mp_context=context,
                                 initializer=_start_worker) as pool:
            yield pool
        return
    from distributed import Client
    with Client(scheduler) as client:
        # pure=False: two equal jobs are two runs (each measures its own wall time)
        yield client.get_executor(pure=False)
