"""Path, velocity and acceleration of body points from sampled attitudes (Theory §3.7, §3.9)."""

from __future__ import annotations

from math import factorial
from typing import NamedTuple, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.checks import finite_array
from .._validation import as_float_array
from ..so3 import quat_apply
from ..so3._coercion import RotationLike, as_quaternion
from .acceleration import angular_acceleration_from_quat
from .motion import point_acceleration, point_velocity
from .rates import angular_velocity_from_quat_rate

__all__ = ["PointMotion", "point_trajectory"]


class PointMotion(NamedTuple):
    """Position, velocity and acceleration of a body point, each ``(..., n, 3)`` in space components.

    Examples
    --------
    A point 0.5 m from the hub of a wheel turning at 3 rad/s: speed ω r, and
    acceleration ω² r towards the hub:

    >>> import numpy as np
    >>> from kreisel.so3 import rotvec_to_quat
    >>> t = np.linspace(0.0, 1.0, 101)
    >>> m = point_trajectory([0.5, 0.0, 0.0], t, rotvec_to_quat(np.outer(3.0 * t, [0, 0, 1])))
    >>> m.position.shape, m.velocity.shape, m.acceleration.shape
    ((101, 3), (101, 3), (101, 3))
    >>> bool(np.allclose(np.linalg.norm(m.velocity, axis=-1), 1.5))
    True
    >>> bool(np.allclose(m.acceleration, -9.0 * m.position, atol=1e-5))
    True
    """

    position: NDArray[np.float64]
    velocity: NDArray[np.float64]
    acceleration: NDArray[np.float64]


class _Samples(Protocol):
    """What :func:`point_trajectory` reads from a Trajectory (a higher layer: not imported here)."""

    @property
    def t(self) -> NDArray[np.float64]: ...

    @property
    def q(self) -> NDArray[np.float64]: ...

    @property
    def omega(self) -> NDArray[np.float64]: ...


