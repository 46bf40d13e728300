"""SU(2), Cayley–Klein parameters and Goldstein's Euler parameters (Theory §A).

The homomorphism SU(2) → SO(3) (Theory §A (1)): ``u(ψ) = exp(-i σ·ψ/2)``
acts by ``u (r·σ) u⁻¹ = (R(u) r)·σ``, and ``i_j <-> -i σ_j`` identifies it
with the unit quaternions (appendix (4)):

    u = [[a, b], [-b*, a*]],  a = q0 - i q3,  b = -q2 - i q1.

``q`` and ``u`` are in one-to-one correspondence (``-q <-> -u``), so these
conversions keep the sign: both are double covers of SO(3).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import kernels
from .._compiled.checks import QUATERNION, SU2, SU2_TOLERANCE
from .._compiled.elementwise import Input, declare, elementwise, kernel, uses
from .._compiled.outputs import deliver, takes_out
from .._validation import as_float_array

__all__ = [
    "quat_to_su2",
    "su2_to_quat",
    "quat_to_cayley_klein",
    "cayley_klein_to_quat",
    "quat_to_euler_parameters",
    "euler_parameters_to_quat",
    "euler_parameters_to_matrix",
]


@kernel
def _su2(q0: float, q1: float, q2: float, q3: float) -> tuple[float, ...]:
    # u = [[a, b], [-b*, a*]] of the unit q, a = q0 - i q3, b = -q2 - i q1, as real and imaginary parts
    q0, q1, q2, q3 = kernels.quat_unit(q0, q1, q2, q3)
    return q0, -q3, -q2, -q1, q2, -q1, q0, q3


@kernel
def _su2_quat(r00: float, i00: float, r01: float, i01: float, r10: float, i10: float, r11: float,
              i11: float) -> tuple[float, float, float, float]:
    # a and b averaged over their two copies, then q = (Re a, -Im b, -Re b, -Im a) normalised
    a_re, a_im = 0.5 * (r00 + r11), 0.5 * (i00 - i11)
    b_re, b_im = 0.5 * (r01 - r10), 0.5 * (i01 + i10)
    return kernels.quat_unit(a_re, -b_im, -b_re, -a_im)


@kernel
def _conjugate_unit(q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float, float]:
    q0, q1, q2, q3 = kernels.quat_unit(q0, q1, q2, q3)
    return q0, -q1, -q2, -q3


@kernel
def _transposed_matrix(e0: float, e1: float, e2: float, e3: float) -> tuple[float, ...]:
    # the printed matrix of e is R(e*) = R(e)ᵀ
    return kernels.quat_matrix(e0, -e1, -e2, -e3)


_ROTATION = Input("q", (4,), QUATERNION)
_su2_matrices = declare(_su2, [_ROTATION], (2, 2, 2), name="quat_to_su2")
_su2_quats = declare(_su2_quat, [Input("u", (2, 2, 2), SU2)], (4,), name="su2_to_quat")
_euler_parameters = declare(_conjugate_unit, [_ROTATION], (4,), name="quat_to_euler_parameters")


def _complex_array(x: ArrayLike, name: str, tail: tuple[int, ...]) -> NDArray[np.complex128]:
    try:
        a = np.asarray(x, dtype=np.complex128)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a complex numeric array, got {type(x).__name__}") from exc
    as_float_array(np.zeros(a.shape), name, tail, finite=False)  # shape check with the shared message
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite (no NaN or inf)")
    return a


def _parts(u: NDArray[np.complex128]) -> NDArray[np.float64]:
    """The real and imaginary parts of ``u`` along a new last axis (a view where ``u`` is C-ordered)."""
    u = np.ascontiguousarray(u)
    return u.view(np.float64).reshape(*u.shape, 2)


@uses(_su2_matrices)
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
    return deliver(_su2_matrices(q).view(np.complex128)[..., 0], out)


@uses(_su2_quats)
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
    return _su2_quats(_parts(_complex_array(u, "u", (2, 2))), out=out)


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


@uses(_su2_quats)
@takes_out
def cayley_klein_to_quat(ck: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Quaternion from Cayley–Klein parameters ``(α, β, γ, δ)`` (inverse of :func:`quat_to_cayley_klein`).

    Examples
    --------
    >>> cayley_klein_to_quat([1.0, 0.0, 0.0, 1.0])
    array([ 1., -0., -0., -0.])
    """
    ck = _complex_array(ck, "ck", (4,))
    return _su2_quats.renamed(u="ck")(_parts(ck.reshape(ck.shape[:-1] + (2, 2))), out=out)


@uses(_euler_parameters)
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
    return _euler_parameters(q, out=out)


@uses(_euler_parameters)
@takes_out
def euler_parameters_to_quat(e: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse of :func:`quat_to_euler_parameters`: ``q = e*``.

    Examples
    --------
    >>> euler_parameters_to_quat([0.0, 0.0, 0.0, -1.0])
    array([ 0., -0., -0.,  1.])
    """
    return _euler_parameters.renamed(q="e")(e, out=out)


@elementwise(_transposed_matrix, [Input("e", (4,), QUATERNION)], (3, 3))
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
