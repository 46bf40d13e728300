"""Euclidean norms that neither overflow nor underflow, and the nearest rotation matrix, in plain NumPy.

Squaring a component above ~1e154 overflows and one below ~1e-162 underflows
to zero, so ``sqrt(x·x)`` is wrong (inf, 0 or digits lost) for finite vectors
far from unit size. As ``math.hypot`` does, the vector is first divided by
its largest component. The compiled kernels do the same in their rare slow
path (:mod:`kreisel._compiled.kernels`).

This module imports no numba: the compiled layer (:mod:`kreisel._compiled`)
builds its input checks on it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


def norm(x: ArrayLike, keepdims: bool = False) -> NDArray[np.float64]:
    """Euclidean norm over the last axis of finite ``x``, accurate for any magnitude."""
    x = np.asarray(x, dtype=np.float64)
    largest = np.max(np.abs(x), axis=-1, keepdims=True)
    scale = np.where(largest > 0.0, largest, 1.0)
    out = largest * np.sqrt(np.sum((x / scale) ** 2, axis=-1, keepdims=True))
    return out if keepdims else out[..., 0]


def unit(x: ArrayLike, name: str) -> NDArray[np.float64]:
    """``x / |x|`` over the last axis, for any nonzero finite magnitude; refuses zero vectors naming ``name``."""
    x = np.asarray(x, dtype=np.float64)
    largest = np.max(np.abs(x), axis=-1, keepdims=True)
    if np.any(largest == 0.0):
        raise ValueError(f"{name} must be nonzero (a zero vector has no direction)")
    scaled = x / largest
    return scaled / np.sqrt(np.sum(scaled * scaled, axis=-1, keepdims=True))


def nearest_rotation(M: ArrayLike) -> NDArray[np.float64]:
    """Nearest rotation matrix (Frobenius norm) to each ``(..., 3, 3)`` matrix.

    ``U diag(1, 1, det(U Vᵀ)) Vᵀ`` from the SVD ``M = U S Vᵀ`` — the special
    orthogonal polar factor (Kabsch).
    """
    U, _, Vt = np.linalg.svd(M)
    d = np.sign(np.linalg.det(U @ Vt))
    U[..., :, 2] *= d[..., None]
    return U @ Vt


#: Largest orthogonality defect ``max |RᵀR − 1|`` of a matrix accepted as a rotation (projected onto SO(3)).
ORTHOGONALITY_TOLERANCE = 1e-6

#: Defects below this are rounding noise of a rotation and pass untouched.
ROUNDING_DEFECT = 1e-13


def checked_rotation_matrices(a: NDArray[np.float64], name: str, worst: float, smallest_det: float,
                              tolerance: float = ORTHOGONALITY_TOLERANCE) -> NDArray[np.float64]:
    """Refuse or accept the matrices ``a`` from their defect ``worst`` and smallest determinant.

    The one verdict of the compiled and the NumPy-only checks: non-finite or
    overflowing entries, a defect above ``tolerance`` or det <= 0 raise
    ``ValueError`` naming ``name``; a defect above rounding level is projected
    onto the nearest rotations.
    """
    if not np.isfinite(worst) or not np.isfinite(smallest_det):
        largest = np.max(np.abs(a))
        if not np.isfinite(largest):
            raise ValueError(f"{name} must be finite rotation matrices (no NaN or inf)")
        # finite entries whose squares overflow: far from orthonormal, not a rotation at any scale
        raise ValueError(f"{name} must be rotation matrices (entries in [-1, 1]), got entries as large as {largest:.3g}")
    if worst > tolerance:
        raise ValueError(
            f"{name} must be rotation matrices: max |R^T R - 1| = {worst:.3g} exceeds {tolerance:g} "
            "(use orthonormalize for a larger projection)"
        )
    if smallest_det <= 0.0:
        raise ValueError(f"{name} must be rotation matrices with det > 0 (got det = {smallest_det:.3g})")
    return nearest_rotation(a) if worst > ROUNDING_DEFECT else a
