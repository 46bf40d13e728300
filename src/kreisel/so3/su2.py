"""SU(2), Cayley–Klein parameters and Goldstein's Euler parameters (Theory §A).

The homomorphism SU(2) → SO(3) (Theory §A (1)): ``u(ψ) = exp(-i σ·ψ/2)``
acts by ``u (r·σ) u⁻¹ = (R(u) r)·σ``, and ``i_j <-> -i σ_j`` identifies it
with the unit quaternions (appendix (4)):

    u = [[a, b], [-b*, a*]],  a = q0 - i q3,  b = -q2 - i q1.

``q`` and ``u`` are in one-to-one correspondence (``-q <-> -u``), so these
conversions keep the sign: both are double covers of SO(3).
"""

from __future__ import annotations

from typing import cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.gufunc import quaternion_array
from .._compiled.outputs import deliver, takes_out
from .._validation import as_float_array
from .._norms import unit

__all__ = [
    "quat_to_su2",
    "su2_to_quat",
    "quat_to_cayley_klein",
    "cayley_klein_to_quat",
    "quat_to_euler_parameters",
    "euler_parameters_to_quat",
    "euler_parameters_to_matrix",
]

#: How far from unitary with unit determinant an SU(2) input may be.
SU2_TOLERANCE = 1e-6


def _unit(q: ArrayLike, name: str = "q") -> NDArray[np.float64]:
    return unit(quaternion_array(q, name), name)


def _complex_array(x: ArrayLike, name: str, tail: tuple[int, ...]) -> NDArray[np.complex128]:
    try:
        a = np.asarray(x, dtype=np.complex128)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a complex numeric array, got {type(x).__name__}") from exc
    as_float_array(np.zeros(a.shape), name, tail, finite=False)  # shape check with the shared message
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite (no NaN or inf)")
    return a


def _quat_from_ab(a: NDArray[np.complex128], b: NDArray[np.complex128], name: str) -> NDArray[np.float64]:
    q = np.stack([a.real, -b.imag, -b.real, -a.imag], axis=-1)
    norm = np.linalg.norm(q, axis=-1, keepdims=True)
    if q.size and np.max(np.abs(norm - 1.0)) > SU2_TOLERANCE:
        raise ValueError(f"{name} must be special unitary: |a|² + |b|² = 1 (within {SU2_TOLERANCE:g})")
    return cast("NDArray[np.float64]", q / norm)


@takes_out
def quat_to_su2(q: ArrayLike, *, out: NDArray[np.complex128] | None = None) -> NDArray[np.complex128]:
    """SU(2) matrix ``u = exp(-i σ·ψ/2)`` of each quaternion (Theory §A (1), (4)).

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Nonzero quaternions (normalised here).

    Returns
    -------
    ndarray of complex, shape (..., 2, 2)

    Examples
    --------
    >>> import numpy as np
    >>> np.round(quat_to_su2([np.cos(0.5), 0.0, 0.0, np.sin(0.5)]), 6) + 0.0   # ψ = 1 about z
    array([[0.877583-0.479426j, 0.      +0.j      ],
           [0.      +0.j      , 0.877583+0.479426j]])
    """
    q = _unit(q)
    a = q[..., 0] - 1j * q[..., 3]
    b = -q[..., 2] - 1j * q[..., 1]
    return deliver(np.stack([np.stack([a, b], axis=-1), np.stack([-b.conj(), a.conj()], axis=-1)], axis=-2), out)


