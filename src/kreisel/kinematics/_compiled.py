"""Lazily built gufuncs that switch to both cores for large batches.

Element kernels are broadcast by :func:`numba.guvectorize`. A gufunc with
explicit signatures compiles (or loads from the on-disk cache) when it is
built, so it is built on first call, keeping ``import kreisel`` light. Large
batches go to the ``parallel`` target; small ones stay on the calling
thread, where starting the thread pool would cost more than the work.
"""

from __future__ import annotations

import numpy as np
from numba import guvectorize, njit

#: Length-3 template argument for kernels whose output length does not
#: occur among their inputs (numba's gufunc layouts have no literal sizes).
THREE = np.zeros(3)

#: Batches with more elements than this (in the first argument) run on all cores.
PARALLEL_ABOVE = 1 << 14


class Kernel:
    """A per-element function broadcast over batches, compiled on first use.

    Parameters
    ----------
    function : callable
        Module-level Python function in gufunc form ``f(in..., out)``.
    signatures : list of str
        numba type signatures.
    layout : str
        gufunc layout such as ``"(3),(3)->(3)"``.
    """

    __slots__ = ("_function", "_signatures", "_layout", "_built")

    def __init__(self, function, signatures, layout):
        self._function = function
        self._signatures = signatures
        self._layout = layout
        self._built = {}

    def _get(self, target):
        g = self._built.get(target)
        if g is None:
            g = guvectorize(self._signatures, self._layout, nopython=True, cache=True, target=target)(
                self._function
            )
            self._built[target] = g
        return g

    def __call__(self, *args):
        target = "parallel" if args[0].size > PARALLEL_ABOVE else "cpu"
        return self._get(target)(*args)


def kernel(signatures, layout):
    """Decorator form of :class:`Kernel`."""
    return lambda function: Kernel(function, signatures, layout)


class RowLoop:
    """An element kernel applied to the rows of broadcast ``(..., k)`` arrays by a compiled loop.

    For the hot rate maps a plain ``prange`` loop over contiguous rows costs
    about half of a gufunc's per-element dispatch. ``loop(*rows, *scalars, out)``
    is a module-level Python function written with ``numba.prange``; it is
    compiled twice on first use, serial and parallel.

    Parameters
    ----------
    loop : callable
        Python loop function over 2-D row arrays.
    out_length : int
        Row length of the output.
    """

    __slots__ = ("_loop", "_out_length", "_built")

    def __init__(self, loop, out_length):
        self._loop = loop
        self._out_length = out_length
        self._built = {}

    def _get(self, parallel):
        f = self._built.get(parallel)
        if f is None:
            f = self._built[parallel] = njit(cache=True, nogil=True, parallel=parallel)(self._loop)
        return f

    def __call__(self, arrays, scalars=()):
        shape = np.broadcast_shapes(*(a.shape[:-1] for a in arrays))
        rows = [
            np.ascontiguousarray(a if a.shape[:-1] == shape else np.broadcast_to(a, shape + a.shape[-1:])).reshape(
                -1, a.shape[-1]
            )
            for a in arrays
        ]
        n = rows[0].shape[0]
        out = np.empty((n, self._out_length))
        self._get(n > PARALLEL_ABOVE)(*rows, *scalars, out)
        return out.reshape(shape + (self._out_length,))


def row_loop(out_length):
    """Decorator form of :class:`RowLoop`."""
    return lambda loop: RowLoop(loop, out_length)
