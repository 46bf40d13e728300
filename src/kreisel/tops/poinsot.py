"""Poinsot's construction of the free top (Theory §5.5–§5.6): polhode, herpolhode, invariable plane."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validation import as_float_array
from .._norms import norm, unit
from ..so3 import quat_apply
from .euler_top import EulerTop

__all__ = ["PoinsotGeometry", "poinsot"]


@dataclass(frozen=True)
class PoinsotGeometry:
    """Sampled curves of Poinsot's construction, ready to plot.

    Attributes
    ----------
    t : (n,) ndarray
        Sample times, s.
    polhode : (n, 3) ndarray
        r = ω/√(2T) in body axes: the contact point on the inertia ellipsoid
        I1 x² + I2 y² + I3 z² = 1, which also lies on I1²x² + I2²y² + I3²z² = J²/(2T)
        (intersection of the energy and momentum ellipsoids, Theory §5.6).
    herpolhode : (n, 2) ndarray
        The same point in space, in coordinates of the invariable plane
        (perpendicular to J; its x axis is the space direction of the
        component of r(0) perpendicular to J).
    herpolhode_space : (n, 3) ndarray
        The contact point in space axes.
    plane_normal : (3,) ndarray
        Unit vector along the space angular momentum.
    plane_distance : float
        √(2T)/|J|, the distance of the invariable plane from the fixed point (Theory §5.5 ii).
    inertia_ellipsoid_axes : (3,) ndarray
        Semi-axes 1/√I_i of the inertia ellipsoid (body axes as given).

    Examples
    --------
    The polhode lies on both the inertia ellipsoid Σ I_i r_i² = 1 and the
    momentum ellipsoid Σ I_i² r_i² = J²/(2T); the herpolhode lies in the
    invariable plane at distance √(2T)/|J| from the fixed point:

    >>> import numpy as np
    >>> top = EulerTop(1.0, 2.0, 3.0)
    >>> omega0 = [0.3, 0.2, 1.0]
    >>> g = poinsot(top, np.linspace(0.0, top.omega_period(omega0), 40), omega0)
    >>> bool(np.allclose(g.polhode**2 @ top.moments, 1.0, rtol=1e-13))
    True
    >>> J, T = float(top.angular_momentum(omega0)), float(top.energy(omega0))
    >>> bool(np.allclose(g.polhode**2 @ top.moments**2, J**2 / (2 * T), rtol=1e-13))
    True
    >>> round(g.plane_distance, 12), round(float(np.sqrt(2 * T) / J), 12)
    (0.585408150526, 0.585408150526)
    """

    t: NDArray[np.float64]
    polhode: NDArray[np.float64]
    herpolhode: NDArray[np.float64]
    herpolhode_space: NDArray[np.float64]
    plane_normal: NDArray[np.float64]
    plane_distance: float
    inertia_ellipsoid_axes: NDArray[np.float64]


def poinsot(top: EulerTop, t: ArrayLike, omega0: ArrayLike, q0: ArrayLike | None = None) -> PoinsotGeometry:
    """Polhode and herpolhode of the free top started with body ω0 (and attitude q0).

    Parameters
    ----------
    top : EulerTop
    t : (n,) array_like
        Sample times; one period of ω, ``top.omega_period(omega0)``, closes the polhode.
    omega0 : (3,) array_like
        Initial body angular velocity, rad/s (not zero).
    q0 : (4,) array_like, optional
        Initial attitude, body -> space.

    Examples
    --------
    >>> import numpy as np
    >>> top = EulerTop(1.0, 2.0, 3.0)
    >>> g = poinsot(top, np.linspace(0, 5, 50), [0.3, 0.2, 1.0])
    >>> bool(np.allclose(g.herpolhode_space @ g.plane_normal, g.plane_distance, rtol=1e-13))
    True
    """
    if not isinstance(top, EulerTop):
        raise TypeError(f"top must be an EulerTop, got {type(top).__name__}")
    omega0 = as_float_array(omega0, "omega0", tail=(3,))
    if omega0.ndim != 1 or not np.any(omega0 != 0.0):
        raise ValueError("omega0 must be one nonzero body angular velocity of shape (3,)")
    tr = top.solve(t, omega0, q0)
    # √(2T) = |√I ω| and |J| = |I ω| as norms that neither overflow nor underflow (ω0 from 1e-300 to 1e300)
    root_energy = norm(np.sqrt(top.moments) * omega0)
    polhode = tr.omega / root_energy
    space = quat_apply(tr.q, polhode)
    momentum = quat_apply(tr.q[0], top.moments * omega0)
    normal = unit(momentum, "omega0")
    start = space[0] - (space[0] @ normal) * normal
    if np.linalg.norm(start) == 0.0:
        # rotation about J itself: any in-plane direction serves
        start = np.cross(normal, [1.0, 0.0, 0.0] if abs(normal[0]) < 0.9 else [0.0, 1.0, 0.0])
    ex = start / np.linalg.norm(start)
    ey = np.cross(normal, ex)
    return PoinsotGeometry(
        t=tr.t,
        polhode=polhode,
        herpolhode=np.stack([space @ ex, space @ ey], axis=-1),
        herpolhode_space=space,
        plane_normal=normal,
        plane_distance=float(root_energy / norm(top.moments * omega0)),
        inertia_ellipsoid_axes=1.0 / np.sqrt(top.moments),
    )
