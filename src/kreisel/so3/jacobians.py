"""The Jacobians of SO(3): the differential of the exponential map and its inverse (Theory §3.4–5).

With ``R = exp(ψ·X)`` (:func:`~kreisel.so3.rotvec_to_matrix`),

    J_l(ψ) = (e^{ψ·X} − 1)/(ψ·X) = 1 + A hat(ψ) + B hat(ψ)²,    J_r(ψ) = J_l(−ψ) = J_l(ψ)ᵀ,

``A = (1 − cos ψ)/ψ²``, ``B = (ψ − sin ψ)/ψ³``: ``exp(ψ + δ) ≈ exp(J_l δ) exp(ψ)
≈ exp(ψ) exp(J_r δ)``, and ``ω = J_l ψ̇``, ``ω′ = J_r ψ̇``
(:mod:`kreisel.kinematics` has these rate maps). The inverses are

    J_l⁻¹ = 1 − ½ hat(ψ) + f hat(ψ)²,    J_r⁻¹ = 1 + ½ hat(ψ) + f hat(ψ)²,

``f = (1 − (ψ/2) cot(ψ/2))/ψ²`` the Bortz coefficient, with poles at
|ψ| = 2π, 4π, … where the entries are NaN and a
:class:`~kreisel.kinematics.RotationVectorSingularityWarning` is issued.
Rotation vectors longer than ``ROTVEC_RANGE`` (1e8 rad, the limit of every
rotation computed from a rotation vector's length) are refused by the
inverses: their entries depend on |ψ| mod 2π, which the rounding of so long
a vector's length no longer determines. Every coefficient is
summed from its series at small ψ, so the matrices are accurate to a few ulp.
The group, its exp/log and its Jacobians live together here, as in Sophus
and manif; the SE(3) Jacobians of :mod:`kreisel.se3` are built on these.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import dexp
from .._compiled.elementwise import uses
from .._compiled.outputs import takes_out
from .._validation import as_float_array, check_tolerance, refuse_long_angle, warn_if_any
from .._norms import norm
from .euler import KinematicSingularityWarning

__all__ = ["left_jacobian", "right_jacobian", "left_jacobian_inverse", "right_jacobian_inverse"]

#: Default singularity threshold on the determinant of a rate map (|sin β| or
#: |cos β| for Euler angles, |sin(ψ/2)| for rotation vectors). Away from it
#: the rates are returned with relative error ≲ 1e-16/|det|, i.e. at worst ~1e-8.
SINGULAR_TOL = 1e-8

_LEFT, _RIGHT = 1.0, -1.0


class RotationVectorSingularityWarning(KinematicSingularityWarning):
    """Rotation-vector rates requested at |ψ| = 2πk (k >= 1): those rates are NaN."""


def check_rotvec_range(angle: ArrayLike, name: str, what: str = "|psi|") -> None:
    """Refuse rotation vectors longer than ``ROTVEC_RANGE`` (1e8 rad) (``angle`` their lengths), naming ``name``."""
    refuse_long_angle(float(np.max(angle, initial=0.0)), name, what)


def singular_or_out_of_range(psi: NDArray[np.float64], values: NDArray[np.float64], category: type[Warning],
                             message: str, name: str = "psi") -> None:
    """Refuse the samples of ``psi`` beyond ``ROTVEC_RANGE`` (1e8 rad), else warn of the poles, where ``values`` is NaN."""
    undefined = np.isnan(values)
    if undefined.any():
        check_rotvec_range(norm(np.broadcast_to(psi, undefined.shape + (3,))[undefined]), name)
        warn_if_any(undefined, category, message)


def _inverse(psi: ArrayLike, sign: float, tol: float, out: NDArray[np.float64] | None) -> NDArray[np.float64]:
    vectors = as_float_array(psi, "psi", (3,), finite=False)
    out = dexp.jacobian_inverse_matrix(vectors, sign, check_tolerance(tol), out=out)
    singular_or_out_of_range(vectors, out[..., 0, 0], RotationVectorSingularityWarning,
                             "SO(3) Jacobian inverse at |psi| = 2*pi*k")
    return out


@uses(dexp.jacobian_matrix)
@takes_out
def left_jacobian(psi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Left Jacobian of SO(3), ``J_l(ψ) = (e^{ψ·X} − 1)/(ψ·X)`` (Theory §3.4).

    ``J_l = 1 + A hat(ψ) + B hat(ψ)²`` maps ψ̇ to the space angular velocity,
    ``ω = J_l(ψ) ψ̇``; also ``exp(ψ + δ) ≈ exp(J_l δ) exp(ψ)``.

    Parameters
    ----------
    psi : array_like, shape (..., 3)
        Rotation vectors ψ of any length.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        J_l(ψ).

    Examples
    --------
    >>> left_jacobian([0.0, 0.0, 0.0])
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    return dexp.jacobian_matrix(psi, _LEFT, out=out)


@uses(dexp.jacobian_matrix)
@takes_out
def right_jacobian(psi: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Right Jacobian of SO(3), ``J_r(ψ) = (1 − e^{−ψ·X})/(ψ·X) = J_l(−ψ) = J_l(ψ)ᵀ``.

    Maps ψ̇ to the body angular velocity, ``ω′ = J_r(ψ) ψ̇`` (Theory §3.4).

    Parameters
    ----------
    psi : array_like, shape (..., 3)
        Rotation vectors; ``J_r(ψ) = J_l(−ψ)``.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        J_r(ψ) = J_l(ψ)ᵀ.

    Examples
    --------
    >>> np.allclose(right_jacobian([0.1, 0.2, 0.3]), left_jacobian([0.1, 0.2, 0.3]).T)
    True
    """
    return dexp.jacobian_matrix(psi, _RIGHT, out=out)


