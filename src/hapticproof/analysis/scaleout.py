"""Run one chunk function serially, in local processes, or on Dask -- results in task order.

DESIGN.md, *Scale out, don't reinvent*: grids of scenes are chunked and mapped with local
processes (:mod:`concurrent.futures`) or Dask (``distributed``); the **same** chunk function runs
in all three modes, so the values cannot depend on the mode. :func:`ordered_map` yields each
task's result in the order of the tasks as soon as it and every earlier one are done (a
streaming writer never holds more than the out-of-order window), and reports progress.

``scheduler``: ``None`` (serial, or ``workers`` local processes), ``"dask"`` (a fresh
``distributed.LocalCluster`` with ``workers`` single-threaded worker processes) or the address of
a running Dask scheduler (``"tcp://host:8786"``; its workers need ``hapticproof`` installed).

>>> list(ordered_map(abs, [-1, 2, -3]))
[1, 2, 3]
"""

from __future__ import annotations

import concurrent.futures
import multiprocessing
import os
import re
import sys
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import Any

from hapticproof.core.errors import InputFormatError

__all__ = ["ordered_map", "ProgressBar", "default_workers", "dask_client", "scheduler_address", "probe_scheduler"]


def default_workers() -> int:
    """The machine's cores available to this process.

    >>> default_workers() >= 1
    True
    """
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


class ProgressBar:
    """A one-line progress bar on stderr, drawn only when stderr is a terminal.

    >>> bar = ProgressBar(10, "map")      # silent under doctest (no terminal)
    >>> bar(5); bar.close()
    """

    def __init__(self, total: int, label: str = "", stream: Any = None, force: bool = False):
        self.total, self.label = max(int(total), 1), label
        self.stream = stream or sys.stderr
        self.active = force or bool(getattr(self.stream, "isatty", lambda: False)())
        self.start = time.perf_counter()
        self._last = -1.0

    def __call__(self, done: int, total: int | None = None) -> None:
        if not self.active:
            return
        total = total or self.total
        now = time.perf_counter()
        if done < total and now - self._last < 0.1:
            return
        self._last = now
        width = 30
        filled = int(width * done / total)
        elapsed = now - self.start
        eta = elapsed / done * (total - done) if done else 0.0
        self.stream.write(f"\r{self.label} [{'#' * filled}{'.' * (width - filled)}] {done}/{total} "
                          f"{elapsed:.1f}s elapsed, ~{eta:.1f}s left ")
        self.stream.flush()

    def close(self) -> None:
        if self.active:
            self.stream.write("\n")
            self.stream.flush()


