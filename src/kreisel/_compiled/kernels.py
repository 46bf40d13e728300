"""Scalar quaternion kernels shared by every compiled loop in kreisel.

Each element operation has one *tuple kernel*: it takes plain numbers and
returns a tuple (``quat_product``, ``rotated``, ``quat_matrix``,
``matrix_entries_quat``, ``rotvec_quat``, ``quat_rotvec``, ``quat_unit``).
The declared array operations of :mod:`kreisel.so3` (:mod:`.elementwise`)
call them with an element's numbers; the array forms below (``qmul``,
``qrotate``, ``write_matrix``, ...) are thin shells for callers that hold
one element in an array, such as the integrators in :mod:`kreisel.dynamics`
and :mod:`kreisel.nav`. Conventions: scalar-first Hamilton quaternions,
``R(q)`` of Theory §2.4.
"""

from __future__ import annotations

import math
import numpy as np
from numpy.typing import NDArray

from . import cached, inlined, vectorised


# ---------------------------------------------------------------------------
# Tuple kernels: one per element operation.


# inlined at numba's level: where LLVM kept it a call (the DOP853 stages of the dense output, q̇ = ½ q ⊗ ω′),
# numba could not drop the reference counts of the arrays around it: six atomic updates per stage
@inlined
def quat_product(p0: float, p1: float, p2: float, p3: float, q0: float, q1: float, q2: float,
                 q3: float) -> tuple[float, float, float, float]:
    """Hamilton product ``p q`` (Theory §2.4: (a0 b0 - a.b, a0 b + b0 a + a x b)).

    The terms are summed in pairs, ``a0 b + b0 a`` and ``a x b`` apart, so
    that ``q* q`` and ``q q*`` have an exactly zero vector part: each pair
    then cancels exactly, where a left-to-right sum left a rounding error.
    """
    return (
        p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3,
        (p0 * q1 + p1 * q0) + (p2 * q3 - p3 * q2),
        (p0 * q2 + p2 * q0) + (p3 * q1 - p1 * q3),
        (p0 * q3 + p3 * q0) + (p1 * q2 - p2 * q1),
    )


#: Components of size in (SIZE_LOW, SIZE_HIGH) have squares that neither overflow nor lose digits
#: to underflow; a quaternion whose largest component is outside is first divided by it (as
#: ``hypot`` does), which leaves every scale-invariant result unchanged.
SIZE_LOW = 1e-140
SIZE_HIGH = 1e140


@vectorised
def largest_component(q0: float, q1: float, q2: float, q3: float) -> float:
    """The largest ``|component|`` of ``q``."""
    return max(max(abs(q0), abs(q1)), max(abs(q2), abs(q3)))


@vectorised
def squarable(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float, float]:
    """``q``, or ``q`` divided by its largest ``|component|`` when squaring it would overflow or underflow."""
    m = largest_component(q0, q1, q2, q3)
    # a division by 1 is exact: one formula for both cases, without a branch, so that loops of it vectorise
    d = 1.0 if SIZE_LOW < m < SIZE_HIGH else m
    return q0 / d, q1 / d, q2 / d, q3 / d


@vectorised
def norm3(x: float, y: float, z: float) -> float:
    """``|(x, y, z)|`` for any finite components (divided by the largest first when squaring would over- or underflow)."""
    m = largest_component(0.0, x, y, z)
    if SIZE_LOW < m < SIZE_HIGH or m == 0.0:
        return math.sqrt(x * x + y * y + z * z)
    x, y, z = x / m, y / m, z / m
    return m * math.sqrt(x * x + y * y + z * z)


@vectorised
def quat_unit(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float, float]:
    """``q / |q|`` for any nonzero finite ``q``."""
    q0, q1, q2, q3 = squarable(q0, q1, q2, q3)
    n = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    return q0 / n, q1 / n, q2 / n, q3 / n


@vectorised
def rotated(q0: float, q1: float, q2: float, q3: float, x: float, y: float, z: float) -> tuple[float, float, float]:
    """``R(q) v`` for a unit quaternion, without forming the matrix."""
    # t = 2 (u x v); v' = v + q0 t + u x t  (u the vector part)
    t0 = 2.0 * (q2 * z - q3 * y)
    t1 = 2.0 * (q3 * x - q1 * z)
    t2 = 2.0 * (q1 * y - q2 * x)
    return x + q0 * t0 + q2 * t2 - q3 * t1, y + q0 * t1 + q3 * t0 - q1 * t2, z + q0 * t2 + q1 * t1 - q2 * t0


