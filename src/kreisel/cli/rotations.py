"""Rotation conversions in plain NumPy, for ``kreisel convert``: no numba is loaded.

``kreisel convert`` runs once per command: importing numba and readying its
compiler for the first cached kernel (which imports ``scipy.linalg`` for
numba's BLAS check) costs over a second of CPU, many times the conversion
itself. This module holds the formulas of the compiled element kernels of
:mod:`kreisel.so3` (:mod:`kreisel._compiled.kernels`, the Euler kernels of
:mod:`kreisel.so3.euler`) written once more as NumPy expressions over whole
columns, with the same branches, the same operation order and the same input
checks, and the NumPy-level conversions (Rodrigues, SU(2)) as
:mod:`kreisel.so3` writes them. ``tests/cli/test_rotations.py`` holds the
compiled kernels to them, and them to the kernels, within a few units in the
last place for every representation, at gimbal lock, half turns, tiny and huge
angles and nearly orthogonal matrices.

Every conversion goes through unit quaternions (scalar first, Theory §2.4):
:func:`to_quat` reads a representation, :func:`from_quat` writes one.
"""

from __future__ import annotations

import numpy as np

from .._norms import checked_rotation_matrices, norm, unit
from .._validation import as_float_array, parse_sequence, refuse_long_angle

__all__ = ["to_quat", "from_quat", "quat_unit", "matrix_quat", "quat_matrix", "rotvec_quat", "quat_rotvec",
           "euler_quat", "quat_euler"]

#: As :data:`kreisel._compiled.kernels.SIZE_LOW` and ``SIZE_HIGH``: components of a size between them
#: square without overflow or loss to underflow
SIZE_LOW = 1e-140
SIZE_HIGH = 1e140
_CONJUGATE = np.array([1.0, -1.0, -1.0, -1.0])


def _columns(a):
    """The last axis of ``a`` as a tuple of arrays."""
    return tuple(np.moveaxis(a, -1, 0))


def _finite(x, name, tail):
    a = as_float_array(x, name, tail, finite=False)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite (no NaN or inf)")
    return a


def _quaternions(q, name):
    """Finite nonzero quaternions ``(..., 4)`` (the checks of ``quaternion_array``)."""
    a = as_float_array(q, name, (4,), finite=False)
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite quaternions (no NaN or inf)")
    if a.size and not np.min(np.max(np.abs(a), axis=-1)) > 0.0:
        raise ValueError(f"{name} must be nonzero quaternions (a zero quaternion is not a rotation)")
    return a


def _squarable(q):
    """``q``, or ``q`` over its largest ``|component|`` where squaring would over- or underflow."""
    m = np.max(np.abs(q), axis=-1, keepdims=True)
    return np.where((SIZE_LOW < m) & (m < SIZE_HIGH), q, q / m)


def _product(p, q):
    """Hamilton product of quaternion columns ``p`` and ``q``."""
    p0, p1, p2, p3 = p
    q0, q1, q2, q3 = q
    return (
        p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3,
        p0 * q1 + p1 * q0 + p2 * q3 - p3 * q2,
        p0 * q2 - p1 * q3 + p2 * q0 + p3 * q1,
        p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0,
    )


def quat_unit(q):
    """``q / |q|`` for finite nonzero quaternions ``(..., 4)`` (``quat_normalize``).

    Examples
    --------
    >>> quat_unit(np.array([0.0, 0.0, 0.0, 2e-300]))
    array([0., 0., 0., 1.])
    """
    q0, q1, q2, q3 = _columns(_squarable(q))
    n = np.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    return np.stack([q0 / n, q1 / n, q2 / n, q3 / n], axis=-1)


