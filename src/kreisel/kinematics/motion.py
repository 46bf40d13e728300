"""Velocity and acceleration of points of, and points moving on, a rigid body (Theory §3.7, §3.9, §4.6–7).

All vectors must be given in one common set of components (space or
body); the formulas are the same in both.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import dexp
from .._compiled.checks import VECTOR, vector_array
from .._compiled.elementwise import Input, declare, kernel, uses
from .._compiled.outputs import takes_out
from .._validation import out_of_range
from ._checks import same_batch, vector_batch

__all__ = [
    "point_velocity",
    "point_acceleration",
    "relative_derivative",
    "VelocityTerms",
    "AccelerationTerms",
    "three_term_velocity",
    "five_term_acceleration",
]


@kernel
def _plus_cross(ax: float, ay: float, az: float, bx: float, by: float, bz: float, cx: float, cy: float,
                cz: float) -> tuple[float, float, float]:
    # c + a × b
    x, y, z = dexp.cross(ax, ay, az, bx, by, bz)
    return cx + x, cy + y, cz + z


@kernel
def _transport(wx: float, wy: float, wz: float, ex: float, ey: float, ez: float, rx: float, ry: float, rz: float,
               ax: float, ay: float, az: float) -> tuple[float, float, float]:
    # a + ε × r + ω × (ω × r)
    tx, ty, tz = dexp.cross(ex, ey, ez, rx, ry, rz)
    vx, vy, vz = dexp.cross(wx, wy, wz, rx, ry, rz)
    cx, cy, cz = dexp.cross(wx, wy, wz, vx, vy, vz)
    return ax + tx + cx, ay + ty + cy, az + tz + cz


# the refusals of an overflow name the arguments of the term-by-term functions, whose sums these are
_VELOCITY = ("omega, r, relative_velocity and reference_velocity", "the velocity")
_ACCELERATION = ("omega, epsilon, r, relative_velocity, relative_acceleration and reference_acceleration",
                 "the acceleration")
_velocities = declare(_plus_cross, [Input(n, (3,), VECTOR) for n in ("omega", "r", "reference_velocity")], (3,),
                      name="point_velocity").refusing(out_of_range(*_VELOCITY).message)
_accelerations = declare(_transport, [Input(n, (3,), VECTOR) for n in ("omega", "epsilon", "r", "reference_acceleration")],
                         (3,), name="point_acceleration").refusing(out_of_range(*_ACCELERATION).message)
_relative_derivatives = declare(_plus_cross, [Input(n, (3,), VECTOR) for n in ("omega", "vector", "relative_rate")],
                                (3,), name="relative_derivative")


@uses(_velocities)
@takes_out
def point_velocity(omega: ArrayLike, r: ArrayLike, reference_velocity: ArrayLike = 0.0, *,
                   out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Velocity of a body-fixed point, ``v_P = v_C + ω × r_CP`` (Theory §3.7).

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity.
    r : array_like, shape (..., 3)
        Position r_CP of the point relative to the reference point C.
    reference_velocity : array_like, shape (..., 3)
        Velocity v_C of the reference point (default at rest).

    Returns
    -------
    ndarray, shape (..., 3)
        v_P in the components the inputs share.

    Examples
    --------
    >>> point_velocity([0.0, 0.0, 2.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0])
    array([1., 2., 0.])
    """
    arrays = vector_batch(omega=omega, r=r, reference_velocity=_as_vector(reference_velocity))
    return _velocities(*arrays, out=out)


