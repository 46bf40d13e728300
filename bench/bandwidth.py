"""The machine's memory bandwidth as compiled loops see it: STREAM-like copy and triad.

``python bench/bandwidth.py`` times, on 1 and 2 numba threads, a copy
``b = a`` and a triad ``c = a + s b`` over 64 MB arrays, each with ordinary
stores and with non-temporal (streaming) stores, and ``np.copyto`` (glibc's
``memcpy``, which streams large copies itself); interleaved, medians and
bests, GB/s counted without the write-allocate read that ordinary stores
cost. It prints only (not part of ``run_all.py``): the numbers go into the
notes of ``bench/RESULTS.md`` when the memory-bound rows are examined.

numba has no streaming store; :func:`stream` is an intrinsic that emits an
LLVM store with ``!nontemporal`` metadata, and :func:`fence` orders those
stores before the loop returns.
"""

from __future__ import annotations

import os
import time

import numba
import numpy as np
from llvmlite import ir
from numba import njit, prange, types
from numba.core import cgutils
from numba.extending import intrinsic

#: Doubles per array (64 MB).
N = 8_000_000
REPEATS = 11


@intrinsic
def stream(typingctx, array, index, value):
    """``array[index] = value`` with a non-temporal store (no read of the cache line first)."""

    def codegen(context, builder, signature, args):
        array_type = signature.args[0]
        view = context.make_array(array_type)(context, builder, args[0])
        pointer = cgutils.get_item_pointer(context, builder, array_type, view, [args[1]], wraparound=False,
                                           boundscheck=False)
        store = builder.store(args[2], pointer)
        store.set_metadata("nontemporal", builder.module.add_metadata([ir.Constant(ir.IntType(32), 1)]))
        return context.get_dummy_value()

    return types.void(array, index, value), codegen


@intrinsic
def fence(typingctx):
    """A full memory fence: streaming stores are weakly ordered."""

    def codegen(context, builder, signature, args):
        builder.fence("seq_cst")
        return context.get_dummy_value()

    return types.void(), codegen


@njit(parallel=True)
def copy(a, b):
    for i in prange(a.size):
        b[i] = a[i]


@njit(parallel=True)
def copy_streaming(a, b):
    for i in prange(a.size):
        stream(b, i, a[i])
    fence()


@njit(parallel=True)
def triad(a, b, c, s):
    for i in prange(a.size):
        c[i] = a[i] + s * b[i]


@njit(parallel=True)
def triad_streaming(a, b, c, s):
    for i in prange(a.size):
        stream(c, i, a[i] + s * b[i])
    fence()


def main():
    a, b, c = np.random.rand(N), np.random.rand(N), np.zeros(N)
    runs = {
        "copy": (lambda: copy(a, c), 2),
        "copy, streaming stores": (lambda: copy_streaming(a, c), 2),
        "triad": (lambda: triad(a, b, c, 3.0), 3),
        "triad, streaming stores": (lambda: triad_streaming(a, b, c, 3.0), 3),
        "np.copyto (memcpy)": (lambda: np.copyto(c, a), 2),
    }
    for threads in (1, 2):
        numba.set_num_threads(threads)
        times = {name: [] for name in runs}
        for run, _ in runs.values():
            run()
        load = os.getloadavg()[0]
        for _ in range(REPEATS):
            for name, (run, _) in runs.items():
                start = time.perf_counter()
                run()
                times[name].append(time.perf_counter() - start)
        print(f"{threads} thread(s), 64 MB arrays, load {load:.1f} -> {os.getloadavg()[0]:.1f}")
        for name, (_, arrays) in runs.items():
            moved = arrays * 8 * N / 1e9
            print(f"  {name:24s} {moved / np.median(times[name]):5.1f} GB/s median, {moved / min(times[name]):5.1f} best")


if __name__ == "__main__":
    main()
