"""Euclidean norms that neither overflow nor underflow, for the Python-level functions.

Squaring a component above ~1e154 overflows and one below ~1e-162 underflows
to zero, so ``sqrt(x·x)`` is wrong (inf, 0 or digits lost) for finite vectors
far from unit size. As ``math.hypot`` does, the vector is first divided by
its largest component. The compiled kernels do the same in their rare slow
path (:mod:`kreisel._compiled.kernels`).
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
