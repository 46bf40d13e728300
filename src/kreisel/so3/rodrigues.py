"""Classical Rodrigues (Gibbs) vectors and modified Rodrigues parameters (MRPs).

Gibbs vector ``g = n tan(ψ/2) = q_v / q0`` (infinite at ψ = π); MRPs
``p = n tan(ψ/4) = q_v / (1 + q0)``, taken with q0 >= 0 so that |p| <= 1
(the "shadow" set ``-p/|p|²`` describes the same rotation). Both are
stereographic-type projections of the unit quaternion (Theory §A:
other parameters describing rigid-body motion).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.gufunc import quaternion_array, vector_array
from .._compiled.outputs import deliver, takes_out
from .._norms import norm, unit

__all__ = ["quat_to_gibbs", "gibbs_to_quat", "quat_to_mrp", "mrp_to_quat"]


def _canonical_unit(q: ArrayLike) -> NDArray[np.float64]:
    q = quaternion_array(q, "q")
    q = unit(q, "q")
    return np.where(q[..., :1] < 0.0, -q, q)


@takes_out
def quat_to_gibbs(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Gibbs vector ``g = n tan(ψ/2)``; refuses ψ = π (q0 = 0) where it is infinite.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(quat_to_gibbs([np.cos(np.pi / 8), 0, 0, np.sin(np.pi / 8)]), 12)   # 90° about z
    array([0.        , 0.        , 0.41421356])
    """
    q = _canonical_unit(q)
    if np.any(q[..., 0] == 0.0):
        raise ValueError("q must not be a half-turn (ψ = π): its Gibbs vector is infinite")
    return deliver(q[..., 1:] / q[..., :1], out)


@takes_out
def gibbs_to_quat(g: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Unit quaternion ``(1, g)/sqrt(1 + |g|²)`` of Gibbs vectors.

    Parameters
    ----------
    g : array_like, shape (..., 3)
        Gibbs vectors ``n tan(ψ/2)``, any length.

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternions with q0 > 0.

    Examples
    --------
    >>> gibbs_to_quat([0.0, 0.0, 1.0])
    array([0.70710678, 0.        , 0.        , 0.70710678])
    """
    g = vector_array(g, "g")
    return deliver(unit(np.concatenate([np.ones(g.shape[:-1] + (1,)), g], axis=-1), "g"), out)


@takes_out
def quat_to_mrp(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Modified Rodrigues parameters ``p = n tan(ψ/4)`` with |p| <= 1.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(quat_to_mrp([0.0, 1.0, 0.0, 0.0]), 12)   # half-turn about x
    array([1., 0., 0.])
    """
    q = _canonical_unit(q)
    return deliver(q[..., 1:] / (1.0 + q[..., :1]), out)


@takes_out
def mrp_to_quat(p: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Unit quaternion ``((1 - |p|²), 2p)/(1 + |p|²)`` of MRPs (any length, shadow set included).

    Parameters
    ----------
    p : array_like, shape (..., 3)
        Modified Rodrigues parameters ``n tan(ψ/4)``.

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternions; a shadow-set |p| > 1 gives the same rotation.

    Examples
    --------
    >>> mrp_to_quat([1.0, 0.0, 0.0])
    array([0., 1., 0., 0.])
    """
    p = vector_array(p, "p")
    # |p| > 1 goes through its shadow -p/|p|² (the same rotation, q -> -q): |p|² never overflows
    length = norm(p, keepdims=True)
    shadow = length > 1.0
    p = np.where(shadow, -(p / np.where(shadow, length, 1.0)) / np.where(shadow, length, 1.0), p)
    p2 = np.sum(p * p, axis=-1, keepdims=True)
    q = np.concatenate([1.0 - p2, 2.0 * p], axis=-1) / (1.0 + p2)
    return deliver(np.where(shadow, -q, q), out)
