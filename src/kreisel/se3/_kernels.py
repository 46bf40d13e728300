"""Compiled per-pose kernels of :mod:`kreisel.se3`, broadcast as lazy gufuncs.

A pose is stored as a unit quaternion ``q`` (scalar first) and a translation
``t``: the displacement ``r -> R(q) r + t`` of Theory §1.3. Everything here
works on one pose and is broadcast by :func:`numba.guvectorize`; the scalar
quaternion algebra comes from :mod:`kreisel._compiled.kernels`.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numba import prange
from numpy.typing import ArrayLike, NDArray

from .._compiled import cached, kernels, parallel
from .._compiled import gufunc as _gufunc
from .._compiled.gufunc import LazyGufunc, checked_in_one_pass, finite3, finite_array, gufunc
from .._compiled.gufunc import loop_rows, piece_results, pieces, refuse_nonfinite, union

from .._validation import as_float_array

_F8 = "f8[:]"


def _signature(n_arrays: int) -> list[str]:
    return ["void(" + ", ".join([_F8] * n_arrays) + ")"]


def split(pose: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Views ``(q, t)`` of packed poses ``(..., 7)``."""
    return pose[..., :4], pose[..., 4:]


@parallel
def _compose_parallel(q1: NDArray[np.float64], t1: NDArray[np.float64], q2: NDArray[np.float64], t2: NDArray[np.float64],
                      q: NDArray[np.float64], t: NDArray[np.float64]) -> None:
    for i in prange(q1.shape[0]):
        a0, a1, a2, a3 = q1[i, 0], q1[i, 1], q1[i, 2], q1[i, 3]
        q[i, 0], q[i, 1], q[i, 2], q[i, 3] = kernels.quat_product(a0, a1, a2, a3, q2[i, 0], q2[i, 1], q2[i, 2], q2[i, 3])
        r0, r1, r2 = kernels.rotated(a0, a1, a2, a3, t2[i, 0], t2[i, 1], t2[i, 2])
        t[i, 0], t[i, 1], t[i, 2] = r0 + t1[i, 0], r1 + t1[i, 1], r2 + t1[i, 2]


@parallel
def _invert_parallel(q: NDArray[np.float64], t: NDArray[np.float64], q_out: NDArray[np.float64],
                     t_out: NDArray[np.float64]) -> None:
    for i in prange(q.shape[0]):
        q0, q1, q2, q3 = q[i, 0], q[i, 1], q[i, 2], q[i, 3]
        r0, r1, r2 = kernels.rotated(q0, -q1, -q2, -q3, t[i, 0], t[i, 1], t[i, 2])
        q_out[i, 0], q_out[i, 1], q_out[i, 2], q_out[i, 3] = q0, -q1, -q2, -q3
        t_out[i, 0], t_out[i, 1], t_out[i, 2] = -r0, -r1, -r2