@vectorised
def quat_matrix(q0: float, q1: float, q2: float, q3: float) -> tuple[float, ...]:
    """Entries of ``R(q)`` (Theory §2.4) row by row, for a possibly non-unit (nonzero, finite) quaternion."""
    q0, q1, q2, q3 = squarable(q0, q1, q2, q3)
    s = 1.0 / (q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    return (
        (q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3) * s,
        2.0 * (q1 * q2 - q0 * q3) * s,
        2.0 * (q1 * q3 + q0 * q2) * s,
        2.0 * (q1 * q2 + q0 * q3) * s,
        (q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3) * s,
        2.0 * (q2 * q3 - q0 * q1) * s,
        2.0 * (q1 * q3 - q0 * q2) * s,
        2.0 * (q2 * q3 + q0 * q1) * s,
        (q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3) * s,
    )


@vectorised
def matrix_entries_quat(r00: float, r01: float, r02: float, r10: float, r11: float, r12: float, r20: float, r21: float,
                        r22: float) -> tuple[float, float, float, float]:
    """Unit quaternion with q0 >= 0 of a rotation matrix given row by row (Shepperd/Markley).

    The component with the largest square is taken from the diagonal and the
    others from sums/differences of off-diagonal pairs divided by it, so no
    digit is lost anywhere, including near ψ = π where the trace formula
    fails. A slightly non-orthogonal matrix gives a nearby rotation after the
    final normalisation.
    """
    tr = r00 + r11 + r22
    if tr >= r00 and tr >= r11 and tr >= r22:
        q0 = 1.0 + tr
        q1 = r21 - r12
        q2 = r02 - r20
        q3 = r10 - r01
    elif r00 >= r11 and r00 >= r22:
        q0 = r21 - r12
        q1 = 1.0 + r00 - r11 - r22
        q2 = r01 + r10
        q3 = r02 + r20
    elif r11 >= r22:
        q0 = r02 - r20
        q1 = r01 + r10
        q2 = 1.0 + r11 - r00 - r22
        q3 = r12 + r21
    else:
        q0 = r10 - r01
        q1 = r02 + r20
        q2 = r12 + r21
        q3 = 1.0 + r22 - r00 - r11
    n = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    if q0 < 0.0:
        n = -n
    return q0 / n, q1 / n, q2 / n, q3 / n


# ---------------------------------------------------------------------------
# Sine and cosine in arithmetic only, so that loops over them vectorise.
#
# libm's sin and cos (which LLVM fuses into one sincos call) are opaque calls:
# a loop that makes them runs one element at a time. :func:`sincos` is plain
# arithmetic: a Cody–Waite reduction x = k π/2 + r, |r| <= π/4, and fdlibm's
# minimax polynomials for sin and cos on [-π/4, π/4] (error below 2^-58),
# evaluated with the reduction's tail as fdlibm's __kernel_sin/__kernel_cos do.
#
# Reduction: π/2 = P1 + P2 + P3 + P4 with P1..P3 of at most 27 significant bits
# and P4 of 53 (the rest is below 2^-141). For |k| < 2^26 every k·P1, k·P2,
# k·P3 is exact, x − k·P1 is exact (Sterbenz: for k >= 1 the two are within a
# factor 2) and the other subtractions are exact two-sums, so r = r_hi + r_lo
# is off by at most k·2^-138 (the rounding of k·P4 and the rest of π/2) plus
# 2^-105 |r|. Scanning the doubles nearest to k π/2 for every k < 2^26 (the
# only arguments where |r| is small) puts that bound at most 2^-55.8 of |r|
# (x = 14461176.67027838), below 0.15 ulp; the closest approach is
# |r| = 2^-60.5 at x = 45.553093477052 (k = 29). Measured against mpmath and
# long double (Theory §2.2, tests/test_compiled.py): at most 0.78 ulp for sin
# and 0.75 ulp for cos
# on 2·10^6 arguments across the range and on the 200 doubles nearest to
# multiples of π/2, where libm has 0.52 and 0.56 ulp.

#: Largest ``|x|`` for which :func:`sincos` is accurate (k = round(2x/π) < 2^26 keeps k·P1..k·P3 exact).
SINCOS_RANGE = 1.0e8
_TWO_OVER_PI = 0.6366197723675814
_PIO2_1 = float.fromhex("0x1.921fb54p+0")
_PIO2_2 = float.fromhex("0x1.10b461p-30")
_PIO2_3 = float.fromhex("0x1.a62633p-58")
_PIO2_4 = float.fromhex("0x1.45c06e0e68948p-86")
#: 1.5·2^52: adding and subtracting it rounds a double below 2^51 to an integer (branch-free rint).
_ROUNDER = 6755399441055744.0
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11


@inlined
def _two_sum(a: float, b: float) -> tuple[float, float]:
    """``a + b`` and its rounding error (Knuth), exactly."""
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


@inlined
def sincos(x: float) -> tuple[float, float]:
    """``(sin x, cos x)`` for ``|x| <= SINCOS_RANGE`` (1e8), within 0.8 ulp, without a libm call.

    Branch-free, so a loop over it vectorises; beyond the range the result is
    meaningless (callers check the range first or fall back to ``math``).
    """
    kf = (x * _TWO_OVER_PI + _ROUNDER) - _ROUNDER
    t, e1 = _two_sum(x - kf * _PIO2_1, -kf * _PIO2_2)
    t, e2 = _two_sum(t, -kf * _PIO2_3)
    t, e3 = _two_sum(t, -kf * _PIO2_4)
    tail = e1 + e2 + e3
    r = t + tail
    rl = tail - (r - t)
    z = r * r
    v = z * r
    sine = r - ((z * (0.5 * rl - v * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6))))) - rl) - v * _S1)
    hz = 0.5 * z
    w = 1.0 - hz
    cosine = w + (((1.0 - w) - hz) + (z * z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6))))) - r * rl))
    # quadrant k mod 4: (sin, cos) = (s, c), (c, -s), (-s, -c), (-c, s)
    n = np.int64(kf)
    odd = (n & 1) != 0
    first = cosine if odd else sine
    second = sine if odd else cosine
    return (-first if (n & 2) != 0 else first), (-second if ((n + 1) & 2) != 0 else second)


