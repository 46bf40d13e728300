"""Output arrays of kreisel's array functions: caller-owned ``out=`` buffers.

Every array function of :mod:`kreisel.so3`, :mod:`kreisel.kinematics` and
:mod:`kreisel.se3` takes ``out=`` (checked by :func:`check_out`, documented
by :func:`takes_out`). Without it, the result is a new numpy array.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar, overload

import numpy as np
from numpy.typing import DTypeLike, NDArray

_Result = TypeVar("_Result", bound=NDArray[Any])
_Out = TypeVar("_Out")
_Function = TypeVar("_Function", bound=Callable[..., Any])


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

    For array functions that are not declared operations: they compute into a new array
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
