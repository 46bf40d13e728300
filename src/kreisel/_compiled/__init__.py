"""kreisel's compiled layer: the one home of the numba machinery every package shares.

It sits below :mod:`kreisel.so3` (every package may import it; it imports no
other kreisel package, only the private helpers ``kreisel._validation``) and
holds

- :mod:`.gufunc`: :class:`~.gufunc.LazyGufunc` (per-element kernels broadcast
  by ``numba.guvectorize``, compiled on first call, with an optional multi-core
  ``prange`` loop for large batches) and the batch input checks;
- :mod:`.kernels`: the scalar quaternion kernels (product, rotation, matrix,
  exp/log) and their array shells;
- :mod:`.dexp`: the scalar kernels of the exponential map's differential
  (rate maps, Jacobians, Bortz coefficient);
- :mod:`.series`: Maclaurin coefficients from exact rationals, for the
  functions that lose digits to cancellation at small angles;
- :mod:`.dop853`: the one adaptive Dormand–Prince 8(5,3) integrator.

The decorator flavours below are the only ways kreisel compiles a function.

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
    Two processes adding different signatures to one on-disk cache index at
    the same moment can pair a signature with the other's machine code.
    ``tests/test_compiled.py`` fails when a test run leaves a shared kernel
    with more than one signature.
Cache rules
    Everything is compiled with ``cache=True`` (:data:`cached`,
    :data:`inlined`, :data:`parallel`) except what takes another compiled
    function as an argument (:data:`generic`): numba would add a new, never
    reused cache entry per process. Such routines are inlined into a cached
    caller with a fixed module-level right-hand side. ``guvectorize`` with
    ``target="parallel"`` cannot be cached, hence the ``prange`` loops.
Inlining and stale caches
    numba keys a cache entry on the file of the compiled function, not on the
    files of the kernels it calls or inlines: after an edit here, a cached
    caller elsewhere keeps the old code. Development trees therefore compile
    into a cache directory keyed by the state of the package sources (the
    test suite: the root ``conftest.py``).
"""

from __future__ import annotations

from numba import njit

#: Cached, GIL-free scalar or array kernel: the default flavour.
cached = njit(cache=True, nogil=True)
#: As :data:`cached`, inlined into its callers at the numba IR level (small
#: models called in the innermost loop of an integrator).
inlined = njit(cache=True, nogil=True, inline="always")
#: Routines that take a compiled function as an argument: not cacheable on
#: their own, always inlined into a cached caller.
generic = njit(nogil=True, inline="always")
#: Cached multi-core loop (``prange``) over flattened batches.
parallel = njit(parallel=True, cache=True)

__all__ = ["cached", "generic", "inlined", "parallel"]