def _poses(loop: Callable[..., None], small: LazyGufunc,
           inputs: tuple[NDArray[np.float64], ...]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(q, t)`` of a large batch from ``loop(*inputs, q, t)`` on all cores, else :func:`split` of ``small(*inputs)``.

    Separate C-ordered q and t, not views of one packed result: the next
    multi-core loop on them would have to copy strided views first.
    """
    batch = inputs[0].shape[:-1]
    n = math.prod(batch)
    if n < _gufunc.PARALLEL_THRESHOLD or any(a.shape[:-1] != batch for a in inputs):
        return split(small(*inputs))
    q, t = np.empty((*batch, 4)), np.empty((*batch, 3))
    loop(*(loop_rows(a) for a in inputs), q.reshape(n, 4), t.reshape(n, 3))
    return q, t


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
    return _poses(_compose_parallel, _compose, (q1, t1, q2, t2))


def invert(q: NDArray[np.float64], t: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(q, t)⁻¹ = (q*, -R(q)ᵀ t)."""
    return _poses(_invert_parallel, _invert, (q, t))


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


@cached
def _moved_rows(q: NDArray[np.float64], t: NDArray[np.float64], p: NDArray[np.float64], out: NDArray[np.float64],
                inverse: bool, start: int, stop: int) -> bool:
    # apply (or apply_inverse) of rows start..stop-1, and whether their points
    # are finite. q and t (or p) hold a row per result or one row (one pose,
    # or one point). A non-finite point makes its result non-finite (the pose
    # is finite), so only a non-finite result sends the loop back to its point.
    last_pose, last_point = q.shape[0] - 1, p.shape[0] - 1
    finite = True
    for i in range(start, stop):
        k, j = min(i, last_pose), min(i, last_point)
        q0, q1, q2, q3 = q[k, 0], q[k, 1], q[k, 2], q[k, 3]
        x, y, z = p[j, 0], p[j, 1], p[j, 2]
        if inverse:
            r0, r1, r2 = kernels.rotated(q0, -q1, -q2, -q3, x - t[k, 0], y - t[k, 1], z - t[k, 2])
        else:
            r0, r1, r2 = kernels.rotated(q0, q1, q2, q3, x, y, z)
            r0, r1, r2 = r0 + t[k, 0], r1 + t[k, 1], r2 + t[k, 2]
        out[i, 0], out[i, 1], out[i, 2] = r0, r1, r2
        if not finite3(r0, r1, r2):
            finite &= finite3(x, y, z)
    return finite


@parallel
def _move_checked(q: NDArray[np.float64], t: NDArray[np.float64], p: NDArray[np.float64], out: NDArray[np.float64],
                  chunk: int, inverse: bool) -> bool:
    n = out.shape[0]
    return piece_results(_moved_rows, (q, t, p, out, inverse), n, chunk, np.empty(pieces(n, chunk), np.bool_)).all()


def move(q: NDArray[np.float64], t: NDArray[np.float64], points: ArrayLike, inverse: bool,
         out: NDArray[np.float64] | None, name: str) -> NDArray[np.float64]:
    """:func:`apply` (or :func:`apply_inverse`) of checked poses to points named ``name`` (checked here).

    A large new result (batches of poses and points alike, or one pose and
    many points) is computed on all cores in the pass that checks the points.
    """
    p = as_float_array(points, name, (3,), finite=False)
    fused = checked_in_one_pass((q, t, p), ((3,),), _move_checked, inverse, single=True) if out is None else None
    if fused is not None:
        (moved,), finite = fused
        refuse_nonfinite(bool(finite), name)
        return moved
    return (apply_inverse if inverse else apply)(q, t, finite_array(p, name), out=out)


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


@cached
def _column_products(a0: float, a1: float, a2: float, b0: float, b1: float, b2: float) -> float:
    return a0 * b0 + a1 * b1 + a2 * b2


@cached
def _rigidity_defect(r00: float, r01: float, r02: float, r10: float, r11: float, r12: float, r20: float, r21: float,
                     r22: float, m30: float, m31: float, m32: float, m33: float) -> float:
    """The largest of |bottom row - (0, 0, 0, 1)| and |RᵀR - 1| of a homogeneous matrix; inf when det R <= 0."""
    defect = max(abs(m33 - 1.0), abs(m30))
    defect = max(defect, abs(_column_products(r00, r10, r20, r00, r10, r20) - 1.0))
    defect = max(defect, abs(_column_products(r00, r10, r20, r01, r11, r21)))
    defect = max(defect, abs(_column_products(r00, r10, r20, r02, r12, r22)))
    defect = max(defect, abs(m31))
    defect = max(defect, abs(_column_products(r01, r11, r21, r01, r11, r21) - 1.0))
    defect = max(defect, abs(_column_products(r01, r11, r21, r02, r12, r22)))
    defect = max(defect, abs(m32))
    defect = max(defect, abs(_column_products(r02, r12, r22, r02, r12, r22) - 1.0))
    det = r00 * (r11 * r22 - r12 * r21) - r01 * (r10 * r22 - r12 * r20) + r02 * (r10 * r21 - r11 * r20)
    return defect if det > 0.0 else math.inf


@gufunc(["void(f8[:, :], f8[:], f8[:])"], "(4,4),(8)->(8)")
def from_matrix(m: NDArray[np.float64], carrier: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    """Packed [q, t, defect] of a homogeneous matrix (:func:`_rigidity_defect`).

    One pass both converts and lets the caller refuse non-rigid matrices.
    """
    out[0], out[1], out[2], out[3] = kernels.matrix_quat(m)
    out[4], out[5], out[6] = m[0, 3], m[1, 3], m[2, 3]
    out[7] = _rigidity_defect(m[0, 0], m[0, 1], m[0, 2], m[1, 0], m[1, 1], m[1, 2], m[2, 0], m[2, 1], m[2, 2],
                              m[3, 0], m[3, 1], m[3, 2], m[3, 3])


@cached
def _poses_rows(m: NDArray[np.float64], q: NDArray[np.float64], t: NDArray[np.float64], tolerance: float, start: int,
                stop: int) -> int:
    # q and t of the homogeneous matrices (rows of 16 entries) start..stop-1
    # that are finite, and their refusal flags (1: a matrix is not finite, 2: a
    # finite one is not rigid within tolerance).
    flags = 0
    for i in range(start, stop):
        finite = True
        for k in range(16):
            finite &= math.isfinite(m[i, k])
        if not finite:
            flags |= 1
            continue
        r00, r01, r02, r10, r11, r12 = m[i, 0], m[i, 1], m[i, 2], m[i, 4], m[i, 5], m[i, 6]
        r20, r21, r22 = m[i, 8], m[i, 9], m[i, 10]
        q[i, 0], q[i, 1], q[i, 2], q[i, 3] = kernels.matrix_entries_quat(r00, r01, r02, r10, r11, r12, r20, r21, r22)
        t[i, 0], t[i, 1], t[i, 2] = m[i, 3], m[i, 7], m[i, 11]
        defect = _rigidity_defect(r00, r01, r02, r10, r11, r12, r20, r21, r22, m[i, 12], m[i, 13], m[i, 14], m[i, 15])
        if not defect <= tolerance:
            flags |= 2
    return flags


@parallel
def _poses_checked(m: NDArray[np.float64], q: NDArray[np.float64], t: NDArray[np.float64], chunk: int,
                   tolerance: float) -> int:
    n = m.shape[0]
    return union(piece_results(_poses_rows, (m, q, t, tolerance), n, chunk, np.empty(pieces(n, chunk), np.int64)))


def poses_of_matrices(matrix: ArrayLike, tolerance: float) -> tuple[NDArray[np.float64], NDArray[np.float64], bool]:
    """``(q, t, rigid)`` of homogeneous matrices ``(..., 4, 4)`` named ``matrix`` (refused here if not finite).

    ``rigid``: every matrix is within ``tolerance`` of a pose (:func:`_rigidity_defect`).
    A large batch is converted on all cores in the pass that checks it.
    """
    a = as_float_array(matrix, "matrix", (4, 4), finite=False)
    fused = checked_in_one_pass((a.reshape(*a.shape[:-2], 16),), ((4,), (3,)), _poses_checked, tolerance)
    if fused is not None:
        (q, t), flags = fused
        refuse_nonfinite(not flags & 1, "matrix")
        return q, t, not flags & 2
    packed = from_matrix(finite_array(a, "matrix", (4, 4)))
    return packed[..., :4], packed[..., 4:7], not (packed.size and not np.max(packed[..., 7]) <= tolerance)
