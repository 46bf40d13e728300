"""Euler kinematic equations for all 24 conventions (Theory §3.6).

For the intrinsic sequence ``"ABC"`` with angles (α, β, γ),
``R = R_a(α) R_b(β) R_c(γ)`` and

    ω  = e_a α̇ + R_a(α) e_b β̇ + R_a(α) R_b(β) e_c γ̇                  (space)
    ω′ = R_c(γ)ᵀ R_b(β)ᵀ e_a α̇ + R_c(γ)ᵀ e_b β̇ + e_c γ̇                 (body)

(for ZXZ these are the chapter's matrices); an extrinsic ``"abc"`` with
(α, β, γ) is the intrinsic ``"CBA"`` with (γ, β, α). The columns c₀, c₁, c₂
of M (ω = M · rates) are unit vectors with c₁ orthogonal to the other two,
so ``c₁ × c₂ ∥ c₀ − (c₀·c₂) c₂`` and the inverse has the cancellation-free
closed form

    α̇ = (c₁ × c₂)·ω / det,   β̇ = c₁·ω,   γ̇ = (c₀ × c₁)·ω / det,

with ``det M`` = −sin β (proper Euler) or ±cos β (Tait–Bryan) taken from the
angle itself. At gimbal lock (det = 0) only the middle rate β̇ is
determined: α̇ and γ̇ are returned as NaN with a :class:`GimbalLockWarning`.
Near it the rates carry a relative error of about 1e-16/|det|.
"""

from __future__ import annotations

import math

from typing import cast

import numpy as np
from numpy.typing import ArrayLike, NDArray
from numba import prange

from .._compiled import cached, dexp, parallel
from .._compiled.outputs import deliver, takes_out
from .._compiled.gufunc import gufunc
from .._validation import check_flag, check_frame, check_tolerance, warn_if_any
from ..so3.euler import parse_sequence
from ._checks import same_batch, vectors
from ._singularity import SINGULAR_TOL, GimbalLockWarning

__all__ = [
    "euler_rate_matrix",
    "euler_rate_matrix_inverse",
    "angular_velocity_from_euler_rates",
    "euler_rates",
    "euler_rates_singular",
]


def _code(seq: str, frame: str) -> NDArray[np.int64]:
    """Kernel code ``(a, b, c, extrinsic, body)``, (a, b, c) the equivalent intrinsic axes."""
    body = check_frame(frame)
    axes, intrinsic = parse_sequence(seq)
    if not intrinsic:
        axes = axes[::-1]
    return np.array([*axes, not intrinsic, body], dtype=np.int64)


# The element kernels take and return scalars and the kernel code as a tuple:
# passing arrays into a compiled call costs about as much as the kernel
# itself, and in the parallel loops every thread would update the reference
# count of the one shared code array.
@cached
def _code_tuple(code: NDArray[np.int64]) -> dexp.EulerCode:
    return code[0], code[1], code[2], code[3], code[4]


@cached
def _omega_element(x0: float, x1: float, x2: float, r0: float, r1: float, r2: float, code: dexp.EulerCode) -> tuple[float, float, float]:
    """ω = M · rates for angles (x0, x1, x2) and rates (r0, r1, r2) in the user's order."""
    c0, c1, c2, det = dexp.euler_columns(x0, x1, x2, code)
    if code[3]:
        r0, r2 = r2, r0
    return (
        r0 * c0[0] + r1 * c1[0] + r2 * c2[0],
        r0 * c0[1] + r1 * c1[1] + r2 * c2[1],
        r0 * c0[2] + r1 * c1[2] + r2 * c2[2],
    )


