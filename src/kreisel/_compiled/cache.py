"""Where kreisel's compiled code is cached on disk, and how processes share that cache safely.

Every function kreisel compiles with ``cache=True`` gets a cache object of
this module (:func:`attach`) instead of numba's default: numba's settings,
locks and other users' functions are left as they are.

One directory per source state
    numba keys a cache entry on the file of the compiled function, not on
    the files of the kernels it calls or inlines, so after an edit of a
    kernel a cached caller elsewhere would keep the old machine code. Here
    every entry is stamped with :func:`source_state`, a digest of the paths,
    sizes and modification times of all of kreisel's sources, and lives in
    a directory named after it: any edit (or upgrade) starts a fresh cache,
    and no run ever loads machine code compiled from other sources.
Where
    ``$NUMBA_CACHE_DIR/kreisel`` if the user set ``NUMBA_CACHE_DIR``; in a
    source checkout (``src/kreisel`` next to ``pyproject.toml``)
    ``.numba_cache`` at the repository root; otherwise the user's cache
    directory (``$XDG_CACHE_HOME`` or ``~/.cache``, then ``kreisel``), or a
    directory of the user's in the temporary directory where that is not
    writable.
Processes sharing a cache
    numba saves an entry by reading the function's index, adding the new
    signature with the next free data-file number and writing index and data
    (each atomically, through a temporary file and a rename). Two processes
    that save *different* signatures of one function at once would pick the
    same number, and the index could pair a signature with the other's
    machine code. :class:`KreiselCache` therefore saves under an exclusive
    ``flock`` on a file of the cache directory, held only for the save: the
    index is read, extended and written by one process at a time. Loading
    needs no lock: a reader sees an old or a new index and data file, never
    a half-written one, and a data file not written yet reads as a miss
    (numba compiles then). Where there is no ``fcntl`` (Windows) saves are
    not serialised; kreisel's array operations compile one signature per
    function (:mod:`.elementwise`), which needs no lock.
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import os
import pathlib
import tempfile
from collections.abc import Iterator
from typing import Any

from numba.core.caching import CompileResultCacheImpl, FunctionCache, _CacheLocator

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None  # type: ignore[assignment]

#: The package sources the cache belongs to.
PACKAGE = pathlib.Path(__file__).resolve().parents[1]
#: Name of the file locked while an entry is saved, in the cache's root directory.
LOCK_NAME = "save.lock"


@functools.cache
def source_state() -> str:
    """Digest of the paths, sizes and modification times of the package's Python sources."""
    digest = hashlib.sha1()
    for path in sorted(PACKAGE.rglob("*.py")):
        stat = path.stat()
        digest.update(f"{path.relative_to(PACKAGE)}:{stat.st_size}:{stat.st_mtime_ns}".encode())
    return digest.hexdigest()[:16]


def checkout_cache_root() -> pathlib.Path | None:
    """``.numba_cache`` of the source checkout kreisel is imported from, or None if it is installed."""
    root = PACKAGE.parents[1]
    if PACKAGE.parent.name != "src" or not (root / "pyproject.toml").is_file():
        return None
    return root / ".numba_cache"


def _writable(path: pathlib.Path) -> bool:
    try:
        path.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=path).close()
    except OSError:
        return False
    return True


@functools.cache
def cache_root() -> pathlib.Path:
    """The directory of this source state's cache (created if missing)."""
    user = os.environ.get("NUMBA_CACHE_DIR")
    checkout = checkout_cache_root()
    if user:
        base = pathlib.Path(user) / "kreisel"
    elif checkout is not None:
        base = checkout
    else:
        base = pathlib.Path(os.environ.get("XDG_CACHE_HOME") or pathlib.Path.home() / ".cache") / "kreisel"
    root = base / source_state()
    if not _writable(root):
        root = pathlib.Path(tempfile.gettempdir()) / f"kreisel-{os.getuid() if hasattr(os, 'getuid') else 'user'}" / source_state()
        root.mkdir(parents=True, exist_ok=True)
    return root


class _Locator(_CacheLocator):
    """Cache files of a function in :func:`cache_root`, under the path of its module in the package."""

    def __init__(self, py_func: Any, py_file: str) -> None:
        self._lineno = py_func.__code__.co_firstlineno
        try:
            relative = pathlib.Path(py_file).resolve().relative_to(PACKAGE).parent
        except ValueError:  # generated code (a declaration's loops): no file of the package
            relative = pathlib.Path("generated")
        self._path = str(cache_root() / relative)

    def get_cache_path(self) -> str:
        return self._path

    def get_source_stamp(self) -> str:
        return source_state()

    def get_disambiguator(self) -> str:
        return str(self._lineno)

    @classmethod
    def from_function(cls, py_func: Any, py_file: str) -> _Locator:
        return cls(py_func, py_file)


class _Impl(CompileResultCacheImpl):
    _locator_classes = [_Locator]


class KreiselCache(FunctionCache):
    """numba's function cache, located by :class:`_Locator` and saved under the cache's file lock."""

    _impl_class = _Impl

    def save_overload(self, sig: Any, data: Any) -> None:
        with _save_lock():
            super().save_overload(sig, data)


@contextlib.contextmanager
def _save_lock() -> Iterator[None]:
    if fcntl is None:  # pragma: no cover - Windows
        yield
        return
    root = cache_root()
    root.mkdir(parents=True, exist_ok=True)  # removed since the process started (a cache clean-up)
    with open(root / LOCK_NAME, "a") as file:
        fcntl.flock(file, fcntl.LOCK_EX)
        yield


def attach(dispatcher: Any) -> Any:
    """Give a numba dispatcher (made without ``cache=True``) kreisel's on-disk cache; returns it."""
    dispatcher._cache = KreiselCache(dispatcher.py_func)
    return dispatcher


__all__ = ["KreiselCache", "attach", "cache_root", "checkout_cache_root", "source_state"]
