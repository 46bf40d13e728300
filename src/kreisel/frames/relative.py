"""Kinematics and mechanics of a particle seen from a moving, rotating frame.

Theory §8.1 (Lagrangian and Hamiltonian of a particle in a non-inertial frame);
the three-term velocity and five-term acceleration of Theory §4.7 are
:func:`kreisel.kinematics.three_term_velocity` and
:func:`kreisel.kinematics.five_term_acceleration`. All vectors are components along the moving
frame's axes unless a docstring says otherwise; every function broadcasts over
leading axes.

A note on Theory §8.1. The chapter's Lagrangian carries the translational term
``-m ṙ·a0``; its Euler–Lagrange equation would give a force ``+m ȧ0`` (a jerk),
not the inertial force ``-m a0``. The chapter's own identity
``(ṙ + ω×r)·v0 = d/dt(r·v0) - r·a0`` (v0, a0 the frame origin's velocity and
acceleration, in moving-frame components) gives the translational potential
``m a0·r`` instead, as in Landau & Lifshitz §39. kreisel uses

    L = ½ m (ṙ + ω×r)² - m a0·r - V,       p = m (ṙ + ω×r),
    H = p²/2m - p·(ω×r) + m a0·r + V = ½ m ṙ² - ½ m (ω×r)² + m a0·r + V,

which the tests check against a simulation in the inertial frame.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

from .._validation import as_float_array, out_of_range, positive_array
from .._norms import norm
from ..kinematics import five_term_acceleration

__all__ = [
    "InertialForces",
    "LagrangianTerms",
    "HamiltonianTerms",
    "inertial_forces",
    "canonical_momentum",
    "velocity_from_momentum",
    "lagrangian_terms",
    "lagrangian",
    "hamiltonian_terms",
    "hamiltonian",
]

InertialForces = namedtuple("InertialForces", ["translational", "coriolis", "centrifugal", "euler", "total"])
InertialForces.__doc__ = """Fictitious (inertial) forces in a moving frame (Theory §8.1).

translational (-m a0), coriolis (-2m ω×ṙ), centrifugal (-m ω×(ω×r)),
euler (-m ω̇×r) and their sum ``total``.

Examples
--------
The same star (no real force): centrifugal outwards plus Coriolis inwards
give exactly the centripetal force m r̈ = -m r of its apparent circle:

>>> f = inertial_forces([1, 0, 0], [0, -1, 0], [0, 0, 1])
>>> (f.centrifugal + 0.0).tolist(), (f.coriolis + 0.0).tolist(), (f.total + 0.0).tolist()
([1.0, 0.0, 0.0], [-2.0, 0.0, 0.0], [-1.0, 0.0, 0.0])
"""

LagrangianTerms = namedtuple("LagrangianTerms", ["kinetic", "coriolis", "centrifugal", "translational", "potential"])
LagrangianTerms.__doc__ = """Terms of L (Theory §8.1), which is their sum.

kinetic ½mṙ², coriolis m ṙ·(ω×r), centrifugal ½m(ω×r)², translational
-m a0·r, potential -V.

Examples
--------
L is frame independent: for the star at rest in space the terms sum to its
inertial kinetic energy, zero:

>>> t = lagrangian_terms([1, 0, 0], [0, -1, 0], [0, 0, 1])
>>> [float(x) for x in t], float(sum(t))
([0.5, -1.0, 0.5, -0.0, -0.0], 0.0)
"""

HamiltonianTerms = namedtuple("HamiltonianTerms", ["kinetic", "coriolis", "translational", "potential"])
HamiltonianTerms.__doc__ = """Terms of H(r, p) (Theory §8.1), which is their sum.

kinetic p²/2m, coriolis -p·(ω×r) (the generalised potential of the Coriolis
and centrifugal forces), translational m a0·r, potential V.

Examples
--------
With constant ω, H is the Jacobi integral ½mṙ² − ½m(ω×r)² + V:

