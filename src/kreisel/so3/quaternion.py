"""Quaternion algebra (Theory §2.4 and appendix (4)): scalar-first Hamilton quaternions.

A quaternion ``q = q0 + q1 i1 + q2 i2 + q3 i3`` is stored as ``[q0, q1, q2, q3]``
with ``i_j i_k = -δ_jk + ε_jkl i_l``. Unit quaternions act on vectors by
``r -> q r q⁻¹`` (active rotation, ``R(q)`` of Theory §2.4); ``q`` and ``-q``
give the same rotation (double cover).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TypeGuard, cast

import numpy as np
from numba import prange
from numpy.typing import ArrayLike, NDArray

from .._compiled import cached, kernels, parallel, vectorised
from .._compiled.outputs import check_out, deliver, takes_out
from .._compiled.gufunc import (
    checked_in_one_pass, checked_loop_into, checked_quat_size, finite3, finite_array, gufunc, piece_results, pieces,
    quaternion_array, refuse_nonfinite, refuse_quaternions, sized_quaternion_array, union, vector_array,
)
from .._validation import ROTVEC_RANGE, as_float_array, batch_shape, check_flag, refuse_long_angle
from .._norms import norm
from .rotvec import quat_to_rotvec

__all__ = [
    "quat_multiply",
    "quat_conjugate",
    "quat_inverse",
    "quat_norm",
    "quat_normalize",
    "quat_apply",
    "quat_identity",
    "quat_power",
]


@cached
def _applied(q0: float, q1: float, q2: float, q3: float, x: float, y: float, z: float) -> tuple[float, float, float]:
    # q v q* / |q|²: the rotation R(q/|q|) applied to v, valid for any nonzero norm.
    q0, q1, q2, q3 = kernels.squarable(q0, q1, q2, q3)
    return _applied_squarable(q0, q1, q2, q3, x, y, z)


@vectorised
def _applied_squarable(q0: float, q1: float, q2: float, q3: float, x: float, y: float,
                       z: float) -> tuple[float, float, float]:
    # _applied of a q that squarable leaves as it is, with unchecked divisions (a loop of it vectorises)
    n2 = q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3
    c0 = q2 * z - q3 * y
    c1 = q3 * x - q1 * z
    c2 = q1 * y - q2 * x
    d = q1 * x + q2 * y + q3 * z
    s = q0 * q0 - q1 * q1 - q2 * q2 - q3 * q3
    return (
        (s * x + 2.0 * (d * q1 + q0 * c0)) / n2,
        (s * y + 2.0 * (d * q2 + q0 * c1)) / n2,
        (s * z + 2.0 * (d * q3 + q0 * c2)) / n2,
    )


#: Quaternions of at least this size (largest |component|) have a finite inverse (1/size < DBL_MAX).
_INVERTIBLE_SIZE = 1e-300


@vectorised
def _conjugate_over(q0: float, q1: float, q2: float, q3: float, n2: float) -> tuple[float, float, float, float]:
    # q* / n2 with unchecked divisions (n2 > 0 wherever it is called), so that a loop of it vectorises
    return q0 / n2, -q1 / n2, -q2 / n2, -q3 / n2


@cached
def _inverted(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float, float]:
    m = kernels.size(q0, q1, q2, q3)
    if kernels.SIZE_LOW < m < kernels.SIZE_HIGH:
        return _conjugate_over(q0, q1, q2, q3, q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    # q* / |q|² = (q/m)* / (|q/m|² m): no square of a huge or tiny component
    q0, q1, q2, q3 = q0 / m, q1 / m, q2 / m, q3 / m
    return _conjugate_over(q0, q1, q2, q3, (q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3) * m)


@parallel
def _multiply_parallel(p: NDArray[np.float64], q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    for i in prange(p.shape[0]):
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = kernels.quat_product(
            p[i, 0], p[i, 1], p[i, 2], p[i, 3], q[i, 0], q[i, 1], q[i, 2], q[i, 3]
        )


@cached
def _unit_product(p0: float, p1: float, p2: float, p3: float, q0: float, q1: float, q2: float,
                  q3: float) -> tuple[float, float, float, float]:
    r0, r1, r2, r3 = kernels.quat_product(p0, p1, p2, p3, q0, q1, q2, q3)
    return kernels.quat_unit(r0, r1, r2, r3)


@parallel
def _compose_parallel(p: NDArray[np.float64], q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    for i in prange(p.shape[0]):
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = _unit_product(
            p[i, 0], p[i, 1], p[i, 2], p[i, 3], q[i, 0], q[i, 1], q[i, 2], q[i, 3]
        )


@cached
def _powered(q0: float, q1: float, q2: float, q3: float, p: float) -> tuple[float, float, float, float]:
    # exp(p log q) with the log's angle in [0, π]; p = 0, ±1 exactly.
    if p == 1.0:
        return kernels.quat_unit(q0, q1, q2, q3)
    if p == -1.0:
        return kernels.quat_unit(q0, -q1, -q2, -q3)
    if p == 0.0:
        return 1.0, 0.0, 0.0, 0.0
    x, y, z = kernels.quat_rotvec(q0, q1, q2, q3)
    return kernels.rotvec_quat(p * x, p * y, p * z)


@parallel
def _power_parallel(q: NDArray[np.float64], p: float, out: NDArray[np.float64]) -> None:
    for i in prange(q.shape[0]):
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = _powered(q[i, 0], q[i, 1], q[i, 2], q[i, 3], p)


@parallel
def _normalize_parallel(q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    for i in prange(q.shape[0]):
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = kernels.quat_unit(q[i, 0], q[i, 1], q[i, 2], q[i, 3])


@parallel
def _inverse_parallel(q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    for i in prange(q.shape[0]):
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = _inverted(q[i, 0], q[i, 1], q[i, 2], q[i, 3])


#: Operations of :func:`_map_checked`.
_NORMALIZE, _INVERT = 0, 1


@vectorised
def _mapped_in_range(q: NDArray[np.float64], out: NDArray[np.float64], start: int, stop: int, operation: int) -> bool:
    # Normalisation or inverse of rows start..stop-1, and whether every row
    # there is finite with its size in (SIZE_LOW, SIZE_HIGH): the
    # formulas of quat_unit and _inverted for such rows, in a loop without a
    # branch over a flat view (a row stride the compiler knows), so that
    # it vectorises; with any row outside, the caller computes the rows anew.
    a = q.reshape(q.size)[4 * start:4 * stop]
    b = out.reshape(out.size)[4 * start:4 * stop]
    inside = True
    for j in range(stop - start):
        i = 4 * j
        q0, q1, q2, q3 = a[i], a[i + 1], a[i + 2], a[i + 3]
        inside &= kernels.squarable_as_is(q0, q1, q2, q3)
        if operation == _NORMALIZE:
            b[i], b[i + 1], b[i + 2], b[i + 3] = kernels.unit_of_squarable(q0, q1, q2, q3)
        else:
            b[i], b[i + 1], b[i + 2], b[i + 3] = _conjugate_over(q0, q1, q2, q3, q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    return inside


@cached
def _mapped_rows(q: NDArray[np.float64], out: NDArray[np.float64], start: int, stop: int, operation: int) -> float:
    # Normalisation or inverse of each q of rows start..stop-1 that is finite
    # and nonzero (the caller refuses the batch otherwise), and the smallest
    # size there as sized_quaternion_array finds it.
    least = np.inf
    for i in range(start, stop):
        q0, q1, q2, q3 = q[i, 0], q[i, 1], q[i, 2], q[i, 3]
        size = checked_quat_size(q0, q1, q2, q3)
        least = min(least, size)
        if size > 0.0:
            if operation == _NORMALIZE:
                out[i, 0], out[i, 1], out[i, 2], out[i, 3] = kernels.quat_unit(q0, q1, q2, q3)
            else:
                out[i, 0], out[i, 1], out[i, 2], out[i, 3] = _inverted(q0, q1, q2, q3)
    return least


@cached
def _mapped_piece(q: NDArray[np.float64], out: NDArray[np.float64], operation: int, start: int, stop: int) -> float:
    # Normalisation or inverse of rows start..stop-1 and a lower bound of their
    # smallest size, exact where it is at most SIZE_LOW (-1: not finite), as
    # sized_quaternion_array finds it: one read of q for both, unless the piece
    # holds a size outside (SIZE_LOW, SIZE_HIGH).
    if _mapped_in_range(q, out, start, stop, operation):
        return kernels.SIZE_LOW
    return _mapped_rows(q, out, start, stop, operation)


@parallel
def _map_checked(q: NDArray[np.float64], out: NDArray[np.float64], chunk: int, operation: int) -> float:
    # _mapped_piece of a batch (into an out that is not q), on all cores
    n = q.shape[0]
    return float(piece_results(_mapped_piece, (q, out, operation), n, chunk, np.empty(pieces(n, chunk))).min())


def _mapped(q: ArrayLike, operation: int, out: NDArray[np.float64] | None) -> tuple[NDArray[np.float64], float]:
    """``(normalised or inverse q, smallest size)``; a large new result is checked in the same pass.

    The size is a lower bound of the smallest, exact where at most
    ``kernels.SIZE_LOW``: what the refusals and the inverse's overflow test need.
    """
    a = as_float_array(q, "q", (4,), finite=False)
    fused = checked_in_one_pass((a,), ((4,),), _map_checked, operation) if out is None else None
    if fused is not None:
        (mapped,), smallest = fused
        refuse_quaternions(smallest, "q")
        return mapped, smallest
    a, smallest = sized_quaternion_array(a, "q")
    filled = checked_loop_into(out, (a,), (4,), _map_checked, operation)
    if filled is not None:
        return filled, smallest
    return (_normalize if operation == _NORMALIZE else _inverse)(a, out=out), smallest


@parallel
def _apply_parallel(q: NDArray[np.float64], v: NDArray[np.float64], sign: float, out: NDArray[np.float64]) -> None:
    # sign = -1 rotates by the conjugate: R(q)ᵀ v.
    for i in prange(q.shape[0]):
        out[i, 0], out[i, 1], out[i, 2] = _applied(
            q[i, 0], sign * q[i, 1], sign * q[i, 2], sign * q[i, 3], v[i, 0], v[i, 1], v[i, 2]
        )


@cached
def _multiplied(p: NDArray[np.float64], q: NDArray[np.float64], out: NDArray[np.float64], start: int, stop: int) -> int:
    # p q of elements start..stop-1 and their refusal flags (1: p holds a
    # non-finite quaternion, 2: q does). A non-finite component of p or q makes
    # its product non-finite (inf times anything is inf or NaN), so only a
    # non-finite product sends the loop back to its inputs.
    bad = 0
    for i in range(start, stop):
        p0, p1, p2, p3 = p[i, 0], p[i, 1], p[i, 2], p[i, 3]
        q0, q1, q2, q3 = q[i, 0], q[i, 1], q[i, 2], q[i, 3]
        r0, r1, r2, r3 = kernels.quat_product(p0, p1, p2, p3, q0, q1, q2, q3)
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = r0, r1, r2, r3
        if checked_quat_size(r0, r1, r2, r3) < 0.0:
            bad |= int(checked_quat_size(p0, p1, p2, p3) < 0.0) | 2 * int(checked_quat_size(q0, q1, q2, q3) < 0.0)
    return bad


@cached
def _rotated(q: NDArray[np.float64], v: NDArray[np.float64], out: NDArray[np.float64], start: int, stop: int,
             sign: float) -> int:
    # R(q) v (sign = -1: R(q)ᵀ v) of elements start..stop-1 whose q is finite
    # and nonzero, and their refusal flags (1: q holds a non-finite quaternion,
    # 2: a zero one, 4: v holds a non-finite vector). A non-finite component of
    # v makes the result non-finite, so only a non-finite result sends the loop
    # back to v.
    bad = 0
    for i in range(start, stop):
        q0, q1, q2, q3 = q[i, 0], q[i, 1], q[i, 2], q[i, 3]
        size = checked_quat_size(q0, q1, q2, q3)
        if size > 0.0:
            x, y, z = v[i, 0], v[i, 1], v[i, 2]
            r0, r1, r2 = _applied(q0, sign * q1, sign * q2, sign * q3, x, y, z)
            out[i, 0], out[i, 1], out[i, 2] = r0, r1, r2
            if not finite3(r0, r1, r2):
                bad |= 4 * int(not finite3(x, y, z))
        else:
            bad |= 1 if size < 0.0 else 2
    return bad


@vectorised
def _rotated_in_range(q: NDArray[np.float64], v: NDArray[np.float64], out: NDArray[np.float64], start: int, stop: int,
                      sign: float) -> bool:
    # _rotated of rows start..stop-1 and whether none of them needs a flag or
    # squarable's division: every q finite with its size in (SIZE_LOW,
    # SIZE_HIGH) and every result finite (then so is every v). No branch, flat
    # views: the loop vectorises; otherwise the caller runs _rotated anew.
    a = q.reshape(q.size)[4 * start:4 * stop]
    b = v.reshape(v.size)[3 * start:3 * stop]
    c = out.reshape(out.size)[3 * start:3 * stop]
    inside = True
    for j in range(stop - start):
        i, k = 4 * j, 3 * j
        q0, q1, q2, q3 = a[i], a[i + 1], a[i + 2], a[i + 3]
        r0, r1, r2 = _applied_squarable(q0, sign * q1, sign * q2, sign * q3, b[k], b[k + 1], b[k + 2])
        c[k], c[k + 1], c[k + 2] = r0, r1, r2
        inside &= kernels.squarable_as_is(q0, q1, q2, q3) & finite3(r0, r1, r2)
    return inside


#: Operations of :func:`_product_checked`.
_MULTIPLY, _APPLY = 0, 1


@cached
def _product_piece(a: NDArray[np.float64], b: NDArray[np.float64], out: NDArray[np.float64], operation: int, sign: float,
                   start: int, stop: int) -> int:
    # p q (a = p, b = q) or R(q) v (a = q, b = v) of rows start..stop-1 and the
    # union of their refusal flags: one read of both inputs for the check and the result.
    if operation == _MULTIPLY:
        return _multiplied(a, b, out, start, stop)
    if _rotated_in_range(a, b, out, start, stop, sign):
        return 0
    return _rotated(a, b, out, start, stop, sign)


@parallel
def _product_checked(a: NDArray[np.float64], b: NDArray[np.float64], out: NDArray[np.float64], chunk: int,
                     operation: int, sign: float) -> int:
    # _product_piece of a batch, on all cores
    n = a.shape[0]
    return union(piece_results(_product_piece, (a, b, out, operation, sign), n, chunk,
                               np.empty(pieces(n, chunk), dtype=np.int64)))


def _then(x: ArrayLike, name: str, tail: tuple[int, ...], previous_checks: Callable[[], object]) -> NDArray[np.float64]:
    """``x`` as a float64 array of trailing shape ``tail``, the second argument of a fused check.

    If ``x`` is refused, ``previous_checks()`` (the checks of the argument
    before it) runs first, so that the refusal is the one of checking each
    argument in turn.
    """
    try:
        return as_float_array(x, name, tail, finite=False)
    except (TypeError, ValueError):
        previous_checks()
        raise


@gufunc(["void(f8[:], f8[:], f8[:])"], "(4),(4)->(4)", parallel=_multiply_parallel)
def _multiply(p: NDArray[np.float64], q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2], out[3] = kernels.quat_product(p[0], p[1], p[2], p[3], q[0], q[1], q[2], q[3])


@gufunc(["void(f8[:], f8[:], f8[:])"], "(4),(4)->(4)", parallel=_compose_parallel)
def _compose(p: NDArray[np.float64], q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2], out[3] = _unit_product(p[0], p[1], p[2], p[3], q[0], q[1], q[2], q[3])


@gufunc(["void(f8[:], f8[:])"], "(4)->(4)", parallel=_normalize_parallel)
def _normalize(q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2], out[3] = kernels.quat_unit(q[0], q[1], q[2], q[3])


@gufunc(["void(f8[:], f8, f8[:])"], "(4),()->(4)", parallel=_power_parallel, shared=(1,))
def _power(q: NDArray[np.float64], p: float, out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2], out[3] = _powered(q[0], q[1], q[2], q[3], p)


@gufunc(["void(f8[:], f8[:])"], "(4)->(4)", parallel=_inverse_parallel)
def _inverse(q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2], out[3] = _inverted(q[0], q[1], q[2], q[3])


@gufunc(["void(f8[:], f8[:], f8, f8[:])"], "(4),(3),()->(3)", parallel=_apply_parallel, shared=(2,))
def _apply(q: NDArray[np.float64], v: NDArray[np.float64], sign: float, out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2] = _applied(q[0], sign * q[1], sign * q[2], sign * q[3], v[0], v[1], v[2])


@cached
def _multiply_one(p: NDArray[np.float64], q: NDArray[np.float64], out: NDArray[np.float64]) -> bool:
    # Writes p q into out only if it is finite (out may be p or q), and says whether it was.
    r0, r1, r2, r3 = kernels.quat_product(p[0], p[1], p[2], p[3], q[0], q[1], q[2], q[3])
    finite = max(max(abs(r0), abs(r1)), max(abs(r2), abs(r3))) <= 1.7976931348623157e308
    if finite:
        out[0], out[1], out[2], out[3] = r0, r1, r2, r3
    return finite


@cached
def _compose_one(p: NDArray[np.float64], q: NDArray[np.float64]) -> NDArray[np.float64]:
    out = np.empty(4)
    out[0], out[1], out[2], out[3] = _unit_product(p[0], p[1], p[2], p[3], q[0], q[1], q[2], q[3])
    return out


def compose_unit(p: NDArray[np.float64], q: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit product ``(p q) / |p q|`` of validated unit quaternions (no input checks).

    The renormalisation keeps long chains of compositions on the unit sphere:
    the rounding of each product would otherwise accumulate in ``|q| - 1``.
    """
    if _is_single(p) and _is_single(q):
        return _compose_one(p, q)
    return _compose(p, q)


