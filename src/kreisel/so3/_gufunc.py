"""Lazily compiled generalized ufuncs and the input checks they rely on.

Every compiled operation of :mod:`kreisel.so3` is a per-element kernel
broadcast by :func:`numba.guvectorize`. Building a gufunc with explicit
signatures compiles (or loads from the on-disk cache) immediately, so the
gufuncs are built on first call instead: ``import kreisel`` stays light and
each operation pays its ~10 ms cache load only when it is used.
"""

from __future__ import annotations

import numpy as np
from numba import guvectorize, njit

from .._validation import as_float_array

#: Nearly orthogonal matrices (max |RᵀR - 1| below this) are projected onto
#: SO(3); farther ones are refused as "not a rotation".
ORTHOGONALITY_TOLERANCE = 1e-6


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
    """

    __slots__ = ("_function", "_signatures", "_layout", "_carriers", "_gufunc")

    def __init__(self, function, signatures, layout):
        ins, out = _parse_layout(layout)
        self._function = function
        self._signatures = signatures
        letters = {n: chr(ord("a") + i) for i, n in enumerate(sorted({d for s in (*ins, out) for d in s}))}
        sym = lambda shape: "(" + ",".join(letters[d] for d in shape) + ")"  # noqa: E731
        self._layout = ",".join(sym(s) for s in ins) + "->" + sym(out)
        self._carriers = tuple(np.empty(s) for s in ins)
        self._gufunc = None

    def __call__(self, *args):
        gufunc = self._gufunc
        if gufunc is None:
            gufunc = self._gufunc = guvectorize(
                self._signatures, self._layout, nopython=True, cache=True
            )(self._function)
        return gufunc(*args, *self._carriers[len(args):])


def gufunc(signatures, layout):
    """Decorator form of :class:`LazyGufunc`."""
    return lambda function: LazyGufunc(function, signatures, layout)


@njit(cache=True, nogil=True)
def _smallest_quat_norm2(flat):
    # One pass, no temporaries: the batch checks must stay cheap next to the
    # memory-bound kernels they guard. NaN compares false, so it is mapped to -1.
    smallest = np.inf
    for i in range(0, flat.size, 4):
        n2 = flat[i] * flat[i] + flat[i + 1] * flat[i + 1] + flat[i + 2] * flat[i + 2] + flat[i + 3] * flat[i + 3]
        if not (n2 <= 1.7e308):
            return -1.0
        if n2 < smallest:
            smallest = n2
    return smallest


@njit(cache=True, nogil=True)
def _all_finite(flat):
    for i in range(flat.size):
        x = flat[i]
        if not (abs(x) <= 1.7976931348623157e308):
            return False
    return True


def finite_array(x, name, tail):
    """Float64 array with trailing shape ``tail`` and only finite entries."""
    a = as_float_array(x, name, tail, finite=False)
    if not _all_finite(a.reshape(-1)):
        raise ValueError(f"{name} must be finite (no NaN or inf)")
    return a


def quaternion_array(q, name="q", nonzero=True):
    """Validate quaternions ``(..., 4)``: finite, and nonzero unless told otherwise.

    The norm is not required to be 1; conversions that need a rotation
    scale by ``1/|q|`` themselves.
    """
    a = as_float_array(q, name, (4,), finite=False)
    if a.size == 0:
        return a
    smallest = _smallest_quat_norm2(np.ascontiguousarray(a).reshape(-1))
    if smallest < 0.0:
        raise ValueError(f"{name} must be finite quaternions (no NaN or inf)")
    if nonzero and not smallest > 1e-300:
        raise ValueError(f"{name} must be nonzero quaternions (a zero quaternion is not a rotation)")
    return a


def vector_array(v, name, length=3):
    """Validate finite vectors ``(..., length)``."""
    return finite_array(v, name, (length,))


@njit(cache=True, nogil=True)
def _orthogonality_defect(flat):
    # Largest |RᵀR - 1| entry and smallest determinant over the batch.
    worst = 0.0
    smallest_det = np.inf
    for s in range(0, flat.size, 9):
        for j in range(3):
            for k in range(j, 3):
                d = flat[s + j] * flat[s + k] + flat[s + 3 + j] * flat[s + 3 + k] + flat[s + 6 + j] * flat[s + 6 + k]
                if j == k:
                    d -= 1.0
                d = abs(d)
                if not (d <= worst):
                    worst = d if d == d else np.inf
        det = (
            flat[s] * (flat[s + 4] * flat[s + 8] - flat[s + 5] * flat[s + 7])
            - flat[s + 1] * (flat[s + 3] * flat[s + 8] - flat[s + 5] * flat[s + 6])
            + flat[s + 2] * (flat[s + 3] * flat[s + 7] - flat[s + 4] * flat[s + 6])
        )
        if not (det >= smallest_det):
            smallest_det = det if det == det else -np.inf
    return worst, smallest_det


#: Defects below this are rounding noise of a rotation and pass untouched.
_ROUNDING_DEFECT = 1e-13


def nearest_rotation(M):
    """Nearest rotation matrix (Frobenius norm) to each ``(..., 3, 3)`` matrix.

    ``U diag(1, 1, det(U Vᵀ)) Vᵀ`` from the SVD ``M = U S Vᵀ`` — the special
    orthogonal polar factor (Kabsch).
    """
    U, _, Vt = np.linalg.svd(M)
    d = np.sign(np.linalg.det(U @ Vt))
    U[..., :, 2] *= d[..., None]
    return U @ Vt


def matrix_array(R, name="R", tolerance=ORTHOGONALITY_TOLERANCE):
    """Validate rotation matrices ``(..., 3, 3)``; project nearly orthogonal ones.

    Matrices with det <= 0, non-finite entries or an orthogonality defect
    ``max |RᵀR - 1|`` above ``tolerance`` raise ``ValueError``. If the defect
    is above rounding level but within ``tolerance``, the batch is replaced by
    its nearest rotations (:func:`nearest_rotation`).
    """
    a = as_float_array(R, name, (3, 3), finite=False)
    if a.size == 0:
        return a
    worst, smallest_det = _orthogonality_defect(np.ascontiguousarray(a).reshape(-1))
    if not np.isfinite(worst) or not np.isfinite(smallest_det):
        raise ValueError(f"{name} must be finite rotation matrices (no NaN or inf)")
    if smallest_det <= 0.0:
        raise ValueError(f"{name} must be rotation matrices with det > 0 (got det = {smallest_det:.3g})")
    if worst > tolerance:
        raise ValueError(
            f"{name} must be rotation matrices: max |R^T R - 1| = {worst:.3g} exceeds {tolerance:g} "
            "(use orthonormalize for a larger projection)"
        )
    if worst > _ROUNDING_DEFECT:
        a = nearest_rotation(a)
    return a
