"""Where independent jobs run: a local pool of threads, or a Dask cluster.

Both are concurrent.futures executors (Dask's through Client.get_executor), so a caller
submits module-level functions and gets futures either way; jobs must be picklable and
return plain data (for Dask). Dask is imported only when a scheduler is named; its address
must read SCHEME://HOST:PORT (address()), and a scheduler not reached within CONNECT_TIMEOUT s
fails the block at once (Unreachable), rather than after Dask's own, configurable, wait.

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

SCHEMES = ("tcp", "tls", "ws", "wss", "ucx")  # Dask's schemes that reach a scheduler over a network
CONNECT_TIMEOUT = 10.0  # s to reach a scheduler (Dask's default is 30 s, and settable in its configuration)


class Unreachable(ConnectionError):
    """No scheduler answered at the address within CONNECT_TIMEOUT s: the message says which and why."""


def address(text: str) -> str:
    """A Dask scheduler's address as SCHEME://HOST:PORT (HOST:PORT: tcp); ValueError saying the
    form where the text is none (Dask's own error was a traceback)."""
    scheme, sep, rest = text.partition("://")
    if not sep:
        scheme, rest = "tcp", text
    host, _, port = rest.rpartition(":")
    if scheme not in SCHEMES or not host.strip("[]") or not port.isdigit() or not 0 < int(port) < 65536:
        raise ValueError(f"--scheduler {text!r} is not a Dask scheduler's address: SCHEME://HOST:PORT, as "
                         f"tcp://host:8786 (schemes: {', '.join(SCHEMES)}; port 1 to 65535)")
    return f"{scheme}://{rest}"


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
    try:
        client = Client(scheduler, timeout=CONNECT_TIMEOUT)
    except Exception as e:  # refused, timed out, or garbage from whatever answered there
        raise Unreachable(f"cannot reach the Dask scheduler at {scheduler} within {CONNECT_TIMEOUT:g} s: "
                          f"{type(e).__name__}: {e}") from None
    with client:
        # pure=False: two equal jobs are two runs (each measures its own wall time)
        yield client.get_executor(pure=False)
