"""Compiled loops of the inertia layer (compiled on first use, cached on disk)."""

from __future__ import annotations

import numpy as np

from .._compiled import cached
from .._compiled.kernels import quat_to_matrix


@cached
def _fill_matrices(q, out):
    # Element slices with numba's layout 'A', as so3's gufuncs pass them: the
    # shared kernel is compiled (and cached on disk) for one signature only.
    for k in range(q.shape[0]):
        quat_to_matrix(q[k, ::1], out[k, :, ::1])


def quaternions_to_matrices(q):
    """R(q) of Theory §2.4 for a contiguous ``(n, 4)`` array of nonzero quaternions."""
    out = np.empty((q.shape[0], 3, 3))
    _fill_matrices(q, out)
    return out
