"""The Lie group SE(3): twists, their matrices and the Jacobians.

Twists (exponential coordinates) are ``ξ = (ω, v)``, **rotation part
first**, with ``ξ^ = [[hat ω, v], [0, 0]]`` and ``T = exp(ξ^)``. This is the
order of scipy's ``RigidTransform.as_exp_coords``. The rotation part is the
rotation vector ψ = ω of Theory §2.2; the translation part ``v`` is the
velocity of the body point passing through the origin during the uniform
screw motion ``exp(s ξ^)`` that reaches ``T`` at ``s = 1`` (Theory §3.8), so
``r_C = J_l(ω) v`` with the SO(3) left Jacobian. The exponential, the
logarithm and the adjoint of poses are ``RigidTransform.from_exp_coords``,
``as_exp_coords`` and ``adjoint``.

Jacobians follow the left/right perturbation convention:
``exp(ξ + δ) ≈ exp(J_l(ξ) δ) exp(ξ) ≈ exp(ξ) exp(J_r(ξ) δ)``. With twists
ordered (ω, v) they are block lower-triangular,
``J_l = [[J, 0], [Q(ω, v), J]]``, ``J`` the SO(3) left Jacobian (the
kernels of :mod:`kreisel.so3.jacobians`, in :mod:`kreisel._compiled.dexp`)
and ``Q`` the coupling matrix given by Barfoot (*State Estimation for
Robotics*, 2017, section on SE(3) Jacobians; blocks swapped here for the
(ω, v) order). The three coefficient functions of
``Q`` are summed from their Maclaurin series at small angles, where the
closed forms lose digits (the series of :mod:`kreisel._compiled.series`,
shared with SO(3)), so the Jacobians keep full accuracy at small
angles and have no singularity below 2π (near π in particular). Tested
against the series ``Σ ad_ξⁿ/(n+1)!`` and finite differences.

Each array function is a scalar kernel and its declaration
(:mod:`kreisel._compiled.elementwise`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import types
from numpy.typing import ArrayLike, NDArray

from .._compiled import dexp
from .._compiled.checks import TWIST, VECTOR, twist_array
from .._compiled.elementwise import Input, Kind, Parameter, declare, elementwise, kernel, uses
from .._compiled.outputs import takes_out
from .._norms import norm
from ..so3.jacobians import SINGULAR_TOL

__all__ = [
    "se3_hat",
    "se3_vee",
    "se3_left_jacobian",
    "se3_right_jacobian",
    "se3_left_jacobian_inverse",
    "se3_right_jacobian_inverse",
]


_LEFT, _RIGHT = 1.0, -1.0


@kernel
def _hat(w0: float, w1: float, w2: float, v0: float, v1: float, v2: float) -> tuple[float, ...]:
    # [[hat ω, v], [0, 0]] row by row
    return 0.0, -w2, w1, v0, w2, 0.0, -w0, v1, -w1, w0, 0.0, v2, 0.0, 0.0, 0.0, 0.0


@kernel
def _vee(m00: float, m01: float, m02: float, m03: float, m10: float, m11: float, m12: float, m13: float, m20: float,
         m21: float, m22: float, m23: float, m30: float, m31: float, m32: float, m33: float) -> tuple[float, ...]:
    # ω of the skew part ½ (A - Aᵀ) of the upper-left block A, v of the last column
    return 0.5 * (m21 - m12), 0.5 * (m02 - m20), 0.5 * (m10 - m01), m03, m13, m23


@kernel
def _coupling(ux: float, uy: float, uz: float, angle: float, v0: float, v1: float, v2: float) -> tuple[float, ...]:
    """Barfoot's Q(ω, v) for ω = angle u, row by row: the lower-left block of the SE(3) left Jacobian.

    ``Q = ½V + b(WV + VW + WVW) + c(WWV + VWW − 3WVW) + d(WVW W + W WVW)``, W = hat(ω), V = hat(v), is,
    by ``hat(a) hat(b) = b aᵀ − (a·b) 1`` and with p = u·v, n = |u|²,
    ``hat(h) + bθ (u vᵀ + v uᵀ) + 2p (dθ³ n − bθ) 1 − 2 dθ³ p u uᵀ``, h = (½ − cθ² n) v + (2cθ² − bθ²) p u,
    with the coefficients times the matching powers of θ (:func:`~kreisel._compiled.dexp.se3_coupling_coefficients`):
    no entry over- or underflows for any finite ω, and no 3×3 product is formed.
    """
    b1, b2, c2, d3 = dexp.se3_coupling_coefficients(angle)
    n = ux * ux + uy * uy + uz * uz
    p = ux * v0 + uy * v1 + uz * v2
    g, k = 0.5 - c2 * n, (2.0 * c2 - b2) * p
    h0, h1, h2 = g * v0 + k * ux, g * v1 + k * uy, g * v2 + k * uz
    s, e = 2.0 * p * (d3 * n - b1), 2.0 * d3 * p
    a01 = b1 * (ux * v1 + v0 * uy) - e * ux * uy
    a02 = b1 * (ux * v2 + v0 * uz) - e * ux * uz
    a12 = b1 * (uy * v2 + v1 * uz) - e * uy * uz
    return (
        2.0 * b1 * ux * v0 - e * ux * ux + s, a01 - h2, a02 + h1,
        a01 + h2, 2.0 * b1 * uy * v1 - e * uy * uy + s, a12 - h0,
        a02 - h1, a12 + h0, 2.0 * b1 * uz * v2 - e * uz * uz + s,
    )  # fmt: skip


@kernel
def _product(a: tuple[float, ...], b: tuple[float, ...]) -> tuple[float, ...]:
    # a b of 3×3 matrices given row by row
    return (
        a[0] * b[0] + a[1] * b[3] + a[2] * b[6], a[0] * b[1] + a[1] * b[4] + a[2] * b[7],
        a[0] * b[2] + a[1] * b[5] + a[2] * b[8],
        a[3] * b[0] + a[4] * b[3] + a[5] * b[6], a[3] * b[1] + a[4] * b[4] + a[5] * b[7],
        a[3] * b[2] + a[4] * b[5] + a[5] * b[8],
        a[6] * b[0] + a[7] * b[3] + a[8] * b[6], a[6] * b[1] + a[7] * b[4] + a[8] * b[7],
        a[6] * b[2] + a[7] * b[5] + a[8] * b[8],
    )  # fmt: skip


@kernel
def _blocks(j: tuple[float, ...], lower: tuple[float, ...]) -> tuple[float, ...]:
    # [[J, 0], [L, J]] row by row
    return (
        j[0], j[1], j[2], 0.0, 0.0, 0.0,
        j[3], j[4], j[5], 0.0, 0.0, 0.0,
        j[6], j[7], j[8], 0.0, 0.0, 0.0,
        lower[0], lower[1], lower[2], j[0], j[1], j[2],
        lower[3], lower[4], lower[5], j[3], j[4], j[5],
        lower[6], lower[7], lower[8], j[6], j[7], j[8],
    )  # fmt: skip


@kernel
def _jacobian(w0: float, w1: float, w2: float, v0: float, v1: float, v2: float, sign: float) -> tuple[float, ...]:
    # J_l(sign ξ) = [[J, 0], [Q, J]], J the SO(3) left Jacobian: J_r(ξ) = J_l(-ξ)
    w0, w1, w2, v0, v1, v2 = sign * w0, sign * w1, sign * w2, sign * v0, sign * v1, sign * v2
    ux, uy, uz, angle = dexp.axis_angle(w0, w1, w2)
    a, b = dexp.dexp_coefficients(angle)
    return _blocks(dexp.jacobian_entries(ux, uy, uz, a, b), _coupling(ux, uy, uz, angle, v0, v1, v2))


@kernel
def _jacobian_inverse(w0: float, w1: float, w2: float, v0: float, v1: float, v2: float,
                      sign: float) -> tuple[float, ...]:
    # J_l(sign ξ)⁻¹ = [[J⁻¹, 0], [-J⁻¹ Q J⁻¹, J⁻¹]] (Q is linear in v: -Q(ω, v) = Q(ω, -v));
    # NaN at the poles |ω| = 2πk of J⁻¹
    w0, w1, w2, v0, v1, v2 = sign * w0, sign * w1, sign * w2, sign * v0, sign * v1, sign * v2
    ux, uy, uz, angle = dexp.axis_angle(w0, w1, w2)
    quadratic = math.nan if dexp.rotvec_singular(angle, SINGULAR_TOL) else dexp.bortz_times_square(angle)
    inverse = dexp.jacobian_entries(ux, uy, uz, -0.5 * angle, quadratic)
    lower = _product(_product(inverse, _coupling(ux, uy, uz, angle, -v0, -v1, -v2)), inverse)
    return _blocks(inverse, lower)


def _invertible_twists(xi: ArrayLike, name: str) -> NDArray[np.float64]:
    """:func:`~kreisel._compiled.checks.twist_array`, refusing the poles of the inverse Jacobians too."""
    a = twist_array(xi, name)
    angle = norm(a[..., :3])
    poles = (angle > math.pi) & (np.abs(np.sin(0.5 * angle)) <= SINGULAR_TOL)
    if poles.any():
        raise ValueError(f"{name} is at a pole of the inverse Jacobian: the rotation part |omega| = "
                         f"{angle[poles].flat[0]:.17g} rad is a multiple of 2*pi (|sin(|omega|/2)| <= {SINGULAR_TOL:g})")
    return a


_jacobians = declare(_jacobian, [Input("xi", (6,), TWIST)], (6, 6), [Parameter("sign", types.float64)],
                     name="se3_jacobian")
_jacobian_inverses = declare(_jacobian_inverse, [Input("xi", (6,), Kind(TWIST.condition, _invertible_twists))],
                             (6, 6), [Parameter("sign", types.float64)], name="se3_jacobian_inverse")


def _inverse(xi: ArrayLike, sign: float, out: NDArray[np.float64] | None) -> NDArray[np.float64]:
    """J_l⁻¹ of ``sign`` ξ; refusals name ``xi``."""
    try:
        return _jacobian_inverses(xi, sign, out=out)
    except ValueError as refusal:
        if "the result overflows" not in str(refusal):
            raise
    # the inputs passed their checks, and J⁻¹ stays below ~1e16 off the poles: the coupling block overflowed
    raise ValueError("xi is out of range: the coupling block J⁻¹ Q J⁻¹ (of size about |J⁻¹|² |v|) "
                     "exceeds the largest float (~1.8e308)")


@elementwise(_hat, [Input("xi", (6,), VECTOR)], (4, 4))
def se3_hat(xi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """4×4 twist matrices ``[[hat ω, v], [0, 0]]`` of twists ``ξ = (ω, v)``.

    Parameters
    ----------
    xi : array_like, shape (..., 6)
        Twists ``(ω, v)``, angular part first.

    Returns
    -------
    ndarray, shape (..., 4, 4)
        ξ^, with a zero bottom row.

    Examples
    --------
    >>> se3_hat([0, 0, 1, 1, 2, 3]) + 0.0          # + 0.0 clears signed zeros
    array([[ 0., -1.,  0.,  1.],
           [ 1.,  0.,  0.,  2.],
           [ 0.,  0.,  0.,  3.],
           [ 0.,  0.,  0.,  0.]])
    """


@elementwise(_vee, [Input("matrix", (4, 4), VECTOR)], (6,))
def se3_vee(matrix: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Twists ``(ω, v)`` of 4×4 twist matrices (inverse of :func:`se3_hat`).

    Parameters
    ----------
    matrix : array_like, shape (..., 4, 4)
        Twist matrices; the skew part of the upper-left block and the last
        column are read.

    Returns
    -------
    ndarray, shape (..., 6)
        ξ = (ω, v).

    Examples
    --------
    >>> se3_vee(se3_hat([1, 2, 3, 4, 5, 6]))
    array([1., 2., 3., 4., 5., 6.])
    """