@vectorised
def rotvec_angle(x: float, y: float, z: float) -> float:
    """``|ψ|`` of a rotation vector (scaled first when the squares would overflow; tiny ones may underflow to 0)."""
    m = largest_component(0.0, x, y, z)
    if m < SIZE_HIGH:
        return math.sqrt(x * x + y * y + z * z)
    return m * math.sqrt((x / m) ** 2 + (y / m) ** 2 + (z / m) ** 2)


@inlined
def rotvec_quat_from(x: float, y: float, z: float, angle: float, sin_half: float,
                     cos_half: float) -> tuple[float, float, float, float]:
    """:func:`rotvec_quat` of ψ = (x, y, z) given ``angle`` = |ψ| and the sine and cosine of its half."""
    if angle < 1e-4:
        # sin(ψ/2)/ψ from its Taylor series: accurate to the last bit at tiny angles
        a2 = x * x + y * y + z * z
        s = 0.5 - a2 / 48.0 + a2 * a2 / 3840.0
        cos_half = 1.0 - a2 / 8.0 + a2 * a2 / 384.0
    else:
        s = sin_half / angle
    return cos_half, s * x, s * y, s * z


@vectorised
def rotvec_quat(x: float, y: float, z: float) -> tuple[float, float, float, float]:
    """Exponential ``(cos(ψ/2), n sin(ψ/2))``, ψ = |(x, y, z)|, with no sign flip.

    sin(ψ/2)/ψ is taken from its Taylor series below ψ = 1e-4 so that the
    result is accurate to the last bit at tiny angles; the half-angle sine and
    cosine come from :func:`sincos` up to ``SINCOS_RANGE``, from libm beyond.
    """
    a = rotvec_angle(x, y, z)
    h = 0.5 * a
    if h <= SINCOS_RANGE:
        sin_half, cos_half = sincos(h)
    else:
        sin_half, cos_half = math.sin(h), math.cos(h)
    return rotvec_quat_from(x, y, z, a, sin_half, cos_half)


