"""Rotation matrices (direction cosine matrices, Theory §1 and §2.1) and quaternions.

``R`` maps body components to space components, ``a = R a′``; ``RᵀR = 1`` and
``det R = 1`` (Theory §2.1 (1)–(2)).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import kernels
from .._compiled.checks import MATRIX, QUATERNION, finite_array
from .._compiled.elementwise import Input, elementwise
from .._compiled.outputs import deliver, takes_out
from .._norms import nearest_rotation

__all__ = ["quat_to_matrix", "matrix_to_quat", "orthonormalize"]


@elementwise(kernels.quat_matrix, [Input("q", (4,), QUATERNION)], (3, 3))
def quat_to_matrix(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Rotation matrix ``R(q)`` exactly as in Theory §2.4, for nonzero quaternions.

    ``q`` is scaled to unit norm implicitly (``R(q) = R(q/|q|)``), and
    ``R(q) = R(-q)``.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Scalar-first quaternions.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        R(q/|q|), orthogonal to rounding.

    Examples
    --------
    >>> import numpy as np
    >>> R = quat_to_matrix([np.cos(np.pi / 4), 0.0, 0.0, np.sin(np.pi / 4)])
    >>> np.round(R, 12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """


@elementwise(kernels.matrix_entries_quat, [Input("R", (3, 3), MATRIX)], (4,))
def matrix_to_quat(R: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Unit quaternion with ``q0 >= 0`` of each rotation matrix.

    Shepperd's method (largest of q0², q1², q2², q3² taken from the diagonal):
    full precision at every angle, including ψ → π. Nearly orthogonal input
    (defect up to 1e-6) is projected onto SO(3) first; det <= 0 or larger
    defects raise ``ValueError``.

    Parameters
    ----------
    R : array_like, shape (..., 3, 3)
        Rotation matrices (nearly orthogonal ones are projected first).

    Returns
    -------
    ndarray, shape (..., 4)
        Unit quaternions, scalar first, q0 >= 0.

    Examples
    --------
    >>> matrix_to_quat([[-1.0, 0, 0], [0, -1.0, 0], [0, 0, 1.0]])    # π about z
    array([0., 0., 0., 1.])
    """


@takes_out
def orthonormalize(R: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Nearest rotation matrix (in the Frobenius norm) to each 3×3 matrix.

    Uses the SVD ``R = U S Vᵀ`` and returns ``U diag(1, 1, ±1) Vᵀ`` with the
    sign making the determinant +1 — the re-orthonormalisation a DCM needs
    after accumulating rounding errors (Theory §2.4 (2) ②).

    Parameters
    ----------
    R : array_like, shape (..., 3, 3)
        Finite matrices of full rank.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        The rotation matrix nearest to each input.

    Examples
    --------
    >>> import numpy as np
    >>> R = orthonormalize([[1.0, 1e-3, 0], [0, 1.0, 0], [0, 0, 1.0]])
    >>> bool(np.allclose(R @ R.T, np.eye(3), atol=1e-15))
    True
    """
    M = finite_array(R, "R", (3, 3))
    if M.size and np.min(np.linalg.svd(M, compute_uv=False)) <= 1e-12 * np.max(np.abs(M)):
        raise ValueError("R must have full rank (a singular matrix has no unique nearest rotation)")
    return deliver(nearest_rotation(M), out)
