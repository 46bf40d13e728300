"""Rotation vectors, generators and the exponential map (Theory §2.2).

The rotation vector ψ = ψ n (the chapter's "Rodrigues parameters" or angular
displacement) parametrises ``R(ψ) = exp(ψ_j X_j)`` with the generators
``X_j`` of Theory §2.2 (2), ``(X_j)_kl = -ε_jkl``. Logarithms return |ψ| <= π.
"""

from __future__ import annotations

import copy
import functools
import math
from fractions import Fraction

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import kernels
from .._compiled.checks import (
    DIRECTION, MATRIX, QUATERNION, ROTVEC, VECTOR, rotation_vector, rotvec_array, vector_array,
)
from .._compiled.elementwise import ArrayOperation, Input, declare, elementwise, kernel, uses
from .._compiled.outputs import deliver, takes_out
from .._validation import as_float_array, check_flag
from .._norms import norm

__all__ = [
    "generators",
    "hat",
    "vee",
    "rotvec_to_matrix",
    "matrix_to_rotvec",
    "rotvec_to_quat",
    "quat_to_rotvec",
    "rotvec_to_axis_angle",
    "axis_angle_to_rotvec",
    "compose_rotvec",
    "bch",
    "adjoint_action",
]


@kernel
def _hat(x: float, y: float, z: float) -> tuple[float, ...]:
    return 0.0, -z, y, z, 0.0, -x, -y, x, 0.0


@kernel
def _vee(a00: float, a01: float, a02: float, a10: float, a11: float, a12: float, a20: float, a21: float,
         a22: float) -> tuple[float, float, float]:
    return 0.5 * (a21 - a12), 0.5 * (a02 - a20), 0.5 * (a10 - a01)


@kernel
def _rotvec_matrix(x: float, y: float, z: float) -> tuple[float, ...]:
    q0, q1, q2, q3 = kernels.rotvec_quat_in_range(x, y, z)
    return kernels.quat_matrix(q0, q1, q2, q3)


@kernel
def _matrix_rotvec(r00: float, r01: float, r02: float, r10: float, r11: float, r12: float, r20: float, r21: float,
                   r22: float) -> tuple[float, float, float]:
    q0, q1, q2, q3 = kernels.matrix_entries_quat(r00, r01, r02, r10, r11, r12, r20, r21, r22)
    return kernels.quat_rotvec(q0, q1, q2, q3)


@kernel
def _axis_angle_rotvec(x: float, y: float, z: float, angle: float) -> tuple[float, float, float]:
    # the axis divided by its largest |component| first, so that no square over- or underflows
    m = max(max(abs(x), abs(y)), abs(z))
    x, y, z = x / m, y / m, z / m
    n = math.sqrt(x * x + y * y + z * z)
    return x / n * angle, y / n * angle, z / n * angle


@kernel
def _compose(ax: float, ay: float, az: float, bx: float, by: float, bz: float) -> tuple[float, float, float]:
    p0, p1, p2, p3 = kernels.rotvec_quat_in_range(ax, ay, az)
    q0, q1, q2, q3 = kernels.rotvec_quat_in_range(bx, by, bz)
    r0, r1, r2, r3 = kernels.quat_product(p0, p1, p2, p3, q0, q1, q2, q3)
    return kernels.quat_rotvec(r0, r1, r2, r3)


@kernel
def _adjoint(q00: float, q01: float, q02: float, q10: float, q11: float, q12: float, q20: float, q21: float,
             q22: float, x: float, y: float, z: float) -> tuple[float, float, float]:
    return q00 * x + q01 * y + q02 * z, q10 * x + q11 * y + q12 * z, q20 * x + q21 * y + q22 * z


_PSI = Input("psi", (3,), ROTVEC)
_R = Input("R", (3, 3), MATRIX)


