"""Davenport angles: rotations about any three axes, the middle one orthogonal to the others.

Euler angles (Theory §2.3) turn about coordinate axes; Davenport (1973)
allowed any unit axes ``n₁, n₂, n₃`` with ``n₂ ⊥ n₁`` and ``n₂ ⊥ n₃``, which
is what a gimbal with non-orthogonal outer axes or a spacecraft's physical
rotation axes give. Intrinsic angles (α, β, γ) mean
``R = R_{n₁}(α) R_{n₂}(β) R_{n₃}(γ)``; extrinsic ones
``R = R_{n₃}(γ) R_{n₂}(β) R_{n₁}(α)``, as scipy's ``from_davenport``.

The inverse reduces to Euler angles: in the orthonormal frame
``F = [n₁, n₂, n₁ × n₂]`` the axes are ``e_x``, ``e_y`` and ``n₃ = R_y(-λ) e_x``,
where λ is the angle from ``n₁`` to ``n₃`` about ``n₂``, so

.. math::

   F^\\mathsf{T} R\\,F\\,R_y(-λ) = R_x(α)\\,R_y(β - λ)\\,R_x(γ),

a proper ``"XYX"`` Euler sequence whose middle angle is β − λ. The angles
inherit the exactness of :func:`quat_to_euler` through gimbal lock
(β = λ or λ + π), where the third intrinsic angle is set to 0.
"""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array
from . import euler as _euler
from .quaternion import quat_multiply
from .matrix import matrix_to_quat

__all__ = ["davenport_to_quat", "quat_to_davenport", "davenport_gimbal_lock"]

#: Largest |cos| between consecutive axes that counts as orthogonal (scipy's).
ORTHOGONAL_AXES_TOLERANCE = 1e-7


def _parse(axes, order):
    """Unit axes ``(k, 3)`` in intrinsic order (k = 1..3) and whether angles are reversed."""
    if order in ("i", "intrinsic"):
        reverse = False
    elif order in ("e", "extrinsic"):
        reverse = True
    else:
        raise ValueError(f"order must be 'i'/'intrinsic' or 'e'/'extrinsic', got {order!r}")
    a = as_float_array(axes, "axes", (3,))
    if a.ndim == 1:
        a = a[None]
    if a.ndim != 2 or not 1 <= a.shape[0] <= 3:
        raise ValueError(f"axes must have shape (3,) or (k, 3) with k = 1, 2 or 3, got {np.shape(axes)}")
    norm = np.linalg.norm(a, axis=-1, keepdims=True)
    if not (norm > 0).all():
        raise ValueError("axes must be nonzero vectors")
    a = a / norm
    dots = np.abs(np.sum(a[1:] * a[:-1], axis=-1))
    if (dots > ORTHOGONAL_AXES_TOLERANCE).any():
        raise ValueError(f"axes: consecutive axes must be orthogonal (|cos| = {dots.max():.3g})")
    return (a[::-1] if reverse else a), reverse


def _frame(axes):
    """``(q_F, λ, seq)``: the frame F = [n₁, n₂, n₁ × n₂] as a quaternion, the offset λ and the Euler sequence."""
    n1 = axes[0]
    n2 = axes[1] if len(axes) > 1 else np.cross(n1, np.eye(3)[np.argmin(np.abs(n1))])
    n2 = n2 / np.linalg.norm(n2)
    n12 = np.cross(n1, n2)
    qf = matrix_to_quat(np.column_stack([n1, n2, n12]))
    lam = np.arctan2(axes[2] @ n12, axes[2] @ n1) if len(axes) == 3 else 0.0
    return qf, lam, "XYX"[: len(axes)]


def _conjugate(q):
    return q * np.array([1.0, -1.0, -1.0, -1.0])


def davenport_to_quat(axes, order, angles, degrees=False):
    """Quaternions of Davenport angles about ``axes`` (scipy's ``Rotation.from_davenport``).

    Parameters
    ----------
    axes : array_like, shape (3,) or (k, 3), k = 1, 2, 3
        Rotation axes (normalised here); the second must be orthogonal to
        the first and the third.
    order : {"i", "intrinsic", "e", "extrinsic"}
    angles : array_like, shape (..., k)
        Radians unless ``degrees=True`` (a scalar for one axis).

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternions, scalar first.

    Examples
    --------
    With the coordinate axes z, x, z these are the Euler angles ``"ZXZ"``:

    >>> import numpy as np
    >>> axes = [[0, 0, 1], [1, 0, 0], [0, 0, 1]]
    >>> from kreisel import euler_to_quat
    >>> bool(np.allclose(davenport_to_quat(axes, "i", [0.3, 0.2, 0.1]), euler_to_quat("ZXZ", [0.3, 0.2, 0.1])))
    True
    """
    axes, reverse = _parse(axes, order)
    qf, lam, seq = _frame(axes)
    angles = _euler._short_angles(angles, len(axes), degrees)[..., : len(axes)]
    if reverse:
        angles = angles[..., ::-1]
    shifted = angles.copy()
    if len(axes) == 3:
        shifted[..., 1] -= lam
    # R = F R_x(α) R_y(β - λ) R_x(γ) R_y(λ) Fᵀ.
    q = _euler.euler_to_quat(seq, shifted)
    q = quat_multiply(q, [np.cos(lam / 2), 0.0, np.sin(lam / 2), 0.0])
    return quat_multiply(quat_multiply(qf, q), _conjugate(qf))


