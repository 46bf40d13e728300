"""Rotation-vector kinematics: the dexp map and the Bortz equation.

With ``R = exp(ψ·X)`` (Theory §3.4),

    ω  = ψ̇ + A ψ×ψ̇ + B ψ×(ψ×ψ̇)  = J_l(ψ) ψ̇      (space components)
    ω′ = ψ̇ − A ψ×ψ̇ + B ψ×(ψ×ψ̇)  = J_r(ψ) ψ̇      (body components)

with ``A = (1 − cos ψ)/ψ²``, ``B = (ψ − sin ψ)/ψ³``, and the inverses
(Theory §3.5; the body one is the Bortz equation)

    ψ̇ = ω′ + ½ ψ×ω′ + f ψ×(ψ×ω′) = J_r⁻¹ ω′,   ψ̇ = ω − ½ ψ×ω + f ψ×(ψ×ω) = J_l⁻¹ ω,

``f = (2 sin ψ − ψ(1 + cos ψ)) / (2ψ² sin ψ) = 1/12 + ψ²/720 + ψ⁴/30240 + …``.

The Jacobian matrices ``J_l``, ``J_r`` and their inverses are in
:mod:`kreisel.so3.jacobians` (next to exp/log; re-exported here).

Accuracy: every coefficient is evaluated without cancellation (series at
small ψ), so the maps are accurate to a few ulp for all ψ; J⁻¹ has poles at
|ψ| = 2π, 4π, … where the rates are NaN (:class:`RotationVectorSingularityWarning`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import dexp
from .._compiled.checks import VECTOR, vector_array
from .._compiled.elementwise import Input, declare, kernel, uses
from .._compiled.outputs import deliver, takes_out
from .._validation import check_tolerance, warn_if_any
from .._norms import norm
from ..so3.jacobians import left_jacobian, left_jacobian_inverse, right_jacobian, right_jacobian_inverse  # noqa: F401
from ..so3.jacobians import check_rotvec_range
from ._checks import frame_sign, vector_batch
from ._singularity import SINGULAR_TOL, RotationVectorSingularityWarning

__all__ = [
    "bortz_coefficient",
    "angular_velocity_from_rotvec_rate",
    "rotvec_rate",
    "rotvec_rate_singular",
]


@kernel
def _bortz(angle: float) -> float:
    return dexp.bortz_coefficient(abs(angle))


_bortz_coefficients = declare(_bortz, [Input("angle", (), VECTOR)], (), name="bortz_coefficient")
_rates_to_omega = dexp.apply_jacobian.renamed(v="psidot")
_omega_to_rates = dexp.apply_jacobian_inverse.renamed(w="omega")


@uses(_bortz_coefficients)
@takes_out
def bortz_coefficient(angle: ArrayLike, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64] | float:
    """The Bortz coefficient ``(2 sin ψ − ψ(1 + cos ψ)) / (2ψ² sin ψ)`` (Theory §3.5).

    Evaluated as ``(1 − (ψ/2) cot(ψ/2))/ψ²``, which is the same function
    without the removable singularity at ψ = π, and from its Maclaurin
    series ``1/12 + ψ²/720 + ψ⁴/30240 + ψ⁶/1209600 + …`` below ψ = 1, so it
    is accurate to a few ulp everywhere; it has poles at ψ = 2πk (k ≥ 1),
    where it returns ±inf or huge values — use :func:`rotvec_rate_singular`.

    Parameters
    ----------
    angle : array_like
        Rotation angle(s) ψ = |ψ| in radians (the function is even).

    Returns
    -------
    ndarray or float
        f(ψ); a float for scalar input.

    Examples
    --------
    >>> float(bortz_coefficient(0.0)) == 1 / 12
    True
    >>> round(float(bortz_coefficient(np.pi)), 15) == round(1 / np.pi**2, 15)
    True
    """
    value = _bortz_coefficients(angle, out=out)
    return value if value.ndim or out is not None else float(value)


@uses(_rates_to_omega)
@takes_out
def angular_velocity_from_rotvec_rate(psi: ArrayLike, psidot: ArrayLike, frame: str = "space", *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Angular velocity from a rotation vector and its rate, the dexp map (Theory §3.4).

    ``ω = ((e^{ψ·X} − 1)/(ψ·X)) ψ̇ = ψ̇ + A ψ×ψ̇ + B ψ×(ψ×ψ̇)`` (space),
    ``ω′ = ((1 − e^{−ψ·X})/(ψ·X)) ψ̇ = ψ̇ − A ψ×ψ̇ + B ψ×(ψ×ψ̇)`` (body), with
    ``A = (1 − cos ψ)/ψ²``, ``B = (ψ − sin ψ)/ψ³``.

    Parameters
    ----------
    psi, psidot : array_like, shape (..., 3)
        Rotation vector ψ (any length, not only |ψ| ≤ π) and its time derivative.
    frame : {"space", "body"}
        Components of the result: ω = J_l(ψ) ψ̇, or ω′ = J_r(ψ) ψ̇.

    Returns
    -------
    ndarray, shape (..., 3)
        ω = J_l ψ̇, or ω′ = J_r ψ̇.

    Examples
    --------
    >>> angular_velocity_from_rotvec_rate([0.0, 0.0, 1.0], [0.0, 0.0, 2.0])
    array([0., 0., 2.])
    """
    sign = frame_sign(frame)
    psi, psidot = vector_batch(psi=psi, psidot=psidot)
    return _rates_to_omega(psi, psidot, sign, out=out)