def quat_matrix(q):
    """Rotation matrices ``R(q)`` ``(..., 3, 3)`` of nonzero quaternions (Theory §2.4).

    Examples
    --------
    >>> quat_matrix(np.array([0.0, 0.0, 0.0, 1.0])) + 0.0
    array([[-1.,  0.,  0.],
           [ 0., -1.,  0.],
           [ 0.,  0.,  1.]])
    """
    q0, q1, q2, q3 = _columns(_squarable(q))
    s = 1.0 / (q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    rows = (
        ((q0 * q0 + q1 * q1 - q2 * q2 - q3 * q3) * s, 2.0 * (q1 * q2 - q0 * q3) * s, 2.0 * (q1 * q3 + q0 * q2) * s),
        (2.0 * (q1 * q2 + q0 * q3) * s, (q0 * q0 - q1 * q1 + q2 * q2 - q3 * q3) * s, 2.0 * (q2 * q3 - q0 * q1) * s),
        (2.0 * (q1 * q3 - q0 * q2) * s, 2.0 * (q2 * q3 + q0 * q1) * s, (q0 * q0 - q1 * q1 - q2 * q2 + q3 * q3) * s),
    )
    return np.stack([np.stack(row, axis=-1) for row in rows], axis=-2)


def _rotation_matrices(R):
    """Checked rotation matrices ``(..., 3, 3)``; nearly orthogonal batches projected (``matrix_array``)."""
    a = as_float_array(R, "R", (3, 3), finite=False)
    if a.size == 0:
        return a
    (a_, b, c), (d, e, f), (g, h, i) = (_columns(row) for row in np.moveaxis(a, -2, 0))
    with np.errstate(over="ignore", invalid="ignore"):  # NaN, inf and overflowing squares: refused below
        worst = np.max([np.abs(a_ * a_ + d * d + g * g - 1.0), np.abs(b * b + e * e + h * h - 1.0),
                        np.abs(c * c + f * f + i * i - 1.0), np.abs(a_ * b + d * e + g * h),
                        np.abs(a_ * c + d * f + g * i), np.abs(b * c + e * f + h * i)])
        smallest_det = np.min(a_ * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g))
    return checked_rotation_matrices(a, "R", float(worst), float(smallest_det))


def matrix_quat(R):
    """Unit quaternions with ``q0 >= 0`` of checked rotation matrices ``(..., 3, 3)`` (Shepperd/Markley).

    Examples
    --------
    >>> matrix_quat(np.array([[-1.0, 0, 0], [0, -1.0, 0], [0, 0, 1.0]]))
    array([0., 0., 0., 1.])
    """
    (r00, r01, r02), (r10, r11, r12), (r20, r21, r22) = (_columns(row) for row in np.moveaxis(R, -2, 0))
    tr = r00 + r11 + r22
    # the component with the largest square comes from the diagonal, the others from off-diagonal pairs
    cases = [(tr >= r00) & (tr >= r11) & (tr >= r22), (r00 >= r11) & (r00 >= r22), r11 >= r22]
    candidates = [
        (1.0 + tr, r21 - r12, r02 - r20, r10 - r01),
        (r21 - r12, 1.0 + r00 - r11 - r22, r01 + r10, r02 + r20),
        (r02 - r20, r01 + r10, 1.0 + r11 - r00 - r22, r12 + r21),
        (r10 - r01, r02 + r20, r12 + r21, 1.0 + r22 - r00 - r11),
    ]
    q0, q1, q2, q3 = (np.select(cases, [c[k] for c in candidates[:3]], candidates[3][k]) for k in range(4))
    n = np.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    n = np.where(q0 < 0.0, -n, n)
    return np.stack([q0 / n, q1 / n, q2 / n, q3 / n], axis=-1)


def _in_range(psi, name):
    """``psi``, refused naming ``name`` if longer than ``ROTVEC_RANGE`` (1e8 rad), as kreisel.so3 does."""
    refuse_long_angle(float(np.max(norm(psi), initial=0.0)), name)
    return psi


def rotvec_quat(psi):
    """Exponential ``(cos(ψ/2), n sin(ψ/2))`` of finite rotation vectors ``(..., 3)``, no sign flip.

    Examples
    --------
    >>> rotvec_quat(np.array([0.0, 0.0, np.pi])).round(12) + 0.0
    array([0., 0., 0., 1.])
    """
    x, y, z = _columns(psi)
    m = np.max(np.abs(psi), axis=-1)
    big = m >= SIZE_HIGH
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        a2 = np.where(big, np.inf, x * x + y * y + z * z)
        scale = np.where(big, m, 1.0)
        a = np.where(big, m * np.sqrt((x / scale) ** 2 + (y / scale) ** 2 + (z / scale) ** 2), np.sqrt(a2))
        # sin(ψ/2)/ψ and cos(ψ/2) from their Taylor series below ψ = 1e-4: exact to the last bit there
        small = a < 1e-4
        s = np.where(small, 0.5 - a2 / 48.0 + a2 * a2 / 3840.0, np.sin(0.5 * a) / a)
        c = np.where(small, 1.0 - a2 / 8.0 + a2 * a2 / 384.0, np.cos(0.5 * a))
    return np.stack([c, s * x, s * y, s * z], axis=-1)


