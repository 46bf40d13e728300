"""Euler angles in all 12 axis sequences, intrinsic and extrinsic (Theory §2.3).

The conversions also take scipy's one- and two-axis sequences (``"y"``,
``"ZX"``): ``"ZX"`` with angles (α, β) is ``R_z(α) R_x(β)``. Such a sequence
covers only part of SO(3); converting a rotation outside that part to it
raises ``ValueError`` instead of dropping the remainder.

A sequence is three letters from ``xyz`` with no two adjacent equal;
uppercase means intrinsic (rotations about the moving axes), lowercase
extrinsic (about the fixed axes), as in scipy. Intrinsic ``"ABC"`` with
angles (α, β, γ) is ``R = R_A(α) R_B(β) R_C(γ)``; extrinsic ``"abc"`` is
``R = R_c(γ) R_b(β) R_a(α)``. The chapter's mechanics angles (φ, θ, ψ) are
``"ZXZ"``: ``R = R_z(φ) R_x(θ) R_z(ψ)``; the quantum-mechanics (α, β, γ) are
``"ZYZ"``; the chapter's Tait–Bryan angles are ``"XYZ"``.

Angles from a rotation use the direct half-angle quaternion method
(Bernardes & Viollet 2022): the middle angle is 2 atan2 of two half-angle
norms and the outer ones are sums/differences of two atan2 half angles. In
gimbal lock (middle angle 0 or π for proper Euler sequences, ±π/2 for
Tait–Bryan) only the sum or difference of the outer angles is determined;
the formula still returns a pair whose rotation reproduces the input to
rounding (~1e-16) at and arbitrarily near the singular angle. At the
singularity, and within an ulp of it (middle angle within 2⁻⁵¹ rad, where the
outer angles would be set by rounding noise), the third intrinsic angle (the
first extrinsic one) is set to 0. :func:`gimbal_lock` reports which inputs are
within a tolerance of it.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numba import types
from numpy.typing import ArrayLike, NDArray

from .._compiled import kernels
from .._compiled.checks import MATRIX, QUATERNION, VECTOR, finite_array, quaternion_array
from .._compiled.elementwise import ArrayOperation, Input, Parameter, declare, kernel, uses
from .._compiled.outputs import deliver, takes_out
from .._validation import AXES as _AXES, as_float_array, check_flag, parse_sequence
from .matrix import matrix_to_quat
from .._norms import unit

__all__ = [
    "parse_sequence",
    "euler_to_quat",
    "quat_to_euler",
    "euler_to_matrix",
    "matrix_to_euler",
    "gimbal_lock",
]

class KinematicSingularityWarning(UserWarning):
    """A parameterisation rate was requested where the parameterisation is singular."""


class GimbalLockWarning(KinematicSingularityWarning):
    """Euler angles at gimbal lock: only the sum or difference of the outer angles is determined.

    Issued by the Euler-rate maps of :mod:`kreisel.kinematics` (whose first
    and third rates are then NaN) and, on request, by
    ``Rotation.as_euler(..., suppress_warnings=False)``.
    """


def _short_sequence(seq: str) -> tuple[tuple[int, ...], bool] | None:
    """``(axes, intrinsic)`` for a one- or two-axis sequence, None for a three-letter one."""
    if not isinstance(seq, str) or len(seq) not in (1, 2):
        return None
    if not (seq.isupper() or seq.islower()) or any(c not in _AXES for c in seq.lower()):
        raise ValueError(f"seq must be 1-3 letters of x, y, z, all uppercase or all lowercase, got {seq!r}")
    if len(seq) == 2 and seq[0] == seq[1]:
        raise ValueError(f"seq must not repeat an axis in adjacent positions, got {seq!r}")
    return tuple(_AXES[c] for c in seq.lower()), seq.isupper()


def _padded(seq: str) -> str:
    """Three-letter sequence equal to ``seq`` when the appended angles are 0."""
    axes = [_AXES[c] for c in seq.lower()]
    while len(axes) < 3:
        axes.append(3 - axes[-1] - axes[-2] if len(axes) == 2 else (axes[0] + 1) % 3)
    full = "".join("xyz"[a] for a in axes)
    return full.upper() if seq.isupper() else full


def _short_angles(angles: ArrayLike, count: int, degrees: bool) -> NDArray[np.float64]:
    """Angles ``(..., count)`` of a short sequence, zero-padded to ``(..., 3)``.

    For one axis a scalar is one rotation, as in scipy.
    """
    single = count == 1 and np.ndim(angles) == 0
    a = finite_array(np.reshape(angles, (1,)) if single else angles, "angles", (count,))
    out = np.zeros((*a.shape[:-1], 3))
    out[..., :count] = np.deg2rad(a) if degrees else a
    return out


#: Largest departure from a short sequence's set of rotations that counts as
#: rounding: |q0 q_C - q_A q_B| for two axes, |(q_B, q_C)| for one (about
#: half the angle to the nearest rotation of the set).
SHORT_SEQUENCE_TOLERANCE = 1e-10


def _short_sequence_angles(seq: str, axes: tuple[int, ...], intrinsic: bool, q: NDArray[np.float64]) -> NDArray[np.float64]:
    """Angles of a one- or two-axis sequence; refuses rotations it cannot represent."""
    if not intrinsic:
        # Extrinsic "ab" is intrinsic "BA" with the angles reversed.
        return _short_sequence_angles(seq, axes[::-1], True, q)[..., ::-1]
    q = unit(q, "q")
    q0 = q[..., 0]
    qa = q[..., 1 + axes[0]]
    if len(axes) == 1:
        others = [1 + j for j in range(3) if j != axes[0]]
        defect = np.hypot(q[..., others[0]], q[..., others[1]])
        angles = (2.0 * np.arctan2(qa, q0))[..., None]
    else:
        # q_A(α) q_B(β) = (cα cβ, sα cβ e_A + cα sβ e_B + sα sβ e_A × e_B) in half angles:
        # each angle is the phase of whichever of its two pairs is the larger.
        c = 3 - axes[0] - axes[1]
        sign = 1.0 if (axes[1] - axes[0]) % 3 == 1 else -1.0
        qb, qc = q[..., 1 + axes[1]], sign * q[..., 1 + c]
        defect = np.abs(q0 * qc - qa * qb)
        cos_pair = np.hypot(q0, qa) >= np.hypot(qb, qc)
        alpha = np.where(cos_pair, np.arctan2(qa, q0), np.arctan2(qc, qb))
        beta = np.where(np.hypot(q0, qb) >= np.hypot(qa, qc), np.arctan2(qb, q0), np.arctan2(qc, qa))
        angles = 2.0 * np.stack([alpha, beta], axis=-1)
    if defect.size and not np.max(defect) <= SHORT_SEQUENCE_TOLERANCE:
        raise ValueError(
            f"the rotation is not of the form of seq {seq!r} (max departure {np.max(defect):.3g}); "
            "use a three-axis sequence"
        )
    return np.where(angles > np.pi, angles - 2.0 * np.pi, np.where(angles < -np.pi, angles + 2.0 * np.pi, angles))


def _intrinsic_axes(seq: str) -> tuple[int, int, int, int]:
    """The kernels' sequence parameters: the axes of the equivalent intrinsic sequence and whether angles are reversed.

    Extrinsic sequences run as the equivalent intrinsic ones with the first
    and third angles swapped (``reverse`` = 1).
    """
    axes, intrinsic = parse_sequence(seq)
    if intrinsic:
        return axes[0], axes[1], axes[2], 0
    return axes[2], axes[1], axes[0], 1


@kernel
def _elementary(angle: float, axis: int) -> tuple[float, float, float, float]:
    h = 0.5 * angle
    s = math.sin(h)
    return math.cos(h), s if axis == 0 else 0.0, s if axis == 1 else 0.0, s if axis == 2 else 0.0


@kernel
def _euler_quat(alpha: float, beta: float, gamma: float, axis0: int, axis1: int, axis2: int,
                reverse: int) -> tuple[float, float, float, float]:
    # Intrinsic product q_A(α) q_B(β) q_C(γ) of elementary half-angle quaternions.
    if reverse:
        alpha, gamma = gamma, alpha
    a0, a1, a2, a3 = _elementary(alpha, axis0)
    b0, b1, b2, b3 = _elementary(beta, axis1)
    c0, c1, c2, c3 = _elementary(gamma, axis2)
    r0, r1, r2, r3 = kernels.quat_product(a0, a1, a2, a3, b0, b1, b2, b3)
    return kernels.quat_product(r0, r1, r2, r3, c0, c1, c2, c3)


@kernel
def _euler_matrix(alpha: float, beta: float, gamma: float, axis0: int, axis1: int, axis2: int,
                  reverse: int) -> tuple[float, ...]:
    q0, q1, q2, q3 = _euler_quat(alpha, beta, gamma, axis0, axis1, axis2, reverse)
    return kernels.quat_matrix(q0, q1, q2, q3)


@kernel
def _quat_euler(q0: float, q1: float, q2: float, q3: float, axis0: int, axis1: int, axis2: int,
                reverse: int) -> tuple[float, float, float]:
    q0, q1, q2, q3 = kernels.squarable(q0, q1, q2, q3)
    return _euler_angles(q0, q1, q2, q3, axis0, axis1, axis2, reverse)


@kernel
def _matrix_euler(r00: float, r01: float, r02: float, r10: float, r11: float, r12: float, r20: float, r21: float,
                  r22: float, axis0: int, axis1: int, axis2: int, reverse: int) -> tuple[float, float, float]:
    q0, q1, q2, q3 = kernels.matrix_entries_quat(r00, r01, r02, r10, r11, r12, r20, r21, r22)
    return _euler_angles(q0, q1, q2, q3, axis0, axis1, axis2, reverse)


#: Gimbal lock as the angle code sees it: the half-angle pair that vanishes at
#: lock is at most this fraction (one ulp of 1) of the other pair.
LOCK = 2.0**-52


@kernel
def _euler_angles(q0: float, q1: float, q2: float, q3: float, axis0: int, axis1: int, axis2: int,
                  reverse: int) -> tuple[float, float, float]:
    # Bernardes & Viollet's method is written for extrinsic sequences; the
    # intrinsic "ABC" is the extrinsic "cba", hence the reversed axes.
    i, j, l = axis2, axis1, axis0
    proper = i == l
    if proper:
        l = 3 - i - j
    # Levi-Civita sign of (i, j, l).
    sign = 1.0 if (j - i) % 3 == 1 else -1.0
    qv = (q1, q2, q3)
    if proper:
        a, b, c, d = q0, qv[i], qv[j], sign * qv[l]
    else:
        a = q0 - qv[j]
        b = qv[i] + sign * qv[l]
        c = q0 + qv[j]
        d = sign * qv[l] - qv[i]
    # (a, b) has norm ~cos(β/2) and phase (α+γ)/2, (c, d) norm ~sin(β/2) and
    # phase (γ-α)/2; at gimbal lock one pair vanishes, but every nonzero
    # pair still carries its phase to full precision.
    ab = _pair_norm(a, b)
    cd = _pair_norm(c, d)
    beta = 2.0 * math.atan2(cd, ab)
    half_sum = math.atan2(b, a)
    half_diff = math.atan2(d, c)
    # At gimbal lock the vanishing pair's phase is arbitrary; choosing it equal
    # to the other phase puts the whole rotation in the first angle and makes
    # the third one 0. Within LOCK of lock the small pair is rounding noise (a
    # quaternion integrated through the identity): its phase would make the
    # outer angles arbitrary, while dropping it moves the quaternion by at most
    # 2 LOCK, rounding.
    if cd <= LOCK * ab:
        half_diff = half_sum
    elif ab <= LOCK * cd:
        half_sum = half_diff
    first = half_sum + half_diff
    third = half_sum - half_diff
    if not proper:
        first *= sign
        beta -= 0.5 * math.pi
    if reverse:
        return _wrap(third), beta, _wrap(first)
    return _wrap(first), beta, _wrap(third)


@kernel
def _pair_norm(a: float, b: float) -> float:
    # The pairs come from a quaternion whose largest entry is of unit size
    # (kernels.squarable), so a² + b² cannot overflow; only below ~1e-150 can
    # it underflow, and there math.hypot (twice as slow in a loop that is
    # mostly transcendental calls) takes over.
    n2 = a * a + b * b
    if n2 > 1e-290:
        return math.sqrt(n2)
    return math.hypot(a, b)


@kernel
def _wrap(x: float) -> float:
    if x > math.pi:
        return x - 2.0 * math.pi
    if x < -math.pi:
        return x + 2.0 * math.pi
    return x


#: The sequence parameters of :func:`_intrinsic_axes`, shared by every element.
SEQUENCE = [Parameter(name, types.int64) for name in ("axis0", "axis1", "axis2", "reverse")]
_ANGLES = Input("angles", (3,), VECTOR)
_quats = declare(_euler_quat, [_ANGLES], (4,), SEQUENCE, name="euler_to_quat")
_matrices = declare(_euler_matrix, [_ANGLES], (3, 3), SEQUENCE, name="euler_to_matrix")
_quat_angles = declare(_quat_euler, [Input("q", (4,), QUATERNION)], (3,), SEQUENCE, name="quat_to_euler")
_matrix_angles = declare(_matrix_euler, [Input("R", (3, 3), MATRIX)], (3,), SEQUENCE, name="matrix_to_euler")


def _angles_array(seq: str, angles: ArrayLike, degrees: bool) -> tuple[str, NDArray[np.float64]]:
    """The sequence and angles ``(..., 3)`` in radians; short sequences are padded."""
    degrees = check_flag(degrees, "degrees")
    short = _short_sequence(seq)
    if short is not None:
        return _padded(seq), _short_angles(angles, len(seq), degrees)
    a = as_float_array(angles, "angles", (3,), finite=False)
    return seq, (np.deg2rad(a) if degrees else a)


@uses(_quats)
@takes_out
def euler_to_quat(seq: str, angles: ArrayLike, degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Quaternion of Euler angles in any of the 24 conventions (Theory §2.3).

    Parameters
    ----------
    seq : str
        Axis sequence, e.g. ``"ZXZ"`` (the mechanics angles φ, θ, ψ of Theory §2.3).
    angles : array_like, shape (..., 3)
        Angles in the order of ``seq``; radians unless ``degrees=True``.

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternions; the sign is that of the product of the three
        elementary half-angle quaternions (not canonicalised).

    One- and two-axis sequences (``"y"``, ``"ZX"``) take angles ``(..., 1)``
    (or a scalar) and ``(..., 2)``.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(euler_to_quat("ZXZ", [90.0, 0.0, 0.0], degrees=True), 12)
    array([0.70710678, 0.        , 0.        , 0.70710678])
    """
    seq, angles = _angles_array(seq, angles, degrees)
    return _quats(angles, *_intrinsic_axes(seq), out=out)


