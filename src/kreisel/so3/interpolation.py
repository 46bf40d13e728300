"""Interpolation and averaging of rotations: slerp and the chordal mean.

Both work on quaternions and respect the double cover: slerp takes the
shorter arc (``q`` and ``-q`` are the same rotation) and the mean is
sign-independent.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import kernels
from .._compiled.checks import QUATERNION, VECTOR, finite_array, quaternion_array
from .._compiled.elementwise import Input, declare, kernel, uses
from .._compiled.outputs import deliver, takes_out
from .._norms import unit
from .._validation import as_float_array
from .quaternion import check_angle_multiple, quat_conjugate, quat_multiply

__all__ = ["quat_slerp", "quat_mean"]


@kernel
def _slerp(p0: float, p1: float, p2: float, p3: float, q0: float, q1: float, q2: float, q3: float,
           t: float) -> tuple[float, float, float, float]:
    # p exp(t log(p* q)) of the unit p and q, the shorter arc; |t| times its angle is at most 1e8 rad, as
    # quat_slerp checks
    p0, p1, p2, p3 = kernels.quat_unit(p0, p1, p2, p3)
    q0, q1, q2, q3 = kernels.quat_unit(q0, q1, q2, q3)
    r0, r1, r2, r3 = kernels.quat_product(p0, -p1, -p2, -p3, q0, q1, q2, q3)
    x, y, z = kernels.quat_rotvec(r0, r1, r2, r3)
    s0, s1, s2, s3 = kernels.rotvec_quat_in_range(t * x, t * y, t * z)
    return kernels.quat_product(p0, p1, p2, p3, s0, s1, s2, s3)


_slerps = declare(_slerp, [Input("p", (4,), QUATERNION), Input("q", (4,), QUATERNION), Input("t", (), VECTOR)], (4,),
                  name="quat_slerp")


@uses(_slerps)
@takes_out
def quat_slerp(p: ArrayLike, q: ArrayLike, t: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Spherical linear interpolation from rotation ``p`` (t = 0) to ``q`` (t = 1).

    ``p exp(t log(p⁻¹ q))`` along the shorter great arc, at constant angular
    rate; ``t`` outside [0, 1] extrapolates. Inputs are normalised.

    Parameters
    ----------
    p, q : array_like, shape (..., 4)
    t : array_like, shape (...)
        Broadcast with the leading axes of ``p`` and ``q``; ``|t|`` times
        the angle from ``p`` to ``q`` must be at most 1e8 rad (see
        :func:`~kreisel.so3.rotvec_to_quat`).

    Examples
    --------
    >>> import numpy as np
    >>> q = quat_slerp([1.0, 0, 0, 0], [0.0, 0, 0, 1.0], 0.5)      # halfway to 180° about z
    >>> np.round(q, 12)
    array([0.70710678, 0.        , 0.        , 0.70710678])
    """
    t = as_float_array(t, "t", (), finite=False)
    if np.isfinite(t).all():
        check_angle_multiple(t, lambda: quat_multiply(quat_conjugate(unit(quaternion_array(p, "p"), "p")),
                                                      unit(quaternion_array(q, "q"), "q")),
                             "t", "|t| times the angle from p to q")
    return _slerps(p, q, t, out=out)


