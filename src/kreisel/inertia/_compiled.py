"""Compiled loops of the inertia layer (compiled on first use, cached on disk)."""

from __future__ import annotations

import numpy as np
from numba import njit

from ..so3._kernels import quat_to_matrix


@njit(cache=True, nogil=True)
def _fill_matrices(q, out):
    for k in range(q.shape[0]):
        quat_to_matrix(q[k], out[k])


def quaternions_to_matrices(q):
    """R(q) of seed 二.4 for a contiguous ``(n, 4)`` array of nonzero quaternions."""
    out = np.empty((q.shape[0], 3, 3))
    _fill_matrices(q, out)
    return out