@takes_out(result="Result array of shape (3, 3, 3)")
def generators(*, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """The generators ``X_1, X_2, X_3`` of Theory §2.2 (2), shape (3, 3, 3).

    ``(X_j)_kl = -ε_jkl``; ``[X_j, X_k] = ε_jkl X_l`` and ``R(ψ) = exp(ψ_j X_j)``.

    Examples
    --------
    >>> generators()[2] + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  0.]])
    """
    return hat(np.eye(3), out=out)


@elementwise(_hat, [Input("v", (3,), VECTOR)], (3, 3))
def hat(v: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Skew matrix ``v·X`` with ``hat(v) w = v × w`` (the matrix A of Theory §2.2 (3)).

    Parameters
    ----------
    v : array_like, shape (..., 3)
        Vectors.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        Antisymmetric matrices.

    Examples
    --------
    >>> hat([1.0, 2.0, 3.0])
    array([[ 0., -3.,  2.],
           [ 3.,  0., -1.],
           [-2.,  1.,  0.]])
    """


@elementwise(_vee, [Input("A", (3, 3), VECTOR)], (3,))
def vee(A: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse of :func:`hat`: the vector of the skew part of ``A``.

    Uses ``(A - Aᵀ)/2``, so a matrix that is skew up to rounding maps to the
    nearest vector.

    Parameters
    ----------
    A : array_like, shape (..., 3, 3)
        Skew (or nearly skew) matrices.

    Examples
    --------
    >>> vee(hat([1.0, 2.0, 3.0]))
    array([1., 2., 3.])
    """


@elementwise(_rotvec_matrix, [_PSI], (3, 3))
def rotvec_to_matrix(psi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Exponential map ``R(ψ) = exp(ψ·X)`` (Theory §2.2 (3), Rodrigues' formula).

    Evaluated through the half-angle quaternion so that every entry is
    accurate to rounding for all |ψ| (series for sin(ψ/2)/ψ below 1e-4).
    ``R(2π n) = 1``.

    Parameters
    ----------
    psi : array_like, shape (..., 3)
        Rotation vectors, at most ``ROTVEC_RANGE`` = 1e8 rad long (longer
        ones are refused: see :func:`rotvec_to_quat`).

    Returns
    -------
    ndarray, shape (..., 3, 3)
        R(ψ), orthogonal to rounding.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(rotvec_to_matrix([np.pi / 2, 0.0, 0.0]), 12) + 0.0
    array([[ 1.,  0.,  0.],
           [ 0.,  0., -1.],
           [ 0.,  1.,  0.]])
    """


@elementwise(_matrix_rotvec, [_R], (3,))
def matrix_to_rotvec(R: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Logarithm ``ψ = log R`` with |ψ| <= π.

    Shepperd's quaternion followed by ψ = 2 atan2(|v|, q0): no loss of
    digits at ψ → 0 or ψ → π (unlike arccos((tr R - 1)/2)). At exactly
    ψ = π both ±ψ are logarithms; the sign follows the extracted quaternion.

    Examples
    --------
    >>> matrix_to_rotvec(np.diag([1.0, -1.0, -1.0]))
    array([3.14159265, 0.        , 0.        ])
    """


_exp = declare(kernels.rotvec_quat_in_range, [_PSI], (4,), name="rotvec_to_quat")


@uses(_exp)
@takes_out
def rotvec_to_quat(psi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Quaternion exponential ``q = (cos(ψ/2), n sin(ψ/2))`` (Theory §A (4)).

    No sign flip: ψ = 2π n gives ``q = -1`` — the double cover SU(2) → SO(3).

    The result depends on |ψ| modulo 4π, and |ψ| is computed with a rounding
    error of about 1.1e-16 |ψ|: rotation vectors longer than ``ROTVEC_RANGE``
    = 1e8 rad (error 1e-8 rad; beyond ~6e16 rad it would exceed 2π) are
    refused with a ValueError. Reduce such an angle modulo 2π first (to
    |ψ| <= π: the same rotation) — in the precision it is known in.

    Parameters
    ----------
    psi : array_like, shape (..., 3)
        Rotation vectors, at most 1e8 rad long.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(rotvec_to_quat([0.0, 0.0, 2 * np.pi]), 12) + 0.0
    array([-1.,  0.,  0.,  0.])
    """
    return _exp(psi, out=out)


def exp_quat(psi: ArrayLike, name: str, out: NDArray[np.float64] | None = None, what: str = "|psi|") -> NDArray[np.float64]:
    """:func:`rotvec_to_quat` of the argument ``name``, refused naming it and ``what`` its length is."""
    return _exp_refusing(name, what)(psi, out=out)


@functools.cache
def _exp_refusing(name: str, what: str) -> ArrayOperation:
    """:func:`rotvec_to_quat`'s operation refusing its input as ``name``, its length as ``what``."""
    operation = copy.copy(_exp)  # the compiled loops shared, as by ArrayOperation.renamed
    operation.inputs = (Input(name, (3,), rotation_vector(what)),)
    return operation


@elementwise(kernels.quat_rotvec, [Input("q", (4,), QUATERNION)], (3,))
def quat_to_rotvec(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Logarithm of nonzero quaternions as rotation vectors with |ψ| <= π.

    ``q`` and ``-q`` give the same ψ; ψ = 2 atan2(|v|, |q0|) is accurate at
    every angle.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Scalar-first quaternions, need not be unit.

    Examples
    --------
    >>> quat_to_rotvec([0.0, 0.0, 0.0, 1.0])
    array([0.        , 0.        , 3.14159265])
    """


def rotvec_to_axis_angle(psi: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Split ψ = ψ n into the unit axis ``n`` and the angle ``ψ >= 0``.

    For ψ = 0 the axis is arbitrary and reported as ``[0, 0, 1]``.

    Returns
    -------
    axis : ndarray, shape (..., 3)
    angle : ndarray, shape (...)

    Examples
    --------
    >>> axis, angle = rotvec_to_axis_angle([0.0, 3.0, 4.0])
    >>> axis, float(angle)
    (array([0. , 0.6, 0.8]), 5.0)
    """
    psi = vector_array(psi, "psi")
    angle = norm(psi)
    zero = angle == 0.0
    axis = psi / np.where(zero, 1.0, angle)[..., None]
    axis[zero] = (0.0, 0.0, 1.0)
    return axis, angle


_axis_angle = declare(_axis_angle_rotvec, [Input("axis", (3,), DIRECTION), Input("angle", (), VECTOR)], (3,),
                      name="axis_angle_to_rotvec")


@uses(_axis_angle)
@takes_out
def axis_angle_to_rotvec(axis: ArrayLike, angle: ArrayLike, degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Rotation vector ψ n from an axis (any nonzero length) and an angle.

    Examples
    --------
    >>> axis_angle_to_rotvec([0.0, 0.0, 2.0], 90.0, degrees=True)
    array([0.        , 0.        , 1.57079633])
    """
    if check_flag(degrees, "degrees"):
        angle = np.deg2rad(as_float_array(angle, "angle", (), finite=False))
    return _axis_angle(axis, angle, out=out)


@elementwise(_compose, [Input("a", (3,), ROTVEC), Input("b", (3,), ROTVEC)], (3,))
def compose_rotvec(a: ArrayLike, b: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Exact composition: ψ with ``exp(ψ·X) = exp(a·X) exp(b·X)``, |ψ| <= π.

    Rotation vectors do not add (Theory §2.2 (4)); this is the closed form the
    BCH series (:func:`bch`) approximates, computed through quaternions.
    ``a`` and ``b`` longer than 1e8 rad are refused (see :func:`rotvec_to_quat`).

    Examples
    --------
    >>> import numpy as np
    >>> np.round(compose_rotvec([np.pi / 2, 0, 0], [0, np.pi / 2, 0]), 4)
    array([1.2092, 1.2092, 1.2092])
    """


def _bernoulli_even(n_max: int) -> list[float]:
    # B_0 … B_n_max by the recurrence Σ_{j<m} C(m+1, j) B_j = -(m+1) B_m, in exact fractions: in
    # floats its cancellations grow the error to 1e-14 by B_28 and on with the order
    B = [Fraction(1)]
    for m in range(1, n_max + 1):
        B.append(-sum((math.comb(m + 1, j) * B[j] for j in range(m)), Fraction(0)) / Fraction(m + 1))
    return [float(x) for x in B]


# Highest ``order`` that :func:`bch` accepts. Its terms of degree n shrink like (|a| + |b|)^n/π^n
# where the series converges, so degree 40 is below the double rounding for |a| + |b| < 1.2
# rad, and beyond it the series diverges; the work grows as order³.
_BCH_MAX_ORDER = 40

# bch refuses ``order`` with order·log10(2(|a| + |b|)) above this: the nested brackets of degree
# n reach (2(|a| + |b|))^n, which must stay well inside the double range (1.8e308).
_BCH_EXPONENT_LIMIT = 300.0


@takes_out
def bch(a: ArrayLike, b: ArrayLike, order: int = 3, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Baker–Campbell–Hausdorff series for ``log(exp(a·X) exp(b·X))`` (Theory §2.2 (4)).

    ``a + b + [a, b]/2 + [a - b, [a, b]]/12 + …`` truncated after the terms of
    total degree ``order``, with ``[a, b] = a × b`` in so(3). The terms are
    generated by Varadarajan's recursion

    ``(n+1) Z_{n+1} = ½[a - b, Z_n] + Σ_p B_2p/(2p)! Σ_{k_1+…+k_2p=n} [Z_k1, […[Z_k2p, a + b]…]]``.

    The error of order ``N`` is O(|ψ|^(N+1)); compare :func:`compose_rotvec`.

    Parameters
    ----------
    a, b : array_like, shape (..., 3)
        Rotation vectors, at most ``ROTVEC_RANGE`` = 1e8 rad long (longer
        ones are refused, as by :func:`rotvec_to_quat`).
    order : int >= 1
        Highest total degree in a and b kept in the series.

    Examples
    --------
    >>> bch([1e-3, 0, 0], [0, 1e-3, 0], order=2)
    array([1.e-03, 1.e-03, 5.e-07])
    """
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or not 1 <= order <= _BCH_MAX_ORDER:
        raise ValueError(f"order must be an integer in [1, {_BCH_MAX_ORDER}], got {order!r}")
    a = rotvec_array(a, "a")
    b = rotvec_array(b, "b")
    a, b = np.broadcast_arrays(a, b)
    span = float(np.max(norm(a) + norm(b), initial=0.0))
    if order > 1 and span > 0.0 and order * math.log10(2.0 * span) > _BCH_EXPONENT_LIMIT:
        raise ValueError(
            f"a, b and order are out of range: with |a| + |b| = {span:.3g} rad the series' terms of degree "
            f"{order} reach about (2 (|a| + |b|))^{order} = 1e{order * math.log10(2.0 * span):.0f}, beyond the "
            f"largest double; lower the order to {int(_BCH_EXPONENT_LIMIT / math.log10(2.0 * span))} or less (the "
            "series converges only for |a| + |b| below about pi: compose_rotvec composes exactly)"
        )
    B = _bernoulli_even(order)
    s = a + b
    d = a - b
    Z = [np.zeros_like(s), s]
    # nested[j][m]: the sum over the ordered splittings m = k_1 + … + k_j of [Z_k1, […[Z_kj, a + b]…]],
    # built as nested[j][m] = Σ_k [Z_k, nested[j-1][m-k]] (the brackets are linear), so degree n costs
    # n² cross products instead of one per splitting (2^(n-1))
    nested = [[s]]
    for n in range(1, order):
        nested[0].append(np.zeros_like(s))
        nested.append([np.zeros_like(s)] * n)
        for j in range(1, n + 1):
            nested[j].append(sum(np.cross(Z[k], nested[j - 1][n - k]) for k in range(1, n - j + 2)))
        term = 0.5 * np.cross(d, Z[n])
        for p in range(1, n // 2 + 1):
            term = term + B[2 * p] / math.factorial(2 * p) * nested[2 * p][n]
        Z.append(term / (n + 1))
    return deliver(np.sum(Z[1:], axis=0), out)


@elementwise(_adjoint, [Input("Q", (3, 3), MATRIX), Input("psi", (3,), VECTOR)], (3,))
def adjoint_action(Q: ArrayLike, psi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Adjoint action of a rotation on rotation vectors: ``ψ -> Q ψ``.

    Implements the identity of Theory §2.2 (5), ``Q R(ψ n) Qᵀ = R(ψ Q n)``: the
    axis turns as a vector and the angle is unchanged (equivalently
    ``Q (ψ·X) Qᵀ = (Qψ)·X``).

    Parameters
    ----------
    Q : array_like, shape (..., 3, 3)
        Rotation matrices.
    psi : array_like, shape (..., 3)
        Rotation vectors (or any vectors: the action is linear).

    Examples
    --------
    >>> Q = rotvec_to_matrix([0.0, 0.0, np.pi / 2])
    >>> np.round(adjoint_action(Q, [0.1, 0.0, 0.0]), 12) + 0.0
    array([0. , 0.1, 0. ])
    """
