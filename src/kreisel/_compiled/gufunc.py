"""Lazily compiled generalized ufuncs and the input checks they rely on.

Every compiled operation of :mod:`kreisel.so3` is a per-element kernel
broadcast by :func:`numba.guvectorize`. Building a gufunc with explicit
signatures compiles (or loads from the on-disk cache) immediately, so the
gufuncs are built on first call instead: ``import kreisel`` stays light and
each operation pays its ~10 ms cache load only when it is used.

Large batches (at least :data:`PARALLEL_THRESHOLD` elements) run on all
cores instead: numba cannot cache ``guvectorize(target="parallel")`` (every
process would recompile, ~0.5 s), but it does cache ``njit(parallel=True)``
loops, so each gufunc may carry a ``prange`` loop over flattened
``(n, *core)`` views that calls the same per-element kernel. The batch
checks below are split into chunks the same way.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from numba import guvectorize, prange
from numba.core.compiler_lock import global_compiler_lock

from .._norms import ORTHOGONALITY_TOLERANCE, checked_rotation_matrices, norm
from .._validation import ROTVEC_RANGE, as_float_array, refuse_long_angle
from . import cached, generic, inlined, parallel
from . import outputs
from numpy import empty

from .outputs import check_out

#: Batches with at least this many elements (rotations, vectors) use the
#: multi-core loops; below it, waking the worker threads costs more than it saves.
PARALLEL_THRESHOLD = 2**14


def _parse_layout(layout):
    """Core shapes of a layout with literal sizes, e.g. ``"(4),(3)->(3,3)"``."""
    ins, out = layout.split("->")

    def shapes(text):
        return [tuple(int(n) for n in part.strip("()").split(",") if n) for part in text.split("),(")]

    return shapes(ins), shapes(out)[0]


class LazyGufunc:
    """A ``numba.guvectorize`` gufunc compiled on its first call.

    The layout uses literal core sizes (``"(4),(4)->(4)"``), translated to
    numba's symbolic form here. numba cannot size an output from nothing, so
    an output size that no real input carries is supplied by a trailing
    *size carrier* input: declared in the function and the layout (e.g.
    ``f(q, carrier3, out)`` with ``"(4),(3)->(3,3)"``) and filled in here
    with an empty array whenever the caller passes fewer arguments.

    Parameters
    ----------
    function : callable
        Module-level Python function in gufunc form ``f(in..., out)``.
    signatures : list of str
        numba type signatures.
    layout : str
        Layout with literal sizes.
    parallel : numba dispatcher, optional
        ``njit(parallel=True, cache=True)`` loop ``g(in..., out)`` over
        C-contiguous, writable ``(n, *core)`` views of the inputs passed by
        the caller (size carriers are not passed) and of the output. Its body
        reads the entries of element ``i`` as numbers, calls the same tuple
        kernel as ``function`` and writes the returned tuple back: an element
        slice ``a[i]`` passed to a compiled call would cost tens of ns to
        build and make every thread update the reference count of the one
        shared array. Read-only inputs are copied so that the loop keeps one
        compiled signature (one compilation, one cache entry). Used when the
        batch has at least :data:`PARALLEL_THRESHOLD` elements and every
        input either has the full batch shape or, if its index is in
        ``shared``, no batch axes.
    shared : tuple of int
        Inputs without batch axes that the parallel loop takes whole: arrays
        such as Euler axis indices, or scalars such as a frame sign or a
        tolerance (passed as Python floats, as to the gufunc).
    """

    __slots__ = ("_function", "_signatures", "_layout", "_carriers", "_gufunc", "_cores", "_out", "_parallel", "_shared")

    def __init__(self, function, signatures, layout, parallel=None, shared=()):
        ins, out = _parse_layout(layout)
        self._cores, self._out = ins, out
        self._parallel, self._shared = parallel, shared
        self._function = function
        self._signatures = signatures
        letters = {n: chr(ord("a") + i) for i, n in enumerate(sorted({d for s in (*ins, out) for d in s}))}
        sym = lambda shape: "(" + ",".join(letters[d] for d in shape) + ")"  # noqa: E731
        self._layout = ",".join(sym(s) for s in ins) + "->" + sym(out)
        self._carriers = tuple(np.empty(s) for s in ins)
        self._gufunc = None

    def __call__(self, *args: ArrayLike, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """The gufunc of ``args`` (the caller's inputs; size carriers are added here).

        ``out`` (keyword only): a writable float64 array of exactly the
        result's shape, filled and returned; it may share memory with an
        input (the result is as if it did not). Without it, results of at
        least :data:`~kreisel._compiled.outputs.RECYCLED_BYTES` are
        allocated on recycled pages (:func:`~kreisel._compiled.outputs.empty`).
        """
        batch = self._batch(args)
        shape = (*batch, *self._out)
        if out is not None:
            check_out(out, shape)
        if self._parallel is not None:
            result = self._call_parallel(args, batch, out)
            if result is not None:
                return result
        gufunc = self._gufunc
        if gufunc is None:
            # kernel and wrapper are two cache entries, the wrapper found by the kernel's symbol name: one hold of
            # the lock shared with other processes (.compile_lock) for both, so that the wrapper is the one of this
            # kernel even if the cache is emptied between the two
            with global_compiler_lock:
                gufunc = self._gufunc = guvectorize(
                    self._signatures, self._layout, nopython=True, cache=True
                )(self._function)
        if out is None:
            return gufunc(*args, *self._carriers[len(args):])
        # numpy copies an input that overlaps out before the loop
        gufunc(*args, *self._carriers[len(args):], out=out)
        return out

    def _batch(self, args):
        """Broadcast batch shape of the caller's inputs (ValueError naming the shapes if none)."""
        batches = [np.shape(a)[: np.ndim(a) - len(core)] for a, core in zip(args, self._cores)]
        first = batches[0]
        if all(b == first for b in batches):
            return first
        try:
            return np.broadcast_shapes(*batches)
        except ValueError:
            raise ValueError(
                "the inputs' batch shapes " + ", ".join(map(str, batches)) + " do not broadcast together"
            ) from None

    def _call_parallel(self, args, batch, out):
        """The parallel loop's result in ``out`` (allocated here if None), or None if the batch is small or broadcast."""
        n = math.prod(batch) if batch else 0
        if n < PARALLEL_THRESHOLD or (out is not None and not out.flags.c_contiguous):
            return None
        for index, (a, core) in enumerate(zip(args, self._cores)):
            if np.shape(a)[: np.ndim(a) - len(core)] != (() if index in self._shared else batch):
                return None
        if out is None:
            out = np.empty((*batch, *self._out))
        flat_out = out.reshape(n, *self._out)
        flat = [
            a if index in self._shared else _loop_input(a, flat_out).reshape(n, *core)
            for index, (a, core) in enumerate(zip(args, self._cores))
        ]
        self._parallel(*flat, flat_out)
        return out


def _loop_input(a, out):
    """C-contiguous writable ``a`` for a parallel loop writing ``out``.

    Each element is read whole before its result is written, so ``a`` may
    be ``out`` itself; an input overlapping ``out`` any other way is copied.
    """
    a = _writable(np.ascontiguousarray(a))
    if np.may_share_memory(a, out) and not (a.ctypes.data == out.ctypes.data and a.size == out.size):
        a = a.copy()
    return a


def _writable(a):
    return a if a.flags.writeable else a.copy()


def gufunc(signatures: list[str], layout: str, parallel: Callable[..., Any] | None = None,
           shared: tuple[int, ...] = ()) -> Callable[[Callable[..., None]], LazyGufunc]:
    """Decorator form of :class:`LazyGufunc`."""
    return lambda function: LazyGufunc(function, signatures, layout, parallel, shared)


_BIG = 1.7976931348623157e308


@cached
def checked_quat_size(q0: float, q1: float, q2: float, q3: float) -> float:
    """The size of ``q``, its largest ``|component|``, or -1 if ``q`` is not finite.

    No squares: they would overflow or underflow far from unit size. NaN
    compares false, so it is mapped to -1.
    """
    a0, a1, a2, a3 = abs(q0), abs(q1), abs(q2), abs(q3)
    if not (a0 <= _BIG and a1 <= _BIG and a2 <= _BIG and a3 <= _BIG):
        return -1.0
    return max(max(a0, a1), max(a2, a3))


@cached
def finite3(x: float, y: float, z: float) -> bool:
    """Whether ``x``, ``y`` and ``z`` are all finite."""
    return abs(x) <= _BIG and abs(y) <= _BIG and abs(z) <= _BIG


@cached
def _smallest_quat_size(flat, start, stop):
    # One pass, no temporaries: the batch checks must stay cheap next to the
    # memory-bound kernels they guard.
    smallest = np.inf
    for i in range(start, stop, 4):
        size = checked_quat_size(flat[i], flat[i + 1], flat[i + 2], flat[i + 3])
        if size < 0.0:
            return -1.0
        if size < smallest:
            smallest = size
    return smallest


@cached
def _all_finite(flat, start, stop):
    for i in range(start, stop):
        x = flat[i]
        if not (abs(x) <= 1.7976931348623157e308):
            return False
    return True


#: Length of the pieces the parallel batch checks split a flat array into
#: (a multiple of 4 and of 9 entries, so no element straddles two pieces).
_CHUNK = 36 * 4096


@generic
def in_pieces(kernel: Callable[..., None], a: NDArray[np.float64], out: NDArray[np.float64], piece: int) -> None:
    """``kernel(a, out, start, stop)`` over the pieces of ``piece`` rows of ``a``, on all cores.

    Inlined into a :data:`~kreisel._compiled.parallel` caller that names a
    module-level ``kernel`` (a routine taking a compiled function cannot be
    cached itself). ``kernel`` writes rows ``start:stop`` of ``out`` and
    reads nothing that another piece writes.
    """
    n = a.shape[0]
    for c in prange(pieces(n, piece)):
        start = c * piece
        kernel(a, out, start, min(n, start + piece))


@generic
def piece_results(kernel: Callable[..., Any], args: tuple[Any, ...], size: int, chunk: int,
                  results: NDArray[Any]) -> NDArray[Any]:
    """``results[c] = kernel(*args, start, stop)`` for the pieces ``start:stop`` of ``chunk`` of ``range(size)``, on all cores.

    The one multi-core loop over the pieces of a batch that yields a result
    per piece (a check's statistic, refusal flags). ``args`` are the
    kernel's arrays and parameters, passed as one tuple: numba inlines no
    function with ``*args``. ``results`` holds a row per piece
    (:func:`pieces`; a tuple-valued kernel fills a row of several columns);
    the caller reduces it to the batch's statistic. Inlined like
    :func:`in_pieces`.
    """
    for c in prange(results.shape[0]):
        start = c * chunk
        results[c] = kernel(*args, start, min(size, start + chunk))
    return results


@inlined
def pieces(size: int, chunk: int) -> int:
    """The number of pieces of ``chunk`` entries ``size`` entries split into."""
    return (size + chunk - 1) // chunk


@inlined
def union(flags: NDArray[np.int64]) -> int:
    """The bitwise or of refusal ``flags`` (one per piece)."""
    every = 0
    for flag in flags:
        every |= flag
    return every


@parallel
def _smallest_quat_size_parallel(flat, chunk):
    return piece_results(_smallest_quat_size, (flat,), flat.size, chunk, np.empty(pieces(flat.size, chunk))).min()


@parallel
def _all_finite_parallel(flat, chunk):
    return piece_results(_all_finite, (flat,), flat.size, chunk, np.empty(pieces(flat.size, chunk), np.bool_)).all()


def _read_only_flat(a):
    """Read-only C-contiguous 1-D view of ``a`` (a copy only if ``a`` is not contiguous).

    numba types writable and read-only arrays apart: passing every batch check
    the same kind of array keeps each compiled for one signature.
    """
    flat = np.ascontiguousarray(a).reshape(-1)
    flat.flags.writeable = False
    return flat


def _large(flat, width):
    return flat.size >= PARALLEL_THRESHOLD * width


def finite_array(x: ArrayLike, name: str, tail: tuple[int, ...] | None = (3,)) -> NDArray[np.float64]:
    """Float64 array with trailing shape ``tail`` and only finite entries (the one such check of kreisel)."""
    a = as_float_array(x, name, tail, finite=False)
    flat = _read_only_flat(a)
    width = math.prod(tail or ())
    refuse_nonfinite(_all_finite_parallel(flat, _CHUNK) if _large(flat, width) else _all_finite(flat, 0, flat.size), name)
    return a


def quaternion_array(q: ArrayLike, name: str = "q", nonzero: bool = True) -> NDArray[np.float64]:
    """Validate quaternions ``(..., 4)``: finite, and nonzero unless told otherwise.

    The norm is not required to be 1; conversions that need a rotation
    scale by ``1/|q|`` themselves.
    """
    return sized_quaternion_array(q, name, nonzero)[0]


def sized_quaternion_array(q: ArrayLike, name: str = "q", nonzero: bool = True) -> tuple[NDArray[np.float64], float]:
    """:func:`quaternion_array` and the smallest size (largest ``|component|``) in the batch, ``inf`` if empty.

    The size comes from the same pass as the checks: callers whose results
    can only overflow for tiny quaternions skip a pass over their result.
    """
    a = as_float_array(q, name, (4,), finite=False)
    if a.size == 0:
        return a, math.inf
    flat = _read_only_flat(a)
    smallest = _smallest_quat_size_parallel(flat, _CHUNK) if _large(flat, 4) else _smallest_quat_size(flat, 0, flat.size)
    refuse_quaternions(smallest, name, nonzero)
    return a, float(smallest)


def refuse_quaternions(smallest: float, name: str, nonzero: bool = True) -> None:
    """ValueError naming ``name`` if the smallest quaternion size of a batch is -1 (not finite) or 0."""
    if smallest < 0.0:
        raise ValueError(f"{name} must be finite quaternions (no NaN or inf)")
    if nonzero and not smallest > 0.0:
        raise ValueError(f"{name} must be nonzero quaternions (a zero quaternion is not a rotation)")


def refuse_nonfinite(finite: bool, name: str) -> None:
    """ValueError naming ``name`` if a batch is not all finite."""
    if not finite:
        raise ValueError(f"{name} must be finite (no NaN or inf)")


#: Elements per piece of a loop that checks its input as it computes.
CHECKED_CHUNK = 2**14


def checked_in_one_pass(inputs: tuple[NDArray[np.float64], ...], cores_out: tuple[tuple[int, ...], ...],
                        loop: Callable[..., Any], *extra: Any,
                        single: bool = False) -> tuple[tuple[NDArray[np.float64], ...], Any] | None:
    """``(results, statistic)`` of a loop that checks its inputs as it computes large new results; None if small.

    ``results`` holds a new C-ordered array per core shape of ``cores_out``
    (separate arrays, not views of one packed result: the next multi-core
    loop would have to copy strided views first).
    ``loop(*flat_inputs, *flat_results, CHECKED_CHUNK, *extra)`` runs on all
    cores over ``(n, core)`` views, computes every element (what it writes
    for one that fails its check is never seen) and returns the batch's
    check statistic. The inputs are read once instead of once to check and once to
    compute, and one multi-core loop starts instead of one per input plus
    one: the check is still done before any work the caller sees, since the
    caller refuses the batch from the statistic and the new results are then
    dropped. With ``out=`` the callers check first instead and then run the
    loop into it (:func:`checked_loop_into`). None also when the inputs'
    batch shapes differ (broadcasting), except that with ``single`` an input
    without batch axes is passed as one row ``(1, core)`` (the loop reads its
    row ``min(i, rows - 1)``).
    """
    batch = _loop_batch(inputs, single)
    if batch is None:
        return None
    n = math.prod(batch)
    results = tuple(empty((*batch, *core)) for core in cores_out)
    flat = (r.reshape(n, *core) for r, core in zip(results, cores_out))
    return results, loop(*map(loop_rows, inputs), *flat, CHECKED_CHUNK, *extra)


def checked_loop_into(out: NDArray[np.float64] | None, inputs: tuple[NDArray[np.float64], ...],
                      core_out: tuple[int, ...], loop: Callable[..., Any], *extra: Any) -> NDArray[np.float64] | None:
    """``out`` filled by a loop of :func:`checked_in_one_pass` on all cores, the inputs checked already; else None.

    Such a loop computes a piece by its fast formulas and, if the piece holds
    an awkward row, computes it again row by row from the inputs, which must
    still be intact then: it gets only an ``out`` that shares no memory with
    them (an input copied to C-ordered rows shares none). None when ``out``
    is None, overlaps an input or is not C-ordered, or when the batch is small or
    broadcast: the caller's gufunc fills ``out`` then (one row at a time, any overlap).
    ``out`` is checked here (:func:`~kreisel._compiled.outputs.check_out`).
    """
    batch = None if out is None else _loop_batch(inputs)
    if batch is None:
        return None
    check_out(out, (*batch, *core_out))
    rows = [loop_rows(a) for a in inputs]
    if not out.flags.c_contiguous or any(np.may_share_memory(a, out) for a in rows):
        return None
    loop(*rows, out.reshape(math.prod(batch), *core_out), CHECKED_CHUNK, *extra)
    return out


def _loop_batch(inputs: tuple[NDArray[np.float64], ...], single: bool = False) -> tuple[int, ...] | None:
    """The batch shape the inputs of a checked loop share if it has at least :data:`PARALLEL_THRESHOLD` rows, else None.

    With ``single``, inputs without batch axes are left out (the loop reads their one row).
    """
    batches = {a.shape[:-1] for a in inputs}
    if single and len(batches) > 1:
        batches.discard(())
    batch = batches.pop()
    return None if batches or math.prod(batch) < PARALLEL_THRESHOLD else batch


def loop_rows(a: NDArray[np.float64]) -> NDArray[np.float64]:
    """``a`` as C-ordered, writable rows ``(n, a.shape[-1])`` for a multi-core loop (a copy only if it is not).

    numba types read-only and strided arrays apart: passing every loop this
    kind of array keeps each compiled for one signature.
    """
    return _writable(np.ascontiguousarray(a)).reshape(-1, a.shape[-1])


def vector_array(v: ArrayLike, name: str, length: int = 3) -> NDArray[np.float64]:
    """Validate finite vectors ``(..., length)``."""
    return finite_array(v, name, (length,))


#: ``ROTVEC_RANGE²``: a rotation vector is accepted when its squared length is at most this (NaN,
#: inf and squares that overflow are not), so one comparison per vector checks both.
_ROTVEC_RANGE_SQUARED = ROTVEC_RANGE * ROTVEC_RANGE


@cached
def rotvec_in_range(x: float, y: float, z: float) -> bool:
    """Whether ``(x, y, z)`` is finite and at most :data:`~kreisel._validation.ROTVEC_RANGE` long."""
    return x * x + y * y + z * z <= _ROTVEC_RANGE_SQUARED


@cached
def _rotvecs_in_range(flat, start, stop):
    # no early exit: the loop vectorises, and a refused batch is rare
    ok = True
    for i in range(start, stop, 3):
        ok &= rotvec_in_range(flat[i], flat[i + 1], flat[i + 2])
    return ok


@parallel
def _rotvecs_in_range_parallel(flat, chunk):
    return piece_results(_rotvecs_in_range, (flat,), flat.size, chunk, np.empty(pieces(flat.size, chunk), np.bool_)).all()


def rotvec_array(psi: ArrayLike, name: str, what: str = "|psi|") -> NDArray[np.float64]:
    """Validate rotation vectors ``(..., 3)``: finite and at most ``ROTVEC_RANGE`` long (the one such check).

    A rotation depends on its vector's length modulo 2π, which rounding no
    longer determines beyond :data:`~kreisel._validation.ROTVEC_RANGE`.
    """
    a = as_float_array(psi, name, (3,), finite=False)
    flat = _read_only_flat(a)
    ok = _rotvecs_in_range_parallel(flat, _CHUNK) if _large(flat, 3) else _rotvecs_in_range(flat, 0, flat.size)
    if not ok:
        refuse_rotvecs(a, name, what)
    return a


def refuse_rotvecs(psi: NDArray[np.float64], name: str, what: str = "|psi|") -> None:
    """The refusal of a batch of rotation vectors that failed :func:`rotvec_in_range` (ValueError naming ``name``)."""
    refuse_nonfinite(bool(np.isfinite(psi).all()), name)
    refuse_long_angle(float(np.max(norm(psi), initial=0.0)), name, what)


@cached
def _orthogonality_defect(flat, start, stop):
    # Largest |RᵀR - 1| entry and smallest determinant over flat[start:stop].
    # max() and min() may drop NaN, so the sum of all defects (NaN or inf
    # for any non-finite entry) rides along and flags the batch instead.
    worst = 0.0
    total = 0.0
    smallest_det = np.inf
    for s in range(start, stop, 9):
        a, b, c = flat[s], flat[s + 1], flat[s + 2]
        d, e, f = flat[s + 3], flat[s + 4], flat[s + 5]
        g, h, i = flat[s + 6], flat[s + 7], flat[s + 8]
        d00 = abs(a * a + d * d + g * g - 1.0)
        d11 = abs(b * b + e * e + h * h - 1.0)
        d22 = abs(c * c + f * f + i * i - 1.0)
        d01 = abs(a * b + d * e + g * h)
        d02 = abs(a * c + d * f + g * i)
        d12 = abs(b * c + e * f + h * i)
        total += d00 + d11 + d22 + d01 + d02 + d12
        worst = max(worst, max(max(max(d00, d11), max(d22, d01)), max(d02, d12)))
        det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
        smallest_det = min(smallest_det, det)
    if not (abs(total) <= 1.7976931348623157e308):
        return np.inf, -np.inf
    return worst, smallest_det


@parallel
def _orthogonality_defect_parallel(flat, chunk):
    defects = piece_results(_orthogonality_defect, (flat,), flat.size, chunk, np.empty((pieces(flat.size, chunk), 2)))
    return defects[:, 0].max(), defects[:, 1].min()


def matrix_array(R: ArrayLike, name: str = "R", tolerance: float = ORTHOGONALITY_TOLERANCE) -> NDArray[np.float64]:
    """Validate rotation matrices ``(..., 3, 3)``; project nearly orthogonal ones.

    Matrices with det <= 0, non-finite entries or an orthogonality defect
    ``max |RᵀR - 1|`` above ``tolerance`` raise ``ValueError``. If the defect
    is above rounding level but within ``tolerance``, the batch is replaced by
    its nearest rotations (:func:`nearest_rotation`).
    """
    a = as_float_array(R, name, (3, 3), finite=False)
    if a.size == 0:
        return a
    flat = _read_only_flat(a)
    if _large(flat, 9):
        worst, smallest_det = _orthogonality_defect_parallel(flat, _CHUNK)
    else:
        worst, smallest_det = _orthogonality_defect(flat, 0, flat.size)
    return checked_rotation_matrices(a, name, float(worst), float(smallest_det), tolerance)
