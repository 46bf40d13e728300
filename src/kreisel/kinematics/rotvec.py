"""Rotation-vector kinematics: the dexp map, the Bortz equation, SO(3) Jacobians.

With ``R = exp(ψ·X)`` (Theory §3.4),

    ω  = ψ̇ + A ψ×ψ̇ + B ψ×(ψ×ψ̇)  = J_l(ψ) ψ̇      (space components)
    ω′ = ψ̇ − A ψ×ψ̇ + B ψ×(ψ×ψ̇)  = J_r(ψ) ψ̇      (body components)

with ``A = (1 − cos ψ)/ψ²``, ``B = (ψ − sin ψ)/ψ³``, and the inverses
(Theory §3.5; the body one is the Bortz equation)

    ψ̇ = ω′ + ½ ψ×ω′ + f ψ×(ψ×ω′) = J_r⁻¹ ω′,   ψ̇ = ω − ½ ψ×ω + f ψ×(ψ×ω) = J_l⁻¹ ω,

``f = (2 sin ψ − ψ(1 + cos ψ)) / (2ψ² sin ψ) = 1/12 + ψ²/720 + ψ⁴/30240 + …``.

Accuracy: every coefficient is evaluated without cancellation (series at
small ψ), so the maps are accurate to a few ulp for all ψ; J⁻¹ has poles at
|ψ| = 2π, 4π, … where the rates are NaN (:class:`RotationVectorSingularityWarning`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import prange

from .._compiled import cached, dexp, parallel
from .._compiled.gufunc import gufunc
from ._checks import frame_sign, tolerance, vector_batch, vectors
from ._singularity import SINGULAR_TOL, RotationVectorSingularityWarning, warn_if_any

__all__ = [
    "bortz_coefficient",
    "angular_velocity_from_rotvec_rate",
    "rotvec_rate",
    "rotvec_rate_singular",
    "left_jacobian",
    "right_jacobian",
    "left_jacobian_inverse",
    "right_jacobian_inverse",
]

_SPACE, _BODY = 1.0, -1.0


@gufunc(["void(f8, f8[:])"], "()->()")
def _bortz(angle, out):
    out[0] = dexp.bortz_coefficient(angle)


# Element kernels on scalars: passing array views into a compiled call costs
# about as much as these kernels. The frame sign and the tolerance are shared
# by the whole batch.


# J v = v + sign A ψ×v + B ψ×(ψ×v): sign +1 is J_l (space), −1 is J_r (body)
@cached
def _dexp_element(x, y, z, v0, v1, v2, sign):
    a, b = dexp.dexp_coefficients(math.sqrt(x * x + y * y + z * z))
    cx, cy, cz = dexp.cross(x, y, z, v0, v1, v2)
    ccx, ccy, ccz = dexp.cross(x, y, z, cx, cy, cz)
    sa = sign * a
    return v0 + sa * cx + b * ccx, v1 + sa * cy + b * ccy, v2 + sa * cz + b * ccz


# J⁻¹ w = w − (sign/2) ψ×w + f ψ×(ψ×w), NaN at the poles |ψ| = 2πk
@cached
def _dexp_inverse_element(x, y, z, w0, w1, w2, sign, tol):
    angle = math.sqrt(x * x + y * y + z * z)
    if dexp.rotvec_singular(angle, tol):
        return math.nan, math.nan, math.nan
    f = dexp.bortz_coefficient(angle)
    cx, cy, cz = dexp.cross(x, y, z, w0, w1, w2)
    ccx, ccy, ccz = dexp.cross(x, y, z, cx, cy, cz)
    h = -0.5 * sign
    return w0 + h * cx + f * ccx, w1 + h * cy + f * ccy, w2 + h * cz + f * ccz


@parallel
def _dexp_apply_parallel(psi, v, sign, out):
    for i in prange(psi.shape[0]):
        out[i, 0], out[i, 1], out[i, 2] = _dexp_element(psi[i, 0], psi[i, 1], psi[i, 2], v[i, 0], v[i, 1], v[i, 2], sign)


@parallel
def _dexp_inverse_apply_parallel(psi, w, sign, tol, out):
    for i in prange(psi.shape[0]):
        out[i, 0], out[i, 1], out[i, 2] = _dexp_inverse_element(
            psi[i, 0], psi[i, 1], psi[i, 2], w[i, 0], w[i, 1], w[i, 2], sign, tol
        )


@gufunc(["void(f8[:], f8[:], f8, f8[:])"], "(3),(3),()->(3)", parallel=_dexp_apply_parallel, shared=(2,))
def _dexp_apply(psi, v, sign, out):
    out[0], out[1], out[2] = _dexp_element(psi[0], psi[1], psi[2], v[0], v[1], v[2], sign)


@gufunc(["void(f8[:], f8[:], f8, f8, f8[:])"], "(3),(3),(),()->(3)", parallel=_dexp_inverse_apply_parallel, shared=(2, 3))
def _dexp_inverse_apply(psi, w, sign, tol, out):
    out[0], out[1], out[2] = _dexp_inverse_element(psi[0], psi[1], psi[2], w[0], w[1], w[2], sign, tol)


@cached
def _write_matrix(x, y, z, linear, quadratic, out):
    # out = 1 + linear hat(ψ) + quadratic hat(ψ)², hat(ψ)² = ψψᵀ − |ψ|² 1
    n2 = x * x + y * y + z * z
    out[0, 0] = 1.0 + quadratic * (x * x - n2)
    out[1, 1] = 1.0 + quadratic * (y * y - n2)
    out[2, 2] = 1.0 + quadratic * (z * z - n2)
    out[0, 1] = quadratic * x * y - linear * z
    out[1, 0] = quadratic * x * y + linear * z
    out[0, 2] = quadratic * x * z + linear * y
    out[2, 0] = quadratic * x * z - linear * y
    out[1, 2] = quadratic * y * z - linear * x
    out[2, 1] = quadratic * y * z + linear * x


@gufunc(["void(f8[:], f8, f8[:, :])"], "(3),()->(3,3)")
def _dexp_matrix(psi, sign, out):
    x, y, z = psi[0], psi[1], psi[2]
    a, b = dexp.dexp_coefficients(math.sqrt(x * x + y * y + z * z))
    _write_matrix(x, y, z, sign * a, b, out)


@gufunc(["void(f8[:], f8, f8, f8[:, :])"], "(3),(),()->(3,3)")
def _dexp_inverse_matrix(psi, sign, tol, out):
    x, y, z = psi[0], psi[1], psi[2]
    angle = math.sqrt(x * x + y * y + z * z)
    if dexp.rotvec_singular(angle, tol):
        out[:, :] = math.nan
        return
    _write_matrix(x, y, z, -0.5 * sign, dexp.bortz_coefficient(angle), out)


def bortz_coefficient(angle):
    """The Bortz coefficient ``(2 sin ψ − ψ(1 + cos ψ)) / (2ψ² sin ψ)`` (Theory §3.5).

    Evaluated as ``(1 − (ψ/2) cot(ψ/2))/ψ²``, which is the same function
    without the removable singularity at ψ = π, and from its Maclaurin
    series ``1/12 + ψ²/720 + ψ⁴/30240 + ψ⁶/1209600 + …`` below ψ = 1, so it
    is accurate to a few ulp everywhere; it has poles at ψ = 2πk (k ≥ 1),
    where it returns ±inf or huge values — use :func:`rotvec_rate_singular`.

    Parameters
    ----------
    angle : array_like
        Rotation angle(s) ψ = |ψ| in radians (the function is even).

    Returns
    -------
    ndarray or float

    Examples
    --------
    >>> float(bortz_coefficient(0.0)) == 1 / 12
    True
    >>> round(float(bortz_coefficient(np.pi)), 15) == round(1 / np.pi**2, 15)
    True
    """
    a = np.abs(np.asarray(angle, dtype=np.float64))
    if not np.all(np.isfinite(a)):
        raise ValueError("angle must be finite")
    out = _bortz(a)
    return out if out.ndim else float(out)


def angular_velocity_from_rotvec_rate(psi, psidot, frame="space"):
    """Angular velocity from a rotation vector and its rate, the dexp map (Theory §3.4).

    ``ω = ((e^{ψ·X} − 1)/(ψ·X)) ψ̇ = ψ̇ + A ψ×ψ̇ + B ψ×(ψ×ψ̇)`` (space),
    ``ω′ = ((1 − e^{−ψ·X})/(ψ·X)) ψ̇ = ψ̇ − A ψ×ψ̇ + B ψ×(ψ×ψ̇)`` (body), with
    ``A = (1 − cos ψ)/ψ²``, ``B = (ψ − sin ψ)/ψ³``.

    Parameters
    ----------
    psi, psidot : array_like, shape (..., 3)
        Rotation vector ψ (any length, not only |ψ| ≤ π) and its time derivative.
    frame : {"space", "body"}

    Returns
    -------
    ndarray, shape (..., 3)

    Examples
    --------
    >>> angular_velocity_from_rotvec_rate([0.0, 0.0, 1.0], [0.0, 0.0, 2.0])
    array([0., 0., 2.])
    """
    sign = frame_sign(frame)
    psi, psidot = vector_batch(psi=psi, psidot=psidot)
    return _dexp_apply(psi, psidot, sign)


def rotvec_rate(psi, omega, frame="space", tol=SINGULAR_TOL):
    """Rotation-vector rate from the angular velocity: dexp⁻¹ (Theory §3.5).

    With body components this is the Bortz equation
    ``ψ̇ = ω′ + ½ ψ×ω′ + f ψ×(ψ×ω′)``; with space components
    ``ψ̇ = ω − ½ ψ×ω + f ψ×(ψ×ω)``, where ``f`` is :func:`bortz_coefficient`.

    Parameters
    ----------
    psi : array_like, shape (..., 3)
        Rotation vector.
    omega : array_like, shape (..., 3)
        Angular velocity in the components given by ``frame``.
    frame : {"space", "body"}
    tol : float
        Samples with |ψ| > π and |sin(|ψ|/2)| ≤ tol (the poles |ψ| = 2πk)
        are singular: their rates are NaN and a
        :class:`RotationVectorSingularityWarning` is issued.

    Returns
    -------
    ndarray, shape (..., 3)

    Examples
    --------
    >>> rotvec_rate([0.0, 0.0, 0.0], [1.0, 2.0, 3.0], frame="body")
    array([1., 2., 3.])
    >>> rotvec_rate([0.1, 0.0, 0.0], [0.0, 1.0, 0.0], frame="body")  # ½ ψ×ω′ + f ψ×(ψ×ω′)
    array([0.        , 0.99916653, 0.05      ])
    """
    sign = frame_sign(frame)
    psi, omega = vector_batch(psi=psi, omega=omega)
    tol = tolerance(tol)
    out = _dexp_inverse_apply(psi, omega, sign, tol)
    warn_if_any(np.isnan(out[..., 0]), RotationVectorSingularityWarning, "rotvec_rate at |psi| = 2*pi*k")
    return out


def rotvec_rate_singular(psi, tol=SINGULAR_TOL):
    """Mask of rotation vectors where :func:`rotvec_rate` is singular (no warning).

    Parameters
    ----------
    psi : array_like, shape (..., 3)
    tol : float
        As in :func:`rotvec_rate`.

    Returns
    -------
    ndarray of bool, shape (...)

    Examples
    --------
    >>> rotvec_rate_singular([[0.0, 0.0, 2 * np.pi], [0.0, 0.0, np.pi]]).tolist()
    [True, False]
    """
    psi = vectors(psi, "psi")
    tol = tolerance(tol)
    angle = np.linalg.norm(psi, axis=-1)
    return (angle > np.pi) & (np.abs(np.sin(0.5 * angle)) <= tol)


def _jacobian(psi, sign):
    return _dexp_matrix(vectors(psi, "psi"), sign)


def _jacobian_inverse(psi, sign, tol):
    psi = vectors(psi, "psi")
    out = _dexp_inverse_matrix(psi, sign, tolerance(tol))
    warn_if_any(np.isnan(out[..., 0, 0]), RotationVectorSingularityWarning, "SO(3) Jacobian inverse at |psi| = 2*pi*k")
    return out


def left_jacobian(psi):
    """Left Jacobian of SO(3), ``J_l(ψ) = (e^{ψ·X} − 1)/(ψ·X)`` (Theory §3.4).

    ``J_l = 1 + A hat(ψ) + B hat(ψ)²`` maps ψ̇ to the space angular velocity,
    ``ω = J_l(ψ) ψ̇``; also ``exp(ψ + δ) ≈ exp(J_l δ) exp(ψ)``.

    Parameters
    ----------
    psi : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> left_jacobian([0.0, 0.0, 0.0])
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    return _jacobian(psi, _SPACE)