@takes_out
def quat_mean(q: ArrayLike, weights: ArrayLike | None = None, axis: int = -2, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Chordal L2 mean of rotations (Markley et al. 2007), sign-independent.

    The rotation minimising ``Σ w_i ‖R - R_i‖_F²`` is the eigenvector of
    ``M = Σ w_i q_i q_iᵀ`` with the largest eigenvalue.

    Parameters
    ----------
    q : array_like, shape (..., n, 4)
        Nonzero quaternions (normalised here); averaged along ``axis``.
    weights : array_like, shape (..., n), optional
        Non-negative weights, not all zero.
    axis : int
        Axis of ``q`` holding the samples (not the last one).

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternions with q0 >= 0.

    Examples
    --------
    >>> import numpy as np
    >>> a = 0.1
    >>> qs = [[np.cos(a), 0, 0, np.sin(a)], [np.cos(a), 0, 0, -np.sin(a)]]
    >>> quat_mean(qs)
    array([1., 0., 0., 0.])
    """
    q = quaternion_array(q, "q")
    if q.ndim < 2:
        raise ValueError(f"q must have shape (..., n, 4) with a sample axis, got {q.shape}")
    if isinstance(axis, bool) or not isinstance(axis, (int, np.integer)):
        raise TypeError(f"axis must be an integer, got {type(axis).__name__}")
    if not -q.ndim <= axis < q.ndim:
        raise ValueError(f"axis {axis} is out of range for q of shape {q.shape}")
    if axis % q.ndim == q.ndim - 1:
        raise ValueError("axis must be a sample axis of q, not the last one (which holds the 4 components)")
    q = np.moveaxis(q, axis, -2)
    if q.shape[-2] == 0:
        raise ValueError("q must hold at least one rotation along axis: the mean of an empty set is undefined")
    q = unit(q, "q")
    if weights is None:
        w = np.ones(q.shape[:-1])
    else:
        w = finite_array(weights, "weights", None)
        if np.any(w < 0) or np.any(np.sum(np.broadcast_to(w, q.shape[:-1]), axis=-1) <= 0):
            raise ValueError("weights must be non-negative and not all zero")
    M = np.einsum("...n,...ni,...nj->...ij", np.broadcast_to(w, q.shape[:-1]), q, q)
    _, vectors = np.linalg.eigh(M)
    mean = vectors[..., :, -1]
    return deliver(np.where(mean[..., :1] < 0.0, -mean, mean), out)


def sample_axes(batch_shape: tuple[int, ...], axis: int | tuple[int, ...] | None) -> tuple[int, ...]:
    """Normalised, sorted batch axes to average over (scipy's ``axis``: None = all)."""
    nd = len(batch_shape)
    if axis is None:
        return tuple(range(nd))
    axes = (axis,) if isinstance(axis, (int, np.integer)) else axis
    if not isinstance(axes, tuple) or not all(isinstance(a, (int, np.integer)) for a in axes):
        raise ValueError(f"axis must be None, an int or a tuple of ints, got {axis!r}")
    if any(not -nd <= a < nd for a in axes):
        raise ValueError(f"axis {axis} is out of bounds for batch shape {tuple(batch_shape)}")
    return tuple(sorted({int(a) % nd for a in axes}))


def gather_samples(x: NDArray[np.float64], batch_nd: int, axes: tuple[int, ...]) -> NDArray[np.float64]:
    """``x`` of shape ``(*batch, *tail)`` as ``(*kept batch, samples, *tail)``, the ``axes`` merged into one."""
    keep = [i for i in range(batch_nd) if i not in axes]
    tail = list(range(batch_nd, x.ndim))
    moved = np.transpose(x, keep + list(axes) + tail)
    return moved.reshape(*[x.shape[i] for i in keep], -1, *x.shape[batch_nd:])


def mean_over(q: NDArray[np.float64], weights: ArrayLike | None, axis: int | tuple[int, ...] | None) -> tuple[NDArray[np.float64], tuple[int, ...]]:
    """Chordal mean of unit quaternions ``(*batch, 4)`` over the batch ``axis`` (None: all axes).

    ``weights`` has the batch shape; returns the quaternions and the normalised axes.
    """
    axes = sample_axes(q.shape[:-1], axis)
    if weights is not None:
        weights = finite_array(weights, "weights", None)
        if weights.shape != q.shape[:-1]:
            raise ValueError(f"weights must have the batch shape {q.shape[:-1]}, got {weights.shape}")
        weights = gather_samples(weights, weights.ndim, axes)
    samples = gather_samples(q, q.ndim - 1, axes)
    if samples.shape[-2] == 0:
        raise ValueError("the mean of an empty set of rotations is undefined")
    return quat_mean(samples, weights, axis=-2), axes
