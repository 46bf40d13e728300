"""Quaternion algebra (Theory §2.4 and appendix (4)): scalar-first Hamilton quaternions.

A quaternion ``q = q0 + q1 i1 + q2 i2 + q3 i3`` is stored as ``[q0, q1, q2, q3]``
with ``i_j i_k = -δ_jk + ε_jkl i_l``. Unit quaternions act on vectors by
``r -> q r q⁻¹`` (active rotation, ``R(q)`` of Theory §2.4); ``q`` and ``-q``
give the same rotation (double cover).

Each array function is a scalar kernel and its declaration
(:mod:`kreisel._compiled.elementwise`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numba import types
from numpy.typing import ArrayLike, NDArray

from .._compiled import kernels
from .._compiled.checks import ANY_QUATERNION, QUATERNION, VECTOR
from .._compiled.elementwise import Input, Parameter, declare, elementwise, kernel, uses
from .._compiled.outputs import deliver, takes_out
from .._norms import norm
from .._validation import ROTVEC_RANGE, as_float_array, batch_shape, check_flag, refuse_long_angle
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


@kernel
def _conjugate(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float, float]:
    return q0, -q1, -q2, -q3


@kernel
def _norm(q0: float, q1: float, q2: float, q3: float) -> float:
    # |q| = m |q/m| (m the largest |component|) where the squares would over- or underflow
    m = kernels.largest_component(q0, q1, q2, q3)
    if kernels.SIZE_LOW < m < kernels.SIZE_HIGH or m == 0.0:
        return math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    q0, q1, q2, q3 = q0 / m, q1 / m, q2 / m, q3 / m
    return m * math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)


@kernel
def _inverse(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float, float]:
    # q* / |q|² as ((q/m)* / |q/m|²) / m, m = 1 unless the squares would over- or underflow
    m = kernels.largest_component(q0, q1, q2, q3)
    d = 1.0 if kernels.SIZE_LOW < m < kernels.SIZE_HIGH else m
    q0, q1, q2, q3 = q0 / d, q1 / d, q2 / d, q3 / d
    n2 = q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3
    return q0 / n2 / d, -q1 / n2 / d, -q2 / n2 / d, -q3 / n2 / d


#: Vectors with a larger |component| are scaled by 1/32 (exactly) before they are rotated.
HUGE_COMPONENT = 1e306


@kernel
def _rotate(q0: float, q1: float, q2: float, q3: float, x: float, y: float, z: float,
            sign: float) -> tuple[float, float, float]:
    # q v q* / |q|²: R(q/|q|) v for any nonzero q; sign = -1 rotates by the conjugate, R(q)ᵀ v.
    # With q divided by its largest |component| (1 <= |q|² <= 4) no intermediate exceeds 21 max |v_i|:
    # only vectors near the largest double need scaling, and the result is finite when its size |v| is.
    m = kernels.largest_component(q0, q1, q2, q3)
    q0, q1, q2, q3 = q0 / m, sign * q1 / m, sign * q2 / m, sign * q3 / m
    down = 0.03125 if kernels.largest_component(0.0, x, y, z) > HUGE_COMPONENT else 1.0
    x, y, z = down * x, down * y, down * z
    c0 = q2 * z - q3 * y
    c1 = q3 * x - q1 * z
    c2 = q1 * y - q2 * x
    d = q1 * x + q2 * y + q3 * z
    s = q0 * q0 - q1 * q1 - q2 * q2 - q3 * q3
    back = 1.0 / (down * (q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3))
    return (
        (s * x + 2.0 * (d * q1 + q0 * c0)) * back,
        (s * y + 2.0 * (d * q2 + q0 * c1)) * back,
        (s * z + 2.0 * (d * q3 + q0 * c2)) * back,
    )


@kernel
def _unit_product(p0: float, p1: float, p2: float, p3: float, q0: float, q1: float, q2: float,
                  q3: float) -> tuple[float, float, float, float]:
    r0, r1, r2, r3 = kernels.quat_product(p0, p1, p2, p3, q0, q1, q2, q3)
    return kernels.quat_unit(r0, r1, r2, r3)


@kernel
def _power(q0: float, q1: float, q2: float, q3: float, p: float) -> tuple[float, float, float, float]:
    # exp(p log q) with the log's angle in [0, π]; p = 0, ±1 exactly
    if p == 1.0:
        return kernels.quat_unit(q0, q1, q2, q3)
    if p == -1.0:
        return kernels.quat_unit(q0, -q1, -q2, -q3)
    if p == 0.0:
        return 1.0, 0.0, 0.0, 0.0
    x, y, z = kernels.quat_rotvec(q0, q1, q2, q3)
    return kernels.rotvec_quat(p * x, p * y, p * z)


_P, _Q = Input("p", (4,), ANY_QUATERNION), Input("q", (4,), ANY_QUATERNION)
_ROTATION = Input("q", (4,), QUATERNION)
_compose = declare(_unit_product, [Input("p", (4,), QUATERNION), _ROTATION], (4,), name="quat_compose")
_rotate_vectors = declare(_rotate, [_ROTATION, Input("v", (3,), VECTOR)], (3,), [Parameter("sign", types.float64)],
                          name="quat_apply")
_powers = declare(_power, [_ROTATION, Input("p", (), VECTOR)], (4,), name="quat_power")


def compose_unit(p: NDArray[np.float64], q: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit product ``(p q) / |p q|`` of unit quaternions.

    The renormalisation keeps long chains of compositions on the unit sphere:
    the rounding of each product would otherwise accumulate in ``|q| - 1``.
    """
    return _compose(p, q)