@uses(_omega_to_rates)
@takes_out
def rotvec_rate(psi: ArrayLike, omega: ArrayLike, frame: str = "space", tol: float = SINGULAR_TOL, *, out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Rotation-vector rate from the angular velocity: dexp⁻¹ (Theory §3.5).

    With body components this is the Bortz equation
    ``ψ̇ = ω′ + ½ ψ×ω′ + f ψ×(ψ×ω′)``; with space components
    ``ψ̇ = ω − ½ ψ×ω + f ψ×(ψ×ω)``, where ``f`` is :func:`bortz_coefficient`.

    Parameters
    ----------
    psi : array_like, shape (..., 3)
        Rotation vector.
    omega : array_like, shape (..., 3)
        Angular velocity in the components given by ``frame``.
    frame : {"space", "body"}
    tol : float
        Samples with |ψ| > π and |sin(|ψ|/2)| ≤ tol (the poles |ψ| = 2πk)
        are singular: their rates are NaN and a
        :class:`RotationVectorSingularityWarning` is issued.

    Returns
    -------
    ndarray, shape (..., 3)
        ψ̇; NaN at the poles |ψ| = 2πk.

    Examples
    --------
    >>> rotvec_rate([0.0, 0.0, 0.0], [1.0, 2.0, 3.0], frame="body")
    array([1., 2., 3.])
    >>> rotvec_rate([0.1, 0.0, 0.0], [0.0, 1.0, 0.0], frame="body")  # ½ ψ×ω′ + f ψ×(ψ×ω′)
    array([0.        , 0.99916653, 0.05      ])
    """
    sign = frame_sign(frame)
    psi, omega = vector_batch(psi=psi, omega=omega)
    out = _omega_to_rates(psi, omega, sign, check_tolerance(tol), out=out)
    warn_if_any(np.isnan(out[..., 0]), RotationVectorSingularityWarning, "rotvec_rate at |psi| = 2*pi*k")
    return out


@takes_out
def rotvec_rate_singular(psi: ArrayLike, tol: float = SINGULAR_TOL, *, out: NDArray[np.bool_] | None = None) -> NDArray[np.bool_]:
    """Mask of rotation vectors where :func:`rotvec_rate` is singular (no warning).

    Parameters
    ----------
    psi : array_like, shape (..., 3)
        Rotation vectors.
    tol : float
        Threshold on |sin(|ψ|/2)|, as in :func:`rotvec_rate`.

    Returns
    -------
    ndarray of bool, shape (...)
        True where |ψ| is within ``tol`` of a pole 2πk (k >= 1).

    Examples
    --------
    >>> rotvec_rate_singular([[0.0, 0.0, 2 * np.pi], [0.0, 0.0, np.pi]]).tolist()
    [True, False]
    """
    psi = vector_array(psi, "psi")
    tol = check_tolerance(tol)
    angle = norm(psi)
    check_rotvec_range(angle, "psi")
    return deliver((angle > np.pi) & (np.abs(np.sin(0.5 * angle)) <= tol), out)