def quat_to_davenport(axes, order, q, degrees=False):
    """Davenport angles about ``axes`` of rotations ``q`` (scipy's ``Rotation.as_davenport``).

    The outer angles are in [-π, π]; the middle one is in [λ, λ + π] or in
    [λ - π, λ] (wrapped to [-π, π]), where λ is the angle from the first axis
    to the third about the second, by the same rule as scipy, so the angles
    agree with scipy's away from gimbal lock. At gimbal lock (middle angle λ
    or λ + π) they are exact without a warning, the third intrinsic angle
    being 0. One- and two-axis sets refuse rotations they cannot represent.

    Examples
    --------
    A gimbal whose third axis is tilted 30° from the first; the middle angle
    comes back on scipy's branch, here the other of the two angle sets that
    give the same rotation:

    >>> import numpy as np
    >>> tilt = np.radians(30)
    >>> axes = [[1, 0, 0], [0, 1, 0], [np.cos(tilt), 0, -np.sin(tilt)]]
    >>> q = davenport_to_quat(axes, "e", [0.4, 1.1, -0.7])
    >>> angles = quat_to_davenport(axes, "e", q)
    >>> np.round(angles, 6)
    array([-2.741593, -0.052802,  2.441593])
    >>> bool(np.allclose(davenport_to_quat(axes, "e", angles), q) or np.allclose(davenport_to_quat(axes, "e", angles), -q))
    True
    """
    axes, reverse = _parse(axes, order)
    qf, lam, seq = _frame(axes)
    q = quat_multiply(quat_multiply(_conjugate(qf), q), qf)
    q = quat_multiply(q, [np.cos(lam / 2), 0.0, -np.sin(lam / 2), 0.0])
    angles = _euler.quat_to_euler(seq, q)
    if len(axes) == 3:
        b = angles[..., 1]
        # scipy's branch: the middle angle in [λ, λ + π] when n₃·(n₂ × n₁) >= 0 (its
        # λ, computed the same way, for the same sign of rounding noise), else in
        # [λ - π, λ], from the other set (α + π, -b, γ + π) of the Euler angles.
        # At gimbal lock (b = 0 or π exactly) both ranges hold the same angle.
        n1, n2, n3 = axes
        other = np.arctan2(np.dot(n1, np.cross(n3, n2)), np.dot(n1, n3)) < 0.0
        if other:
            flip = (b > 0.0) & (b < np.pi)
            angles[..., 0] = np.where(flip, angles[..., 0] + np.pi, angles[..., 0])
            angles[..., 2] = np.where(flip, angles[..., 2] + np.pi, angles[..., 2])
            angles[..., 1] = np.where(flip, -b, b)
        angles[..., 1] += lam
        angles = np.where(angles > np.pi, angles - 2.0 * np.pi, np.where(angles < -np.pi, angles + 2.0 * np.pi, angles))
    if reverse:
        angles = np.ascontiguousarray(angles[..., ::-1])
    return np.rad2deg(angles) if degrees else angles


def davenport_gimbal_lock(axes, order, angles, degrees=False, tolerance=1e-7):
    """Which Davenport angle triples have the middle angle within ``tolerance`` of λ or λ + π.

    There the first and third axes line up and only the sum or difference of
    the outer angles is determined.

    Examples
    --------
    >>> davenport_gimbal_lock([[0, 0, 1], [1, 0, 0], [0, 0, 1]], "i", [[0.3, 0.0, 0.1], [0.3, 0.5, 0.1]])
    array([ True, False])
    """
    axes, _ = _parse(axes, order)
    _, lam, _ = _frame(axes)
    a = as_float_array(angles, "angles", (3,))
    offset = np.abs(np.angle(np.exp(1j * ((np.deg2rad(a[..., 1]) if degrees else a[..., 1]) - lam))))
    tol = np.deg2rad(tolerance) if degrees else tolerance
    return np.minimum(offset, np.pi - offset) <= tol