def quat_rotvec(q):
    """Logarithm of nonzero quaternions ``(..., 4)`` as rotation vectors with ``|ψ| <= π``.

    Examples
    --------
    >>> quat_rotvec(np.array([0.0, 0.0, 0.0, 1.0]))
    array([0.        , 0.        , 3.14159265])
    """
    q = np.where(q[..., :1] < 0.0, -q, q)
    q0, q1, q2, q3 = _columns(_squarable(q))
    v = np.sqrt(q1 * q1 + q2 * q2 + q3 * q3)
    with np.errstate(divide="ignore", invalid="ignore"):
        # ψ/|v| tends to 2/q0 at small |v|: its series there, 2 atan2(|v|, q0)/|v| elsewhere
        r = v / q0
        k = np.where(v < 1e-8 * q0, 2.0 / q0 * (1.0 - r * r / 3.0), 2.0 * np.arctan2(v, q0) / v)
    return np.stack([k * q1, k * q2, k * q3], axis=-1)


def _intrinsic(seq):
    """Axes of the intrinsic sequence equal to ``seq`` and whether its first and third angles swap."""
    axes, intrinsic = parse_sequence(seq)
    return (axes, False) if intrinsic else (axes[::-1], True)


def euler_quat(seq, angles):
    """Quaternions of Euler angles ``(..., 3)`` in radians: the product of the elementary half-angle quaternions.

    Examples
    --------
    >>> euler_quat("ZXZ", np.radians([90.0, 0.0, 0.0])).round(6) + 0.0
    array([0.707107, 0.      , 0.      , 0.707107])
    """
    axes, reverse = _intrinsic(seq)
    alpha, beta, gamma = _columns(angles)
    if reverse:
        alpha, gamma = gamma, alpha
    zero = np.zeros_like(beta)
    factors = []
    for angle, axis in zip((alpha, beta, gamma), axes):
        s = np.sin(0.5 * angle)
        factors.append((np.cos(0.5 * angle), *(s if k == axis else zero for k in range(3))))
    return np.stack(_product(_product(factors[0], factors[1]), factors[2]), axis=-1)


def _pair_norm(a, b):
    """``|(a, b)|`` of entries of a unit quaternion; ``hypot`` where the squares would underflow."""
    n2 = a * a + b * b
    return np.where(n2 > 1e-290, np.sqrt(n2), np.hypot(a, b))


def _wrap(x):
    return np.where(x > np.pi, x - 2.0 * np.pi, np.where(x < -np.pi, x + 2.0 * np.pi, x))


def quat_euler(seq, q):
    """Euler angles ``(..., 3)`` in radians of unit quaternions (the half-angle method of Theory §2.3).

    Exact through gimbal lock: where the middle angle is singular the third
    intrinsic (first extrinsic) angle is 0.

    Examples
    --------
    >>> quat_euler("ZXZ", euler_quat("ZXZ", np.array([0.3, 0.2, 0.1]))).round(12)
    array([0.3, 0.2, 0.1])
    """
    axes, reverse = _intrinsic(seq)
    # Bernardes & Viollet write the method for extrinsic sequences: intrinsic "ABC" is extrinsic "cba"
    i, j, l = axes[2], axes[1], axes[0]
    proper = i == l
    if proper:
        l = 3 - i - j
    sign = 1.0 if (j - i) % 3 == 1 else -1.0
    q0, *qv = _columns(q)
    if proper:
        a, b, c, d = q0, qv[i], qv[j], sign * qv[l]
    else:
        a, b, c, d = q0 - qv[j], qv[i] + sign * qv[l], q0 + qv[j], sign * qv[l] - qv[i]
    ab, cd = _pair_norm(a, b), _pair_norm(c, d)
    beta = 2.0 * np.arctan2(cd, ab)
    half_sum, half_diff = np.arctan2(b, a), np.arctan2(d, c)
    # at exact gimbal lock the vanishing pair's phase is arbitrary: the other one puts the whole rotation
    # into the first angle
    half_sum, half_diff = (np.where((cd != 0.0) & (ab == 0.0), half_diff, half_sum),
                           np.where(cd == 0.0, half_sum, half_diff))
    first, third = half_sum + half_diff, half_sum - half_diff
    if not proper:
        first = first * sign
        beta = beta - 0.5 * np.pi
    if reverse:
        first, third = third, first
    return np.stack([_wrap(first), beta, _wrap(third)], axis=-1)


def _radians(angles, degrees):
    return np.deg2rad(angles) if degrees else angles


