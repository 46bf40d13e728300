"""Angular acceleration ε = dω/dt from second derivatives of any parameterisation (Theory §3.9).

Space and body components are related by ``ε′ = Rᵀ ε`` (the term Ṙᵀω
vanishes because hat(ω)ᵀω = 0), so ``ε′ = dω′/dt`` as well.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import dexp
from .._compiled.outputs import deliver, takes_out
from .._compiled.gufunc import quaternion_array
from .._validation import check_frame, out_of_range
from ..so3 import quat_conjugate, quat_multiply
from .._norms import norm
from ..so3.euler import parse_sequence
from ._checks import batch_shape, frame_sign, rotation_batch, same_batch, vector_batch, vectors
from .euler import _angles, euler_rate_matrix
from .rates import _skew_part_vee

__all__ = [
    "angular_acceleration",
    "angular_acceleration_from_quat",
    "angular_acceleration_from_rotvec",
    "angular_acceleration_from_euler",
]


@takes_out
def angular_acceleration(R: ArrayLike, Rdot: ArrayLike, Rddot: ArrayLike, frame: str = "space", *,
                         out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Angular acceleration from a rotation matrix and its first two derivatives.

    ``hat(ε) = skew(R̈ Rᵀ)`` (space) and ``hat(ε′) = skew(Rᵀ R̈)`` (body): the
    derivative of hat(ω) = Ṙ Rᵀ is R̈ Rᵀ + Ṙ Ṙᵀ, whose second term is symmetric.

    Parameters
    ----------
    R, Rdot, Rddot : array_like, shape (..., 3, 3)
        Rotation matrices (body → space) and their first and second time
        derivatives; batch shapes broadcast.
    frame : {"space", "body"}
        Components of the result: ε from R̈ Rᵀ, or ε′ from Rᵀ R̈.

    Returns
    -------
    ndarray, shape (..., 3)
        The vector of the antisymmetric part, so inexact data (finite
        differences) give the nearest angular acceleration.

    Examples
    --------
    Rotation about z with angle t²/2 (ω = t, ε = 1):

    >>> t = 0.7
    >>> c, s = np.cos(t * t / 2), np.sin(t * t / 2)
    >>> R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    >>> Rd = t * np.array([[-s, -c, 0], [c, -s, 0], [0, 0, 0]])
    >>> Rdd = np.array([[-s, -c, 0], [c, -s, 0], [0, 0, 0]]) - t * t * np.array([[c, -s, 0], [s, c, 0], [0, 0, 0]])
    >>> angular_acceleration(R, Rd, Rdd).round(15) + 0.0
    array([0., 0., 1.])
    """
    body = check_frame(frame)
    R, Rdot, Rddot = rotation_batch(R, Rdot=Rdot, Rddot=Rddot)
    Rt = np.swapaxes(R, -1, -2)
    return deliver(_skew_part_vee(Rt @ Rddot if body else Rddot @ Rt), out)