def dask_client(scheduler: str, workers: int | None = None):
    """A ``distributed.Client``: a new ``LocalCluster`` for ``"dask"``, else the given address."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise InputFormatError("--scheduler needs Dask: pip install 'hapticproof[dask]'") from None
    if scheduler == "dask":
        import logging

        cluster = LocalCluster(n_workers=workers or default_workers(), threads_per_worker=1, processes=True,
                               dashboard_address=None, silence_logs=logging.ERROR)
        return Client(cluster)
    host, port = scheduler_address(scheduler)
    if scheduler.startswith("tcp://"):
        probe_scheduler(host, port, scheduler)
    try:
        return Client(scheduler, timeout="10s")
    except (OSError, ValueError, TypeError, MemoryError) as err:
        raise InputFormatError(f"--scheduler {scheduler}: cannot connect ({type(err).__name__}: {str(err)[:160]})") from None


_HOST = re.compile(r"(?:[A-Za-z0-9](?:[A-Za-z0-9-]{0,61}[A-Za-z0-9])?)(?:\.[A-Za-z0-9](?:[A-Za-z0-9-]{0,61}[A-Za-z0-9])?)*")


def scheduler_address(text: str) -> tuple[str, int]:
    """``tcp://HOST:PORT`` or ``tls://HOST:PORT`` (a host name, an IPv4 address or ``[IPv6]``, a
    port from 1 to 65535), checked before anything connects; anything else is one line.

    >>> scheduler_address("tcp://10.0.0.5:8786")
    ('10.0.0.5', 8786)
    >>> scheduler_address("tcp://")
    Traceback (most recent call last):
    ...
    hapticproof.core.errors.InputFormatError: --scheduler 'tcp://': expected 'dask' or tcp://HOST:PORT (e.g. tcp://10.0.0.5:8786)
    """
    import ipaddress

    refuse = InputFormatError(f"--scheduler {text[:80]!r}: expected 'dask' or tcp://HOST:PORT (e.g. tcp://10.0.0.5:8786)")
    scheme, sep, rest = text.partition("://")
    if not sep or scheme not in ("tcp", "tls") or not text.isascii() or not text.isprintable():
        raise refuse
    if rest.startswith("["):
        host, close, port_text = rest[1:].partition("]")
        if not close or not port_text.startswith(":"):
            raise refuse
        port_text = port_text[1:]
        try:
            ipaddress.IPv6Address(host)
        except ValueError:
            raise refuse from None
    else:
        host, colon, port_text = rest.rpartition(":")
        if not colon or not host or not _HOST.fullmatch(host) or len(host) > 253:
            raise refuse
    if not (port_text.isascii() and port_text.isdigit() and len(port_text) <= 5 and 1 <= int(port_text) <= 65535):
        raise refuse
    return host, int(port_text)


#: The largest handshake a Dask scheduler sends first (its first 8 bytes are the message's
#: length): a service that is not Dask (an SSH or mail server's banner read as a length) would
#: make Dask allocate exabytes.
MAX_HANDSHAKE = 1 << 20


def probe_scheduler(host: str, port: int, shown: str, seconds: float = 5.0) -> None:
    """Connect once and read what the service says first: a Dask scheduler sends its handshake
    (an 8-byte length, then that many bytes) as soon as it accepts; anything else -- a banner, a
    length above :data:`MAX_HANDSHAKE`, silence -- is one line, before Dask reads a byte."""
    import socket
    import struct

    try:
        with socket.create_connection((host, port), timeout=seconds) as sock:
            sock.settimeout(seconds)
            head = b""
            while len(head) < 8:
                chunk = sock.recv(8 - len(head))
                if not chunk:
                    break
                head += chunk
    except TimeoutError:
        head = None
    except OSError as err:
        raise InputFormatError(f"--scheduler {shown}: cannot connect ({err.strerror or type(err).__name__})") from None
    if head is None or len(head) < 8:
        raise InputFormatError(f"--scheduler {shown}: no Dask scheduler answers there (no handshake within {seconds:g} s)")
    (length,) = struct.unpack("<Q", head)
    if length > MAX_HANDSHAKE:
        raise InputFormatError(f"--scheduler {shown}: the service there does not speak Dask's protocol "
                               f"(its first message claims {length} bytes)")



def ordered_map(func: Callable[[Any], Any], tasks: Sequence[Any], *, workers: int = 1, scheduler: str | None = None,
                progress: Callable[[int, int], None] | None = None, client: Any = None) -> Iterator[Any]:
    """``func(task)`` for every task, yielded in task order (streaming).

    ``workers > 1`` without ``scheduler``: a process pool (fork where available: the workers
    start with this process's imports). ``scheduler``/``client``: Dask. ``func`` and the tasks
    must be picklable (module-level functions, plain data).
    """
    tasks = list(tasks)
    total = len(tasks)
    if client is None and scheduler is None and (workers <= 1 or total <= 1):
        for i, task in enumerate(tasks):
            yield func(task)
            if progress:
                progress(i + 1, total)
        return
    if client is not None or scheduler is not None:
        yield from _dask_map(func, tasks, workers, scheduler, progress, client)
        return
    method = "fork" if "fork" in multiprocessing.get_all_start_methods() else None
    context = multiprocessing.get_context(method)
    from hapticproof.core.processes import die_with_parent

    with concurrent.futures.ProcessPoolExecutor(max_workers=min(workers, total), mp_context=context,
                                                initializer=die_with_parent, initargs=(os.getpid(),)) as pool:
        futures = {pool.submit(func, task): i for i, task in enumerate(tasks)}
        yield from _in_order(((futures[f], f.result()) for f in concurrent.futures.as_completed(futures)), total, progress)


def _in_order(done: Iterable[tuple[int, Any]], total: int, progress) -> Iterator[Any]:
    waiting: dict[int, Any] = {}
    nxt = 0
    count = 0
    for index, result in done:
        count += 1
        waiting[index] = result
        if progress:
            progress(count, total)
        while nxt in waiting:
            yield waiting.pop(nxt)
            nxt += 1


def _dask_map(func, tasks, workers, scheduler, progress, client) -> Iterator[Any]:
    own = client is None
    if own:
        client = dask_client(scheduler, workers)
    try:
        from distributed import as_completed

        futures = client.map(func, tasks, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        yield from _in_order(((index[f.key], f.result()) for f in as_completed(futures)), len(tasks), progress)
    finally:
        if own:
            cluster = getattr(client, "cluster", None)
            client.close()
            if cluster is not None:
                cluster.close()
