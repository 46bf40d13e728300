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

from .._compiled import kernels
from .._compiled.checks import GIBBS_QUATERNION, QUATERNION, VECTOR
from .._compiled.elementwise import Input, elementwise, kernel

__all__ = ["quat_to_gibbs", "gibbs_to_quat", "quat_to_mrp", "mrp_to_quat"]


@kernel
def _gibbs(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float]:
    # q_v / q0 does not depend on the scale or sign of q
    return q1 / q0, q2 / q0, q3 / q0


@kernel
def _gibbs_quat(x: float, y: float, z: float) -> tuple[float, float, float, float]:
    return kernels.quat_unit(1.0, x, y, z)


@kernel
def _mrp(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float]:
    q0, q1, q2, q3 = kernels.quat_unit(q0, q1, q2, q3)
    if q0 < 0.0:
        q0, q1, q2, q3 = -q0, -q1, -q2, -q3
    d = 1.0 + q0
    return q1 / d, q2 / d, q3 / d


@kernel
def _mrp_quat(x: float, y: float, z: float) -> tuple[float, float, float, float]:
    # |p| > 1 goes through its shadow -p/|p|² (the same rotation, q -> -q): |p|² never overflows
    length = kernels.norm3(x, y, z)
    sign = 1.0
    if length > 1.0:
        x, y, z = -(x / length) / length, -(y / length) / length, -(z / length) / length
        sign = -1.0
    p2 = x * x + y * y + z * z
    d = 1.0 + p2
    return sign * ((1.0 - p2) / d), sign * (2.0 * x / d), sign * (2.0 * y / d), sign * (2.0 * z / d)


@elementwise(_gibbs, [Input("q", (4,), GIBBS_QUATERNION)], (3,))
def quat_to_gibbs(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Gibbs vector ``g = n tan(ψ/2)``; refuses ψ = π (q0 = 0) where it is infinite.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(quat_to_gibbs([np.cos(np.pi / 8), 0, 0, np.sin(np.pi / 8)]), 12)   # 90° about z
    array([0.        , 0.        , 0.41421356])
    """


@elementwise(_gibbs_quat, [Input("g", (3,), VECTOR)], (4,))
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


@elementwise(_mrp, [Input("q", (4,), QUATERNION)], (3,))
def quat_to_mrp(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Modified Rodrigues parameters ``p = n tan(ψ/4)`` with |p| <= 1.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(quat_to_mrp([0.0, 1.0, 0.0, 0.0]), 12)   # half-turn about x
    array([1., 0., 0.])
    """


@elementwise(_mrp_quat, [Input("p", (3,), VECTOR)], (4,))
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
