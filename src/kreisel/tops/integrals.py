"""Which first integrals a simulated rigid body has, and their values along a trajectory.

A first integral is a function of the state that the exact motion keeps
constant; how much a numerical trajectory changes it measures the integrator's
error. Which functions are integrals depends on the model that was simulated:

* free body (no torque): the kinetic energy T and the space angular momentum
  J, all three components (Theory §5.2);
* heavy top (uniform gravity about a fixed pivot): the energy E = T + V and
  the vertical component J_z (Theory §6.2); T, |J| and the direction of J are
  *not* conserved;
* heavy symmetric (Lagrange) top, centre of mass on the symmetry axis: also
  J_3, the component along that axis (Theory §6.2);
* Kovalevskaya top, moments (2 I3, 2 I3, I3) and centre of mass in the
  equatorial plane: also Kovalevskaya's K (Theory §7).

Any other torque (damping, constant torques, callables) has no first integral
kreisel knows of: :func:`first_integrals` then returns none.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..so3 import quat_apply

if TYPE_CHECKING:
    from ..dynamics.torques import TorqueModel
    from ..dynamics.trajectory import Trajectory

__all__ = ["FirstIntegral", "FirstIntegrals", "first_integrals"]

_RTOL = 1e-9  # moments this close count as equal, a lever this close to an axis lies on it


@dataclasses.dataclass(frozen=True)
class FirstIntegral:
    """One conserved quantity sampled along a trajectory.

    Attributes
    ----------
    symbol : str
        Short name, e.g. ``"E"``, ``"J_z"``.
    name : str
        What it is, in words, e.g. ``"energy T + V"``.
    unit : str
        SI unit of the values.
    values : ndarray
        Its value at every sample, shape ``(batch..., n)`` or ``(batch..., n, 3)``
        for the space angular momentum J of a free body.
    scale : ndarray
        Positive size the change is measured against (batch shape), e.g. |J(0)|
        for a component of J, so that a quantity that starts at zero has a
        meaningful relative change.

    Examples
    --------
    >>> f = FirstIntegral("E", "energy", "J", np.array([2.0, 2.0, 2.5]), np.array(2.0))
    >>> float(f.relative_change())
    0.25
    """

    symbol: str
    name: str
    unit: str
    values: NDArray[np.float64]
    scale: NDArray[np.float64]

    def relative_change(self) -> NDArray[np.float64]:
        """Largest |value(t) − value(t0)| over the trajectory, divided by ``scale`` (batch shape).

        Examples
        --------
        For the vector J the change is the length of J(t) − J(t0):

        >>> J = FirstIntegral("J", "angular momentum", "kg m²/s", np.array([[0.0, 0.0, 2.0], [0.0, 0.02, 2.0]]),
        ...                   np.array(2.0))
        >>> float(J.relative_change())
        0.01
        """
        change = self.values - self.values[..., :1, :] if self.is_vector else self.values - self.values[..., :1]
        size = np.linalg.norm(change, axis=-1) if self.is_vector else np.abs(change)
        relative: NDArray[np.float64] = np.max(size, axis=-1) / self.scale
        return relative

    @property
    def is_vector(self) -> bool:
        """True for a vector integral (the space J of a free body)."""
        return self.symbol == "J"

    @property
    def initial(self) -> NDArray[np.float64]:
        """The value at the first sample."""
        return self.values[..., 0, :] if self.is_vector else self.values[..., 0]


@dataclasses.dataclass(frozen=True)
class FirstIntegrals:
    """The model that was simulated and its first integrals along the trajectory.

    Attributes
    ----------
    model : str
        ``"free body"``, ``"heavy top"``, ``"heavy symmetric (Lagrange) top"``,
        ``"Kovalevskaya top"`` or ``"driven body"`` (a torque without known integrals).
    integrals : tuple of FirstIntegral
        Empty for a driven body.

    Examples
    --------
    Iterating gives the integrals; ``len`` says how many the model has:

    >>> import kreisel as kr
    >>> found = kr.tops.first_integrals(kr.EulerTop(1, 2, 3).solve(np.linspace(0, 1, 11), [0.1, 1.0, 0.1]))
    >>> found.model, len(found), [f.symbol for f in found]
    ('free body', 2, ['T', 'J'])
    """

    model: str
    integrals: tuple[FirstIntegral, ...]

    def __iter__(self) -> Iterator[FirstIntegral]:
        return iter(self.integrals)

    def __len__(self) -> int:
        return len(self.integrals)


def first_integrals(traj: Trajectory, torque: TorqueModel | Callable[..., ArrayLike] | None = None) -> FirstIntegrals:
    """The first integrals of the model that produced ``traj``, sampled along it.

    Parameters
    ----------
    traj : Trajectory
        Attitude and body angular velocity of a rigid body (batches allowed).
    torque : TorqueModel, optional
        The torque it was simulated with: None for a free body, a
        :class:`~kreisel.dynamics.GravityTorque` for a heavy top (sums of
        gravity torques act as one); any other torque has no known integrals.

    Returns
    -------
    FirstIntegrals

    Examples
    --------
    A fast heavy symmetric top keeps E = T + V, J_z and J_3, although T and |J|
    change as it nutates:

    >>> import numpy as np, kreisel as kr
    >>> gravity = kr.dynamics.GravityTorque(1.0, [0.0, 0.0, 1.0])
    >>> q0 = kr.euler_to_quat("ZXZ", [0.0, 30.0, 0.0], degrees=True)
    >>> tr = kr.simulate([1.0, 1.0, 0.5], np.linspace(0.0, 5.0, 501), [0.0, 0.0, 20.0], q0=q0, torque=gravity)
    >>> found = first_integrals(tr, gravity)
    >>> found.model, [f.symbol for f in found]
    ('heavy symmetric (Lagrange) top', ['E', 'J_z', 'J_3'])
    >>> bool(max(f.relative_change() for f in found) < 1e-9)
    True
    >>> bool(np.ptp(tr.energy) > 1e-3)   # the kinetic energy alone is not conserved
    True
    """
    inertia = traj.inertia
    T = traj.energy
    J_body = traj.angular_momentum_body
    J0 = np.linalg.norm(J_body[..., 0, :], axis=-1)
    J_scale = np.where(J0 > 0, J0, 1.0)
    gravity = _gravity(torque)
    if torque is not None and gravity is None:
        return FirstIntegrals("driven body", ())
    if gravity is None or gravity[0] == 0.0 or not np.any(gravity[1]):   # no net gravity torque: a free body
        return FirstIntegrals("free body", (
            FirstIntegral("T", "kinetic energy", "J", T, _positive(np.abs(T[..., 0]))),
            FirstIntegral("J", "angular momentum (space)", "kg m²/s", traj.angular_momentum_space, J_scale),
        ))
    weight, lever = gravity
    up = quat_apply(traj.q, np.array([0.0, 0.0, 1.0]), inverse=True)   # γ = Rᵀ e_z, body components
    V = weight * np.einsum("i,...i->...", lever, up)
    E = T + V
    # E mixes T and V: measure it against the larger of T(0) and the potential's range m g l
    E_scale = _positive(np.maximum(np.abs(T[..., 0]), weight * np.linalg.norm(lever)))
    found = [FirstIntegral("E", "energy T + V", "J", E, E_scale),
             FirstIntegral("J_z", "vertical angular momentum", "kg m²/s", np.einsum("...i,...i->...", J_body, up),
                           J_scale)]
    model = "heavy top"
    moments, axes = np.linalg.eigh(inertia.reshape(-1, 3, 3)[0])
    if inertia.ndim > 2 and not np.allclose(inertia, inertia.reshape(-1, 3, 3)[0], rtol=_RTOL, atol=0.0):
        return FirstIntegrals(model, tuple(found))   # a batch of different bodies: the common integrals only
    unit_lever = lever / np.linalg.norm(lever)
    along = np.abs(axes.T @ unit_lever)     # |cos| between the lever and each principal axis
    for k in range(3):
        others = [m for i, m in enumerate(moments) if i != k]
        if abs(along[k] - 1.0) < _RTOL and abs(others[0] - others[1]) <= _RTOL * moments.max():
            found.append(FirstIntegral("J_3", "angular momentum about the symmetry axis", "kg m²/s",
                                       J_body @ unit_lever, J_scale))
            model = "heavy symmetric (Lagrange) top"
            break
    kovalevskaya = _kovalevskaya(moments, axes, lever, weight, traj.omega, up)
    if kovalevskaya is not None:
        found.append(kovalevskaya)
        model = "Kovalevskaya top"
    return FirstIntegrals(model, tuple(found))


def _positive(scale: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.where(scale > 0, scale, 1.0)


def _gravity(torque: object) -> tuple[float, NDArray[np.float64]] | None:
    """``(weight, lever)`` of a gravity torque (or a sum of them), None if ``torque`` is not one."""
    from ..dynamics.torques import GravityTorque, TorqueSum

    parts = torque.models if isinstance(torque, TorqueSum) else (torque,)
    gravity = [part for part in parts if isinstance(part, GravityTorque)]
    if len(gravity) != len(parts):
        return None
    weight = sum((part.weight for part in gravity), 0.0)
    moment = sum((part.weight * part.lever for part in gravity), np.zeros(3))   # Σ m_i g l_i = (Σ m_i g) l_centre
    return weight, moment / weight if weight > 0.0 else moment


def _kovalevskaya(moments: NDArray[np.float64], axes: NDArray[np.float64], lever: NDArray[np.float64], weight: float, omega: NDArray[np.float64],
                  up: NDArray[np.float64]) -> FirstIntegral | None:
    """Kovalevskaya's K (Theory §7) if the body and lever are Kovalevskaya's case, else None."""
    short = int(np.argmin(moments))
    others = [m for i, m in enumerate(moments) if i != short]
    I3 = moments[short]
    if not all(abs(m - 2.0 * I3) <= _RTOL * m for m in others):
        return None
    e3 = axes[:, short]
    if abs(lever @ e3) > _RTOL * np.linalg.norm(lever):
        return None
    # body frame of Theory §7: e1 along the centre of mass, e3 the short axis, e2 = e3 × e1
    e1 = lever / np.linalg.norm(lever)
    e2 = np.cross(e3, e1)
    frame = np.stack([e1, e2, e3])
    p, q, _ = np.moveaxis(omega @ frame.T, -1, 0)
    g1, g2, _ = np.moveaxis(up @ frame.T, -1, 0)
    c = weight * np.linalg.norm(lever) / I3
    K = (p * p - q * q - c * g1) ** 2 + (2.0 * p * q - c * g2) ** 2
    return FirstIntegral("K", "Kovalevskaya's integral", "rad⁴/s⁴", K, _positive(np.maximum(np.abs(K[..., 0]), c * c)))
