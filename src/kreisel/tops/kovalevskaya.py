"""The Kovalevskaya top (Theory §7): I1 = I2 = 2 I3, centre of mass in the equatorial plane.

Body axes: centre of mass at l e1; γ = the upward vertical in body components,
γ = Rᵀ e_z; ω = (p, q, r); c = mgl/I3. Euler–Poisson equations (Theory §7):
2ṗ = qr, 2q̇ = −pr + cγ3, ṙ = −cγ2, γ̇ = γ × ω. Four integrals: the energy,
the area integral J·γ, the geometric |γ|² = 1 and Kovalevskaya's

    K = (p² − q² − cγ1)² + (2pq − cγ2)².
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validation import as_float_array, check_principal_moments
from ..dynamics import GravityTorque, simulate
from ..dynamics.trajectory import Trajectory
from ..so3 import quat_apply
from .euler_top import _check_moments

__all__ = ["KovalevskayaTop", "KovalevskayaIntegrals"]


@dataclass(frozen=True)
class KovalevskayaIntegrals:
    """The four first integrals of the Kovalevskaya top, each an array over time.

    Attributes
    ----------
    energy : ndarray
        H = I3 (p² + q² + r²/2) + mgl γ1 (kinetic plus potential energy), J.
    area : ndarray
        J·γ / I3 = 2pγ1 + 2qγ2 + rγ3 (vertical angular momentum over I3), rad/s.
    geometric : ndarray
        |γ|² (= 1).
    kovalevskaya : ndarray
        K = (p² − q² − cγ1)² + (2pq − cγ2)², rad⁴/s⁴.

    Examples
    --------
    For ω = (0.5, 0.2, 1) with the vertical along body axis 3 (c = mgl/I3 = 1):

    >>> top = KovalevskayaTop(1.0, 1.0)
    >>> ints = top.integrals([0.5, 0.2, 1.0], [0.0, 0.0, 1.0])
    >>> round(float(ints.energy), 12), float(ints.area), float(ints.geometric)   # I3 (p² + q² + r²/2) = 0.79
    (0.79, 1.0, 1.0)
    """

    energy: NDArray[np.float64]
    area: NDArray[np.float64]
    geometric: NDArray[np.float64]
    kovalevskaya: NDArray[np.float64]


class KovalevskayaTop:
    """Heavy top in Kovalevskaya's case: moments (2 I3, 2 I3, I3), centre of mass on body axis 1.

    Parameters
    ----------
    I3 : float
        Moment about the third (short) axis, kg m²; I1 = I2 = 2 I3 about the pivot.
    mgl : float
        Weight times the distance from the pivot to the centre of mass (> 0), N m.

    Examples
    --------
    >>> import numpy as np
    >>> top = KovalevskayaTop(1.0, 1.0)
    >>> ints = top.integrals([[0.5, 0.2, 1.0]], [[0.0, 0.0, 1.0]])
    >>> round(float(ints.kovalevskaya[0]), 6)  # (0.25 - 0.04)² + (0.2)²
    0.0841
    """

    I3: float
    mgl: float

    def __init__(self, I3: float, mgl: float) -> None:
        self.I3, self.mgl = _check_moments((I3, mgl), ("I3", "mgl"))
        self.moments = check_principal_moments([2.0 * self.I3, 2.0 * self.I3, self.I3], "KovalevskayaTop moments")
        self.c = self.mgl / self.I3

    def __repr__(self) -> str:
        return f"KovalevskayaTop(I3={self.I3:g}, mgl={self.mgl:g})"

    def integrals(self, omega: ArrayLike, gamma: ArrayLike) -> KovalevskayaIntegrals:
        """The four integrals for body ω = (p, q, r) and upward vertical γ, broadcast.

        Parameters
        ----------
        omega : (..., 3) array_like
            Body angular velocity, rad/s.
        gamma : (..., 3) array_like
            Upward unit vertical in body components (Rᵀ e_z).

        Returns
        -------
        KovalevskayaIntegrals

        Examples
        --------
        Kovalevskaya's fourth integral is what makes this top integrable: with the
        centre of mass tipped onto the horizontal (γ1 = 0), K = (p² − q²)² + (2pq − c γ2)²:

        >>> import numpy as np
        >>> top = KovalevskayaTop(2.0, 1.0)   # c = mgl/I3 = 0.5
        >>> ints = top.integrals([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [0.0, 1.0, 0.0])
        >>> ints.kovalevskaya.round(12).tolist()   # (1 + 0.25, 1 + 0.25)
        [1.25, 1.25]
        >>> ints.energy.round(12).tolist(), ints.area.tolist()   # I3 (p² + q²); 2 q γ2
        ([2.0, 2.0], [0.0, 2.0])
        """
        omega = as_float_array(omega, "omega", tail=(3,))
        gamma = as_float_array(gamma, "gamma", tail=(3,))
        p, q, r = np.moveaxis(omega, -1, 0)
        g1, g2, g3 = np.moveaxis(gamma, -1, 0)
        c = self.c
        with np.errstate(over="ignore", invalid="ignore"):
            integrals = KovalevskayaIntegrals(
                energy=self.I3 * (p * p + q * q + 0.5 * r * r) + self.mgl * g1,
                area=2.0 * p * g1 + 2.0 * q * g2 + r * g3,
                geometric=g1 * g1 + g2 * g2 + g3 * g3,
                kovalevskaya=(p * p - q * q - c * g1) ** 2 + (2.0 * p * q - c * g2) ** 2,
            )
        # K grows like |ω|⁴ (past 1e308 from |ω| ~ 1e77): an inf there is no value of the integral
        for name, value in vars(integrals).items():
            if not np.all(np.isfinite(value)):
                raise ValueError(f"omega and gamma are out of range: the integral {name} exceeds the largest "
                                 "double (K grows like |omega|**4, the energy like |omega|**2)")
        return integrals

    def simulate(self, t: ArrayLike, omega0: ArrayLike, q0: ArrayLike | None = None, method: str | None = None,
                 **options: Any) -> Trajectory:
        """Integrate with :func:`kreisel.simulate` and :class:`kreisel.dynamics.GravityTorque`.

        Weight ``mgl`` at the body lever (1, 0, 0): only m g l enters. ``options``
        go to :func:`kreisel.simulate` (``dt``, ``rtol``, ``atol``).

        Returns
        -------
        Trajectory
            With the extra array ``gamma`` (n, 3), the upward vertical in the body;
            ``integrals(tr.omega, tr.gamma)`` gives the four integrals.

        Examples
        --------
        >>> import numpy as np
        >>> top = KovalevskayaTop(1.0, 1.0)
        >>> tr = top.simulate(np.linspace(0, 10, 3), [0.5, 0.2, 1.0], [np.cos(0.4), np.sin(0.4), 0, 0])
        >>> K = top.integrals(tr.omega, tr.gamma).kovalevskaya
        >>> bool(np.allclose(K, K[0], rtol=1e-9))
        True
        """
        torque = GravityTorque(self.mgl, [1.0, 0.0, 0.0])
        tr = simulate(self.moments, t, omega0, q0, torque=torque, method=method, **options)
        gamma = quat_apply(tr.q, np.array([0.0, 0.0, 1.0]), inverse=True)
        return Trajectory(tr.t, tr.q, tr.omega, tr.inertia, meta=tr.meta, gamma=gamma)