@uses(_matrices)
@takes_out
def euler_to_matrix(seq: str, angles: ArrayLike, degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Rotation matrix of Euler angles, e.g. the chapter's ``R_z(φ) R_x(θ) R_z(ψ)`` for ``"ZXZ"``.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(euler_to_matrix("xyz", [0.0, 0.0, 90.0], degrees=True), 12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    seq, angles = _angles_array(seq, angles, degrees)
    return _matrices(angles, *_intrinsic_axes(seq), out=out)


def _finish(angles: NDArray[np.float64], degrees: bool) -> NDArray[np.float64]:
    return np.rad2deg(angles, out=angles) if degrees else angles


def _angles_of(seq: str, x: ArrayLike, angles: ArrayOperation, quaternions: Callable[[ArrayLike], NDArray[np.float64]],
               degrees: bool, out: NDArray[np.float64] | None) -> NDArray[np.float64]:
    """The angles of ``seq`` of quaternions or matrices ``x``: the operation ``angles`` for three axes, the
    unit quaternions of ``x`` for one or two."""
    degrees = check_flag(degrees, "degrees")
    short = _short_sequence(seq)
    if short is not None:
        return deliver(_finish(_short_sequence_angles(seq, *short, quaternions(x)), degrees), out)
    return _finish(angles(x, *_intrinsic_axes(seq), out=out), degrees)


@uses(_quat_angles)
@takes_out
def quat_to_euler(seq: str, q: ArrayLike, degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Euler angles of nonzero quaternions (direct half-angle method).

    Ranges: first and third angle in [-π, π]; middle angle in [0, π] for
    proper Euler sequences (``"ZXZ"``, …) and [-π/2, π/2] for Tait–Bryan
    ones. The rotation rebuilt from the angles matches ``q`` to rounding even
    at and near gimbal lock (see :func:`gimbal_lock`).

    One- and two-axis sequences return ``(..., 1)`` and ``(..., 2)`` angles in
    [-π, π], unique and exact everywhere; a rotation that the sequence cannot
    represent (departure above ``SHORT_SEQUENCE_TOLERANCE``) raises ``ValueError``.

    Parameters
    ----------
    seq : str
        Axis sequence (uppercase intrinsic, lowercase extrinsic; one to three axes).
    q : array_like, shape (..., 4)
        Scalar-first quaternions, need not be unit.
    degrees : bool
        Return degrees instead of radians.

    Returns
    -------
    ndarray, shape (..., len(seq))
        One angle per axis of ``seq``, in the ranges above.

    Examples
    --------
    >>> import numpy as np
    >>> q = euler_to_quat("ZXZ", [0.3, 0.2, 0.1])
    >>> np.round(quat_to_euler("ZXZ", q), 12)
    array([0.3, 0.2, 0.1])
    >>> np.round(quat_to_euler("ZX", euler_to_quat("ZX", [0.3, -2.0])), 12)
    array([ 0.3, -2. ])
    """
    return _angles_of(seq, q, _quat_angles, lambda q: quaternion_array(q, "q"), degrees, out)


@uses(_matrix_angles)
@takes_out
def matrix_to_euler(seq: str, R: ArrayLike, degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Euler angles of rotation matrices, exact through gimbal lock.

    Goes through Shepperd's quaternion and the half-angle method, so no
    warning is raised and no digit is lost near the singular middle angle;
    use :func:`gimbal_lock` to find the singular inputs.

    Parameters
    ----------
    seq : str
        Axis sequence, as in :func:`quat_to_euler`.
    R : array_like, shape (..., 3, 3)
        Rotation matrices.
    degrees : bool
        Return degrees.

    Returns
    -------
    ndarray, shape (..., len(seq))
        Angles in the ranges of :func:`quat_to_euler`.

    Examples
    --------
    >>> import numpy as np
    >>> R = euler_to_matrix("ZXZ", [0.3, 0.2, 0.1])
    >>> np.round(matrix_to_euler("ZXZ", R), 12)
    array([0.3, 0.2, 0.1])
    """
    return _angles_of(seq, R, _matrix_angles, matrix_to_quat, degrees, out)


@takes_out
def gimbal_lock(seq: str, angles: ArrayLike, degrees: bool = False, tolerance: float = 1e-7, *,
                out: NDArray[np.bool_] | None = None) -> NDArray[np.bool_]:
    """Which Euler-angle triples are within ``tolerance`` of gimbal lock.

    Gimbal lock (Theory §2.3 (3)) is a middle angle of 0 or π for proper Euler
    sequences and ±π/2 for Tait–Bryan sequences: the first and third axes
    coincide and only the sum or difference of the outer angles is defined.

    Parameters
    ----------
    seq : str
    angles : array_like, shape (..., 3)
        e.g. the output of :func:`matrix_to_euler`.
    tolerance : float
        Distance of the middle angle from the singular value, in radians
        (in degrees when ``degrees=True``).

    Returns
    -------
    ndarray of bool, shape (...)
        True where the middle angle is within ``tolerance`` of its singular value.

    Examples
    --------
    >>> gimbal_lock("ZXZ", [[0.3, 0.0, 0.1], [0.3, 0.5, 0.1]])
    array([ True, False])
    """
    axes, _ = parse_sequence(seq)
    degrees = check_flag(degrees, "degrees")
    a = finite_array(angles, "angles", (3,))
    middle = np.deg2rad(a[..., 1]) if degrees else a[..., 1]
    tol = np.deg2rad(tolerance) if degrees else tolerance
    if axes[0] == axes[2]:
        distance = np.minimum(np.abs(middle), np.abs(np.abs(middle) - np.pi))
    else:
        distance = np.abs(np.abs(middle) - 0.5 * np.pi)
    return deliver(distance <= tol, out)