def to_quat(name, seq, values, degrees=False):
    """Unit quaternions ``(n, 4)`` of rotations given as rows in representation ``name``.

    Parameters
    ----------
    name : str
        ``quat``, ``matrix`` (rows ``(n, 3, 3)``), ``rotvec``, ``euler`` (with
        ``seq``), ``axis_angle`` (axis, then angle), ``gibbs``, ``mrp`` or
        ``euler_parameters``.
    seq : str
        Euler axis sequence for ``euler``, else ignored.
    values : array_like, shape (n, k)
    degrees : bool
        Angles (``euler``, ``axis_angle``, ``rotvec``) in degrees.

    Raises ``ValueError`` for values that are no rotation, with the message of
    the matching :mod:`kreisel.so3` function.

    Examples
    --------
    >>> to_quat("euler", "ZXZ", [[90.0, 0.0, 0.0]], degrees=True).round(6) + 0.0
    array([[0.707107, 0.      , 0.      , 0.707107]])
    """
    if name == "quat":
        return quat_unit(_quaternions(values, "q"))
    if name == "euler_parameters":
        return unit(_quaternions(values, "e"), "e") * _CONJUGATE
    if name == "matrix":
        return matrix_quat(_rotation_matrices(values))
    if name == "euler":
        return euler_quat(seq, _radians(_finite(values, "angles", (3,)), degrees))
    if name == "rotvec":
        return rotvec_quat(_in_range(_finite(_radians(as_float_array(values, "rotvec", (3,), finite=False), degrees),
                                             "rotvec", (3,)), "rotvec"))
    if name == "axis_angle":
        values = as_float_array(values, "axis_angle", (4,), finite=False)
        axis, angle = _finite(values[..., :3], "axis", (3,)), _finite(values[..., 3], "angle", ())
        return rotvec_quat(_in_range(_finite(unit(axis, "axis") * _radians(angle, degrees)[..., None], "psi", (3,)),
                                     "angle"))
    if name == "gibbs":
        g = _finite(values, "g", (3,))
        return unit(np.concatenate([np.ones(g.shape[:-1] + (1,)), g], axis=-1), "g")
    if name == "mrp":
        p = _finite(values, "p", (3,))
        # |p| > 1 goes through its shadow -p/|p|² (the same rotation, q -> -q): |p|² never overflows
        length = norm(p, keepdims=True)
        shadow = length > 1.0
        p = np.where(shadow, -(p / np.where(shadow, length, 1.0)) / np.where(shadow, length, 1.0), p)
        p2 = np.sum(p * p, axis=-1, keepdims=True)
        q = np.concatenate([1.0 - p2, 2.0 * p], axis=-1) / (1.0 + p2)
        return np.where(shadow, -q, q)
    raise ValueError(f"cannot read rotations from {name!r}")


def from_quat(q, name, seq="", degrees=False):
    """Rotations given by unit quaternions ``q`` ``(n, 4)`` as rows ``(n, k)`` of representation ``name``.

    ``name`` is one of :func:`to_quat`'s, or ``su2`` and ``cayley_klein``
    (complex rows of 4: ``a, b, -b*, a*``). Gibbs vectors of half turns raise
    ``ValueError``.

    Examples
    --------
    >>> from_quat(np.array([[np.sqrt(0.5), 0.0, 0.0, np.sqrt(0.5)]]), "euler", "ZXZ", degrees=True).round(9) + 0.0
    array([[90.,  0.,  0.]])
    >>> from_quat(np.array([[np.sqrt(0.5), 0.0, 0.0, np.sqrt(0.5)]]), "axis_angle", degrees=True).round(9) + 0.0
    array([[ 0.,  0.,  1., 90.]])
    """
    if name == "quat":
        return q
    if name == "matrix":
        return quat_matrix(q).reshape(q.shape[:-1] + (9,))
    if name == "rotvec":
        return np.rad2deg(quat_rotvec(q)) if degrees else quat_rotvec(q)
    if name == "euler":
        return np.rad2deg(quat_euler(seq, q)) if degrees else quat_euler(seq, q)
    if name == "axis_angle":
        psi = quat_rotvec(q)
        angle = norm(psi)
        zero = angle == 0.0
        axis = psi / np.where(zero, 1.0, angle)[..., None]
        axis[zero] = (0.0, 0.0, 1.0)
        return np.concatenate([axis, (np.rad2deg(angle) if degrees else angle)[..., None]], axis=-1)
    q = unit(q, "q")
    if name == "euler_parameters":
        return q * _CONJUGATE
    if name in ("su2", "cayley_klein"):
        a, b = q[..., 0] - 1j * q[..., 3], -q[..., 2] - 1j * q[..., 1]
        return np.stack([a, b, -b.conj(), a.conj()], axis=-1)
    q = np.where(q[..., :1] < 0.0, -q, q)
    if name == "gibbs":
        if np.any(q[..., 0] == 0.0):
            raise ValueError("q must not be a half-turn (ψ = π): its Gibbs vector is infinite")
        return q[..., 1:] / q[..., :1]
    if name == "mrp":
        return q[..., 1:] / (1.0 + q[..., :1])
    raise ValueError(f"cannot write rotations as {name!r}")
