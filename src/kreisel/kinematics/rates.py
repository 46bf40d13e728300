"""Angular velocity from the rotation matrix and from quaternions (Theory §3.1–3).

``hat(ω) = Ṙ Rᵀ`` (space components), ``hat(ω′) = Rᵀ Ṙ`` (body components),
``q̇ = ½ ω q = ½ q ω′``.
"""

from __future__ import annotations

import numpy as np
from numba import types
from numpy.typing import ArrayLike, NDArray

from .._compiled import kernels
from .._compiled.checks import MATRIX, QUATERNION, VECTOR
from .._compiled.elementwise import Input, Parameter, declare, kernel, uses
from .._compiled.outputs import takes_out
from .._validation import check_frame
from ._checks import frame_sign, matrix_batch, same_batch, vectors

__all__ = ["angular_velocity", "quat_rate", "angular_velocity_from_quat_rate"]


@kernel
def _skew_vee(r00: float, r01: float, r02: float, r10: float, r11: float, r12: float, r20: float, r21: float,
              r22: float, d00: float, d01: float, d02: float, d10: float, d11: float, d12: float, d20: float,
              d21: float, d22: float, body: int) -> tuple[float, float, float]:
    # vee of the antisymmetric part of D Rᵀ (space) or Rᵀ D (body): the least-squares angular
    # velocity when Ṙ Rᵀ is not exactly antisymmetric (noisy or finite-difference data)
    if body:
        return (
            0.5 * ((r02 * d01 + r12 * d11 + r22 * d21) - (r01 * d02 + r11 * d12 + r21 * d22)),
            0.5 * ((r00 * d02 + r10 * d12 + r20 * d22) - (r02 * d00 + r12 * d10 + r22 * d20)),
            0.5 * ((r01 * d00 + r11 * d10 + r21 * d20) - (r00 * d01 + r10 * d11 + r20 * d21)),
        )
    return (
        0.5 * ((d20 * r10 + d21 * r11 + d22 * r12) - (d10 * r20 + d11 * r21 + d12 * r22)),
        0.5 * ((d00 * r20 + d01 * r21 + d02 * r22) - (d20 * r00 + d21 * r01 + d22 * r02)),
        0.5 * ((d10 * r00 + d11 * r01 + d12 * r02) - (d00 * r10 + d01 * r11 + d02 * r12)),
    )


#: vee of the antisymmetric part of a matrix's product with a rotation's transpose; a rotation ``R``
#: is checked like every rotation matrix of kreisel (orthogonal to within ``ORTHOGONALITY_TOLERANCE``,
#: det > 0): a scaled matrix or a reflection would silently scale or flip the angular velocity.
skew_vee = declare(_skew_vee, [Input("R", (3, 3), MATRIX), Input("Rdot", (3, 3), VECTOR)], (3,),
                   [Parameter("body", types.int64)], name="angular_velocity")


