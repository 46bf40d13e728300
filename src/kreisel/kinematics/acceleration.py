"""Angular acceleration ε = dω/dt from second derivatives of any parameterisation (Theory §3.9).

Space and body components are related by ``ε′ = Rᵀ ε`` (the term Ṙᵀω
vanishes because hat(ω)ᵀω = 0), so ``ε′ = dω′/dt`` as well.
"""

from __future__ import annotations

import numpy as np
from numba import types
from numpy.typing import ArrayLike, NDArray

from .._compiled import dexp, kernels
from .._compiled.checks import QUATERNION, VECTOR, finite_array
from .._compiled.elementwise import Input, Parameter, declare, kernel, uses
from .._compiled.outputs import takes_out
from .._validation import check_frame, out_of_range
from ._checks import batch_shape, frame_sign, matrix_batch, vector_batch
from .euler import SEQUENCE, _angles, _code
from .rates import skew_vee

__all__ = [
    "angular_acceleration",
    "angular_acceleration_from_quat",
    "angular_acceleration_from_rotvec",
    "angular_acceleration_from_euler",
]


@kernel
def _quat_acceleration(q0: float, q1: float, q2: float, q3: float, d0: float, d1: float, d2: float, d3: float,
                       a0: float, a1: float, a2: float, a3: float, sign: float) -> tuple[float, float, float]:
    # q = m u with m the largest |component|: q⁻¹ = u*/k, k = |u|² m, |u|² in [1, 4], and with r = q̇ u*,
    # c = q̈ u* (u* q̇, u* q̈ in body components) ε = 2 vec(c/k − (r/k)²) = 2 (c⃗/k − 2 (r₀/k)(r⃗/k)):
    # no intermediate over- or underflows unless ε does (|q|² would beyond ~1e±154)
    m = kernels.largest_component(q0, q1, q2, q3)
    u0, u1, u2, u3 = q0 / m, -q1 / m, -q2 / m, -q3 / m
    k = (u0 * u0 + u1 * u1 + u2 * u2 + u3 * u3) * m
    if sign > 0.0:
        r0, r1, r2, r3 = kernels.quat_product(d0, d1, d2, d3, u0, u1, u2, u3)
        _, c1, c2, c3 = kernels.quat_product(a0, a1, a2, a3, u0, u1, u2, u3)
    else:
        r0, r1, r2, r3 = kernels.quat_product(u0, u1, u2, u3, d0, d1, d2, d3)
        _, c1, c2, c3 = kernels.quat_product(u0, u1, u2, u3, a0, a1, a2, a3)
    s = 2.0 * (r0 / k)
    return 2.0 * (c1 / k - s * (r1 / k)), 2.0 * (c2 / k - s * (r2 / k)), 2.0 * (c3 / k - s * (r3 / k))


@kernel
def _euler_acceleration(x0: float, x1: float, x2: float, r0: float, r1: float, r2: float, e0: float, e1: float,
                        e2: float, a: int, b: int, c: int, extrinsic: int, body: int) -> tuple[float, float, float]:
    # ε = Σ r̈ᵢ cᵢ + r₀ r₁ c₀×c₁ + r₂ (r₀ c₀ + r₁ c₁)×c₂ in the intrinsic order
    c0, c1, c2, det = dexp.euler_columns(x0, x1, x2, a, b, c, extrinsic, body)
    if extrinsic:
        r0, r2, e0, e2 = r2, r0, e2, e0
    p0, p1, p2 = dexp.cross(c0[0], c0[1], c0[2], c1[0], c1[1], c1[2])
    s0, s1, s2 = dexp.cross(r0 * c0[0] + r1 * c1[0], r0 * c0[1] + r1 * c1[1], r0 * c0[2] + r1 * c1[2],
                            c2[0], c2[1], c2[2])
    r01 = r0 * r1
    return (
        e0 * c0[0] + e1 * c1[0] + e2 * c2[0] + r01 * p0 + r2 * s0,
        e0 * c0[1] + e1 * c1[1] + e2 * c2[1] + r01 * p1 + r2 * s1,
        e0 * c0[2] + e1 * c1[2] + e2 * c2[2] + r01 * p2 + r2 * s2,
    )


_from_matrices = skew_vee.renamed(Rdot="Rddot")
_from_quat = declare(_quat_acceleration, [Input("q", (4,), QUATERNION), Input("qdot", (4,), VECTOR),
                                          Input("qddot", (4,), VECTOR)], (3,), [Parameter("sign", types.float64)],
                     name="angular_acceleration_from_quat").refusing(
    "q, qdot and qddot are out of range: the angular acceleration (of size |qddot|/|q| + |qdot|²/|q|²) exceeds "
    "the largest float (~1.8e308)")
# quadratic in ψ̇: rates beyond ~1e154 rad/s give an acceleration beyond the largest double
_from_rotvec = dexp.apply_jacobian_rate.renamed(v="psidot", acc="psiddot").refusing(
    out_of_range("psidot and psiddot", "the angular acceleration").message)
# products of rates: rates beyond ~1e154 rad/s give an acceleration beyond the largest double
_from_euler = declare(_euler_acceleration, [Input("angles", (3,), VECTOR), Input("rates", (3,), VECTOR),
                                            Input("accelerations", (3,), VECTOR)], (3,), SEQUENCE,
                      name="angular_acceleration_from_euler").refusing(
    out_of_range("rates and accelerations", "the angular acceleration").message)


@uses(_from_matrices)
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
    R, Rdot, Rddot = matrix_batch(R=R, Rdot=Rdot, Rddot=Rddot)
    finite_array(Rdot, "Rdot", (3, 3))
    return _from_matrices(R, Rddot, int(body), out=out)


@uses(_from_quat)
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
    sign = frame_sign(frame)
    q, qdot, qddot = vector_batch(4, q=q, qdot=qdot, qddot=qddot)
    return _from_quat(q, qdot, qddot, sign, out=out)


@uses(_from_rotvec)
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
    return _from_rotvec(psi, psidot, psiddot, sign, out=out)


@uses(_from_euler)
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
    code = _code(seq, frame)
    angles = _angles(angles, degrees)
    rates = _angles(rates, degrees, "rates")
    accelerations = _angles(accelerations, degrees, "accelerations")
    batch_shape(("angles", angles, 1), ("rates", rates, 1), ("accelerations", accelerations, 1))
    return _from_euler(angles, rates, accelerations, *code, out=out)
