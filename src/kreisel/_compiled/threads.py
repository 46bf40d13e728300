"""How many threads a multi-core loop of kreisel runs on: numba's, or fewer while the machine is oversubscribed.

Every multi-core loop (:data:`~kreisel._compiled.parallel`) is a numba
``prange`` loop. numba splits its iterations into one equal share per thread
before the loop starts (with its OpenMP layer ``numba.set_parallel_chunksize``
only cuts the shares smaller, still assigned up front), and the call returns
when the last share is done. With more runnable tasks than cores, one thread
waits for a core for whole time slices while the others spin at the loop's
end: at load 6 on 2 cores a 10^6-quaternion inverse took 30–60 ms on two
threads against 2–3 ms on one. A loop of tens of milliseconds or more
spans many time slices, so a thread waiting for a core costs it a fraction,
not a multiple, and two threads also get two shares of the cores: the
chunks of a batch simulation (:func:`kreisel._compiled.chunks.run_chunked`,
about 50 ms each) run inside :func:`numbas_count` and keep numba's count
whatever the load (2000 bodies, rk4, 1000 steps, with four busy processes on
2 cores, 15 runs each in alternation: 192 ms median on numba's 2 threads
against 285 ms with the count lowered to one).

So each call first reads how many tasks the machine has runnable at that
moment (Linux: ``/proc/loadavg``, 3–7 µs, read again after
:data:`READING_SECONDS` at the earliest, so that a loop of small batches
does not pay it each time) and runs on as many threads fewer than numba's
current count as there are runnable tasks beyond the cores, at least one
(:func:`threads_for`). The count includes the caller
and kreisel's worker threads still spinning after a previous loop, so on a
quiet machine it never exceeds the cores and every loop runs on numba's
count, unchanged. Where the count cannot be read, or with the environment
variable ``KREISEL_ADAPTIVE_THREADS=0`` (read at import), loops always run
on numba's count. Results never depend on the thread count: every loop
writes each element's (or piece's) result on its own and reduces the
pieces' results in order afterwards.
"""

from __future__ import annotations

import contextlib
import os
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

import numba

__all__ = ["ADAPTIVE", "READING_SECONDS", "ParallelLoop", "last_threads", "numbas_count", "runnable_tasks",
           "threads_for"]

#: Whether loops run on fewer threads while the machine is oversubscribed (never with
#: ``KREISEL_ADAPTIVE_THREADS=0``, nor when numba has one thread: ``NUMBA_NUM_THREADS=1``).
ADAPTIVE = os.environ.get("KREISEL_ADAPTIVE_THREADS", "1") != "0" and numba.config.NUMBA_NUM_THREADS > 1

#: Cores the runnable tasks of ``/proc/loadavg`` (counted over the whole machine) share.
_CORES = os.cpu_count() or 1

#: A count of runnable tasks is used for this long (a machine's load changes over seconds, a loop takes µs to ms).
READING_SECONDS = 1e-3

_loadavg: list[int | None] = []
#: When the last count was read, and the count.
_last: list[Any] = [-1.0, None]


def runnable_tasks() -> int | None:
    """Tasks running or waiting for a core on the whole machine, the caller included; None if unknown.

    The count read at most :data:`READING_SECONDS` ago, or a new one.
    """
    now = time.monotonic()
    if now - _last[0] < READING_SECONDS:
        return _last[1]
    if not _loadavg:
        try:
            _loadavg.append(os.open("/proc/loadavg", os.O_RDONLY))
        except OSError:
            _loadavg.append(None)
    count = None
    if _loadavg[0] is not None:
        try:
            # "0.52 0.58 0.59 3/215 12345": the fourth field is runnable/existing tasks
            count = int(os.pread(_loadavg[0], 128, 0).split()[3].split(b"/")[0])
        except (OSError, IndexError, ValueError):
            _loadavg[0] = None  # a /proc of another layout (a sandbox): numba's count from now on
    _last[:] = now, count
    return count


def threads_for(configured: int, runnable: int | None) -> int:
    """Threads for a loop: ``configured`` less the ``runnable`` tasks beyond the cores, at least one."""
    if runnable is None:
        return configured
    return max(1, min(configured, configured - (runnable - _CORES)))


#: Threads the last loop was given when fewer than numba's count, else None.
_given: list[int | None] = [None]


def last_threads() -> int:
    """Threads the most recent multi-core loop ran on (numba's count unless it was lowered)."""
    return _given[0] or numba.get_num_threads()


#: How deep the calling thread is in :func:`numbas_count` (numba's thread count is per thread too).
_held = threading.local()


@contextlib.contextmanager
def numbas_count() -> Iterator[None]:
    """Within this context the calling thread's loops run on numba's count, whatever the load (long loops)."""
    depth = getattr(_held, "depth", 0)
    _held.depth = depth + 1
    try:
        yield
    finally:
        _held.depth = depth


class ParallelLoop:
    """A compiled multi-core loop called on :func:`threads_for` threads; its dispatcher's attributes pass through."""

    __slots__ = ("dispatcher",)

    def __init__(self, dispatcher: Callable[..., Any]) -> None:
        self.dispatcher = dispatcher

    def __call__(self, *args: Any) -> Any:
        runnable = runnable_tasks() if ADAPTIVE and not getattr(_held, "depth", 0) else None
        if runnable is None or runnable <= _CORES:
            _given[0] = None
            return self.dispatcher(*args)
        configured = numba.get_num_threads()
        _given[0] = threads_for(configured, runnable)
        numba.set_num_threads(_given[0])
        try:
            return self.dispatcher(*args)
        finally:
            numba.set_num_threads(configured)

    def __getattr__(self, name: str) -> Any:
        return getattr(self.dispatcher, name)
