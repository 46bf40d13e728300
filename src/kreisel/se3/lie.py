"""The Lie group SE(3): twists, exponential and logarithm, adjoint, Jacobians.

Twists (exponential coordinates) are ``ξ = (ω, v)``, **rotation part
first**, with ``ξ^ = [[hat ω, v], [0, 0]]`` and ``T = exp(ξ^)``. This is the
order of scipy's ``RigidTransform.as_exp_coords``. The rotation part is the
rotation vector ψ = ω of Theory §2.2; the translation part ``v`` is the
velocity of the body point passing through the origin during the uniform
screw motion ``exp(s ξ^)`` that reaches ``T`` at ``s = 1`` (Theory §3.8), so
``r_C = J_l(ω) v`` with the SO(3) left Jacobian.

Jacobians follow the left/right perturbation convention:
``exp(ξ + δ) ≈ exp(J_l(ξ) δ) exp(ξ) ≈ exp(ξ) exp(J_r(ξ) δ)``. With twists
ordered (ω, v) they are block lower-triangular,
``J_l = [[J, 0], [Q(ω, v), J]]``, ``J`` the SO(3) left Jacobian (from
:mod:`kreisel.so3.jacobians`) and ``Q`` the coupling matrix given by Barfoot
(*State Estimation for Robotics*, 2017, section on SE(3) Jacobians; blocks
swapped here for the (ω, v) order). The three coefficient functions of
``Q`` are summed from their Maclaurin series at small angles, where the
closed forms lose digits (the series of :mod:`kreisel._compiled.series`,
shared with SO(3)), so the Jacobians keep full accuracy at small
angles and have no singularity below 2π (near π in particular). Tested
against the series ``Σ ad_ξⁿ/(n+1)!`` and finite differences.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import dexp
from .._compiled.outputs import deliver, takes_out
from .._compiled.gufunc import finite_array, gufunc
from .._validation import as_float_array
from ..so3 import hat, quat_to_rotvec, vee
from ..so3.rotvec import exp_quat
from .._norms import norm
from ..so3.jacobians import SINGULAR_TOL, check_rotvec_range
from ..so3.jacobians import left_jacobian as so3_left_jacobian
from ..so3.jacobians import left_jacobian_inverse as so3_left_jacobian_inverse

__all__ = [
    "se3_hat",
    "se3_vee",
    "se3_left_jacobian",
    "se3_right_jacobian",
    "se3_left_jacobian_inverse",
    "se3_right_jacobian_inverse",
]


_LEFT = 1.0


@gufunc(["void(f8, f8[:], f8[:])"], "(),(4)->(4)")
def _coupling_coefficients(theta: float, carrier4: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2], out[3] = dexp.se3_coupling_coefficients(theta)


def _q_coefficients(theta: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """bθ, bθ², cθ², dθ³ with b = (θ - sin θ)/θ³, c = (θ² + 2 cos θ - 2)/(2θ⁴), d = (2θ - 3 sin θ + θ cos θ)/(2θ⁵)."""
    c = _coupling_coefficients(theta)
    return c[..., 0], c[..., 1], c[..., 2], c[..., 3]


# Q depends on |ω| mod 2π at its full size |v|/|ω| for long ω, like dexp⁻¹ at its full size: both
# Jacobians and their inverses refuse rotation parts beyond ROTVEC_RANGE (1e8 rad), as does exp.
_ROTATION_PART = "the rotation part |omega|"


def _split(xi: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    return xi[..., :3], xi[..., 3:]


@takes_out
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
    xi = finite_array(xi, "xi", (6,))
    omega, v = _split(xi)
    m = np.zeros(xi.shape[:-1] + (4, 4))
    m[..., :3, :3] = hat(omega)
    m[..., :3, 3] = v
    return deliver(m, out)


@takes_out
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
    m = as_float_array(matrix, "matrix", (4, 4))
    return deliver(np.concatenate([vee(m[..., :3, :3]), m[..., :3, 3]], axis=-1), out)


def exp(xi: NDArray[np.float64], name: str, what: str = _ROTATION_PART) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(q, r_C)`` of ``exp(ξ^)`` for finite twists ``(..., 6)`` named ``name``.

    Rotation parts longer than ``ROTVEC_RANGE`` (1e8 rad) are refused, naming ``what`` their length is.
    """
    omega, v = _split(xi)
    quat = exp_quat(omega, name, what=what)
    # r_C = J_l(ω) v: the dexp map ψ̇ -> ω (space) of Theory §3.4, applied to v
    return quat, dexp.apply_jacobian(omega, v, _LEFT)


