"""Compiled per-pose kernels of :mod:`kreisel.se3`, broadcast as lazy gufuncs.

A pose is stored as a unit quaternion ``q`` (scalar first) and a translation
``t``: the displacement ``r -> R(q) r + t`` of Theory §1.3. Everything here
works on one pose and is broadcast by :func:`numba.guvectorize`; the scalar
quaternion algebra comes from :mod:`kreisel._compiled.kernels`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import prange
from numpy.typing import NDArray

from .._compiled import kernels, parallel
from .._compiled.gufunc import gufunc

_F8 = "f8[:]"


def _signature(n_arrays: int) -> list[str]:
    return ["void(" + ", ".join([_F8] * n_arrays) + ")"]


def split(pose: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Views ``(q, t)`` of packed poses ``(..., 7)``."""
    return pose[..., :4], pose[..., 4:]


# Results are packed as [q, t] in one (7,) core: one output array per call.
@gufunc(_signature(6), "(4),(3),(4),(3),(7)->(7)")
def _compose(q1: NDArray[np.float64], t1: NDArray[np.float64], q2: NDArray[np.float64], t2: NDArray[np.float64], carrier: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    kernels.qmul(q1, q2, out[:4])
    kernels.qrotate(q1, t2, out[4:])
    out[4] += t1[0]
    out[5] += t1[1]
    out[6] += t1[2]


@gufunc(_signature(4), "(4),(3),(7)->(7)")
def _invert(q: NDArray[np.float64], t: NDArray[np.float64], carrier: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    out[0] = q[0]
    out[1] = -q[1]
    out[2] = -q[2]
    out[3] = -q[3]
    kernels.qrotate_inverse(q, t, out[4:])
    out[4] = -out[4]
    out[5] = -out[5]
    out[6] = -out[6]


def compose(q1: NDArray[np.float64], t1: NDArray[np.float64], q2: NDArray[np.float64], t2: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(q1, t1)(q2, t2) = (q1 q2, R(q1) t2 + t1): apply pose 2, then pose 1."""
    return split(_compose(q1, t1, q2, t2))


def invert(q: NDArray[np.float64], t: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(q, t)⁻¹ = (q*, -R(q)ᵀ t)."""
    return split(_invert(q, t))


@gufunc(_signature(4), "(4),(3),(3)->(3)")
def apply(q: NDArray[np.float64], t: NDArray[np.float64], p: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """r_P = R r′_CP + r_C (Theory §1.3, Chasles)."""
    kernels.qrotate(q, p, out)
    out[0] += t[0]
    out[1] += t[1]
    out[2] += t[2]


@gufunc(_signature(4), "(4),(3),(3)->(3)")
def apply_inverse(q: NDArray[np.float64], t: NDArray[np.float64], p: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """r′_CP = Rᵀ (r_P - r_C): space point back to body components."""
    d0 = p[0] - t[0]
    d1 = p[1] - t[1]
    d2 = p[2] - t[2]
    # qrotate_inverse reads v[i] only before it writes out[i]: safe in place,
    # and no per-pose temporary is allocated.
    out[0] = d0
    out[1] = d1
    out[2] = d2
    kernels.qrotate_inverse(q, out, out)


@parallel
def _as_matrix_parallel(q: NDArray[np.float64], t: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    for i in prange(q.shape[0]):
        kernels.write_matrix_at(out, i, q[i, 0], q[i, 1], q[i, 2], q[i, 3])
        out[i, 0, 3], out[i, 1, 3], out[i, 2, 3] = t[i, 0], t[i, 1], t[i, 2]
        out[i, 3, 0], out[i, 3, 1], out[i, 3, 2], out[i, 3, 3] = 0.0, 0.0, 0.0, 1.0


@gufunc(["void(f8[:], f8[:], f8[:, :])"], "(4),(3)->(4,4)", parallel=_as_matrix_parallel)
def as_matrix(q: NDArray[np.float64], t: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """Homogeneous matrix [[R(q), t], [0, 0, 0, 1]]."""
    kernels.write_matrix(q[0], q[1], q[2], q[3], out)
    for i in range(3):
        out[i, 3] = t[i]
        out[3, i] = 0.0
    out[3, 3] = 1.0


@gufunc(["void(f8[:, :], f8[:], f8[:])"], "(4,4),(8)->(8)")
def from_matrix(m: NDArray[np.float64], carrier: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """Packed [q, t, defect] of a homogeneous matrix.

    ``defect`` is the largest of |bottom row - (0, 0, 0, 1)| and
    |RᵀR - 1| (inf when det R <= 0) for finite input, so one pass both
    converts and lets the caller refuse non-rigid matrices.
    """
    q0, q1, q2, q3 = kernels.matrix_quat(m)
    out[0] = q0
    out[1] = q1
    out[2] = q2
    out[3] = q3
    defect = abs(m[3, 3] - 1.0)
    for i in range(3):
        out[4 + i] = m[i, 3]
        defect = max(defect, abs(m[3, i]))
        for j in range(i, 3):
            d = m[0, i] * m[0, j] + m[1, i] * m[1, j] + m[2, i] * m[2, j]
            if i == j:
                d -= 1.0
            defect = max(defect, abs(d))
    det = (
        m[0, 0] * (m[1, 1] * m[2, 2] - m[1, 2] * m[2, 1])
        - m[0, 1] * (m[1, 0] * m[2, 2] - m[1, 2] * m[2, 0])
        + m[0, 2] * (m[1, 0] * m[2, 1] - m[1, 1] * m[2, 0])
    )
    if not det > 0.0:
        defect = math.inf
    out[7] = defect