@cached
def _rates_element(x0: float, x1: float, x2: float, w0: float, w1: float, w2: float, code: dexp.EulerCode,
                   tol: float) -> tuple[float, float, float]:
    """Rates in the user's order for angles (x0, x1, x2) and ω = (w0, w1, w2)."""
    c0, c1, c2, det = dexp.euler_columns(x0, x1, x2, code)
    middle = c1[0] * w0 + c1[1] * w1 + c1[2] * w2
    if abs(det) <= tol:
        return math.nan, middle, math.nan
    a0, a1, a2 = dexp.cross(c1[0], c1[1], c1[2], c2[0], c2[1], c2[2])
    b0, b1, b2 = dexp.cross(c0[0], c0[1], c0[2], c1[0], c1[1], c1[2])
    inv = 1.0 / det
    r0 = (a0 * w0 + a1 * w1 + a2 * w2) * inv
    r2 = (b0 * w0 + b1 * w1 + b2 * w2) * inv
    if code[3]:
        return r2, middle, r0
    return r0, middle, r2


# The kernel code (and the tolerance) are shared by the whole batch; the
# array is read as ``code[::1]``, numba's layout 'A' as in the gufuncs, so
# _code_tuple is compiled for one signature.


@parallel
def _omega_from_rates_parallel(angles: NDArray[np.float64], rates: NDArray[np.float64], code: NDArray[np.int64],
                               out: NDArray[np.float64]) -> None:
    axes = _code_tuple(code[::1])
    for i in prange(angles.shape[0]):
        out[i, 0], out[i, 1], out[i, 2] = _omega_element(
            angles[i, 0], angles[i, 1], angles[i, 2], rates[i, 0], rates[i, 1], rates[i, 2], axes
        )


@parallel
def _rates_from_omega_parallel(angles: NDArray[np.float64], w: NDArray[np.float64], code: NDArray[np.int64], tol: float,
                               out: NDArray[np.float64]) -> None:
    axes = _code_tuple(code[::1])
    for i in prange(angles.shape[0]):
        out[i, 0], out[i, 1], out[i, 2] = _rates_element(
            angles[i, 0], angles[i, 1], angles[i, 2], w[i, 0], w[i, 1], w[i, 2], axes, tol
        )


@gufunc(["void(f8[:], f8[:], i8[:], f8[:])"], "(3),(3),(5)->(3)", parallel=_omega_from_rates_parallel, shared=(2,))
def _omega_from_rates(angles: NDArray[np.float64], rates: NDArray[np.float64], code: NDArray[np.int64], out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2] = _omega_element(angles[0], angles[1], angles[2], rates[0], rates[1], rates[2], _code_tuple(code))


@gufunc(["void(f8[:], f8[:], i8[:], f8, f8[:])"], "(3),(3),(5),()->(3)", parallel=_rates_from_omega_parallel, shared=(2, 3))
def _rates_from_omega(angles: NDArray[np.float64], w: NDArray[np.float64], code: NDArray[np.int64], tol: float, out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2] = _rates_element(angles[0], angles[1], angles[2], w[0], w[1], w[2], _code_tuple(code), tol)


@gufunc(["void(f8[:], i8[:], f8[:, :])"], "(3),(5)->(3,3)")
def _matrix(angles: NDArray[np.float64], code: NDArray[np.int64], out: NDArray[np.float64]) -> None:
    c0, c1, c2, det = dexp.euler_columns(angles[0], angles[1], angles[2], _code_tuple(code))
    if code[3]:
        c0, c2 = c2, c0
    for i in range(3):
        out[i, 0] = c0[i]
        out[i, 1] = c1[i]
        out[i, 2] = c2[i]


@gufunc(["void(f8[:], i8[:], f8, f8[:, :])"], "(3),(5),()->(3,3)")
def _matrix_inverse(angles: NDArray[np.float64], code: NDArray[np.int64], tol: float, out: NDArray[np.float64]) -> None:
    c0, c1, c2, det = dexp.euler_columns(angles[0], angles[1], angles[2], _code_tuple(code))
    first, last = (2, 0) if code[3] else (0, 2)
    inv = math.nan if abs(det) <= tol else 1.0 / det
    a = dexp.cross(c1[0], c1[1], c1[2], c2[0], c2[1], c2[2])
    b = dexp.cross(c0[0], c0[1], c0[2], c1[0], c1[1], c1[2])
    for i in range(3):
        out[1, i] = c1[i]
        out[first, i] = a[i] * inv
        out[last, i] = b[i] * inv


