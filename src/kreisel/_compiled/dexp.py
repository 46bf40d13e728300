"""Kernels of the exponential map's differential: the SO(3) Jacobians and the rate maps.

The scalar kernels take and return plain floats and tuples so that the loops
of the declared array operations (:mod:`.elementwise`) and the integrators of
higher layers can call them without allocating.
The SO(3) Jacobians ``J = 1 + sign A hat(ψ) + B hat(ψ)²`` (sign +1: left,
−1: right) and their inverses are also broadcast here over batches
(:data:`apply_jacobian`, :data:`jacobian_matrix`, ...), because three
layers use them: ``kreisel.so3`` (the Jacobian matrices), ``kreisel.kinematics``
(the rate maps of Theory §3.4–5) and ``kreisel.se3`` (exp/log of twists).
Conventions as in :mod:`kreisel._compiled.kernels`.
"""

from __future__ import annotations

import math

from numba import types

from .._validation import ROTVEC_RANGE
from . import cached, generic, kernels
from .checks import ROTVEC, VECTOR
from .elementwise import Input, Parameter, declare, kernel
from .series import (
    BORTZ_SERIES,
    BORTZ_SERIES_BELOW,
    COSINE_REMAINDER_SERIES,
    COSINE_REMAINDER_SLOPE_SERIES,
    SE3_COUPLING_SERIES,
    SE3_SERIES_BELOW,
    SINE_REMAINDER_SERIES,
    SINE_REMAINDER_SERIES_BELOW,
    SINE_REMAINDER_SLOPE_SERIES,
    SLOPE_SERIES_BELOW,
)

@generic
def horner(coefficients: tuple[float, ...], x: float) -> float:
    """Polynomial with ``coefficients`` highest order first, at ``x``.

    Compiled for each length of ``coefficients``, so inlined into its cached
    callers rather than cached itself (one signature per cached kernel).
    """
    acc = 0.0
    for c in coefficients:
        acc = acc * x + c
    return acc


@cached
def cross(ax: float, ay: float, az: float, bx: float, by: float, bz: float) -> tuple[float, float, float]:
    return ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx


@cached
def axis_angle(x: float, y: float, z: float) -> tuple[float, float, float, float]:
    """Unit axis and angle of the rotation vector ``(x, y, z)``, for any finite size (axis 0 at angle 0).

    The maps below are written with the unit axis ``u`` and coefficients
    multiplied by powers of the angle (``A ψ`` instead of ``A``, so that
    ``A ψ×v = (Aψ) u×v``): neither the norm nor ``ψ×(ψ×v)`` overflows or
    underflows for huge or tiny rotation vectors, and no coefficient does.
    """
    angle = kernels.norm3(x, y, z)
    if angle == 0.0:
        return 0.0, 0.0, 0.0, 0.0
    return x / angle, y / angle, z / angle, angle


@cached
def sine_remainder(angle: float) -> float:
    """``B = (ψ - sin ψ)/ψ³`` of Theory §3.4, from its series below ψ = 1."""
    if angle < SINE_REMAINDER_SERIES_BELOW:
        return horner(SINE_REMAINDER_SERIES, angle * angle)
    return (1.0 - math.sin(angle) / angle) / angle / angle


@cached
def dexp_coefficients(angle: float) -> tuple[float, float]:
    """``Aψ = (1 - cos ψ)/ψ`` and ``Bψ² = 1 - sin ψ/ψ``, with A and B of Theory §3.4.

    ``Aψ = sin(ψ/2) · sin(ψ/2)/(ψ/2)`` has no cancellation; ``Bψ²`` is summed
    from the series of B below ψ = 1.
    """
    if angle == 0.0:
        return 0.0, 0.0
    h = 0.5 * angle
    s = math.sin(h)
    if angle < SINE_REMAINDER_SERIES_BELOW:
        b = horner(SINE_REMAINDER_SERIES, angle * angle) * angle * angle
    else:
        b = 1.0 - math.sin(angle) / angle
    return s * (s / h), b