def right_jacobian(psi):
    """Right Jacobian of SO(3), ``J_r(ψ) = (1 − e^{−ψ·X})/(ψ·X) = J_l(−ψ) = J_l(ψ)ᵀ``.

    Maps ψ̇ to the body angular velocity, ``ω′ = J_r(ψ) ψ̇`` (Theory §3.4).

    Parameters
    ----------
    psi : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> np.allclose(right_jacobian([0.1, 0.2, 0.3]), left_jacobian([0.1, 0.2, 0.3]).T)
    True
    """
    return _jacobian(psi, _BODY)


def left_jacobian_inverse(psi, tol=SINGULAR_TOL):
    """Inverse left Jacobian, ``J_l⁻¹ = 1 − ½ hat(ψ) + f hat(ψ)²``.

    ``ψ̇ = J_l⁻¹(ψ) ω`` (space components); ``f`` is :func:`bortz_coefficient`.
    Singular (NaN, with :class:`RotationVectorSingularityWarning`) at |ψ| = 2πk.

    Parameters
    ----------
    psi : array_like, shape (..., 3)
    tol : float
        Singularity threshold on |sin(|ψ|/2)|, as in :func:`rotvec_rate`.

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> psi = [0.3, -0.2, 0.5]
    >>> np.allclose(left_jacobian_inverse(psi) @ left_jacobian(psi), np.eye(3))
    True
    """
    return _jacobian_inverse(psi, _SPACE, tol)


def right_jacobian_inverse(psi, tol=SINGULAR_TOL):
    """Inverse right Jacobian, ``J_r⁻¹ = 1 + ½ hat(ψ) + f hat(ψ)²`` — the Bortz matrix (Theory §3.5).

    ``ψ̇ = J_r⁻¹(ψ) ω′`` (body components). Singular at |ψ| = 2πk.

    Parameters
    ----------
    psi : array_like, shape (..., 3)
    tol : float
        Singularity threshold on |sin(|ψ|/2)|, as in :func:`rotvec_rate`.

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> psi = [0.3, -0.2, 0.5]
    >>> np.allclose(right_jacobian_inverse(psi) @ right_jacobian(psi), np.eye(3))
    True
    """
    return _jacobian_inverse(psi, _BODY, tol)
