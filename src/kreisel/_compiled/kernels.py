"""Scalar quaternion kernels shared by every compiled loop in kreisel.

Each element operation has one *tuple kernel*: it takes plain numbers and
returns a tuple (``quat_product``, ``rotated``, ``quat_matrix``,
``matrix_entries_quat``, ``rotvec_quat``, ``quat_rotvec``, ``quat_unit``).
The serial gufuncs and the multi-core ``prange`` loops of :mod:`kreisel.so3`
both read their arrays into these and write the tuples back, so no array
slice is ever passed per element: a slice argument costs tens of ns to build,
and in a parallel loop every thread would update the reference count of the
one shared parent array. The array forms below (``qmul``, ``qrotate``,
``quat_to_matrix``, ...) are thin shells over the tuple kernels for callers
with per-element arrays, such as the integrators in :mod:`kreisel.dynamics`
and :mod:`kreisel.nav`. Conventions: scalar-first Hamilton quaternions,
``R(q)`` of Theory §2.4.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from . import cached, inlined


# ---------------------------------------------------------------------------
# Tuple kernels: one per element operation.


@cached
def quat_product(p0: float, p1: float, p2: float, p3: float, q0: float, q1: float, q2: float,
                 q3: float) -> tuple[float, float, float, float]:
    """Hamilton product ``p q`` (Theory §2.4: (a0 b0 - a.b, a0 b + b0 a + a x b))."""
    return (
        p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3,
        p0 * q1 + p1 * q0 + p2 * q3 - p3 * q2,
        p0 * q2 - p1 * q3 + p2 * q0 + p3 * q1,
        p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0,
    )


#: Components of size in (SIZE_LOW, SIZE_HIGH) have squares that neither overflow nor lose digits
#: to underflow; a quaternion whose largest component is outside is first divided by it (as
#: ``hypot`` does), which leaves every scale-invariant result unchanged.
SIZE_LOW = 1e-140
SIZE_HIGH = 1e140


@cached
def size(q0: float, q1: float, q2: float, q3: float) -> float:
    """The largest ``|component|`` of ``q``."""
    return max(max(abs(q0), abs(q1)), max(abs(q2), abs(q3)))


@cached
def squarable(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float, float]:
    """``q``, or ``q`` divided by its largest ``|component|`` when squaring it would overflow or underflow."""
    m = size(q0, q1, q2, q3)
    if SIZE_LOW < m < SIZE_HIGH:
        return q0, q1, q2, q3
    return q0 / m, q1 / m, q2 / m, q3 / m


@cached
def norm3(x: float, y: float, z: float) -> float:
    """``|(x, y, z)|`` for any finite components (divided by the largest first when squaring would over- or underflow)."""
    m = size(0.0, x, y, z)
    if SIZE_LOW < m < SIZE_HIGH or m == 0.0:
        return math.sqrt(x * x + y * y + z * z)
    x, y, z = x / m, y / m, z / m
    return m * math.sqrt(x * x + y * y + z * z)


@cached
def quat_unit(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float, float]:
    """``q / |q|`` for any nonzero finite ``q``."""
    q0, q1, q2, q3 = squarable(q0, q1, q2, q3)
    n = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    return q0 / n, q1 / n, q2 / n, q3 / n


@cached
def rotated(q0: float, q1: float, q2: float, q3: float, x: float, y: float, z: float) -> tuple[float, float, float]:
    """``R(q) v`` for a unit quaternion, without forming the matrix."""
    # t = 2 (u x v); v' = v + q0 t + u x t  (u the vector part)
    t0 = 2.0 * (q2 * z - q3 * y)
    t1 = 2.0 * (q3 * x - q1 * z)
    t2 = 2.0 * (q1 * y - q2 * x)
    return x + q0 * t0 + q2 * t2 - q3 * t1, y + q0 * t1 + q3 * t0 - q1 * t2, z + q0 * t2 + q1 * t1 - q2 * t0


@cached
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


@cached
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


@cached
def rotvec_quat(x: float, y: float, z: float) -> tuple[float, float, float, float]:
    """Exponential ``(cos(ψ/2), n sin(ψ/2))``, ψ = |(x, y, z)|, with no sign flip.

    sin(ψ/2)/ψ is taken from its Taylor series below ψ = 1e-4 so that the
    result is accurate to the last bit at tiny angles.
    """
    m = size(0.0, x, y, z)
    if m < SIZE_HIGH:
        a2 = x * x + y * y + z * z
        a = math.sqrt(a2)
    else:  # the squares would overflow (a2 is then only used below 1e-4)
        a2 = np.inf
        a = m * math.sqrt((x / m) ** 2 + (y / m) ** 2 + (z / m) ** 2)
    if a < 1e-4:
        s = 0.5 - a2 / 48.0 + a2 * a2 / 3840.0
        c = 1.0 - a2 / 8.0 + a2 * a2 / 384.0
    else:
        s = math.sin(0.5 * a) / a
        c = math.cos(0.5 * a)
    return c, s * x, s * y, s * z


@cached
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
def quat_to_matrix(q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """``out = R(q)`` exactly as printed in Theory §2.4 (q need not be unit: it is scaled)."""
    write_matrix(q[0], q[1], q[2], q[3], out)


@cached
def matrix_quat(R: NDArray[np.float64]) -> tuple[float, float, float, float]:
    """:func:`matrix_entries_quat` of a 3×3 array."""
    return matrix_entries_quat(R[0, 0], R[0, 1], R[0, 2], R[1, 0], R[1, 1], R[1, 2], R[2, 0], R[2, 1], R[2, 2])


@cached
def rotvec_to_quat(psi: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """``out`` = :func:`rotvec_quat` of ``psi``."""
    out[0], out[1], out[2], out[3] = rotvec_quat(psi[0], psi[1], psi[2])


@cached
def quat_to_rotvec(q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """``out`` = :func:`quat_rotvec` of ``q``."""
    out[0], out[1], out[2] = quat_rotvec(q[0], q[1], q[2], q[3])
