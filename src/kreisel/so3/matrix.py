"""Rotation matrices (direction cosine matrices, Theory §1 and §2.1) and quaternions.

``R`` maps body components to space components, ``a = R a′``; ``RᵀR = 1`` and
``det R = 1`` (Theory §2.1 (1)–(2)).
"""

from __future__ import annotations

import numpy as np
from numba import prange
from numpy.typing import ArrayLike, NDArray

from .._compiled import kernels, parallel
from .._compiled.outputs import deliver, takes_out
from .._compiled.gufunc import finite_array, gufunc, matrix_array, quaternion_array
from .._norms import nearest_rotation

__all__ = ["quat_to_matrix", "matrix_to_quat", "orthonormalize"]


@parallel
def _quat_to_matrix_parallel(q: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    for i in prange(q.shape[0]):
        kernels.write_matrix_at(out, i, q[i, 0], q[i, 1], q[i, 2], q[i, 3])


@parallel
def _matrix_to_quat_parallel(R: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    for i in prange(R.shape[0]):
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = kernels.matrix_entries_quat(
            R[i, 0, 0], R[i, 0, 1], R[i, 0, 2], R[i, 1, 0], R[i, 1, 1], R[i, 1, 2], R[i, 2, 0], R[i, 2, 1], R[i, 2, 2]
        )


@gufunc(["void(f8[:], f8[:], f8[:, :])"], "(4),(3)->(3,3)", parallel=_quat_to_matrix_parallel)
def _quat_to_matrix(q: NDArray[np.float64], carrier3: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    kernels.write_matrix(q[0], q[1], q[2], q[3], out)


@gufunc(["void(f8[:, :], f8[:], f8[:])"], "(3,3),(4)->(4)", parallel=_matrix_to_quat_parallel)
def _matrix_to_quat(R: NDArray[np.float64], carrier4: NDArray[np.float64], out: NDArray[np.float64]) -> None:
    out[0], out[1], out[2], out[3] = kernels.matrix_quat(R)


@takes_out
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
    return _quat_to_matrix(quaternion_array(q, "q"), out=out)


@takes_out
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
    return _matrix_to_quat(matrix_array(R, "R"), out=out)


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