def log(quat: NDArray[np.float64], translation: NDArray[np.float64]) -> NDArray[np.float64]:
    """Twists ``(ω, v)`` with ``|ω| <= π`` of poses given as unit quaternions and translations."""
    omega = quat_to_rotvec(quat)
    # v = J_l(ω)⁻¹ r_C: the inverse dexp map of Theory §3.5 (no pole for |ω| <= π)
    v = dexp.apply_jacobian_inverse(omega, translation, _LEFT, SINGULAR_TOL)
    return np.concatenate([omega, v], axis=-1)


def adjoint(rotation_matrix: NDArray[np.float64], translation: NDArray[np.float64]) -> NDArray[np.float64]:
    """``Ad_T = [[R, 0], [hat(t) R, R]]``: ``T exp(ξ^) T⁻¹ = exp((Ad_T ξ)^)`` for ξ = (ω, v)."""
    batch = np.broadcast_shapes(rotation_matrix.shape[:-2], translation.shape[:-1])
    a = np.zeros(batch + (6, 6))
    a[..., :3, :3] = rotation_matrix
    a[..., 3:, 3:] = rotation_matrix
    a[..., 3:, :3] = hat(translation) @ rotation_matrix
    return a


def _coupling(omega: NDArray[np.float64], v: NDArray[np.float64], theta: NDArray[np.float64]) -> NDArray[np.float64]:
    """Barfoot's Q(ω, v), the lower-left block of the SE(3) left Jacobian, for ω of length ``theta``.

    ``Q = ½V + b(WV + VW + WVW) + c(WWV + VWW − 3WVW) + d(WVW W + W WVW)`` with W = hat(ω),
    V = hat(v), written with the unit axis u (W = θ hat(u)) and the coefficients times the
    matching powers of θ: no entry over- or underflows for any finite ω.
    """
    b1, b2, c2, d3 = (c[..., None, None] for c in _q_coefficients(theta))
    U = hat(omega / np.where(theta > 0.0, theta, 1.0)[..., None])
    V = hat(v)
    UV, VU = U @ V, V @ U
    UVU = UV @ U
    return 0.5 * V + b1 * (UV + VU) + (b2 - 3.0 * c2) * UVU + c2 * (U @ UV + VU @ U) + d3 * (UVU @ U + U @ UVU)


def _blocks(diagonal: NDArray[np.float64], lower: NDArray[np.float64]) -> NDArray[np.float64]:
    batch = np.broadcast_shapes(diagonal.shape[:-2], lower.shape[:-2])
    j = np.zeros(batch + (6, 6))
    j[..., :3, :3] = diagonal
    j[..., 3:, 3:] = diagonal
    j[..., 3:, :3] = lower
    return j


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
    xi = finite_array(xi, "xi", (6,))
    omega, v = _split(xi)
    theta = norm(omega)
    check_rotvec_range(theta, "xi", _ROTATION_PART)
    return deliver(_blocks(so3_left_jacobian(omega), _coupling(omega, v, theta)), out)


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
    return deliver(se3_left_jacobian(-finite_array(xi, "xi", (6,))), out)


@takes_out
def se3_left_jacobian_inverse(xi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse of :func:`se3_left_jacobian`, ``[[J⁻¹, 0], [-J⁻¹ Q J⁻¹, J⁻¹]]``, without a matrix solve.

    Finite for ``|ω| < 2π`` (logarithms have ``|ω| <= π``); rotation parts longer than 1e8 rad
    are refused, as by :func:`se3_left_jacobian`.

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
    xi = finite_array(xi, "xi", (6,))
    omega, v = _split(xi)
    theta = norm(omega)
    check_rotvec_range(theta, "xi", _ROTATION_PART)
    inverse = so3_left_jacobian_inverse(omega)
    with np.errstate(over="ignore", invalid="ignore"):
        lower = -inverse @ _coupling(omega, v, theta) @ inverse
    if not np.isfinite(lower[np.isfinite(inverse[..., 0, 0])]).all():
        raise ValueError("xi is out of range: the coupling block J⁻¹ Q J⁻¹ (of size about |J⁻¹|² |v|) "
                         "exceeds the largest float (~1.8e308)")
    return deliver(_blocks(inverse, lower), out)


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
    return deliver(se3_left_jacobian_inverse(-finite_array(xi, "xi", (6,))), out)
