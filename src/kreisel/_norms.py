"""Euclidean norms that neither overflow nor underflow, and the nearest rotation matrix, in plain NumPy.

Squaring a component above ~1e154 overflows and one below ~1e-162 underflows
to zero, so ``sqrt(x·x)`` is wrong (inf, 0 or digits lost) for finite vectors
far from unit size. As ``math.hypot`` does, the vector is first divided by
its largest component. The compiled kernels do the same in their rare slow
path (:mod:`kreisel._compiled.kernels`).

This module imports no numba: ``kreisel convert`` uses it without loading
the compiled layer (:mod:`kreisel.cli.rotations`).
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