@inlined
def rotvec_quat_in_range(x: float, y: float, z: float) -> tuple[float, float, float, float]:
    """:func:`rotvec_quat` of a rotation vector at most ``SINCOS_RANGE`` rad long, to the bit.

    What the rotation-vector checks admit (at most 1e8 rad); longer vectors give meaningless
    numbers. No libm call and no scaling branch: a loop over it vectorises.
    """
    a = math.sqrt(x * x + y * y + z * z)
    sin_half, cos_half = sincos(0.5 * a)
    return rotvec_quat_from(x, y, z, a, sin_half, cos_half)


@vectorised
def quat_rotvec(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float]:
    """Logarithm of a nonzero quaternion as a rotation vector with |ψ| <= π.

    ψ = 2 atan2(|v|, |q0|) (after choosing the hemisphere q0 >= 0) is well
    conditioned at every angle, including ψ -> 0 and ψ -> π; the factor ψ/|v|
    is expanded at small |v| where it tends to 2/q0.
    """
    if q0 < 0.0:
        q0, q1, q2, q3 = -q0, -q1, -q2, -q3
    q0, q1, q2, q3 = squarable(q0, q1, q2, q3)  # the result depends only on the direction of q
    v = math.sqrt(q1 * q1 + q2 * q2 + q3 * q3)
    if v < 1e-8 * q0:
        r = v / q0
        k = 2.0 / q0 * (1.0 - r * r / 3.0)
    else:
        k = 2.0 * math.atan2(v, q0) / v
    return k * q1, k * q2, k * q3


# ---------------------------------------------------------------------------
# Array forms for callers holding one element in an array.


@cached
def qmul(p: NDArray[np.float64], q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """Hamilton product ``out = p q`` (``out`` may be ``p`` or ``q``)."""
    out[0], out[1], out[2], out[3] = quat_product(p[0], p[1], p[2], p[3], q[0], q[1], q[2], q[3])


@cached
def qnormalize(q: NDArray[np.float64]) -> None:
    """Scale ``q`` in place to unit norm."""
    q[0], q[1], q[2], q[3] = quat_unit(q[0], q[1], q[2], q[3])


@cached
def qrotate(q: NDArray[np.float64], v: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """``out = R(q) v`` for a unit quaternion, without forming the matrix (``out`` may be ``v``)."""
    out[0], out[1], out[2] = rotated(q[0], q[1], q[2], q[3], v[0], v[1], v[2])


@cached
def qrotate_inverse(q: NDArray[np.float64], v: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """``out = R(q)^T v`` for a unit quaternion, the rotation by its conjugate (``out`` may be ``v``)."""
    out[0], out[1], out[2] = rotated(q[0], -q[1], -q[2], -q[3], v[0], v[1], v[2])


@cached
def write_matrix(q0: float, q1: float, q2: float, q3: float, out: NDArray[np.float64]) -> None:
    """Write ``R(q)`` (Theory §2.4) of a possibly non-unit quaternion into ``out``."""
    (
        out[0, 0], out[0, 1], out[0, 2],
        out[1, 0], out[1, 1], out[1, 2],
        out[2, 0], out[2, 1], out[2, 2],
    ) = quat_matrix(q0, q1, q2, q3)  # fmt: skip


@inlined
def write_matrix_at(out: NDArray[np.float64], i: int, q0: float, q1: float, q2: float, q3: float) -> None:
    """Write ``R(q)`` into the top-left 3×3 block of ``out[i]``, entry by entry (the ``prange`` loops' form).

    Inlined: a ``prange`` index is ``int64`` or ``uint64`` depending on the loop, which would give a
    compiled kernel two signatures.
    """
    (
        out[i, 0, 0], out[i, 0, 1], out[i, 0, 2],
        out[i, 1, 0], out[i, 1, 1], out[i, 1, 2],
        out[i, 2, 0], out[i, 2, 1], out[i, 2, 2],
    ) = quat_matrix(q0, q1, q2, q3)  # fmt: skip


@cached
def matrix_quat(R: NDArray[np.float64]) -> tuple[float, float, float, float]:
    """:func:`matrix_entries_quat` of a 3×3 array."""
    return matrix_entries_quat(R[0, 0], R[0, 1], R[0, 2], R[1, 0], R[1, 1], R[1, 2], R[2, 0], R[2, 1], R[2, 2])