@takes_out
def su2_to_quat(u: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Quaternion of each SU(2) matrix (inverse of :func:`quat_to_su2`, sign kept).

    ``u`` must be ``[[a, b], [-b*, a*]]`` with ``|a|² + |b|² = 1`` up to 1e-6;
    the two copies of ``a`` and ``b`` are averaged and the result normalised.

    Examples
    --------
    >>> su2_to_quat(np.array([[1j, 0], [0, -1j]])) + 0.0
    array([ 0.,  0.,  0., -1.])
    """
    u = _complex_array(u, "u", (2, 2))
    a = 0.5 * (u[..., 0, 0] + u[..., 1, 1].conj())
    b = 0.5 * (u[..., 0, 1] - u[..., 1, 0].conj())
    mismatch = np.maximum(np.abs(u[..., 0, 0] - u[..., 1, 1].conj()), np.abs(u[..., 0, 1] + u[..., 1, 0].conj()))
    if mismatch.size and np.max(mismatch) > SU2_TOLERANCE:
        raise ValueError("u must have the SU(2) form [[a, b], [-conj(b), conj(a)]]")
    return deliver(_quat_from_ab(a, b, "u"), out)


@takes_out
def quat_to_cayley_klein(q: ArrayLike, *, out: NDArray[np.complex128] | None = None) -> NDArray[np.complex128]:
    """Cayley–Klein parameters ``(α, β, γ, δ)`` = the entries of ``u`` (Theory §A (3)).

    ``u = [[α, β], [γ, δ]]`` with ``δ = α*``, ``γ = -β*``, ``αδ - βγ = 1``.

    Returns
    -------
    ndarray of complex, shape (..., 4)

    Examples
    --------
    >>> quat_to_cayley_klein([1.0, 0.0, 0.0, 0.0]) + 0.0
    array([1.+0.j, 0.+0.j, 0.+0.j, 1.+0.j])
    """
    u = quat_to_su2(q)
    return deliver(u.reshape(u.shape[:-2] + (4,)), out)


@takes_out
def cayley_klein_to_quat(ck: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Quaternion from Cayley–Klein parameters ``(α, β, γ, δ)`` (inverse of :func:`quat_to_cayley_klein`).

    Examples
    --------
    >>> cayley_klein_to_quat([1.0, 0.0, 0.0, 1.0])
    array([ 1., -0., -0., -0.])
    """
    ck = _complex_array(ck, "ck", (4,))
    return deliver(su2_to_quat(ck.reshape(ck.shape[:-1] + (2, 2))), out)


@takes_out
def quat_to_euler_parameters(q: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Euler parameters ``(e0, e1, e2, e3)`` as defined in the Theory §A (2).

    ``e0 = cos(ψ/2)``, ``e_j = -n_j sin(ψ/2)``, i.e. ``e = q*/|q|``. The
    printed matrix :func:`euler_parameters_to_matrix` of these parameters is
    the active ``R`` of the rotation (body → space).

    Convention note (passive): Goldstein (3rd ed., §4.5) writes the same
    printed matrix as the *passive* transformation ``A`` (space components →
    body components, ``A = Rᵀ``) with ``e = (cos(Φ/2), n sin(Φ/2))`` — that is
    ``e = q``. The two readings agree because ``A(q) = R(q)ᵀ = R(q*)``; pass
    ``q`` itself to :func:`euler_parameters_to_matrix` to get Goldstein's ``A``.

    Examples
    --------
    >>> quat_to_euler_parameters([0.0, 0.0, 0.0, 1.0])
    array([ 0., -0., -0., -1.])
    """
    e = _unit(q) * np.array([1.0, -1.0, -1.0, -1.0])
    return deliver(e, out)


@takes_out
def euler_parameters_to_quat(e: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse of :func:`quat_to_euler_parameters`: ``q = e*``.

    Examples
    --------
    >>> euler_parameters_to_quat([0.0, 0.0, 0.0, -1.0])
    array([ 0., -0., -0.,  1.])
    """
    return deliver(_unit(e, "e") * np.array([1.0, -1.0, -1.0, -1.0]), out)


@takes_out
def euler_parameters_to_matrix(e: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """The matrix printed in Theory §A (2) (Goldstein's ``A``) of Euler parameters.

    ``[[e0²+e1²-e2²-e3², 2(e1e2+e0e3), 2(e1e3-e0e2)], …]``. With the chapter's
    ``e = q*`` it is the active ``R(q)``; with Goldstein's ``e = q`` it is the
    passive ``A = R(q)ᵀ``. ``e`` is normalised first.

    Examples
    --------
    >>> import numpy as np
    >>> e = quat_to_euler_parameters([np.cos(0.3), 0.0, 0.0, np.sin(0.3)])
    >>> np.round(euler_parameters_to_matrix(e), 6)
    array([[ 0.825336, -0.564642,  0.      ],
           [ 0.564642,  0.825336,  0.      ],
           [ 0.      ,  0.      ,  1.      ]])
    """
    e0, e1, e2, e3 = np.moveaxis(_unit(e, "e"), -1, 0)
    matrix = np.stack(
        [
            np.stack([e0**2 + e1**2 - e2**2 - e3**2, 2 * (e1 * e2 + e0 * e3), 2 * (e1 * e3 - e0 * e2)], axis=-1),
            np.stack([2 * (e1 * e2 - e0 * e3), e0**2 - e1**2 + e2**2 - e3**2, 2 * (e2 * e3 + e0 * e1)], axis=-1),
            np.stack([2 * (e1 * e3 + e0 * e2), 2 * (e2 * e3 - e0 * e1), e0**2 - e1**2 - e2**2 + e3**2], axis=-1),
        ],
        axis=-2,
    )
    return deliver(matrix, out)