@cached
def dexp_coefficient_slopes(angle: float) -> tuple[float, float, float]:
    """``A'ψ``, ``B'ψ²`` and ``Bψ``: the coefficients of the time derivative of the dexp matrix."""
    if angle < SLOPE_SERIES_BELOW:
        x = angle * angle
        return (
            horner(COSINE_REMAINDER_SLOPE_SERIES, x) * x,
            horner(SINE_REMAINDER_SLOPE_SERIES, x) * x * angle,
            sine_remainder(angle) * angle,
        )
    a, b = dexp_coefficients(angle)
    return (math.sin(angle) - 2.0 * a) / angle, (3.0 * math.sin(angle) / angle - math.cos(angle) - 2.0) / angle, b / angle


@cached
def se3_coupling_coefficients(angle: float) -> tuple[float, float, float, float]:
    """The coefficients of the coupling block Q of the SE(3) Jacobians (Barfoot), times powers of the angle:
    ``bψ``, ``bψ²``, ``cψ²`` and ``dψ³`` with ``b = (ψ − sin ψ)/ψ³`` (:func:`sine_remainder`),
    ``c = (ψ² + 2 cos ψ − 2)/(2ψ⁴)`` and ``d = (2ψ − 3 sin ψ + ψ cos ψ)/(2ψ⁵)``, for Q written with
    the unit axis (no power of a huge or tiny angle is formed); c and d from their series below ψ = 2."""
    # the square is formed of the clipped angle: compiled code may hoist it out of the series
    # branches, and beyond 1e154 it would overflow (numpy then warns of the overflow)
    small = min(angle, SE3_SERIES_BELOW)
    x = small * small
    if angle < SINE_REMAINDER_SERIES_BELOW:
        b = horner(SINE_REMAINDER_SERIES, x)
        b1, b2 = b * angle, b * x
    else:
        b2 = 1.0 - math.sin(angle) / angle
        b1 = b2 / angle
    if angle < SE3_SERIES_BELOW:
        return b1, b2, horner(COSINE_REMAINDER_SERIES, x) * x, horner(SE3_COUPLING_SERIES, x) * x * angle
    sn = math.sin(angle)
    cs = math.cos(angle)
    return b1, b2, 0.5 - (1.0 - cs) / angle / angle, (2.0 + cs - 3.0 * sn / angle) / (2.0 * angle)


@cached
def bortz_coefficient(angle: float) -> float:
    """``(2 sin ψ - ψ(1 + cos ψ)) / (2ψ² sin ψ)`` of Theory §3.5, written as
    ``(1 - (ψ/2) cot(ψ/2))/ψ²`` (finite at ψ = π, poles at ψ = 2πk) and
    summed from its series 1/12 + ψ²/720 + ψ⁴/30240 + ... below ψ = 1."""
    if angle < BORTZ_SERIES_BELOW:
        return horner(BORTZ_SERIES, angle * angle)
    return bortz_times_square(angle) / angle / angle


@cached
def bortz_times_square(angle: float) -> float:
    """The Bortz coefficient times ψ², ``1 - (ψ/2) cot(ψ/2)``, finite for every finite angle off the poles."""
    if angle < BORTZ_SERIES_BELOW:
        return horner(BORTZ_SERIES, angle * angle) * angle * angle
    h = 0.5 * angle
    return 1.0 - h * math.cos(h) / math.sin(h)




@cached
def rotvec_singular(angle: float, tol: float) -> bool:
    """True where dexp⁻¹ is not computed: its poles |ψ| = 2πk, k >= 1, within ``|sin(ψ/2)| <= tol``,
    and beyond :data:`ROTVEC_RANGE`."""
    return angle > math.pi and (angle > ROTVEC_RANGE or abs(math.sin(0.5 * angle)) <= tol)


@cached
def _plus_cross_terms(ux: float, uy: float, uz: float, v0: float, v1: float, v2: float, linear: float,
                      quadratic: float) -> tuple[float, float, float]:
    """``v + linear u×v + quadratic u×(u×v)``."""
    cx, cy, cz = cross(ux, uy, uz, v0, v1, v2)
    ccx, ccy, ccz = cross(ux, uy, uz, cx, cy, cz)
    return v0 + linear * cx + quadratic * ccx, v1 + linear * cy + quadratic * ccy, v2 + linear * cz + quadratic * ccz


@kernel
def jacobian_times(x: float, y: float, z: float, v0: float, v1: float, v2: float, sign: float) -> tuple[float, float, float]:
    """``J v = v + sign A ψ×v + B ψ×(ψ×v)``: sign +1 is J_l (ψ̇ -> ω), −1 is J_r (ψ̇ -> ω′)."""
    ux, uy, uz, angle = axis_angle(x, y, z)
    a, b = dexp_coefficients(angle)
    return _plus_cross_terms(ux, uy, uz, v0, v1, v2, sign * a, b)


