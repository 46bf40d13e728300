"""Output arrays of kreisel's array functions: caller-owned ``out=`` buffers and recycled large ones.

Every array function of :mod:`kreisel.so3`, :mod:`kreisel.kinematics` and
:mod:`kreisel.se3` takes ``out=`` (checked by :func:`check_out`, documented
by :func:`takes_out`). Without it, the result is a new array from :func:`empty`.

Why large results are recycled
------------------------------
glibc's ``malloc`` serves a block above its mmap threshold (at most 32 MiB)
with a fresh ``mmap`` and unmaps it on ``free``. numpy allocates arrays with
``malloc``, so a 10^6-rotation result of 72 MB (matrices) or 128 MB (4×4
poses) arrives as untouched pages every call, and the first write to each
page faults it in: the kernel zeroes it and, in a virtual machine whose free
memory has been returned to the host, the host maps it again. That costs far
more than the computation (quat → matrix: ~5 ms of compiled loop, 30–500 ms
of faults depending on where the pages come from, worst with numpy's
transparent huge pages taken from memory the host has reclaimed). Smaller
blocks stay in malloc's heap after the first ``free`` and are reused with
their pages already mapped.

So results of at least :data:`RECYCLED_BYTES` come from a pool of slabs that
kreisel keeps mapped: the returned array is a view of a slab whose base
object gives the slab back to the pool when the last view of it dies.
At most :data:`IDLE_BYTES` of unused slabs are kept (the most recently
released); the rest go back to the operating system as usual.

The trade-off: memory the program no longer uses stays with the process.
256 MiB holds the slabs of a loop that alternates the largest common results
of a batch of 10^6 (72 MB of rotation matrices and 128 MB of 4×4 poses), so
such a loop never faults its results in again; a smaller cap would drop one of
them at every turn. :func:`release_memory` gives the idle slabs back at once,
e.g. after the heavy part of a program (the next large result then maps fresh
pages again), and assigning ``IDLE_BYTES = 0`` keeps none.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable
from typing import Any, TypeVar, overload

import numpy as np
from numpy.typing import DTypeLike, NDArray

_Result = TypeVar("_Result", bound=NDArray[Any])
_Out = TypeVar("_Out")
_Function = TypeVar("_Function", bound=Callable[..., Any])

#: Results of at least this many bytes come from the pool (glibc's largest mmap threshold).
RECYCLED_BYTES = 32 * 2**20
#: Unused slabs kept mapped for the next large result, in bytes.
IDLE_BYTES = 256 * 2**20

_lock = threading.RLock()  # re-entrant: a result may die (and release its slab) inside the pool's own code
#: Unused slabs (1-D float64 arrays), most recently released last.
_idle: list[NDArray[np.float64]] = []


def _release(slab: NDArray[np.float64]) -> None:
    with _lock:
        _idle.append(slab)
        kept = 0
        for index in range(len(_idle) - 1, -1, -1):
            kept += _idle[index].nbytes
            if kept > IDLE_BYTES:
                del _idle[: index + 1]
                break


def _take(size: int) -> NDArray[np.float64] | None:
    """An unused slab of ``size`` to ``size * 5/4`` doubles (the closest fit), or None."""
    with _lock:
        fits = [slab for slab in _idle if size <= slab.size <= size + size // 4]
        if not fits:
            return None
        best = min(fits, key=lambda slab: slab.size)
        for index, slab in enumerate(_idle):
            if slab is best:
                del _idle[index]
                break
        return best


def release_memory() -> int:
    """Give the idle memory kept for large results back to the operating system.

    Array functions of :mod:`kreisel.so3`, :mod:`kreisel.kinematics` and
    :mod:`kreisel.se3` place results of at least 32 MiB (e.g. 10^6 rotation
    matrices) on memory that kreisel reuses once the result is gone, since
    mapping fresh pages for every such result can cost several times the
    computation. Up to 256 MiB of it may stay with the process while unused
    (see :ref:`out-arrays`); this frees it now. Results still alive are not
    affected, and their memory is kept for reuse when they die.

    Returns
    -------
    int
        The number of bytes released.

    Examples
    --------
    >>> import numpy as np
    >>> import kreisel as kr
    >>> R = kr.quat_to_matrix(np.tile([1.0, 0.0, 0.0, 0.0], (500_000, 1)))  # 36 MB
    >>> del R                                   # its memory waits for the next large result
    >>> kr.release_memory() >= 36_000_000
    True
    >>> kr.release_memory()
    0
    """
    with _lock:
        released = sum(slab.nbytes for slab in _idle)
        _idle.clear()
    return released


class _Lease:
    """Base object of a recycled result: holds its slab and returns it when the result dies."""

    __slots__ = ("_slab", "__array_interface__")

    def __init__(self, slab: NDArray[np.float64], shape: tuple[int, ...]) -> None:
        self._slab = slab
        self.__array_interface__ = {"shape": shape, "typestr": "<f8", "data": (slab.ctypes.data, False), "version": 3}

    def __del__(self, release: Callable[[NDArray[np.float64]], None] = _release) -> None:  # bound now: module globals may be gone at interpreter exit
        release(self._slab)


def empty(shape: tuple[int, ...]) -> NDArray[np.float64]:
    """A new float64 array of ``shape``; recycled pages when it has at least :data:`RECYCLED_BYTES`."""
    size = math.prod(shape)
    if 8 * size < RECYCLED_BYTES:
        return np.empty(shape)
    slab = _take(size)
    if slab is None:
        slab = np.empty(size)
    return np.asarray(_Lease(slab, tuple(shape)))


def check_out(out: _Out, shape: tuple[int, ...], dtype: DTypeLike = np.float64, name: str = "out") -> _Out:
    """Refuse an ``out=`` that is not a writable ndarray of exactly ``shape`` and ``dtype``; return it.

    Raises
    ------
    TypeError
        ``out`` is not a numpy array, or has another dtype.
    ValueError
        Wrong shape, or read-only.
    """
    dtype = np.dtype(dtype)
    if not isinstance(out, np.ndarray):
        raise TypeError(f"{name} must be a numpy array ({dtype}, shape {tuple(shape)}), got {type(out).__name__}")
    if out.dtype != dtype:
        raise TypeError(f"{name} must have dtype {dtype}, got {out.dtype}")
    if out.shape != tuple(shape):
        raise ValueError(f"{name} must have shape {tuple(shape)}, got {out.shape}")
    if not out.flags.writeable:
        raise ValueError(f"{name} must be writable (it is read-only)")
    return out


def deliver(result: _Result, out: _Result | None, name: str = "out") -> _Result:
    """``result``, or ``result`` copied into a checked ``out`` of its shape and dtype, which is returned.

    For array functions not built on a gufunc: they compute into a new array
    first, so ``out`` may share memory with any input.
    """
    if out is None:
        return result
    result = np.asarray(result)
    check_out(out, result.shape, result.dtype, name)
    np.copyto(out, result)
    return out


#: What the ``out`` entry of a docstring says unless :func:`takes_out` is told otherwise.
OUT_RESULT = "Result array, may share memory with an input"
#: The first line of every ``out`` entry.
OUT_HEADER = "out : ndarray, optional"
#: How every ``out`` entry ends: the keyword-only rule and the reference page.
OUT_REFERENCE = "(keyword only; :ref:`out-arrays`)."


def out_entry(result: str = OUT_RESULT, indent: str = "") -> str:
    """The numpydoc ``out`` entry saying ``result`` (lines may be broken with ``\n``), indented by ``indent``."""
    lines = f"{result} {OUT_REFERENCE}".split("\n")
    return "\n".join([indent + OUT_HEADER] + [f"{indent}    {line}" for line in lines])


def with_out_entry(doc: str, result: str = OUT_RESULT) -> str:
    """``doc`` with the ``out`` entry last in its Parameters section, which is created before the first
    section when there is none.

    Plain ``str.find`` (this runs at import for every array function, a few µs each): numpydoc sections
    are found by their dashed underlines, whose indentation the entry takes, so it fits a docstring as
    written in the source and as Python 3.13 stores it (common indentation removed).
    """
    rule = doc.find("---")
    line = doc.rfind("\n", 0, rule) + 1
    indent = doc[line:rule]
    if rule < 0 or line == 0 or indent.strip():
        raise ValueError("a docstring with out= needs numpydoc sections (at least Examples)")
    entry = out_entry(result, indent)
    parameters = doc.find(f"\n{indent}Parameters\n{indent}---")
    if parameters < 0:
        first = doc.rfind("\n", 0, line - 1) + 1  # the title line of the first section
        return f"{doc[:first]}{indent}Parameters\n{indent}----------\n{entry}\n\n{doc[first:]}"
    start = doc.find("\n", parameters + 2 * len(indent) + 14)  # the end of the underline
    following = doc.find(f"\n{indent}---", start)
    end = len(doc) if following < 0 else doc.rfind("\n", 0, following)  # before the next section's title
    if f"\n{indent}out :" in doc[start:end]:
        raise ValueError("the out entry is written by takes_out: remove the one typed in the docstring")
    at = start + len(doc[start:end].rstrip())  # after the last entry, before the blank lines that end the section
    return f"{doc[:at]}\n{entry}{doc[at:]}"


@overload
def takes_out(function: _Function, /) -> _Function: ...
@overload
def takes_out(*, result: str) -> Callable[[_Function], _Function]: ...
def takes_out(function: _Function | None = None, /, *, result: str = OUT_RESULT) -> Any:
    """Mark an array function or method as taking a keyword-only ``out=None`` and document it there.

    Adds the one standard ``out`` entry (:func:`out_entry`) to the Parameters section of its docstring,
    so that no docstring types it out by hand. ``@takes_out(result="...")`` says what the result array
    is where the standard words do not fit. The function itself is returned unchanged.

    Raises
    ------
    TypeError
        The function has no keyword-only ``out`` defaulting to None.
    """

    def document(function: _Function) -> _Function:
        if (function.__kwdefaults__ or {}).get("out", ...) is not None:
            raise TypeError(f"{function.__qualname__} takes no keyword-only out=None")
        if function.__doc__ is not None:  # None under python -OO
            function.__doc__ = with_out_entry(function.__doc__, result)
        return function

    return document if function is None else document(function)
