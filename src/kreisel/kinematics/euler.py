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

import numpy as np
from numba import types
from numpy.typing import ArrayLike, NDArray

from .._compiled import dexp
from .._compiled.checks import VECTOR, vector_array
from .._compiled.elementwise import Input, Parameter, declare, kernel, uses
from .._compiled.outputs import deliver, takes_out
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


def _code(seq: str, frame: str) -> tuple[int, int, int, int, int]:
    """The kernels' sequence parameters ``(a, b, c, extrinsic, body)``, (a, b, c) the equivalent intrinsic axes."""
    body = check_frame(frame)
    axes, intrinsic = parse_sequence(seq)
    if not intrinsic:
        axes = axes[::-1]
    return axes[0], axes[1], axes[2], int(not intrinsic), int(body)


@kernel
def _omega(x0: float, x1: float, x2: float, r0: float, r1: float, r2: float, a: int, b: int, c: int, extrinsic: int,
           body: int) -> tuple[float, float, float]:
    # ω = M · rates for angles (x0, x1, x2) and rates (r0, r1, r2) in the user's order
    c0, c1, c2, det = dexp.euler_columns(x0, x1, x2, a, b, c, extrinsic, body)
    if extrinsic:
        r0, r2 = r2, r0
    return (
        r0 * c0[0] + r1 * c1[0] + r2 * c2[0],
        r0 * c0[1] + r1 * c1[1] + r2 * c2[1],
        r0 * c0[2] + r1 * c1[2] + r2 * c2[2],
    )


@kernel
def _rates(x0: float, x1: float, x2: float, w0: float, w1: float, w2: float, a: int, b: int, c: int, extrinsic: int,
           body: int, tol: float) -> tuple[float, float, float]:
    # rates in the user's order for angles (x0, x1, x2) and ω = (w0, w1, w2); NaN first and third at gimbal lock
    c0, c1, c2, det = dexp.euler_columns(x0, x1, x2, a, b, c, extrinsic, body)
    middle = c1[0] * w0 + c1[1] * w1 + c1[2] * w2
    if abs(det) <= tol:
        return math.nan, middle, math.nan
    a0, a1, a2 = dexp.cross(c1[0], c1[1], c1[2], c2[0], c2[1], c2[2])
    b0, b1, b2 = dexp.cross(c0[0], c0[1], c0[2], c1[0], c1[1], c1[2])
    inv = 1.0 / det
    r0 = (a0 * w0 + a1 * w1 + a2 * w2) * inv
    r2 = (b0 * w0 + b1 * w1 + b2 * w2) * inv
    if extrinsic:
        return r2, middle, r0
    return r0, middle, r2


@kernel
def _matrix(x0: float, x1: float, x2: float, a: int, b: int, c: int, extrinsic: int, body: int) -> tuple[float, ...]:
    c0, c1, c2, det = dexp.euler_columns(x0, x1, x2, a, b, c, extrinsic, body)
    if extrinsic:
        c0, c2 = c2, c0
    return c0[0], c1[0], c2[0], c0[1], c1[1], c2[1], c0[2], c1[2], c2[2]


@kernel
def _matrix_inverse(x0: float, x1: float, x2: float, a: int, b: int, c: int, extrinsic: int, body: int,
                    tol: float) -> tuple[float, ...]:
    # rows (c₁ × c₂)/det, c₁, (c₀ × c₁)/det in the intrinsic order, the outer two swapped for an extrinsic sequence
    c0, c1, c2, det = dexp.euler_columns(x0, x1, x2, a, b, c, extrinsic, body)
    inv = math.nan if abs(det) <= tol else 1.0 / det
    f0, f1, f2 = dexp.cross(c1[0], c1[1], c1[2], c2[0], c2[1], c2[2])
    l0, l1, l2 = dexp.cross(c0[0], c0[1], c0[2], c1[0], c1[1], c1[2])
    f0, f1, f2, l0, l1, l2 = f0 * inv, f1 * inv, f2 * inv, l0 * inv, l1 * inv, l2 * inv
    if extrinsic:
        return l0, l1, l2, c1[0], c1[1], c1[2], f0, f1, f2
    return f0, f1, f2, c1[0], c1[1], c1[2], l0, l1, l2


#: The sequence parameters of :func:`_code`, shared by every element.
SEQUENCE = [Parameter(name, types.int64) for name in ("a", "b", "c", "extrinsic", "body")]
_TOL = Parameter("tol", types.float64)
_ANGLES = Input("angles", (3,), VECTOR)
_to_omega = declare(_omega, [_ANGLES, Input("rates", (3,), VECTOR)], (3,), SEQUENCE,
                    name="angular_velocity_from_euler_rates")
_to_rates = declare(_rates, [_ANGLES, Input("omega", (3,), VECTOR)], (3,), [*SEQUENCE, _TOL], name="euler_rates",
                    singular=True)
_matrices = declare(_matrix, [_ANGLES], (3, 3), SEQUENCE, name="euler_rate_matrix")
_inverse_matrices = declare(_matrix_inverse, [_ANGLES], (3, 3), [*SEQUENCE, _TOL], name="euler_rate_matrix_inverse",
                            singular=True)


def _angles(angles: ArrayLike, degrees: bool, name: str = "angles") -> NDArray[np.float64]:
    a = vectors(angles, name)
    return np.deg2rad(a) if check_flag(degrees, "degrees") else a


@uses(_matrices)
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
    return _matrices(_angles(angles, degrees), *code, out=out)


@uses(_inverse_matrices)
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
    out = _inverse_matrices(_angles(angles, degrees), *code, tol, out=out)
    warn_if_any(np.isnan(out[..., 0, 0]), GimbalLockWarning, f"Euler-rate matrix inverse of {seq!r} at gimbal lock")
    return np.rad2deg(out, out=out) if degrees else out


@uses(_to_omega)
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
    return _to_omega(angles, rates, *code, out=out)


@uses(_to_rates)
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
    out = _to_rates(angles, omega, *code, tol, out=out)
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
    middle = _angles(vector_array(angles, "angles"), degrees)[..., 1]
    det = np.sin(middle) if axes[0] == axes[2] else np.cos(middle)
    return deliver(np.abs(det) <= tol, out)