def _angles(angles: ArrayLike, degrees: bool, name: str = "angles") -> NDArray[np.float64]:
    a = vectors(angles, name)
    return np.deg2rad(a) if check_flag(degrees, "degrees") else a


@takes_out
def euler_rate_matrix(seq: str, angles: ArrayLike, frame: str = "space", degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """The 3×3 matrix M of the Euler kinematic equations, ``ω = M · (α̇, β̇, γ̇)`` (Theory §3.6).

    For ``"ZXZ"`` (φ, θ, ψ) the space matrix is the chapter's
    ``[[0, cos φ, sin φ sin θ], [0, sin φ, −cos φ sin θ], [1, 0, cos θ]]`` and
    the body matrix ``[[sin θ sin ψ, cos ψ, 0], [sin θ cos ψ, −sin ψ, 0], [cos θ, 0, 1]]``.
    Column j is the axis about which angle j turns, in ``frame`` components.

    Parameters
    ----------
    seq : str
        Axis sequence, e.g. ``"ZXZ"`` (uppercase intrinsic, lowercase extrinsic).
    angles : array_like, shape (..., 3)
    frame : {"space", "body"}
    degrees : bool
        Angles in degrees (M is dimensionless either way).

    Returns
    -------
    ndarray, shape (..., 3, 3)
        M, whose columns are the rotation axes of the three angles in ``frame``
        components.

    Examples
    --------
    >>> euler_rate_matrix("ZXZ", [0.0, np.pi / 2, 0.0], frame="body").round(12) + 0.0
    array([[0., 1., 0.],
           [1., 0., 0.],
           [0., 0., 1.]])
    """
    code = _code(seq, frame)
    return _matrix(_angles(angles, degrees), code, out=out)


@takes_out
def euler_rate_matrix_inverse(seq: str, angles: ArrayLike, frame: str = "space", degrees: bool = False,
                              tol: float = SINGULAR_TOL, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse of :func:`euler_rate_matrix`: ``(α̇, β̇, γ̇) = M⁻¹ ω`` (Theory §3.6).

    For ``"ZXZ"`` body components this is the chapter's
    ``[[sin ψ/sin θ, cos ψ/sin θ, 0], [cos ψ, −sin ψ, 0], [−cot θ sin ψ, −cot θ cos ψ, 1]]``.
    At gimbal lock (|det M| ≤ ``tol``) the first and third rows are NaN and
    a :class:`GimbalLockWarning` is issued; the middle row is always defined.

    Parameters
    ----------
    seq : str
    angles : array_like, shape (..., 3)
    frame : {"space", "body"}
    degrees : bool
        Angles in degrees; the matrix then maps rad/s to deg/s.
    tol : float
        Singularity threshold on |det M| = |sin β| (proper Euler) or |cos β| (Tait–Bryan).

    Returns
    -------
    ndarray, shape (..., 3, 3)
        M⁻¹; NaN at gimbal lock.

    Examples
    --------
    >>> M = euler_rate_matrix("xyz", [0.1, 0.2, 0.3])
    >>> np.allclose(euler_rate_matrix_inverse("xyz", [0.1, 0.2, 0.3]) @ M, np.eye(3))
    True
    """
    code = _code(seq, frame)
    tol = check_tolerance(tol)
    out = _matrix_inverse(_angles(angles, degrees), code, tol, out=out)
    warn_if_any(np.isnan(out[..., 0, 0]), GimbalLockWarning, f"Euler-rate matrix inverse of {seq!r} at gimbal lock")
    return np.rad2deg(out, out=out) if degrees else out


@takes_out
def angular_velocity_from_euler_rates(seq: str, angles: ArrayLike, rates: ArrayLike, frame: str = "space",
                                      degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Angular velocity from Euler angles and their rates (Theory §3.6, Euler kinematic equations).

    Parameters
    ----------
    seq : str
        Axis sequence, e.g. ``"ZXZ"`` for the chapter's (φ, θ, ψ).
    angles, rates : array_like, shape (..., 3)
        Angles and their time derivatives (rad and rad/s, or deg and deg/s
        with ``degrees=True``); batch shapes broadcast.
    frame : {"space", "body"}
        Components of the returned angular velocity (always rad/s).
    degrees : bool
        Angles in degrees and rates in deg/s.

    Returns
    -------
    ndarray, shape (..., 3)
        ω (space) or ω′ (body), rad/s.

    Examples
    --------
    Pure spin ψ̇ about the body z axis:

    >>> angular_velocity_from_euler_rates("ZXZ", [0.3, 0.4, 0.5], [0.0, 0.0, 2.0], frame="body")
    array([0., 0., 2.])
    """
    code = _code(seq, frame)
    angles = _angles(angles, degrees)
    angles, rates = same_batch(1, angles=angles, rates=_angles(rates, degrees, "rates"))
    return _omega_from_rates(angles, rates, code, out=out)


@takes_out
def euler_rates(seq: str, angles: ArrayLike, omega: ArrayLike, frame: str = "space", degrees: bool = False,
                tol: float = SINGULAR_TOL, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Euler-angle rates from the angular velocity (Theory §3.6, inverted Euler kinematic equations).

    At gimbal lock (|sin β| ≤ ``tol`` for proper Euler sequences, |cos β| ≤ ``tol``
    for Tait–Bryan) the first and third rates are NaN — only their sum or
    difference is determined — and a :class:`GimbalLockWarning` is issued;
    the middle rate is always returned. :func:`euler_rates_singular` gives
    the mask without warnings.

    Parameters
    ----------
    seq : str
    angles : array_like, shape (..., 3)
    omega : array_like, shape (..., 3)
        Angular velocity (rad/s) in the components given by ``frame``.
    frame : {"space", "body"}
        Components in which ``omega`` is given.
    degrees : bool
        Angles in degrees; rates are then returned in deg/s.
    tol : float
        Gimbal-lock threshold on |sin β| (proper Euler) or |cos β| (Tait–Bryan).

    Returns
    -------
    ndarray, shape (..., 3)
        The rates of the three angles; the first and third are NaN at gimbal lock.

    Examples
    --------
    >>> euler_rates("ZXZ", [0.3, 0.4, 0.5], [1.0, 0.0, 2.0], frame="body")
    array([1.2311324 , 0.87758256, 0.86605197])
    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     euler_rates("ZXZ", [0.3, 0.0, 0.5], [1.0, 0.0, 2.0], frame="body")
    array([       nan, 0.87758256,        nan])
    """
    code = _code(seq, frame)
    tol = check_tolerance(tol)
    angles = _angles(angles, degrees)
    angles, omega = same_batch(1, angles=angles, omega=vectors(omega, "omega"))
    out = _rates_from_omega(angles, omega, code, tol, out=out)
    warn_if_any(np.isnan(out[..., 0]), GimbalLockWarning, f"euler_rates of {seq!r} at gimbal lock")
    return np.rad2deg(out, out=out) if degrees else out


@takes_out
def euler_rates_singular(seq: str, angles: ArrayLike, degrees: bool = False, tol: float = SINGULAR_TOL, *,
                         out: NDArray[np.bool_] | None = None) -> NDArray[np.bool_]:
    """Mask of the Euler angles at which :func:`euler_rates` is singular (no warning).

    Parameters
    ----------
    seq : str
    angles : array_like, shape (..., 3)
    degrees : bool
    tol : float
        Threshold on |sin β| or |cos β|, as in :func:`euler_rates`.

    Returns
    -------
    ndarray of bool, shape (...)
        True at gimbal lock: |sin β| <= ``tol`` (proper Euler) or |cos β| <= ``tol``
        (Tait–Bryan), β the middle angle.

    Examples
    --------
    >>> euler_rates_singular("ZXZ", [[0.1, 0.0, 0.2], [0.1, 0.5, 0.2]]).tolist()
    [True, False]
    >>> euler_rates_singular("xyz", [10.0, 90.0, 0.0], degrees=True).tolist()
    True
    """
    axes, _ = parse_sequence(seq)
    tol = check_tolerance(tol)
    middle = _angles(angles, degrees)[..., 1]
    det = np.sin(middle) if axes[0] == axes[2] else np.cos(middle)
    return deliver(np.abs(det) <= tol, out)