>>> r, v, omega = [2.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0]
>>> h = hamiltonian_terms(r, canonical_momentum(r, v, omega), omega)
>>> float(h.kinetic), float(h.coriolis), float(sum(h))
(4.5, -6.0, -1.5)
>>> 0.5 * 1.0**2 - 0.5 * 2.0**2
-1.5
"""


def _vectors(**named):
    return [as_float_array(v, k, tail=(3,)) for k, v in named.items()]


def _dot(a, b):
    return np.sum(a * b, axis=-1)


def _energy_terms(compute, which, names):
    """``compute()``'s energy terms, refused naming ``names`` where a term or their sum overflows."""
    with np.errstate(over="ignore", invalid="ignore"):
        terms = compute()
        total = sum(terms)
    if not (np.isfinite(total).all() and all(np.isfinite(x).all() for x in terms)):
        raise ValueError(f"{names} are out of range: the terms of the {which} overflow double precision "
                         "(exceed 1.8e308 J)")
    shape = np.broadcast_shapes(*(np.shape(x) for x in terms))
    return [np.broadcast_to(x, shape).copy() for x in terms]


def inertial_forces(r, v, omega, omega_dot=(0.0, 0.0, 0.0), a0=(0.0, 0.0, 0.0), mass=1.0):
    """Fictitious forces on a particle observed in a moving frame (Theory §8.1).

    m r̈ = F - m a0 - 2m ω×ṙ - m ω×(ω×r) - m ω̇×r, all in moving-frame
    components; this returns the four inertial terms separately.

    Parameters
    ----------
    r, v : (..., 3) array_like
        Position and velocity relative to the frame (``v = ṙ`` of the
        components).
    omega, omega_dot : (..., 3) array_like
        Angular velocity of the frame and its time derivative.
    a0 : (..., 3) array_like
        Acceleration of the frame origin (moving-frame components).
    mass : float or array_like
        Particle mass, kg.

    Returns
    -------
    InertialForces

    Examples
    --------
    >>> f = inertial_forces([1, 0, 0], [0, 1, 0], [0, 0, 1])
    >>> (f.centrifugal + 0.0).tolist(), (f.coriolis + 0.0).tolist()
    ([1.0, 0.0, 0.0], [2.0, 0.0, 0.0])
    """
    r, v, omega, omega_dot, a0 = _vectors(r=r, v=v, omega=omega, omega_dot=omega_dot, a0=a0)
    m = positive_array(mass, "mass")[..., None]
    with out_of_range("r, v, omega, omega_dot, a0 and mass", "an inertial force") as guard:
        try:
            # each inertial force is -m times a transport or Coriolis term of the five-term acceleration
            a = five_term_acceleration(omega, omega_dot, r, v, 0.0, a0)
        except ValueError:  # the arguments are checked above: only a term beyond the largest double is left
            guard.refuse()
        translational, euler, centrifugal, coriolis = (-m * x for x in (a.translational, a.tangential,
                                                                       a.centripetal, a.coriolis))
        total = guard.check(translational + coriolis + centrifugal + euler)
        guard.check(translational, coriolis, centrifugal, euler)
    shape = total.shape
    return InertialForces(
        *(np.broadcast_to(x, shape).copy() for x in (translational, coriolis, centrifugal, euler)), total
    )


def canonical_momentum(r, v, omega, mass=1.0):
    """Canonical momentum p = m (ṙ + ω×r) (Theory §8.1): the inertial momentum minus m v0.

    Examples
    --------
    >>> canonical_momentum([1, 0, 0], [0, 0, 0], [0, 0, 1], mass=2.0).tolist()
    [0.0, 2.0, 0.0]
    """
    r, v, omega = _vectors(r=r, v=v, omega=omega)
    m = positive_array(mass, "mass")[..., None]
    return m * (v + np.cross(omega, r))


def velocity_from_momentum(r, p, omega, mass=1.0):
    """Relative velocity ṙ = p/m - ω×r, the inverse of :func:`canonical_momentum`.

    Examples
    --------
    >>> velocity_from_momentum([1, 0, 0], [0, 2, 0], [0, 0, 1], mass=2.0).tolist()
    [0.0, 0.0, 0.0]
    """
    r, p, omega = _vectors(r=r, p=p, omega=omega)
    m = positive_array(mass, "mass")[..., None]
    return p / m - np.cross(omega, r)