def _is_single(x: object) -> TypeGuard[NDArray[np.float64]]:
    # Writable arrays only: a read-only one would compile (and cache) a second
    # signature of _multiply_one.
    return type(x) is np.ndarray and x.shape == (4,) and x.dtype == np.float64 and x.flags.writeable


@takes_out
def quat_multiply(p: ArrayLike, q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Hamilton product ``p q`` (Theory §2.4), broadcasting over leading axes.

    ``R(p q) = R(p) R(q)``: the product first applies ``q``, then ``p``.

    Parameters
    ----------
    p, q : array_like, shape (..., 4)
        Scalar-first quaternions (any finite values; not necessarily unit).

    Returns
    -------
    ndarray, shape (..., 4)
        p q, not normalised (|p q| = |p| |q|).

    Examples
    --------
    >>> import numpy as np
    >>> quat_multiply([0, 1, 0, 0], [0, 0, 1, 0])      # i1 i2 = i3
    array([0., 0., 0., 1.])
    """
    if _is_single(p) and _is_single(q) and (out is None or (_is_single(out) and out.flags.c_contiguous)):
        # One-rotation fast path (the gufunc dispatch plus two validation
        # calls cost several µs). Any NaN/inf in p or q makes some product
        # component non-finite, so a finite result proves finite inputs;
        # otherwise the checked path below raises the proper error.
        product = np.empty(4) if out is None else out
        if _multiply_one(p, q, product):
            return product
    a = as_float_array(p, "p", (4,), finite=False)
    b = _then(q, "q", (4,), lambda: quaternion_array(a, "p", nonzero=False))
    fused = checked_in_one_pass((a, b), ((4,),), _product_checked, _MULTIPLY, 1.0) if out is None else None
    if fused is not None:
        (product,), bad = fused
        if bad & 1:
            refuse_quaternions(-1.0, "p")
        if bad & 2:
            refuse_quaternions(-1.0, "q")
        return product
    a = quaternion_array(a, "p", nonzero=False)
    b = quaternion_array(b, "q", nonzero=False)
    return _multiply(a, b, out=out)


@takes_out
def quat_conjugate(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Conjugate ``q* = q0 - q·i`` (Theory §2.4); the inverse rotation for unit ``q``.

    Examples
    --------
    >>> quat_conjugate([1.0, 2.0, 3.0, 4.0])
    array([ 1., -2., -3., -4.])
    """
    q = quaternion_array(q, "q", nonzero=False)
    if out is None:
        out = np.empty(q.shape)
    check_out(out, q.shape)
    first = q[..., 0].copy() if np.may_share_memory(q, out) else q[..., 0]
    np.negative(q, out=out)
    out[..., 0] = first
    return out


@takes_out
def quat_norm(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Norm ``|q| = sqrt(q* q)``, shape ``(...)``.

    Examples
    --------
    >>> float(quat_norm([1.0, 1.0, 1.0, 1.0]))
    2.0
    """
    return deliver(norm(quaternion_array(q, "q", nonzero=False)), out)


@takes_out
def quat_inverse(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse ``q⁻¹ = q* / |q|²`` (Theory §2.4) of nonzero quaternions.

    Examples
    --------
    >>> quat_inverse([0.0, 0.0, 2.0, 0.0])
    array([ 0. , -0. , -0.5, -0. ])
    """
    with np.errstate(over="ignore"):
        inverse, smallest = _mapped(q, _INVERT, out)
    # |q⁻¹| = 1/|q| <= 1/size: only a batch holding a size near 1/DBL_MAX needs the pass over its result
    if smallest < _INVERTIBLE_SIZE and not np.isfinite(inverse).all():
        raise ValueError("q is out of range: the inverse of a quaternion this small (|q| < ~1e-308) overflows")
    return inverse


@takes_out
def quat_normalize(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Scale nonzero quaternions to unit norm (the renormalisation of Theory §2.4 (2) ②).

    Raises ``ValueError`` for zero or non-finite input rather than returning NaN.

    Examples
    --------
    >>> quat_normalize([2.0, 0.0, 0.0, 0.0])
    array([1., 0., 0., 0.])
    """
    return _mapped(q, _NORMALIZE, out)[0]


@takes_out
def quat_apply(q: ArrayLike, v: ArrayLike, inverse: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Rotate vectors: ``R(q) v`` (or ``R(q)ᵀ v`` with ``inverse=True``).

    With ``R`` mapping body to space components this turns body components
    ``a′`` into space components ``a = R a′``; ``inverse=True`` goes back.
    ``q`` need not be unit: it stands for the rotation ``q/|q|``.

    Parameters
    ----------
    q : array_like, shape (..., 4)
    v : array_like, shape (..., 3)
        Broadcast against ``q`` over the leading axes.
    inverse : bool
        Rotate by ``R(q)ᵀ`` instead (space → body components).

    Returns
    -------
    ndarray, shape (..., 3)
        The rotated vectors, with the broadcast batch shape.

    Examples
    --------
    >>> import numpy as np
    >>> q = [np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)]       # 90° about z
    >>> np.round(quat_apply(q, [1.0, 0.0, 0.0]), 12) + 0.0
    array([0., 1., 0.])
    """
    return rotate_vectors(q, v, inverse, out)


def rotate_vectors(q: ArrayLike, v: ArrayLike, inverse: bool = False, out: NDArray[np.float64] | None = None,
                   name: str = "v") -> NDArray[np.float64]:
    """:func:`quat_apply` with the vectors' argument named ``name`` in its refusals (checked once)."""
    sign = -1.0 if check_flag(inverse, "inverse") else 1.0
    a = as_float_array(q, "q", (4,), finite=False)
    b = _then(v, name, (3,), lambda: quaternion_array(a, "q"))
    fused = checked_in_one_pass((a, b), ((3,),), _product_checked, _APPLY, sign) if out is None else None
    if fused is not None:
        (rotated,), bad = fused
        if bad & 3:
            refuse_quaternions(-1.0 if bad & 1 else 0.0, "q")
        refuse_nonfinite(not (bad & 4), name)
        return rotated
    a, b = quaternion_array(a, "q"), vector_array(b, name)
    filled = checked_loop_into(out, (a, b), (3,), _product_checked, _APPLY, sign)
    return _apply(a, b, sign, out=out) if filled is None else filled


@takes_out
def quat_power(q: ArrayLike, p: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Powers ``q^p = exp(p log q)`` of rotations: the same axis, ``p`` times the angle.

    The logarithm takes the rotation angle in [0, π] (the double cover's
    sign of ``q`` does not matter), so fractional powers follow the shortest
    path from the identity, as scipy's ``Rotation.__pow__``; ``p = -1`` is
    the inverse and ``p = 0`` the identity, exactly.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Nonzero quaternions (normalised here).
    p : float or array_like, shape (...)
        Exponents, broadcast against the batch. ``|p|`` times the angle of
        ``q`` must be at most 1e8 rad (see :func:`~kreisel.so3.rotvec_to_quat`).

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternions.

    Examples
    --------
    A third of a quarter turn about z is a 30° turn:

    >>> import numpy as np
    >>> q = np.array([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)])
    >>> np.allclose(quat_power(q, 1 / 3), [np.cos(np.pi / 12), 0.0, 0.0, np.sin(np.pi / 12)])
    True
    """
    # type(), not isinstance: numpy scalars and bools take the general path
    if _is_single(q) and type(p) in (int, float) and abs(cast(float, p)) <= _SAFE_FACTOR and q.any() and np.isfinite(q).all():
        # One rotation: the compiled kernel without the gufunc dispatch.
        return deliver(np.array(_powered(q[0], q[1], q[2], q[3], float(cast(float, p)))), out)
    q = quaternion_array(q, "q")
    exponent = finite_array(p, "p", ())
    check_angle_multiple(exponent, lambda: q, "p", "|p| times the angle of q")
    return _power(q, float(exponent) if exponent.ndim == 0 else exponent, out=out)


#: Factors of a rotation angle in [0, π] that cannot take it beyond ``ROTVEC_RANGE``.
_SAFE_FACTOR = ROTVEC_RANGE / math.pi


def check_angle_multiple(factor: NDArray[np.float64], rotations: Callable[[], NDArray[np.float64]], name: str,
                         what: str) -> None:
    """Refuse ``factor`` (named ``name``) where ``|factor|`` times a rotation angle exceeds 1e8 rad.

    ``rotations()`` gives the nonzero quaternions whose angles (in [0, π])
    are multiplied, broadcast against ``factor``; it is called only when some
    ``|factor|`` could reach the limit.
    """
    largest = float(np.max(np.abs(factor), initial=0.0))
    if largest > _SAFE_FACTOR:
        angle = norm(quat_to_rotvec(rotations()))
        refuse_long_angle(float(np.max(np.abs(factor) * angle, initial=0.0)), name, what)


@takes_out
def quat_identity(shape: int | tuple[int, ...] | None = (), *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Identity quaternions ``[1, 0, 0, 0]`` of batch shape ``shape``.

    Examples
    --------
    >>> quat_identity(2)
    array([[1., 0., 0., 0.],
           [1., 0., 0., 0.]])
    """
    identity = np.zeros((*batch_shape(shape), 4))
    identity[..., 0] = 1.0
    return deliver(identity, out)
