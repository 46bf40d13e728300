"""Rotation vectors, generators and the exponential map (Theory §2.2).

The rotation vector ψ = ψ n (the chapter's "Rodrigues parameters" or angular
displacement) parametrises ``R(ψ) = exp(ψ_j X_j)`` with the generators
``X_j`` of Theory §2.2 (2), ``(X_j)_kl = -ε_jkl``. Logarithms return |ψ| <= π.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
from numba import prange
from numpy.typing import ArrayLike, NDArray

from .._compiled import cached, kernels, parallel
from .._compiled.outputs import deliver, takes_out
from .._compiled.gufunc import (
    checked_in_one_pass, finite_array, gufunc, in_pieces, matrix_array, piece_results, pieces, quaternion_array,
    refuse_rotvecs, rotvec_array, rotvec_in_range, vector_array,
)
from .._validation import as_float_array, check_flag
from .._norms import norm, unit

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


@cached
def _matrix_rotvec(r00: float, r01: float, r02: float, r10: float, r11: float, r12: float, r20: float, r21: float,
                   r22: float) -> tuple[float, float, float]:
    q0, q1, q2, q3 = kernels.matrix_entries_quat(r00, r01, r02, r10, r11, r12, r20, r21, r22)
    return kernels.quat_rotvec(q0, q1, q2, q3)


#: Rotation vectors per piece of the multi-core exp loops (each piece runs the vectorised block
#: kernels of :mod:`kreisel._compiled.kernels` over its range).
_PIECE = 4096


@parallel
def _rotvec_to_quat_parallel(psi: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    in_pieces(kernels.rotvec_quats, psi, out, _PIECE)  # psi checked (at most 1e8 rad long) by the caller


@cached
def _rotvec_quats_checked(psi: NDArray[np.float64], out: NDArray[np.float64], start: int, stop: int) -> bool:
    # exp of each psi of rows start..stop-1 and whether all were finite and in
    # range (the caller refuses the batch otherwise): one read of psi for the
    # check and the result. The kernel turns NaN or inf into NaN without
    # raising, so it runs unguarded.
    flat = psi.reshape(psi.size)[3 * start:3 * stop]  # indices from 0 and a known stride: the check vectorises
    ok = True
    for i in range(0, flat.size, 3):
        ok &= rotvec_in_range(flat[i], flat[i + 1], flat[i + 2])
    kernels.rotvec_quats(psi, out, start, stop)
    return ok


@parallel
def _rotvec_to_quat_checked(psi: NDArray[np.float64], out: NDArray[np.float64], chunk: int) -> np.bool_:
    n = psi.shape[0]
    return piece_results(_rotvec_quats_checked, (psi, out), n, chunk, np.empty(pieces(n, chunk), np.bool_)).all()


@parallel
def _quat_to_rotvec_parallel(q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    for i in prange(q.shape[0]):
        out[i, 0], out[i, 1], out[i, 2] = kernels.quat_rotvec(q[i, 0], q[i, 1], q[i, 2], q[i, 3])


@parallel
def _rotvec_to_matrix_parallel(psi: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    in_pieces(kernels.rotvec_matrices, psi, out, _PIECE)  # psi checked (at most 1e8 rad long) by the caller


@parallel
def _matrix_to_rotvec_parallel(R: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    for i in prange(R.shape[0]):
        out[i, 0], out[i, 1], out[i, 2] = _matrix_rotvec(
            R[i, 0, 0], R[i, 0, 1], R[i, 0, 2], R[i, 1, 0], R[i, 1, 1], R[i, 1, 2], R[i, 2, 0], R[i, 2, 1], R[i, 2, 2]
        )


@gufunc(["void(f8[:], f8[:], f8[:])"], "(3),(4)->(4)", parallel=_rotvec_to_quat_parallel)
def _rotvec_to_quat(psi: NDArray[np.float64], carrier4: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2], out[3] = kernels.rotvec_quat(psi[0], psi[1], psi[2])


@gufunc(["void(f8[:], f8[:], f8[:])"], "(4),(3)->(3)", parallel=_quat_to_rotvec_parallel)
def _quat_to_rotvec(q: NDArray[np.float64], carrier3: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2] = kernels.quat_rotvec(q[0], q[1], q[2], q[3])


@gufunc(["void(f8[:], f8[:, :])"], "(3)->(3,3)", parallel=_rotvec_to_matrix_parallel)
def _rotvec_to_matrix(psi: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    q0, q1, q2, q3 = kernels.rotvec_quat(psi[0], psi[1], psi[2])
    kernels.write_matrix(q0, q1, q2, q3, out)


@gufunc(["void(f8[:, :], f8[:])"], "(3,3)->(3)", parallel=_matrix_to_rotvec_parallel)
def _matrix_to_rotvec(R: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    q0, q1, q2, q3 = kernels.matrix_quat(R)
    out[0], out[1], out[2] = kernels.quat_rotvec(q0, q1, q2, q3)


@gufunc(["void(f8[:], f8[:], f8[:])"], "(3),(3)->(3)")
def _compose_rotvec(a: NDArray[np.float64], b: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    p0, p1, p2, p3 = kernels.rotvec_quat(a[0], a[1], a[2])
    q0, q1, q2, q3 = kernels.rotvec_quat(b[0], b[1], b[2])
    r0, r1, r2, r3 = kernels.quat_product(p0, p1, p2, p3, q0, q1, q2, q3)
    out[0], out[1], out[2] = kernels.quat_rotvec(r0, r1, r2, r3)


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


@takes_out
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
    v = vector_array(v, "v")
    A = np.zeros(v.shape + (3,))
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    A[..., 0, 1], A[..., 0, 2] = -z, y
    A[..., 1, 0], A[..., 1, 2] = z, -x
    A[..., 2, 0], A[..., 2, 1] = -y, x
    return deliver(A, out)


@takes_out
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
    A = finite_array(A, "A", (3, 3))
    v = 0.5 * np.stack([A[..., 2, 1] - A[..., 1, 2], A[..., 0, 2] - A[..., 2, 0], A[..., 1, 0] - A[..., 0, 1]], axis=-1)
    return deliver(v, out)


@takes_out
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
    return _rotvec_to_matrix(rotvec_array(psi, "psi"), out=out)


@takes_out
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
    return _matrix_to_rotvec(matrix_array(R, "R"), out=out)


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
    return exp_quat(psi, "psi", out)


def exp_quat(psi: ArrayLike, name: str, out: NDArray[np.float64] | None = None, what: str = "|psi|") -> NDArray[np.float64]:
    """:func:`rotvec_to_quat` of the argument ``name``, refused naming it and ``what`` its length is."""
    a = as_float_array(psi, name, (3,), finite=False)
    fused = checked_in_one_pass((a,), ((4,),), _rotvec_to_quat_checked) if out is None else None
    if fused is not None:
        (quats,), accepted = fused
        if not accepted:
            refuse_rotvecs(a, name, what)
        return quats
    return _rotvec_to_quat(rotvec_array(a, name, what), out=out)


@takes_out
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
    return _quat_to_rotvec(quaternion_array(q, "q"), out=out)


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


@takes_out
def axis_angle_to_rotvec(axis: ArrayLike, angle: ArrayLike, degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Rotation vector ψ n from an axis (any nonzero length) and an angle.

    Examples
    --------
    >>> axis_angle_to_rotvec([0.0, 0.0, 2.0], 90.0, degrees=True)
    array([0.        , 0.        , 1.57079633])
    """
    axis = vector_array(axis, "axis")
    angle = finite_array(angle, "angle", ())
    if check_flag(degrees, "degrees"):
        angle = np.deg2rad(angle)
    return deliver(unit(axis, "axis") * angle[..., None], out)


@takes_out
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
    a = rotvec_array(a, "a")
    b = rotvec_array(b, "b")
    return _compose_rotvec(a, b, out=out)


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


@takes_out
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
    # contiguous: einsum sums in another order over a strided Q, and the result would depend on the layout
    Q = np.ascontiguousarray(matrix_array(Q, "Q"))
    psi = np.ascontiguousarray(vector_array(psi, "psi"))
    return deliver(np.einsum("...ij,...j->...i", Q, psi), out)
