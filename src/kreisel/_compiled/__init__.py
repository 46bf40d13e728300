"""kreisel's compiled layer: the one home of the numba machinery every package shares.

It sits below :mod:`kreisel.so3` (every package may import it; it imports no
other kreisel package, only the private helpers ``kreisel._validation`` and ``kreisel._norms``) and
holds

- :mod:`.gufunc`: :class:`~.gufunc.LazyGufunc` (per-element kernels broadcast
  by ``numba.guvectorize``, compiled on first call, with an optional multi-core
  ``prange`` loop for large batches), the batch input checks and the
  multi-core loops over the pieces of a batch (:func:`~.gufunc.in_pieces`,
  :func:`~.gufunc.piece_results`);
- :mod:`.outputs`: the ``out=`` checks, the ``out`` entry of every docstring
  (:func:`~.outputs.takes_out`) and the recycled pages of large
  results (fresh 10^6-element outputs would otherwise fault their pages in
  on every call);
- :mod:`.kernels`: the scalar quaternion kernels (product, rotation, matrix,
  exp/log) and their array shells;
- :mod:`.dexp`: the scalar kernels of the exponential map's differential
  (rate maps, Jacobians, Bortz coefficient);
- :mod:`.series`: Maclaurin coefficients from exact rationals, for the
  functions that lose digits to cancellation at small angles;
- :mod:`.dop853`: the one adaptive Dormand–Prince 8(5,3) integrator;
- :mod:`.compile_lock`: one compilation at a time among the processes that
  share a cache directory;
- :mod:`.threads`: the thread count of each multi-core loop (numba's, fewer
  while the machine has more runnable tasks than cores).

The decorator flavours below are the only ways kreisel compiles a function
(besides user callables, compiled per call, and one object-mode callback).

Invariants
----------
One kernel per element operation
    A kernel takes plain numbers and returns a tuple; gufuncs and ``prange``
    loops read their arrays into it and write the tuple back. No array slice
    is built per element (tens of ns each, and every thread of a parallel loop
    would update the reference count of the one parent array).
One layout per shared kernel
    A kernel that several compiled callers use (the array shells of
    :mod:`.kernels`, such as ``quat_to_matrix``) is compiled for one type
    signature only: callers pass element slices with numba's layout ``'A'``,
    as gufuncs do, and read-only inputs are copied before a parallel loop.
    (Two processes adding different signatures to one on-disk cache index
    at the same moment could pair a signature with the other's machine code;
    :mod:`.compile_lock` now keeps them apart.)
    ``tests/test_compiled.py`` fails when a test run leaves a shared kernel
    with more than one signature.
Cache rules
    Everything is compiled with ``cache=True`` (:data:`cached`,
    :data:`inlined`, :data:`parallel`) except what takes another compiled
    function as an argument (:data:`generic`): numba would add a new, never
    reused cache entry per process. Such routines are inlined into a cached
    caller with a fixed module-level right-hand side; the loops over pieces
    of a batch are such routines, each inlined into a :data:`parallel`
    caller that names its per-piece kernel. ``guvectorize`` with
    ``target="parallel"`` cannot be cached, hence the ``prange`` loops.
Inlining and stale caches
    numba keys a cache entry on the file of the compiled function, not on the
    files of the kernels it calls or inlines: after an edit here, a cached
    caller elsewhere keeps the old code. An installed kreisel is safe (an
    upgrade rewrites every file, and with it every entry's source stamp), and
    kreisel leaves numba's cache location alone there. A source checkout
    (``src/kreisel`` next to ``pyproject.toml``: an editable install, or
    ``PYTHONPATH=src``) compiles into ``.numba_cache/<state>/`` at the
    repository root instead, ``<state>`` a digest of the paths, sizes and
    modification times of the package sources, so any edit starts a fresh
    cache: tests, ``make demo``, ``make bench`` and ``make docs`` never run
    stale machine code. A ``NUMBA_CACHE_DIR`` set by the user is respected.
Processes sharing a cache
    The pytest-xdist workers and the command-line runs they start, dask or
    multiprocessing workers on a fresh install: processes that share a
    cache directory load or compile one at a time, under numba's compiler
    lock made an inter-process file lock (:mod:`.compile_lock`), so what one
    compiled the others load. Without it, a gufunc kernel saved by one
    process next to the wrapper saved by another segfaulted every process
    that loaded them. Where there is no ``fcntl`` (Windows), each test
    worker compiles into a directory of its own.
"""

from __future__ import annotations

import hashlib
import os
import pathlib
from collections.abc import Callable
from typing import Any, TypeVar, cast

import numba
from numba import njit

from . import compile_lock
from .threads import ParallelLoop

#: The package sources this layer belongs to.
_PACKAGE = pathlib.Path(__file__).resolve().parents[1]


def source_state():
    """Digest of the paths, sizes and modification times of the package's Python sources."""
    digest = hashlib.sha1()
    for path in sorted(_PACKAGE.rglob("*.py")):
        stat = path.stat()
        digest.update(f"{path.relative_to(_PACKAGE)}:{stat.st_size}:{stat.st_mtime_ns}".encode())
    return digest.hexdigest()[:16]


def checkout_cache_root():
    """``.numba_cache`` of the source checkout kreisel is imported from, or None if it is installed."""
    root = _PACKAGE.parents[1]
    if _PACKAGE.parent.name != "src" or not (root / "pyproject.toml").is_file():
        return None
    return root / ".numba_cache"


def _use_checkout_cache(shared):
    caches = checkout_cache_root()
    if caches is None or os.environ.get("NUMBA_CACHE_DIR"):
        return
    # without an inter-process lock (no fcntl), each test worker keeps a cache of its own
    numba.config.CACHE_DIR = str(caches / source_state() / ("shared" if shared else
                                                             os.environ.get("PYTEST_XDIST_WORKER", "main")))


# before any kernel is decorated: numba picks a function's cache directory then
_use_checkout_cache(compile_lock.install())

# to type checkers a flavour returns the function it compiles (numba has no annotations for njit)
_Function = TypeVar("_Function", bound=Callable[..., Any])

#: Cached, GIL-free scalar or array kernel: the default flavour.
cached: Callable[[_Function], _Function] = njit(cache=True, nogil=True)
#: As :data:`cached`, inlined into its callers at the numba IR level (small
#: models called in the innermost loop of an integrator).
inlined: Callable[[_Function], _Function] = njit(cache=True, nogil=True, inline="always")
#: As :data:`cached`, with numpy's error model: a division by zero gives inf
#: or nan instead of raising, so a loop that divides needs no test per element
#: and vectorises (SIMD). For such loops and the element kernels they call,
#: where the divisors are never zero (a loop that may meet a zero divisor
#: flags its piece and leaves it to a checked loop).
vectorised: Callable[[_Function], _Function] = njit(cache=True, nogil=True, error_model="numpy")
#: Routines compiled anew for each argument type (a compiled function, a tuple
#: of any length): never cached on their own, always inlined into a cached caller.
generic: Callable[[_Function], _Function] = njit(nogil=True, inline="always")
_parallel_jit = njit(parallel=True, cache=True)


def parallel(function: _Function) -> _Function:
    """Cached multi-core loop (``prange``) over flattened batches, on :mod:`.threads`' count of threads."""
    return cast(_Function, ParallelLoop(_parallel_jit(function)))


__all__ = ["cached", "checkout_cache_root", "generic", "inlined", "parallel", "source_state", "vectorised"]
