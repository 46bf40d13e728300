"""One compilation at a time among the processes that share an on-disk numba cache.

numba loads, compiles and saves every cache entry under its global compiler
lock, a thread lock: processes do not see each other's. Two processes that
compile the same functions into one cache at once (pytest workers and the
command-line runs they start, dask or multiprocessing workers on a fresh
install) then break it two ways:

- a gufunc is two entries, its kernel and a wrapper that numba looks up by
  the kernel's symbol name, which carries a per-process compilation counter:
  the kernel saved by one process and the wrapper saved by the other give a
  null function pointer, and the first call segfaults (every later process
  loading that pair does too);
- two processes adding different signatures to one index pick the same data
  file, so a signature can be paired with the other's machine code.

:func:`install` makes numba's compiler lock also hold an exclusive ``flock``
on a lock file in the cache directory while a thread of the process holds it
(the outermost hold: nested compilations are inside it). Every load-or-
compile-and-save of numba then runs alone among the processes sharing the
cache, so an entry is saved only by the process that found it missing, and
never replaced: a gufunc's wrapper, built in the same hold as its kernel
(:class:`~kreisel._compiled.gufunc.LazyGufunc` holds the lock across both),
is always built for the kernel the cache holds. Without ``fcntl`` (Windows)
the lock stays a thread lock.
"""

from __future__ import annotations

import os
import threading
from typing import IO

import numba
from numba.core.caching import FunctionCache
from numba.core.compiler_lock import global_compiler_lock

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None  # type: ignore[assignment]

#: Lock file name, in the directory numba caches this module's functions in.
LOCK_NAME = "compile.lock"

_paths: dict[str, str] = {}


def lock_path() -> str:
    """The lock file of the cache numba uses now (``numba.config.CACHE_DIR``, or next to the sources, or per user).

    numba picks a cache directory per source directory with the same rules
    for all of kreisel's packages; the one of this module stands for them.
    """
    key = numba.config.CACHE_DIR
    if key not in _paths:
        _paths[key] = os.path.join(FunctionCache(lock_path).cache_path, LOCK_NAME)
    return _paths[key]


def _locked_file() -> IO[str] | None:
    """The lock file, open and locked by this process; None if it cannot be opened (numba cannot cache there either)."""
    try:
        file = open(lock_path(), "a")
    except (OSError, RuntimeError):  # RuntimeError: numba finds no cache directory at all
        return None
    try:
        fcntl.flock(file, fcntl.LOCK_EX)
    except BaseException:
        file.close()
        raise
    return file


class ProcessesLock:
    """A re-entrant thread lock whose outermost hold also locks the cache's lock file.

    It has the interface numba's compiler lock uses of the thread lock it
    replaces (``acquire()``, ``release()``, ``_is_owned()``). A hold taken
    on the thread lock before :func:`install` swapped it in is released
    without touching the file.
    """

    def __init__(self, threads: threading.RLock) -> None:
        self._threads = threads
        # changed only by the thread holding ``threads``
        self._depth = 0
        self._file: IO[str] | None = None

    def acquire(self) -> bool:
        self._threads.acquire()
        if self._depth == 0:
            try:
                self._file = _locked_file()
            except BaseException:
                self._threads.release()
                raise
        self._depth += 1
        return True

    def release(self) -> None:
        if self._depth:
            self._depth -= 1
            if self._depth == 0 and self._file is not None:
                self._file.close()
                self._file = None
        self._threads.release()

    def _is_owned(self) -> bool:
        return bool(self._threads._is_owned())  # type: ignore[attr-defined]


def install() -> bool:
    """Make numba's compiler lock one among processes (once per process); False where there is no ``fcntl``."""
    if fcntl is None:
        return False
    threads = global_compiler_lock._lock
    if isinstance(threads, ProcessesLock):
        return True
    # swapped while held, so that no other thread is inside numba's compiler at that moment
    with threads:
        global_compiler_lock._lock = ProcessesLock(threads)
    return True
