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

import math
from typing import TypeAlias, cast

import numpy as np
from numba import types
from numpy.typing import ArrayLike, NDArray

from .._compiled import kernels
from .._compiled.checks import QUATERNION, VECTOR
from .._compiled.elementwise import Input, Parameter, declare, kernel, uses
from .._compiled.outputs import deliver, takes_out
from .._validation import as_float_array, check_flag
from . import euler as _euler
from .quaternion import quat_multiply
from .matrix import matrix_to_quat

__all__ = ["davenport_to_quat", "quat_to_davenport", "davenport_gimbal_lock"]

#: Largest |cos| between consecutive axes that counts as orthogonal (scipy's).
ORTHOGONAL_AXES_TOLERANCE = 1e-7

#: What :func:`_setup` returns: ``(count, reverse, seq, lam, before, after, inverse_after, other)``.
_Setup: TypeAlias = tuple[int, bool, str, float, NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], bool]


def _setup(axes: ArrayLike, order: str) -> _Setup:
    """Checked axes and the fixed factors of both conversions, computed once per axes and order.

    Returns ``(count, reverse, seq, lam, before, after, inverse_after, other)`` with
    ``q = before ⊗ q_euler ⊗ after``, ``q_euler = conj(before) ⊗ q ⊗ inverse_after``
    and ``other`` the choice of scipy's angle branch (see :func:`quat_to_davenport`).
    """
    a = as_float_array(axes, "axes", (3,))
    key = (a.tobytes(), a.shape, order)
    found = _SETUPS.get(key)
    if found is None:
        unit, reverse = _parse(a, order)
        qf, lam, seq = _frame(unit)
        qy = np.array([np.cos(lam / 2), 0.0, np.sin(lam / 2), 0.0])
        # scipy's λ, computed the same way, for the same sign of rounding noise.
        other = len(unit) == 3 and np.arctan2(np.dot(unit[0], np.cross(unit[2], unit[1])), np.dot(unit[0], unit[2])) < 0.0
        found = (len(unit), reverse, seq, lam, qf, quat_multiply(qy, _conjugate(qf)), quat_multiply(qf, _conjugate(qy)), other)
        if len(_SETUPS) < 256:
            _SETUPS[key] = found
    return found


_SETUPS: dict[tuple[bytes, tuple[int, ...], str], _Setup] = {}


@kernel
def _davenport_angles(q0: float, q1: float, q2: float, q3: float, f0: float, f1: float, f2: float, f3: float,
                      g0: float, g1: float, g2: float, g3: float, lam: float, other: int,
                      reverse: int) -> tuple[float, float, float]:
    # XYX Euler angles of conj(f) q g, shifted by λ, on scipy's branch
    q0, q1, q2, q3 = kernels.squarable(q0, q1, q2, q3)
    a0, a1, a2, a3 = kernels.quat_product(f0, -f1, -f2, -f3, q0, q1, q2, q3)
    e0, e1, e2, e3 = kernels.quat_product(a0, a1, a2, a3, g0, g1, g2, g3)
    first, b, third = _euler._euler_angles(e0, e1, e2, e3, 0, 1, 0, 0)
    # scipy's branch: the middle angle in [λ, λ + π] when n₁·(n₃ × n₂) >= 0, else
    # in [λ - π, λ], from the other set (α + π, -b, γ + π) of the Euler angles.
    # At gimbal lock (b = 0 or π exactly) both ranges hold the same angle.
    if other and 0.0 < b < math.pi:
        first, b, third = _euler._wrap(first + math.pi), -b, _euler._wrap(third + math.pi)
    middle = _euler._wrap(b + lam)
    if reverse:
        return third, middle, first
    return first, middle, third


@kernel
def _davenport_quat(x: float, y: float, z: float, f0: float, f1: float, f2: float, f3: float, g0: float, g1: float,
                    g2: float, g3: float, lam: float, reverse: int) -> tuple[float, float, float, float]:
    # f ⊗ q_XYX(α, β - λ, γ) ⊗ g
    if reverse:
        x, z = z, x
    e0, e1, e2, e3 = _euler._euler_quat(x, y - lam, z, 0, 1, 0, 0)
    a0, a1, a2, a3 = kernels.quat_product(f0, f1, f2, f3, e0, e1, e2, e3)
    return kernels.quat_product(a0, a1, a2, a3, g0, g1, g2, g3)


#: The fixed factors of :func:`_setup` (``q = f ⊗ q_euler ⊗ g``) and λ, shared by every element.
_FACTORS = [Parameter(name, types.float64) for name in ("f0", "f1", "f2", "f3", "g0", "g1", "g2", "g3", "lam")]
_REVERSE = Parameter("reverse", types.int64)
_quats = declare(_davenport_quat, [Input("angles", (3,), VECTOR)], (4,), [*_FACTORS, _REVERSE],
                 name="davenport_to_quat")