@takes_out
def angular_acceleration_from_quat(q: ArrayLike, qdot: ArrayLike, qddot: ArrayLike, frame: str = "space", *,
                                   out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Angular acceleration from a quaternion and its first two derivatives.

    With ``ω = 2 vec(q̇ q⁻¹)``: ``ε = 2 vec(q̈ q⁻¹ − (q̇ q⁻¹)²)`` (space) and
    ``ε′ = 2 vec(q⁻¹ q̈ − (q⁻¹ q̇)²)`` (body); for unit q the squared term is
    real and drops out, leaving ε = 2 vec(q̈ q*).

    Parameters
    ----------
    q, qdot, qddot : array_like, shape (..., 4)
        Scalar-first quaternions (need not be unit) and their first and second
        time derivatives.
    frame : {"space", "body"}
        Components of the result: ε from q̈ q⁻¹, or ε′ from q⁻¹ q̈.

    Returns
    -------
    ndarray, shape (..., 3)
        The angular acceleration of the rotation of q/|q|.

    Examples
    --------
    >>> angular_acceleration_from_quat([1.0, 0, 0, 0], [0.0, 0, 0, 0], [0.0, 0.5, 0, 0])
    array([1., 0., 0.])
    """
    body = check_frame(frame)
    q, qdot, qddot = same_batch(
        1, q=quaternion_array(q), qdot=vectors(qdot, "qdot", 4), qddot=vectors(qddot, "qddot", 4)
    )
    # q = |q| u with u a unit quaternion: q⁻¹ = u*/|q|, so ε = 2 vec(q̈ u*)/|q| − 2 vec((q̇ u*)²)/|q|²
    # (space); the powers of |q| are divided out last, so no intermediate over- or underflows
    # unless ε does (|q|² itself would beyond ~1e±154).
    size = norm(q, keepdims=True)
    u_inv = quat_conjugate(q / size)
    if body:
        rate, curvature = quat_multiply(u_inv, qdot), quat_multiply(u_inv, qddot)
    else:
        rate, curvature = quat_multiply(qdot, u_inv), quat_multiply(qddot, u_inv)
    # vec(r²) = 2 r₀ r⃗ for a quaternion r
    with np.errstate(over="ignore", invalid="ignore"):
        eps = 2.0 * (curvature[..., 1:] / size - 2.0 * (rate[..., :1] / size) * (rate[..., 1:] / size))
    if not np.isfinite(eps).all():
        raise ValueError("q, qdot and qddot are out of range: the angular acceleration (of size "
                         "|qddot|/|q| + |qdot|²/|q|²) exceeds the largest float (~1.8e308)")
    return deliver(eps, out)


@takes_out
def angular_acceleration_from_rotvec(psi: ArrayLike, psidot: ArrayLike, psiddot: ArrayLike, frame: str = "space", *,
                                     out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Angular acceleration from a rotation vector and its first two derivatives.

    Differentiates the dexp map of Theory §3.4, ``ω = J(ψ) ψ̇``; the
    coefficient derivatives are summed from their series at small ψ, and ψ
    enters through its unit axis and its length (no squares of it), so the
    result is accurate to a few ulp for all ψ, from 1e-300 to 1e300.

    Parameters
    ----------
    psi, psidot, psiddot : array_like, shape (..., 3)
        Rotation vector (any length) and its first and second time derivatives.
    frame : {"space", "body"}
        Components of the result: ε through J_l(ψ), or ε′ through J_r(ψ).

    Returns
    -------
    ndarray, shape (..., 3)
        ε (space) or ε′ (body), the time derivative of the dexp map.

    Examples
    --------
    >>> angular_acceleration_from_rotvec([0.0, 0.0, 1.0], [0.0, 0.0, 2.0], [0.0, 0.0, 3.0])
    array([0., 0., 3.])
    """
    sign = frame_sign(frame)
    psi, psidot, psiddot = vector_batch(psi=psi, psidot=psidot, psiddot=psiddot)
    with out_of_range("psidot and psiddot", "the angular acceleration") as guard:
        # quadratic in ψ̇: rates beyond ~1e154 rad/s give an acceleration beyond the largest double
        epsilon: NDArray[np.float64] = guard.check(dexp.apply_jacobian_rate(psi, psidot, psiddot, sign, out=out))
    return epsilon


@takes_out
def angular_acceleration_from_euler(seq: str, angles: ArrayLike, rates: ArrayLike, accelerations: ArrayLike,
                                    frame: str = "space", degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Angular acceleration from Euler angles and their first two derivatives (Theory §3.6, §3.9).

    With the rate-matrix columns c₀, c₁, c₂ in the order of the equivalent
    intrinsic sequence (outermost rotation first) and its rates r:
    ``ε = Σ r̈ᵢ cᵢ + r₀ r₁ c₀×c₁ + r₂ (r₀ c₀ + r₁ c₁)×c₂``, in either frame.

    Parameters
    ----------
    seq : str
    angles, rates, accelerations : array_like, shape (..., 3)
        Angles and their first and second time derivatives (radians, or
        degrees with ``degrees=True``).
    frame : {"space", "body"}
        Components of the result (the rate-matrix columns cᵢ are taken in
        that frame).
    degrees : bool
        Angles and their derivatives in degrees (ε is in rad/s² either way).

    Returns
    -------
    ndarray, shape (..., 3)
        ε in rad/s².

    Examples
    --------
    >>> angular_acceleration_from_euler("ZXZ", [0.0, 0.5, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], frame="body")
    array([0., 0., 1.])
    """
    _, intrinsic = parse_sequence(seq)
    M = euler_rate_matrix(seq, angles, frame=frame, degrees=degrees)
    rates = _angles(rates, degrees, "rates")
    accelerations = _angles(accelerations, degrees, "accelerations")
    batch_shape(("angles", M, 2), ("rates", rates, 1), ("accelerations", accelerations, 1))
    order = slice(None) if intrinsic else slice(None, None, -1)
    c = np.swapaxes(M, -1, -2)[..., order, :]
    r = rates[..., order]
    c0, c1, c2 = c[..., 0, :], c[..., 1, :], c[..., 2, :]
    r0, r1, r2 = r[..., 0:1], r[..., 1:2], r[..., 2:3]
    with out_of_range("rates and accelerations", "the angular acceleration") as guard:
        # products of rates: rates beyond ~1e154 rad/s give an acceleration beyond the largest double
        epsilon = guard.check(
            np.einsum("...ij,...i->...j", M.swapaxes(-1, -2), accelerations)
            + r0 * r1 * np.cross(c0, c1)
            + r2 * np.cross(r0 * c0 + r1 * c1, c2)
        )
    return deliver(epsilon, out)