def _difference_weights(t: NDArray[np.float64], order: int, width: int = 5) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
    """Finite-difference stencils on a (possibly non-uniform) grid.

    Each sample uses the ``width`` nearest samples (centred inside, shifted
    at the ends) and the weights that differentiate the interpolating
    polynomial exactly: errors O(h^(width-order)) everywhere, ends included.
    """
    n = t.size
    width = min(width, n)
    first = np.clip(np.arange(n) - width // 2, 0, n - width)
    index = first[:, None] + np.arange(width)
    h = (t[-1] - t[0]) / (n - 1)  # scaling keeps the Vandermonde systems well conditioned
    offsets = (t[index] - t[:, None]) / h
    vandermonde = offsets[:, None, :] ** np.arange(width)[None, :, None]
    rhs = np.zeros((n, width))
    rhs[:, order] = factorial(order)
    return index, np.linalg.solve(vandermonde, rhs[..., None])[..., 0] / h**order


def _time_derivative(x: NDArray[np.float64], t: NDArray[np.float64], order: int = 1) -> NDArray[np.float64]:
    index, weights = _difference_weights(t, order)
    derivative: NDArray[np.float64] = np.einsum("...nkc,nk->...nc", x[..., index, :], weights)
    return derivative


def _continuous(q: NDArray[np.float64]) -> NDArray[np.float64]:
    # q and -q are the same attitude; differentiate a sign-continuous sequence.
    flips = np.cumsum(np.sum(q[..., 1:, :] * q[..., :-1, :], axis=-1) < 0.0, axis=-1) % 2
    sign = np.concatenate([np.ones(q.shape[:-2] + (1,)), np.where(flips == 1, -1.0, 1.0)], axis=-1)
    continuous: NDArray[np.float64] = q * sign[..., None]
    return continuous


def point_trajectory(body_point: ArrayLike, t: ArrayLike | None = None, rotation: RotationLike | None = None,
                     translation: ArrayLike | None = None, trajectory: _Samples | None = None) -> PointMotion:
    """Path, velocity and acceleration of a body point of a moving rigid body (Theory §3.7, §3.9).

    ``r_P = R r′_CP + r_C``, ``v_P = ω × r_CP + v_C`` and
    ``a_P = ε × r_CP + ω × (ω × r_CP) + a_C`` (rotational, centripetal and
    translational transport terms of Theory §3.9), with ``r_CP = R r′_CP``.
    ``v_C``, ``a_C``, ω and ε are taken from the samples by five-point finite
    differences on the (possibly non-uniform) time grid, ends included:
    errors O(Δt⁴) for velocities and O(Δt³) for accelerations (exact for
    polynomials of degree 4). From quaternion samples ``ω = 2 vec(q̇ q*)``
    and ``ε = 2 vec(q̈ q*)`` (space components); a
    :class:`~kreisel.dynamics.trajectory.Trajectory` supplies ω exactly.

    Parameters
    ----------
    body_point : array_like, shape (..., 3)
        Body components ``r′_CP`` of the point relative to the base point C,
        broadcast against the batch axes (not the time axis).
    t : array_like, shape (n,), optional
        Sample times (taken from ``trajectory`` when it is given).
    rotation : Rotation or array_like, optional
        Attitudes ``R(t)``: a ``Rotation``, matrices ``(..., n, 3, 3)`` or
        quaternions ``(..., n, 4)``. Give either this or ``trajectory``.
    translation : array_like, shape (..., n, 3), optional
        ``r_C(t)``; default zero (rotation about a fixed point C).
    trajectory : Trajectory, optional
        A simulated or exact attitude history (its ``q``, ``omega``, ``t``).

    Returns
    -------
    PointMotion
        ``position``, ``velocity``, ``acceleration`` as ``(..., n, 3)``.

    Examples
    --------
    >>> import numpy as np
    >>> from kreisel.so3 import rotvec_to_quat
    >>> t = np.linspace(0.0, 1.0, 201)
    >>> q = rotvec_to_quat(np.outer(2.0 * t, [0, 0, 1]))        # ω = 2 rad/s about z
    >>> m = point_trajectory([1.0, 0.0, 0.0], t, q)
    >>> np.round(m.velocity[0], 9) + 0.0                          # ω × r at t = 0
    array([0., 2., 0.])
    >>> np.round(m.acceleration[100], 6) + 0.0                    # -ω² r_CP at t = 0.5
    array([-2.161209, -3.365884,  0.      ])
    """
    if trajectory is not None:
        if rotation is not None or t is not None:
            raise ValueError("give either trajectory or (t, rotation), not both")
        if not all(hasattr(trajectory, name) for name in ("t", "q", "omega")):
            raise TypeError(f"trajectory must be a Trajectory (with t, q, omega), got {type(trajectory).__name__}")
        t = trajectory.t
        quat = trajectory.q
        omega = quat_apply(quat, trajectory.omega)
    else:
        if rotation is None or t is None:
            raise ValueError("give t and rotation (or a trajectory)")
        t = as_float_array(t, "t")
        quat = _continuous(as_quaternion(rotation, "rotation"))
        omega = None
    if t.ndim != 1 or t.size < 3 or not np.all(np.diff(t) > 0.0):
        raise ValueError(f"t must be increasing sample times, at least 3 of them, got shape {t.shape}")
    if quat.shape[-2:-1] != (t.size,):
        raise ValueError(f"rotation must have {t.size} samples along its time axis (-2), got shape {quat.shape}")
    if omega is None:
        qdot = _time_derivative(quat, t)
        omega = angular_velocity_from_quat_rate(quat, qdot, frame="space")
        epsilon = angular_acceleration_from_quat(quat, qdot, _time_derivative(quat, t, 2), frame="space")
    else:
        epsilon = _time_derivative(omega, t)
    if translation is None:
        translation = np.zeros(3)
    translation = finite_array(translation, "translation")
    if translation.ndim > 1 and translation.shape[-2] not in (1, t.size):
        raise ValueError(f"translation must have {t.size} samples along axis -2, got shape {translation.shape}")
    body_point = finite_array(body_point, "body_point")[..., None, :]

    arm = quat_apply(quat, body_point)
    r_c = np.broadcast_to(translation, np.broadcast_shapes(translation.shape, (t.size, 3)))
    v_c = _time_derivative(r_c, t)
    a_c = _time_derivative(r_c, t, 2)
    return PointMotion(arm + r_c, point_velocity(omega, arm, v_c), point_acceleration(omega, epsilon, arm, a_c))
