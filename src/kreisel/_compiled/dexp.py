"""Scalar kernels of the kinematic maps (one element each, compiled by numba).

They take and return plain floats and tuples so that the gufunc loops in
this package (and integrators in higher layers) can inline them without
allocating. Conventions as in :mod:`kreisel._compiled.kernels`.
"""

from __future__ import annotations

import math

from . import cached, generic, series


_BORTZ_SERIES = series.BORTZ_SERIES
_BORTZ_SERIES_BELOW = series.BORTZ_SERIES_BELOW
_SINE_REMAINDER_SERIES = series.SINE_REMAINDER_SERIES
_SINE_REMAINDER_SERIES_BELOW = series.SINE_REMAINDER_SERIES_BELOW
_COSINE_REMAINDER_SLOPE_SERIES = series.COSINE_REMAINDER_SLOPE_SERIES
_SINE_REMAINDER_SLOPE_SERIES = series.SINE_REMAINDER_SLOPE_SERIES
_SLOPE_SERIES_BELOW = series.SLOPE_SERIES_BELOW


@generic
def horner(coefficients, x):
    """Polynomial with ``coefficients`` highest order first, at ``x``.

    Compiled for each length of ``coefficients``, so inlined into its cached
    callers rather than cached itself (one signature per cached kernel).
    """
    acc = 0.0
    for c in coefficients:
        acc = acc * x + c
    return acc


@cached
def cross(ax, ay, az, bx, by, bz):
    return ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx


@cached
def dexp_coefficients(angle):
    """``A = (1 - cos ψ)/ψ²`` and ``B = (ψ - sin ψ)/ψ³`` of Theory §3.4.

    A is evaluated as ½ (sin(ψ/2)/(ψ/2))², which has no cancellation; B
    from its series below ψ = 1.
    """
    if angle == 0.0:
        return 0.5, 1.0 / 6.0
    h = 0.5 * angle
    sinc = math.sin(h) / h
    a = 0.5 * sinc * sinc
    if angle < _SINE_REMAINDER_SERIES_BELOW:
        b = horner(_SINE_REMAINDER_SERIES, angle * angle)
    else:
        b = (angle - math.sin(angle)) / (angle * angle * angle)
    return a, b


@cached
def dexp_coefficient_slopes(angle):
    """``A'(ψ)/ψ`` and ``B'(ψ)/ψ`` for the time derivative of the dexp matrix."""
    if angle < _SLOPE_SERIES_BELOW:
        x = angle * angle
        return horner(_COSINE_REMAINDER_SLOPE_SERIES, x), horner(_SINE_REMAINDER_SLOPE_SERIES, x)
    sn = math.sin(angle)
    cs = math.cos(angle)
    a2 = angle * angle
    da = (angle * sn - 2.0 * (1.0 - cs)) / (a2 * a2)
    db = (3.0 * sn - angle * cs - 2.0 * angle) / (a2 * a2 * angle)
    return da, db


@cached
def bortz_coefficient(angle):
    """``(2 sin ψ - ψ(1 + cos ψ)) / (2ψ² sin ψ)`` of Theory §3.5, written as
    ``(1 - (ψ/2) cot(ψ/2))/ψ²`` (finite at ψ = π, poles at ψ = 2πk) and
    summed from its series 1/12 + ψ²/720 + ψ⁴/30240 + ... below ψ = 1."""
    if angle < _BORTZ_SERIES_BELOW:
        return horner(_BORTZ_SERIES, angle * angle)
    h = 0.5 * angle
    return (1.0 - h * math.cos(h) / math.sin(h)) / (angle * angle)


@cached
def rotvec_singular(angle, tol):
    """True where dexp⁻¹ has a pole: |ψ| = 2πk, k >= 1, within ``|sin(ψ/2)| <= tol``."""
    return angle > math.pi and abs(math.sin(0.5 * angle)) <= tol


@cached
def axis_rotate(k, c, s, x, y, z):
    """Active rotation of (x, y, z) about coordinate axis ``k`` by the angle with cosine c, sine s."""
    if k == 0:
        return x, c * y - s * z, s * y + c * z
    if k == 1:
        return c * x + s * z, y, c * z - s * x
    return c * x - s * y, s * x + c * y, z


@cached
def unit(k):
    if k == 0:
        return 1.0, 0.0, 0.0
    if k == 1:
        return 0.0, 1.0, 0.0
    return 0.0, 0.0, 1.0


@cached
def euler_columns(x0, x1, x2, code):
    """Columns of the Euler-rate matrix M (ω = M · rates) and det M.

    ``(x0, x1, x2)`` are the angles in the user's order and
    ``code = (a, b, c, extrinsic, body)`` with (a, b, c) the axes of the
    intrinsic sequence equivalent to the user's one (an extrinsic "abc"
    with angles (α, β, γ) is the intrinsic "CBA" with (γ, β, α)); columns
    are returned in that intrinsic order. Theory §3.6 for ZXZ, generally:
    space  ω  = e_a α̇ + R_a(α) e_b β̇ + R_a(α) R_b(β) e_c γ̇,
    body   ω′ = R_c(γ)ᵀ R_b(β)ᵀ e_a α̇ + R_c(γ)ᵀ e_b β̇ + e_c γ̇.
    det M = c0·(c1×c2) is −sin β for proper Euler sequences and
    ε_abc cos β for Tait–Bryan ones, in either frame (det R = 1).
    """
    a, b, c = code[0], code[1], code[2]
    if code[3]:
        first, middle, last = x2, x1, x0
    else:
        first, middle, last = x0, x1, x2
    cb = math.cos(middle)
    sb = math.sin(middle)
    if code[4]:
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