@kernel
def jacobian_inverse_times(x: float, y: float, z: float, w0: float, w1: float, w2: float, sign: float,
                           tol: float) -> tuple[float, float, float]:
    """``J⁻¹ w = w − (sign/2) ψ×w + f ψ×(ψ×w)``, NaN at the poles |ψ| = 2πk (:func:`rotvec_singular`)."""
    ux, uy, uz, angle = axis_angle(x, y, z)
    if rotvec_singular(angle, tol):
        return math.nan, math.nan, math.nan
    return _plus_cross_terms(ux, uy, uz, w0, w1, w2, -0.5 * sign * angle, bortz_times_square(angle))


@kernel
def jacobian_rate_times(x: float, y: float, z: float, v0: float, v1: float, v2: float, a0: float, a1: float, a2: float,
                        sign: float) -> tuple[float, float, float]:
    """``d/dt (J(ψ) ψ̇) = J ψ̈ + J̇ ψ̇`` for ψ̇ = v, ψ̈ = a: the angular acceleration of Theory §3.9.

    Since hat(ψ̇)ψ̇ = 0, ``J̇ψ̇ = (u·ψ̇)(sign A'ψ u×ψ̇ + B'ψ² u×(u×ψ̇)) + Bψ ψ̇×(u×ψ̇)``.
    """
    ux, uy, uz, angle = axis_angle(x, y, z)
    a, b = dexp_coefficients(angle)
    da, db, bl = dexp_coefficient_slopes(angle)
    jx, jy, jz = _plus_cross_terms(ux, uy, uz, a0, a1, a2, sign * a, b)
    p = ux * v0 + uy * v1 + uz * v2
    cx, cy, cz = cross(ux, uy, uz, v0, v1, v2)
    ccx, ccy, ccz = cross(ux, uy, uz, cx, cy, cz)
    dx, dy, dz = cross(v0, v1, v2, cx, cy, cz)
    lin = sign * da
    return (
        jx + p * (lin * cx + db * ccx) + bl * dx,
        jy + p * (lin * cy + db * ccy) + bl * dy,
        jz + p * (lin * cz + db * ccz) + bl * dz,
    )


@cached
def jacobian_entries(ux: float, uy: float, uz: float, linear: float, quadratic: float) -> tuple[float, ...]:
    """Entries of ``1 + linear hat(u) + quadratic hat(u)²`` row by row, with ``hat(u)² = uuᵀ − |u|² 1``."""
    n2 = ux * ux + uy * uy + uz * uz
    return (
        1.0 + quadratic * (ux * ux - n2), quadratic * ux * uy - linear * uz, quadratic * ux * uz + linear * uy,
        quadratic * ux * uy + linear * uz, 1.0 + quadratic * (uy * uy - n2), quadratic * uy * uz - linear * ux,
        quadratic * ux * uz - linear * uy, quadratic * uy * uz + linear * ux, 1.0 + quadratic * (uz * uz - n2),
    )


_PSI, _V = Input("psi", (3,), VECTOR), Input("v", (3,), VECTOR)
_SIGN = Parameter("sign", types.float64)
#: ``J(ψ) v``; ``sign`` +1.0 (left) or −1.0 (right).
apply_jacobian = declare(jacobian_times, [_PSI, _V], (3,), [_SIGN], name="apply_jacobian")
#: ``J(ψ)⁻¹ w`` of rotation vectors within ``ROTVEC_RANGE``, NaN where |sin(|ψ|/2)| <= ``tol`` and |ψ| > π.
apply_jacobian_inverse = declare(jacobian_inverse_times, [Input("psi", (3,), ROTVEC), Input("w", (3,), VECTOR)], (3,),
                                 [_SIGN, Parameter("tol", types.float64)], name="apply_jacobian_inverse", singular=True)
#: ``d/dt (J(ψ) ψ̇)`` of ψ, ψ̇ = ``v`` and ψ̈ = ``acc``.
apply_jacobian_rate = declare(jacobian_rate_times, [_PSI, _V, Input("acc", (3,), VECTOR)], (3,), [_SIGN],
                              name="apply_jacobian_rate")


