"""Angular velocity from the rotation matrix and from quaternions (Theory §3.1–3).

``hat(ω) = Ṙ Rᵀ`` (space components), ``hat(ω′) = Rᵀ Ṙ`` (body components),
``q̇ = ½ ω q = ½ q ω′``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import kernels
from .._compiled.gufunc import gufunc, quaternion_array
from .._compiled.outputs import deliver, takes_out
from .._validation import check_frame
from ._checks import frame_sign, rotation_batch, same_batch, vectors

__all__ = ["angular_velocity", "quat_rate", "angular_velocity_from_quat_rate"]


def _skew_part_vee(A: NDArray[Any]) -> NDArray[np.float64]:
    # vee of the antisymmetric part: the least-squares angular velocity when
    # Ṙ Rᵀ is not exactly antisymmetric (noisy or finite-difference data)
    return 0.5 * np.stack(
        [A[..., 2, 1] - A[..., 1, 2], A[..., 0, 2] - A[..., 2, 0], A[..., 1, 0] - A[..., 0, 1]], axis=-1
    )


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
    R, Rdot = rotation_batch(R, Rdot=Rdot)
    A = np.swapaxes(R, -1, -2) @ Rdot if body else Rdot @ np.swapaxes(R, -1, -2)
    return deliver(_skew_part_vee(A), out)


# sign = +1: space (q̇ = ½ ω q), sign = -1: body (q̇ = ½ q ω′); the two
# products differ only in the sign of the cross-product term.
@gufunc(["void(f8[:], f8[:], f8, f8[:])"], "(4),(3),()->(4)")
def _quat_rate(q: NDArray[np.float64], w: NDArray[np.float64], sign: float, out: NDArray[np.float64]) -> None:
    q0, vx, vy, vz = q[0], q[1], q[2], q[3]
    wx, wy, wz = w[0], w[1], w[2]
    cx = wy * vz - wz * vy
    cy = wz * vx - wx * vz
    cz = wx * vy - wy * vx
    out[0] = -0.5 * (wx * vx + wy * vy + wz * vz)
    out[1] = 0.5 * (q0 * wx + sign * cx)
    out[2] = 0.5 * (q0 * wy + sign * cy)
    out[3] = 0.5 * (q0 * wz + sign * cz)


# ω = 2 vec(q̇ q⁻¹) (space) or 2 vec(q⁻¹ q̇) (body), q⁻¹ = q*/|q|²: exact also
# for non-unit q, whose rotation R(q/|q|) is what the angular velocity describes.
# q is divided by its largest component m first: q̇ q⁻¹ = q̇ (q/m)* / (|q/m|² m),
# so neither |q|² nor a product of q and q̇ over- or underflows unless ω does.
@gufunc(["void(f8[:], f8[:], f8, f8[:], f8[:])"], "(4),(4),(),(3)->(3)")
def _quat_angular_velocity(q: NDArray[np.float64], qd: NDArray[np.float64], sign: float, carrier3: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    m = kernels.size(q[0], q[1], q[2], q[3])
    q0, vx, vy, vz = q[0] / m, q[1] / m, q[2] / m, q[3] / m
    p0, px, py, pz = qd[0], qd[1], qd[2], qd[3]
    s = 2.0 / (q0 * q0 + vx * vx + vy * vy + vz * vz)
    cx = py * vz - pz * vy
    cy = pz * vx - px * vz
    cz = px * vy - py * vx
    out[0] = s * (q0 * px - p0 * vx - sign * cx) / m
    out[1] = s * (q0 * py - p0 * vy - sign * cy) / m
    out[2] = s * (q0 * pz - p0 * vz - sign * cz) / m


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
    q, omega = same_batch(1, q=quaternion_array(q), omega=vectors(omega, "omega"))
    return _quat_rate(q, omega, sign, out=out)


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
    q, qdot = same_batch(1, q=quaternion_array(q), qdot=vectors(qdot, "qdot", 4))
    with np.errstate(over="ignore"):
        omega = _quat_angular_velocity(q, qdot, sign, out=out)
    if not np.isfinite(omega).all():
        raise ValueError("q and qdot are out of range: the angular velocity 2|qdot|/|q| exceeds "
                         "the largest float (~1.8e308)")
    return omega