@uses(dexp.jacobian_inverse_matrix)
@takes_out
def left_jacobian_inverse(psi: ArrayLike, tol: float = SINGULAR_TOL, *,
                          out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse left Jacobian, ``J_l⁻¹ = 1 − ½ hat(ψ) + f hat(ψ)²``.

    ``ψ̇ = J_l⁻¹(ψ) ω`` (space components); ``f`` is the Bortz coefficient
    (:func:`kreisel.kinematics.bortz_coefficient`). Singular (NaN, with
    :class:`~kreisel.kinematics.RotationVectorSingularityWarning`) at |ψ| = 2πk.

    Parameters
    ----------
    psi : array_like, shape (..., 3)
    tol : float
        Samples with |ψ| > π and |sin(|ψ|/2)| <= tol are singular.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        J_l⁻¹(ψ); NaN at |ψ| = 2πk.

    Examples
    --------
    >>> psi = [0.3, -0.2, 0.5]
    >>> np.allclose(left_jacobian_inverse(psi) @ left_jacobian(psi), np.eye(3))
    True
    """
    return _inverse(psi, _LEFT, tol, out)


@uses(dexp.jacobian_inverse_matrix)
@takes_out
def right_jacobian_inverse(psi: ArrayLike, tol: float = SINGULAR_TOL, *,
                           out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Inverse right Jacobian, ``J_r⁻¹ = 1 + ½ hat(ψ) + f hat(ψ)²`` — the Bortz matrix (Theory §3.5).

    ``ψ̇ = J_r⁻¹(ψ) ω′`` (body components). Singular at |ψ| = 2πk.

    Parameters
    ----------
    psi : array_like, shape (..., 3)
    tol : float
        As in :func:`left_jacobian_inverse`.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        The Bortz matrix J_r⁻¹(ψ), NaN at the poles.

    Examples
    --------
    ``J_r⁻¹(ψ) = J_l⁻¹(−ψ)``:

    >>> np.allclose(right_jacobian_inverse([0.3, -0.2, 0.5]), left_jacobian_inverse([-0.3, 0.2, -0.5]))
    True
    """
    return _inverse(psi, _RIGHT, tol, out)