def lagrangian_terms(r, v, omega, a0=(0.0, 0.0, 0.0), potential=0.0, mass=1.0):
    """The terms of the moving-frame Lagrangian of Theory §8.1 (see the module note on a0).

    Parameters
    ----------
    r, v : (..., 3) array_like
        Position and relative velocity ṙ.
    omega : (..., 3) array_like
        Frame angular velocity.
    a0 : (..., 3) array_like
        Frame origin acceleration.
    potential : float or array_like
        V(t, r) already evaluated at the points, J.
    mass : float or array_like
        kg.

    Returns
    -------
    LagrangianTerms

    Examples
    --------
    >>> t = lagrangian_terms([1, 0, 0], [0, 1, 0], [0, 0, 1])
    >>> float(t.kinetic), float(t.coriolis), float(t.centrifugal)
    (0.5, 1.0, 0.5)
    """
    r, v, omega, a0 = _vectors(r=r, v=v, omega=omega, a0=a0)
    potential = as_float_array(potential, "potential")
    m = positive_array(mass, "mass")

    def compute():
        wr = np.cross(omega, r)
        return 0.5 * m * _dot(v, v), m * _dot(v, wr), 0.5 * m * _dot(wr, wr), -m * _dot(a0, r), -potential

    return LagrangianTerms(*_energy_terms(compute, "Lagrangian", "r, v, omega, a0, potential and mass"))


def lagrangian(r, v, omega, a0=(0.0, 0.0, 0.0), potential=0.0, mass=1.0):
    """L = ½ m (ṙ + ω×r)² - m a0·r - V (Theory §8.1), J.

    Examples
    --------
    >>> float(lagrangian([1, 0, 0], [0, 1, 0], [0, 0, 1]))
    2.0
    """
    r, v, omega, a0 = _vectors(r=r, v=v, omega=omega, a0=a0)
    potential = as_float_array(potential, "potential")
    m = positive_array(mass, "mass")

    def compute():
        # the inertial speed as a whole: its square overflows only when the kinetic energy does, and
        # ṙ and ω×r may cancel
        speed = norm(v + np.cross(omega, r))
        return 0.5 * m * speed * speed, -m * _dot(a0, r), -potential

    return sum(_energy_terms(compute, "Lagrangian", "r, v, omega, a0, potential and mass"))


def hamiltonian_terms(r, p, omega, a0=(0.0, 0.0, 0.0), potential=0.0, mass=1.0):
    """The terms of H(r, p) = p²/2m - p·(ω×r) + m a0·r + V (Theory §8.1).

    Parameters
    ----------
    r, p : (..., 3) array_like
        Position and canonical momentum (:func:`canonical_momentum`).
    omega, a0, potential, mass
        As in :func:`lagrangian_terms`.

    Returns
    -------
    HamiltonianTerms

    Examples
    --------
    >>> h = hamiltonian_terms([1, 0, 0], [0, 2, 0], [0, 0, 1])
    >>> float(h.kinetic), float(h.coriolis)
    (2.0, -2.0)
    """
    r, p, omega, a0 = _vectors(r=r, p=p, omega=omega, a0=a0)
    potential = as_float_array(potential, "potential")
    m = positive_array(mass, "mass")

    def compute():
        return _dot(p, p) / (2.0 * m), -_dot(p, np.cross(omega, r)), m * _dot(a0, r), potential

    return HamiltonianTerms(*_energy_terms(compute, "Hamiltonian", "r, p, omega, a0, potential and mass"))


def hamiltonian(r, p, omega, a0=(0.0, 0.0, 0.0), potential=0.0, mass=1.0):
    """H(r, p) of Theory §8.1; conserved (the Jacobi integral) when ω, a0, V do not depend on t.

    Examples
    --------
    >>> float(hamiltonian([1, 0, 0], [0, 1, 0], [0, 0, 1]))
    -0.5
    """
    return sum(hamiltonian_terms(r, p, omega, a0, potential, mass))