@elementwise(kernels.quat_product, [_P, _Q], (4,))
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


@elementwise(_conjugate, [_Q], (4,))
def quat_conjugate(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Conjugate ``q* = q0 - q·i`` (Theory §2.4); the inverse rotation for unit ``q``.

    Examples
    --------
    >>> quat_conjugate([1.0, 2.0, 3.0, 4.0])
    array([ 1., -2., -3., -4.])
    """


@elementwise(_norm, [_Q], ())
def quat_norm(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Norm ``|q| = sqrt(q* q)``, shape ``(...)``.

    Examples
    --------
    >>> float(quat_norm([1.0, 1.0, 1.0, 1.0]))
    2.0
    """


@elementwise(_inverse, [_ROTATION], (4,))
def quat_inverse(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse ``q⁻¹ = q* / |q|²`` (Theory §2.4) of nonzero quaternions.

    Examples
    --------
    >>> quat_inverse([0.0, 0.0, 2.0, 0.0])
    array([ 0. , -0. , -0.5, -0. ])
    """


@elementwise(kernels.quat_unit, [_ROTATION], (4,))
def quat_normalize(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Scale nonzero quaternions to unit norm (the renormalisation of Theory §2.4 (2) ②).

    Raises ``ValueError`` for zero or non-finite input rather than returning NaN.

    Examples
    --------
    >>> quat_normalize([2.0, 0.0, 0.0, 0.0])
    array([1., 0., 0., 0.])
    """


@uses(_rotate_vectors)
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
    """:func:`quat_apply` with the vectors' argument named ``name`` in its refusals."""
    sign = -1.0 if check_flag(inverse, "inverse") else 1.0
    operation = _rotate_vectors if name == "v" else _rotate_vectors.renamed(v=name)
    return operation(q, v, sign, out=out)


@uses(_powers)
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
    q = as_float_array(q, "q", (4,), finite=False)
    exponent = as_float_array(p, "p", (), finite=False)
    if np.isfinite(exponent).all():
        check_angle_multiple(exponent, lambda: q, "p", "|p| times the angle of q")
    return _powers(q, exponent, out=out)


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