@uses(_accelerations)
@takes_out
def point_acceleration(omega: ArrayLike, epsilon: ArrayLike, r: ArrayLike, reference_acceleration: ArrayLike = 0.0, *,
                       out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Acceleration of a body-fixed point (Theory §3.9).

    ``a_P = a_C + ε × r_CP + ω × (ω × r_CP)``: translational, rotational
    (tangential) and centripetal (axipetal, 向轴) transport accelerations.

    Parameters
    ----------
    omega, epsilon : array_like, shape (..., 3)
        Angular velocity and angular acceleration.
    r : array_like, shape (..., 3)
        Position r_CP relative to the reference point C.
    reference_acceleration : array_like, shape (..., 3)
        Acceleration a_C of the reference point (default 0).

    Returns
    -------
    ndarray, shape (..., 3)
        a_P = a_C + ε × r + ω × (ω × r), in the inputs' components.

    Examples
    --------
    >>> point_acceleration([0.0, 0.0, 2.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
    array([-4.,  0.,  0.])
    """
    arrays = vector_batch(omega=omega, epsilon=epsilon, r=r, reference_acceleration=_as_vector(reference_acceleration))
    return _accelerations(*arrays, out=out)


@uses(_relative_derivatives)
@takes_out
def relative_derivative(omega: ArrayLike, vector: ArrayLike, relative_rate: ArrayLike, *,
                        out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
    """Rate of change of a vector from its rate relative to the body (Theory §4.6).

    ``B′ = dA′/dt + ω′ × A′``: the components of B = dA/dt on the body axes
    from the time derivative of A's body components. In space components
    the same formula reads ``dA/dt = R dA′/dt + ω × A``.

    Parameters
    ----------
    omega : array_like, shape (..., 3)
        Angular velocity of the body.
    vector : array_like, shape (..., 3)
        The vector A.
    relative_rate : array_like, shape (..., 3)
        dA′/dt, the rate seen from the body.

    Returns
    -------
    ndarray, shape (..., 3)
        The rate of change seen from space, in the components of the inputs.

    Examples
    --------
    A vector fixed in a body spinning about z:

    >>> relative_derivative([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    array([0., 1., 0.])
    """
    arrays = vector_batch(omega=omega, vector=vector, relative_rate=relative_rate)
    return _relative_derivatives(*arrays, out=out)


class VelocityTerms(NamedTuple):
    """Absolute velocity of a point moving on a body, term by term (Theory §4.7).

    Examples
    --------
    A person walking at 1 m/s radially outwards on a turntable spinning at
    0.5 rad/s, 2 m from the axis: the turntable carries them sideways at ω r:

    >>> v = three_term_velocity([0.0, 0.0, 0.5], [2.0, 0.0, 0.0], [1.0, 0.0, 0.0])
    >>> v.relative.tolist(), v.rotational.tolist(), v.total.tolist()
    ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0])
    """

    translational: NDArray[np.float64]  #: v_C, transport velocity of the reference point (平动牵连速度)
    relative: NDArray[np.float64]  #: v_CP = R d r′_CP/dt, velocity relative to the body (相对速度)
    rotational: NDArray[np.float64]  #: ω × r_CP, rotational transport velocity (转动牵连速度)

    @property
    def total(self) -> NDArray[np.float64]:
        """The absolute velocity, the sum of the three terms."""
        return self.translational + self.relative + self.rotational


class AccelerationTerms(NamedTuple):
    """Absolute acceleration of a point moving on a body, term by term (Theory §4.7).

    Examples
    --------
    The same walker (1 m/s outwards, 2 m out, table at 0.5 rad/s and speeding
    up at 0.1 rad/s²): Coriolis 2 ω v sideways, centripetal ω² r inwards,
    tangential ε r sideways:

    >>> a = five_term_acceleration([0, 0, 0.5], [0, 0, 0.1], [2.0, 0, 0], [1.0, 0, 0], [0, 0, 0])
    >>> a.coriolis.tolist(), a.centripetal.tolist(), a.tangential.tolist()
    ([0.0, 1.0, 0.0], [-0.5, 0.0, 0.0], [0.0, 0.2, 0.0])
    >>> a.total.round(12).tolist()
    [-0.5, 1.2, 0.0]
    """

    translational: NDArray[np.float64]  #: a_C (平动牵连加速度)
    tangential: NDArray[np.float64]  #: ε × r_CP, rotational transport acceleration (转动牵连加速度)
    centripetal: NDArray[np.float64]  #: ω × (ω × r_CP), axipetal acceleration (向轴加速度)
    relative: NDArray[np.float64]  #: a_CP = R d² r′_CP/dt², acceleration relative to the body (相对加速度)
    coriolis: NDArray[np.float64]  #: 2 ω × v_CP (Coriolis 加速度)

    @property
    def total(self) -> NDArray[np.float64]:
        """The absolute acceleration, the sum of the five terms."""
        return self.translational + self.tangential + self.centripetal + self.relative + self.coriolis


def _as_vector(value: ArrayLike) -> ArrayLike:
    return np.broadcast_to(np.asarray(value, dtype=float), (3,)) if np.ndim(value) == 0 else value


def _finite_batch(**named: ArrayLike) -> tuple[NDArray[np.float64], ...]:
    """Finite ``(..., 3)`` arrays of the keyword arguments, in order, with broadcastable batch shapes."""
    return same_batch(1, **{name: vector_array(x, name) for name, x in named.items()})


def three_term_velocity(omega: ArrayLike, r: ArrayLike, relative_velocity: ArrayLike,
                        reference_velocity: ArrayLike = 0.0) -> VelocityTerms:
    """Velocity of a point moving relative to a body: ``v_P = v_C + v_CP + ω × r_CP`` (Theory §4.7).

    Parameters
    ----------
    omega : array_like, shape (..., 3)
    r : array_like, shape (..., 3)
        Position r_CP of the point relative to the body's reference point C.
    relative_velocity : array_like, shape (..., 3)
        v_CP = R d r′_CP/dt: the velocity seen from the body, in the same
        components as the other vectors (not d r_CP/dt).
    reference_velocity : array_like, shape (..., 3)
        v_C (default 0).

    Returns
    -------
    VelocityTerms
        ``translational``, ``relative``, ``rotational``, and their ``total``.

    Examples
    --------
    >>> terms = three_term_velocity([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0])
    >>> terms.rotational, terms.total
    (array([0., 1., 0.]), array([1., 1., 0.]))
    """
    omega, r, v_rel, v_c = _finite_batch(
        omega=omega, r=r, relative_velocity=_as_vector(relative_velocity), reference_velocity=_as_vector(reference_velocity)
    )
    shape = np.broadcast_shapes(omega.shape, r.shape, v_rel.shape, v_c.shape)
    with out_of_range(*_VELOCITY) as guard:
        rotational = np.cross(omega, r)
        guard.check(rotational, v_c + v_rel + rotational)
    return VelocityTerms(*(np.array(np.broadcast_to(x, shape)) for x in (v_c, v_rel, rotational)))


def five_term_acceleration(omega: ArrayLike, epsilon: ArrayLike, r: ArrayLike, relative_velocity: ArrayLike,
                           relative_acceleration: ArrayLike, reference_acceleration: ArrayLike = 0.0) -> AccelerationTerms:
    """Acceleration of a point moving relative to a body, as five named terms (Theory §4.7).

    ``a_P = a_C + ε × r_CP + ω × (ω × r_CP) + a_CP + 2 ω × v_CP``:
    translational, tangential (rotational transport), centripetal, relative
    and Coriolis accelerations.

    Parameters
    ----------
    omega, epsilon : array_like, shape (..., 3)
        Angular velocity and angular acceleration of the body.
    r : array_like, shape (..., 3)
        Position r_CP relative to the body's reference point C.
    relative_velocity, relative_acceleration : array_like, shape (..., 3)
        v_CP = R d r′_CP/dt and a_CP = R d² r′_CP/dt², seen from the body
        (0 for a body-fixed point).
    reference_acceleration : array_like, shape (..., 3)
        a_C (default 0).

    Returns
    -------
    AccelerationTerms
        The five terms and their ``total``.

    Examples
    --------
    A bead sliding outwards at 1 m/s along a rod turning at 2 rad/s:

    >>> terms = five_term_acceleration([0, 0, 2.0], [0, 0, 0], [0.5, 0, 0], [1.0, 0, 0], [0, 0, 0])
    >>> terms.coriolis, terms.centripetal
    (array([0., 4., 0.]), array([-2.,  0.,  0.]))
    """
    omega, epsilon, r, v_rel, a_rel, a_c = _finite_batch(
        omega=omega,
        epsilon=epsilon,
        r=r,
        relative_velocity=_as_vector(relative_velocity),
        relative_acceleration=_as_vector(relative_acceleration),
        reference_acceleration=_as_vector(reference_acceleration),
    )
    shape = np.broadcast_shapes(omega.shape, epsilon.shape, r.shape, v_rel.shape, a_rel.shape, a_c.shape)
    with out_of_range(*_ACCELERATION) as guard:
        terms = (a_c, np.cross(epsilon, r), np.cross(omega, np.cross(omega, r)), a_rel, 2.0 * np.cross(omega, v_rel))
        guard.check(*terms, sum(terms))
    return AccelerationTerms(*(np.array(np.broadcast_to(x, shape)) for x in terms))