@uses(_jacobians)
@takes_out
def se3_left_jacobian(xi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Left Jacobian of SE(3), ``(..., 6, 6)``: ``exp(ξ + δ) ≈ exp(J_l δ) exp(ξ)``.

    Also the map from ``ξ̇`` to the space twist ``(Ṫ T⁻¹)^∨`` of ``T = exp(ξ)``. Rotation parts
    longer than 1e8 rad are refused (the coupling block then depends on |ω| mod 2π, which the
    rounding of |ω| no longer determines).

    Parameters
    ----------
    xi : array_like, shape (..., 6)
        Twists ``(ω, v)``.

    Returns
    -------
    ndarray, shape (..., 6, 6)
        ``[[J_l(ω), 0], [Q(ω, v), J_l(ω)]]``.

    Examples
    --------
    >>> import numpy as np
    >>> np.allclose(se3_left_jacobian(np.zeros(6)), np.eye(6))
    True
    """
    return _jacobians(xi, _LEFT, out=out)


@uses(_jacobians)
@takes_out
def se3_right_jacobian(xi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Right Jacobian of SE(3): ``exp(ξ + δ) ≈ exp(ξ) exp(J_r δ)``; ``J_r(ξ) = J_l(-ξ)``.

    Parameters
    ----------
    xi : array_like, shape (..., 6)
        Twists; ``J_r(ξ) = J_l(−ξ)``.

    Returns
    -------
    ndarray, shape (..., 6, 6)
        J_r(ξ), the left Jacobian at −ξ.

    Examples
    --------
    >>> xi = np.array([0.1, 0.2, 0.3, 1.0, 2.0, 3.0])
    >>> np.allclose(se3_right_jacobian(xi), se3_left_jacobian(-xi))
    True
    """
    return _jacobians(xi, _RIGHT, out=out)


@uses(_jacobian_inverses)
@takes_out
def se3_left_jacobian_inverse(xi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse of :func:`se3_left_jacobian`, ``[[J⁻¹, 0], [-J⁻¹ Q J⁻¹, J⁻¹]]``, without a matrix solve.

    Finite for ``|ω| < 2π`` (logarithms have ``|ω| <= π``); its poles ``|ω| = 2πk`` (within
    ``|sin(|ω|/2)| <= 1e-8``) and rotation parts longer than 1e8 rad are refused.

    Parameters
    ----------
    xi : array_like, shape (..., 6)
        Twists ``(ω, v)`` with ``|ω| < 2π``.

    Returns
    -------
    ndarray, shape (..., 6, 6)
        J_l⁻¹(ξ), built blockwise.

    Examples
    --------
    >>> import numpy as np
    >>> xi = np.array([0.1, 0.2, 0.3, 1.0, 2.0, 3.0])
    >>> np.allclose(se3_left_jacobian_inverse(xi) @ se3_left_jacobian(xi), np.eye(6))
    True
    """
    return _inverse(xi, _LEFT, out)


@uses(_jacobian_inverses)
@takes_out
def se3_right_jacobian_inverse(xi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse of :func:`se3_right_jacobian`; ``J_r⁻¹(ξ) = J_l⁻¹(-ξ)``.

    Parameters
    ----------
    xi : array_like, shape (..., 6)
        Twists, as in :func:`se3_left_jacobian_inverse`.

    Returns
    -------
    ndarray, shape (..., 6, 6)
        The inverse of J_r(ξ) = J_l(−ξ).

    Examples
    --------
    >>> xi = np.array([3.0, 0.2, 0.3, 1.0, 2.0, 3.0])
    >>> np.allclose(se3_right_jacobian_inverse(xi) @ se3_right_jacobian(xi), np.eye(6))
    True
    """
    return _inverse(xi, _RIGHT, out)