_angles = declare(_davenport_angles, [Input("q", (4,), QUATERNION)], (3,),
                  [*_FACTORS, Parameter("other", types.int64), _REVERSE], name="quat_to_davenport")


def _parse(axes: ArrayLike, order: str) -> tuple[NDArray[np.float64], bool]:
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
    largest = np.max(np.abs(a), axis=-1, keepdims=True)
    if not (largest > 0).all():
        raise ValueError("axes must be nonzero vectors")
    # divided by a power of two near the largest component first (exact): the squares of the
    # norm neither over- nor underflow, and unit-size axes keep the bits of scipy's normalisation,
    # on whose rounding the choice of angle branch below depends
    a = np.ldexp(a, -np.frexp(largest)[1])
    a = a / np.linalg.norm(a, axis=-1, keepdims=True)
    dots = np.abs(np.sum(a[1:] * a[:-1], axis=-1))
    if (dots > ORTHOGONAL_AXES_TOLERANCE).any():
        raise ValueError(f"axes: consecutive axes must be orthogonal (|cos| = {dots.max():.3g})")
    return (a[::-1] if reverse else a), reverse


def _frame(axes: NDArray[np.float64]) -> tuple[NDArray[np.float64], float, str]:
    """``(q_F, λ, seq)``: the frame F = [n₁, n₂, n₁ × n₂] as a quaternion, the offset λ and the Euler sequence."""
    n1 = axes[0]
    n2 = axes[1] if len(axes) > 1 else np.cross(n1, np.eye(3)[np.argmin(np.abs(n1))])
    n2 = n2 / np.linalg.norm(n2)
    n12 = np.cross(n1, n2)
    qf = matrix_to_quat(np.column_stack([n1, n2, n12]))
    lam = np.arctan2(axes[2] @ n12, axes[2] @ n1) if len(axes) == 3 else 0.0
    return qf, lam, "XYX"[: len(axes)]


def _conjugate(q: NDArray[np.float64]) -> NDArray[np.float64]:
    return cast("NDArray[np.float64]", q * np.array([1.0, -1.0, -1.0, -1.0]))


@uses(_quats)
@takes_out
def davenport_to_quat(axes: ArrayLike, order: str, angles: ArrayLike, degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
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
    count, reverse, seq, lam, before, after, _, _ = _setup(axes, order)
    degrees = check_flag(degrees, "degrees")
    if count == 3:
        a = as_float_array(angles, "angles", (3,), finite=False)
        return _quats(np.deg2rad(a) if degrees else a, *before, *after, lam, int(reverse), out=out)
    angles = _euler._short_angles(angles, count, degrees)[..., :count]
    if reverse:
        angles = angles[..., ::-1]
    # R = F R_x(α) R_y(β) Fᵀ (λ = 0 for fewer than three axes).
    return deliver(quat_multiply(quat_multiply(before, _euler.euler_to_quat(seq, angles)), after), out)


@uses(_angles)
@takes_out
def quat_to_davenport(axes: ArrayLike, order: str, q: ArrayLike, degrees: bool = False, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
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
    count, reverse, seq, lam, before, _, inverse_after, other = _setup(axes, order)
    degrees = check_flag(degrees, "degrees")
    if count == 3:
        angles = _angles(q, *before, *inverse_after, lam, int(other), int(reverse), out=out)
        return np.rad2deg(angles, out=angles) if degrees else angles
    angles = _euler.quat_to_euler(seq, quat_multiply(quat_multiply(_conjugate(before), q), inverse_after))
    if reverse:
        angles = np.ascontiguousarray(angles[..., ::-1])
    return deliver(np.rad2deg(angles) if degrees else angles, out)


@takes_out
def davenport_gimbal_lock(axes: ArrayLike, order: str, angles: ArrayLike, degrees: bool = False, tolerance: float = 1e-7,
                          *, out: NDArray[np.bool_] | None = None) -> NDArray[np.bool_]:
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
    degrees = check_flag(degrees, "degrees")
    a = as_float_array(angles, "angles", (3,))
    # the middle angle in its own statement: nested in the expression below, mypy spends a minute on the overloads
    middle: NDArray[np.float64] = np.deg2rad(a[..., 1]) if degrees else a[..., 1]
    offset = np.abs(np.angle(np.exp(1j * (middle - lam))))
    tol = np.deg2rad(tolerance) if degrees else tolerance
    return deliver(np.minimum(offset, np.pi - offset) <= tol, out)