@uses(skew_vee)
@takes_out
def angular_velocity(R: ArrayLike, Rdot: ArrayLike, frame: str = "space", *,
                     out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Angular velocity from the rotation matrix and its time derivative (Theory §3.1).

    ``hat(ω) = Ṙ Rᵀ`` in space components, ``hat(ω′) = Rᵀ Ṙ`` in body
    components (Theory §3.6). The antisymmetric part is taken, so for inexact
    data (e.g. finite differences) the result is the least-squares ω.

    Parameters
    ----------
    R, Rdot : array_like, shape (..., 3, 3)
        Rotation matrices (body → space; anything else is refused) and their
        time derivatives; batch shapes broadcast.
    frame : {"space", "body"}
        Components of the returned angular velocity.

    Returns
    -------
    ndarray, shape (..., 3)
        ω or ω′: the vector of the antisymmetric part of Ṙ Rᵀ or Rᵀ Ṙ.

    Examples
    --------
    >>> import numpy as np
    >>> t = 0.3
    >>> R = np.array([[np.cos(t), -np.sin(t), 0], [np.sin(t), np.cos(t), 0], [0, 0, 1]])
    >>> Rdot = 2.0 * np.array([[-np.sin(t), -np.cos(t), 0], [np.cos(t), -np.sin(t), 0], [0, 0, 0]])
    >>> angular_velocity(R, Rdot)
    array([0., 0., 2.])
    """
    body = check_frame(frame)
    R, Rdot = matrix_batch(R=R, Rdot=Rdot)
    return skew_vee(R, Rdot, int(body), out=out)


@kernel
def _quat_rate(q0: float, vx: float, vy: float, vz: float, wx: float, wy: float, wz: float,
               sign: float) -> tuple[float, float, float, float]:
    # sign = +1: space (q̇ = ½ ω q), sign = -1: body (q̇ = ½ q ω′); the two
    # products differ only in the sign of the cross-product term.
    cx = wy * vz - wz * vy
    cy = wz * vx - wx * vz
    cz = wx * vy - wy * vx
    return (
        -0.5 * (wx * vx + wy * vy + wz * vz),
        0.5 * (q0 * wx + sign * cx),
        0.5 * (q0 * wy + sign * cy),
        0.5 * (q0 * wz + sign * cz),
    )


@kernel
def _quat_angular_velocity(q0: float, q1: float, q2: float, q3: float, p0: float, px: float, py: float, pz: float,
                           sign: float) -> tuple[float, float, float]:
    # ω = 2 vec(q̇ q⁻¹) (space) or 2 vec(q⁻¹ q̇) (body), q⁻¹ = q*/|q|²: exact also
    # for non-unit q, whose rotation R(q/|q|) is what the angular velocity describes.
    # q is divided by its largest component m first: q̇ q⁻¹ = q̇ (q/m)* / (|q/m|² m),
    # so neither |q|² nor a product of q and q̇ over- or underflows unless ω does.
    m = kernels.largest_component(q0, q1, q2, q3)
    q0, vx, vy, vz = q0 / m, q1 / m, q2 / m, q3 / m
    s = 2.0 / (q0 * q0 + vx * vx + vy * vy + vz * vz)
    cx = py * vz - pz * vy
    cy = pz * vx - px * vz
    cz = px * vy - py * vx
    return (
        s * (q0 * px - p0 * vx - sign * cx) / m,
        s * (q0 * py - p0 * vy - sign * cy) / m,
        s * (q0 * pz - p0 * vz - sign * cz) / m,
    )


_SIGN = Parameter("sign", types.float64)
_ROTATION = Input("q", (4,), QUATERNION)
_quat_rates = declare(_quat_rate, [_ROTATION, Input("omega", (3,), VECTOR)], (4,), [_SIGN], name="quat_rate")
_quat_omega = declare(_quat_angular_velocity, [_ROTATION, Input("qdot", (4,), VECTOR)], (3,), [_SIGN],
                      name="angular_velocity_from_quat_rate").refusing(
    "q and qdot are out of range: the angular velocity 2|qdot|/|q| exceeds the largest float (~1.8e308)")


@uses(_quat_rates)
@takes_out
def quat_rate(q: ArrayLike, omega: ArrayLike, frame: str = "space", *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Quaternion rate from the angular velocity (Theory §3.3).

    ``q̇ = ½ ω q`` with space components, ``q̇ = ½ q ω′`` with body
    components (pure quaternions ω = (0, ω)); the latter is the attitude
    equation of strapdown navigation.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Scalar-first attitude quaternions (body → space).
    omega : array_like, shape (..., 3)
        Angular velocity in the components given by ``frame``.
    frame : {"space", "body"}
        ``"space"``: ω is ω and q̇ = ½ ω q; ``"body"``: ω is ω′ and q̇ = ½ q ω′.

    Returns
    -------
    ndarray, shape (..., 4)
        q̇, orthogonal to q (the norm is preserved).

    Examples
    --------
    >>> quat_rate([0.6, 0.8, 0.0, 0.0], [2.0, 0.0, 0.0])
    array([-0.8,  0.6,  0. ,  0. ])
    """
    sign = frame_sign(frame)
    q, omega = same_batch(1, q=vectors(q, "q", 4), omega=vectors(omega, "omega"))
    return _quat_rates(q, omega, sign, out=out)


@uses(_quat_omega)
@takes_out
def angular_velocity_from_quat_rate(q: ArrayLike, qdot: ArrayLike, frame: str = "space", *,
                                    out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Angular velocity from a quaternion and its rate (Theory §3.3).

    ``ω = 2 q̇ q*`` (space) and ``ω′ = 2 q* q̇`` (body), taking the vector
    part; ``q*`` is replaced by ``q⁻¹ = q*/|q|²`` so that non-unit
    quaternions give the angular velocity of the rotation they represent.

    Parameters
    ----------
    q, qdot : array_like, shape (..., 4)
        Scalar-first quaternions (need not be unit) and their time derivatives.
    frame : {"space", "body"}
        Components of the result: ω from q̇ q⁻¹, or ω′ from q⁻¹ q̇.

    Returns
    -------
    ndarray, shape (..., 3)
        ω or ω′ of the rotation that q/|q| represents.

    Examples
    --------
    >>> angular_velocity_from_quat_rate([1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0], frame="body")
    array([0., 0., 2.])
    """
    sign = frame_sign(frame)
    q, qdot = same_batch(1, q=vectors(q, "q", 4), qdot=vectors(qdot, "qdot", 4))
    return _quat_omega(q, qdot, sign, out=out)
