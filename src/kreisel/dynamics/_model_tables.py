"""What torque and force models share: rows of floats, sums, callbacks and the compiled sum.

A model is encoded as rows of a small float table (``row[0]`` the kind,
``row[1:]`` its parameters) that the compiled integrators read inside their
time loop; models of one family add with ``+`` into a flat sum. Each family
gives the contribution of one row as a compiled *term*; :func:`sum_rows`
adds the terms (and the Python callables, kind :data:`CALLBACK`) into three
slots of the integrators' scratch array.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from typing import Any, Generic, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray
from numba import njit, objmode

from .._compiled import generic

ROW_SIZE = 10
CALLBACK = -1  # the kind of a row that calls a registered Python function (the same in every family)

# a family's sum class: to type checkers a model plus a model of its family is that family's sum
_Sum = TypeVar("_Sum", bound="RowSum")
_Function = TypeVar("_Function", bound=Callable[..., Any])
# a family's compiled term: (rows, i, q0, q1, q2, q3, y) -> the row's contribution, three scalars
_Term = Callable[[NDArray[np.float64], int, float, float, float, float, NDArray[np.float64]], tuple[float, float, float]]


def row(kind: int, *vectors: ArrayLike) -> NDArray[np.float64]:
    """One table row ``(1, ROW_SIZE)``: the kind, then the flattened parameter vectors."""
    r = np.zeros(ROW_SIZE)
    r[0] = kind
    flat = np.concatenate([np.ravel(v) for v in vectors]) if vectors else np.zeros(0)
    r[1:1 + flat.size] = flat
    return r[None, :]


def in_principal_axes(rows: NDArray[np.float64], axes: NDArray[np.float64] | None, vector_kinds: tuple[int, ...],
                      matrix_kinds: tuple[int, ...] = ()) -> NDArray[np.float64]:
    """``rows`` with their body parameters in principal axes, ``a_principal = axesᵀ a_body``.

    Rows of ``vector_kinds`` hold a body vector in ``row[1:4]``, rows of
    ``matrix_kinds`` a body matrix in ``row[1:10]``; ``axes=None`` (the body
    axes are principal) returns ``rows`` itself.
    """
    if axes is None:
        return rows
    out = rows.copy()
    for r in out:
        kind = int(r[0])
        if kind in vector_kinds:
            r[1:4] = axes.T @ r[1:4]
        elif kind in matrix_kinds:
            r[1:10] = (axes.T @ r[1:10].reshape(3, 3) @ axes).ravel()
    return out


class RowModel(Generic[_Sum]):
    """Base of a model family; subclasses set ``_sum`` to the family's sum class."""

    _sum: type[_Sum]

    def rows(self) -> NDArray[np.float64]:
        """The model's table rows (body vectors in body coordinates), shape ``(k, ROW_SIZE)``."""
        raise NotImplementedError

    def __add__(self, other: RowModel[_Sum]) -> _Sum:
        family = self._sum.family
        if not (isinstance(self, family) and isinstance(other, family)):
            return NotImplemented
        return self._sum(self, other)


class RowSum:
    """Flat sum of models of the family ``family`` (named ``noun`` in messages)."""

    family: type[RowModel[Any]]
    noun = ""
    models: tuple[RowModel[Any], ...]

    def __init__(self, *models: RowModel[Any]) -> None:
        flat: list[RowModel[Any]] = []
        for m in models:
            if not isinstance(m, self.family):
                raise TypeError(f"{type(self).__name__} takes {self.noun} models, got {type(m).__name__}")
            flat.extend(m.models if isinstance(m, RowSum) else [m])
        self.models = tuple(flat)

    def rows(self) -> NDArray[np.float64]:
        if not self.models:
            return np.zeros((0, ROW_SIZE))
        return np.concatenate([m.rows() for m in self.models])


# Python callables are looked up by id from the compiled loop: a table row
# carries only numbers, so the registry maps that number back to the function
# and to whether it also takes the centre of mass position and velocity.
_CALLBACKS: dict[int, tuple[Callable[..., ArrayLike], bool]] = {}
_IDS = itertools.count(1)


def register_callback(function: Callable[..., ArrayLike], translation: bool = False) -> NDArray[np.float64]:
    """Store a model callable; return its :data:`CALLBACK` table row.

    ``function(t, q, omega_body)``, or with ``translation=True``
    ``function(t, q, omega_body, position, velocity)``, returns a (3,) vector.
    """
    key = next(_IDS)
    _CALLBACKS[key] = (function, translation)
    return row(CALLBACK, [key])


def release_callback(rows: NDArray[np.float64] | None) -> None:
    """Forget the callables of a table's :data:`CALLBACK` rows."""
    if rows is None:
        return
    for r in rows:
        if int(r[0]) == CALLBACK:
            _CALLBACKS.pop(int(r[1]), None)


def _call_registered(key: float, t: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
    function, translation = _CALLBACKS[int(key)]
    args: tuple[Any, ...] = (t, y[3:7] / np.linalg.norm(y[3:7]), y[0:3].copy())
    if translation:
        args += (y[7:10].copy(), y[10:13].copy())
    return np.ascontiguousarray(function(*args), dtype=np.float64)


# object mode holds the GIL, so not the nogil flavour (typed as kreisel._compiled types its flavours)
_with_gil: Callable[[_Function], _Function] = njit(cache=True)


@_with_gil
def _callback_into(key: float, t: float, y: NDArray[np.float64], scratch: NDArray[np.float64], at: int) -> None:
    with objmode(r="float64[:]"):
        r = _call_registered(key, t, y)
    scratch[at] += r[0]
    scratch[at + 1] += r[1]
    scratch[at + 2] += r[2]


# takes the family's ``term`` as an argument: inlined into a cached kernel of each family,
# for the reason given in kreisel._compiled.dop853 (a compiled function argument cannot be cached)
@generic
def sum_rows(term: _Term, rows: NDArray[np.float64], t: float, y: NDArray[np.float64], scratch: NDArray[np.float64],
             at: int) -> None:
    """``scratch[at:at+3]`` = Σ ``term(rows, i, q, y)`` over the rows, then the callables' values.

    ``y = (ω′, q, ...)``; ``term`` gets the unit attitude as four scalars
    (stage states of explicit Runge-Kutta methods are not exactly unit) and
    returns three scalars; it returns zeros for kinds it does not know.
    """
    n = rows.shape[0]
    s0 = 0.0
    s1 = 0.0
    s2 = 0.0
    if n > 0:
        norm = math.sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6])
        q0, q1, q2, q3 = y[3] / norm, y[4] / norm, y[5] / norm, y[6] / norm
        for i in range(n):
            a0, a1, a2 = term(rows, i, q0, q1, q2, q3, y)
            s0 += a0
            s1 += a1
            s2 += a2
    scratch[at] = s0
    scratch[at + 1] = s1
    scratch[at + 2] = s2
    for i in range(n):
        if int(rows[i, 0]) == CALLBACK:
            _callback_into(rows[i, 1], t, y, scratch, at)