@kernel
def _jacobian(x: float, y: float, z: float, sign: float) -> tuple[float, ...]:
    ux, uy, uz, angle = axis_angle(x, y, z)
    a, b = dexp_coefficients(angle)
    return jacobian_entries(ux, uy, uz, sign * a, b)


@kernel
def _jacobian_inverse(x: float, y: float, z: float, sign: float, tol: float) -> tuple[float, ...]:
    ux, uy, uz, angle = axis_angle(x, y, z)
    if rotvec_singular(angle, tol):
        nan = math.nan
        return nan, nan, nan, nan, nan, nan, nan, nan, nan
    return jacobian_entries(ux, uy, uz, -0.5 * sign * angle, bortz_times_square(angle))


#: The matrices ``J(ψ)`` of rotation vectors ``(..., 3)``, taking ``(psi, sign)``.
jacobian_matrix = declare(_jacobian, [_PSI], (3, 3), [_SIGN], name="jacobian_matrix")
#: The matrices ``J(ψ)⁻¹``, taking ``(psi, sign, tol)``; all NaN at the poles as in :data:`apply_jacobian_inverse`.
jacobian_inverse_matrix = declare(_jacobian_inverse, [Input("psi", (3,), ROTVEC)], (3, 3),
                                  [_SIGN, Parameter("tol", types.float64)], name="jacobian_inverse_matrix", singular=True)


@cached
def axis_rotate(k: int, c: float, s: float, x: float, y: float, z: float) -> tuple[float, float, float]:
    """Active rotation of (x, y, z) about coordinate axis ``k`` by the angle with cosine c, sine s."""
    if k == 0:
        return x, c * y - s * z, s * y + c * z
    if k == 1:
        return c * x + s * z, y, c * z - s * x
    return c * x - s * y, s * x + c * y, z


@cached
def unit(k: int) -> tuple[float, float, float]:
    if k == 0:
        return 1.0, 0.0, 0.0
    if k == 1:
        return 0.0, 1.0, 0.0
    return 0.0, 0.0, 1.0


@cached
def euler_columns(x0: float, x1: float, x2: float, a: int, b: int, c: int, extrinsic: int,
                  body: int) -> tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float], float]:
    """Columns of the Euler-rate matrix M (ω = M · rates) and det M.

    ``(x0, x1, x2)`` are the angles in the user's order, (a, b, c) the axes
    0, 1, 2 of the intrinsic sequence equivalent to the user's one (an
    extrinsic "abc" with angles (α, β, γ) is the intrinsic "CBA" with
    (γ, β, α)), ``extrinsic`` and ``body`` 0 or 1; columns are returned in
    that intrinsic order. Theory §3.6 for ZXZ, generally:
    space  ω  = e_a α̇ + R_a(α) e_b β̇ + R_a(α) R_b(β) e_c γ̇,
    body   ω′ = R_c(γ)ᵀ R_b(β)ᵀ e_a α̇ + R_c(γ)ᵀ e_b β̇ + e_c γ̇.
    det M = c0·(c1×c2) is −sin β for proper Euler sequences and
    ε_abc cos β for Tait–Bryan ones, in either frame (det R = 1).
    """
    if extrinsic:
        first, middle, last = x2, x1, x0
    else:
        first, middle, last = x0, x1, x2
    cb = math.cos(middle)
    sb = math.sin(middle)
    if body:
        cg = math.cos(last)
        sg = math.sin(last)
        ex, ey, ez = unit(a)
        ex, ey, ez = axis_rotate(b, cb, -sb, ex, ey, ez)
        c0 = axis_rotate(c, cg, -sg, ex, ey, ez)
        ex, ey, ez = unit(b)
        c1 = axis_rotate(c, cg, -sg, ex, ey, ez)
        c2 = unit(c)
    else:
        ca = math.cos(first)
        sa = math.sin(first)
        c0 = unit(a)
        ex, ey, ez = unit(b)
        c1 = axis_rotate(a, ca, sa, ex, ey, ez)
        ex, ey, ez = unit(c)
        ex, ey, ez = axis_rotate(b, cb, sb, ex, ey, ez)
        c2 = axis_rotate(a, ca, sa, ex, ey, ez)
    if a == c:
        det = -sb
    else:
        det = cb if (b - a) % 3 == 1 else -cb
    return c0, c1, c2, det
