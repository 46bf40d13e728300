"""Mass properties (mass, centre of mass, central inertia) and composite bodies."""

from __future__ import annotations

from collections.abc import Iterable
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validation import as_float, as_float_array, check_inertia_tensor, check_principal_moments, positive_array
from ..so3._coercion import RotationLike
from .tensors import (
    _outer_term,
    as_rotation_matrix,
    point_inertia,
)

__all__ = ["MassProperties", "from_points", "combine"]


class MassProperties(NamedTuple):
    """Mass, centre of mass and inertia tensor about the centre of mass.

    Attributes
    ----------
    mass : float
        kg.
    com : (3,) ndarray
        Centre of mass, m, in the coordinates the body was described in.
    inertia : (3, 3) ndarray
        Inertia tensor about ``com`` in the same axes, kg m².

    Examples
    --------
    :func:`from_points` returns the mass properties of point masses; the
    parallel-axis theorem gives the tensor about any other point:

    >>> import kreisel as kr
    >>> p = kr.inertia.from_points([1.0, 3.0], [[0.0, 0.0, 0.0], [4.0, 0.0, 0.0]])
    >>> p.mass, p.com.tolist()
    (4.0, [3.0, 0.0, 0.0])
    >>> p.inertia.diagonal().round(12).tolist(), p.about([0, 0, 0]).diagonal().round(12).tolist()
    ([0.0, 12.0, 12.0], [0.0, 48.0, 48.0])
    """

    mass: float
    com: np.ndarray
    inertia: np.ndarray

    def about(self, point: ArrayLike) -> NDArray[np.float64]:
        """Inertia tensor about ``point`` (same axes), by the parallel-axis theorem (Theory §4.1).

        Examples
        --------
        >>> import numpy as np, kreisel as kr
        >>> rod = kr.inertia.MassProperties(3.0, np.array([0, 0, 1.0]), kr.inertia.thin_rod(3.0, 2.0))
        >>> rod.about([0, 0, 0]).diagonal()
        array([4., 4., 0.])
        """
        p = as_float_array(point, "point", tail=(3,))
        return self.inertia + _outer_term(self.mass, self.com - p)

    def transformed(self, position: ArrayLike | None = None, rotation: RotationLike | None = None) -> MassProperties:
        """The same body placed at a pose: com → position + R com, I → R I Rᵀ.

        Parameters
        ----------
        position : (3,) array_like, optional
            Where the origin of the body's coordinates goes (default: stays).
        rotation : (3, 3) or (4,) array_like or rotation object, optional
            Orientation R of the body's axes (body → new components).

        Examples
        --------
        >>> import numpy as np, kreisel as kr
        >>> part = kr.inertia.MassProperties(1.0, np.zeros(3), np.diag([1.0, 2.0, 3.0]))
        >>> moved = part.transformed([1.0, 0, 0], [np.sqrt(0.5), 0, 0, np.sqrt(0.5)])
        >>> moved.com
        array([1., 0., 0.])
        >>> np.round(moved.inertia.diagonal(), 12)
        array([2., 1., 3.])
        """
        com = np.asarray(self.com, dtype=np.float64)
        inertia = np.asarray(self.inertia, dtype=np.float64)
        if rotation is not None:
            R = as_rotation_matrix(rotation)
            if R.shape != (3, 3):
                raise ValueError(f"rotation must describe a single rotation, got shape {R.shape}")
            com = R @ com
            inertia = R @ inertia @ R.T
            inertia = 0.5 * (inertia + inertia.T)
        if position is not None:
            com = com + as_float_array(position, "position", tail=(3,)).reshape(3)
        return MassProperties(self.mass, com, inertia)


def from_points(masses: ArrayLike, positions: ArrayLike) -> MassProperties:
    """Mass properties of a set of point masses.

    Parameters
    ----------
    masses : (N,) array_like
        Point masses >= 0 with a positive sum, kg.
    positions : (N, 3) array_like
        Positions, m.

    Returns
    -------
    MassProperties
        Inertia about the centre of mass.

    Examples
    --------
    >>> import kreisel as kr
    >>> p = kr.inertia.from_points([1.0, 3.0], [[0, 0, 0], [4.0, 0, 0]])
    >>> p.com
    array([3., 0., 0.])
    >>> p.inertia.diagonal()
    array([ 0., 12., 12.])
    """
    m = positive_array(masses, "masses", allow_zero=True)
    r = as_float_array(positions, "positions", tail=(3,))
    if m.ndim != 1 or r.shape != (m.size, 3):
        raise ValueError(f"masses must be (N,) and positions (N, 3), got {m.shape} and {r.shape}")
    with np.errstate(over="ignore"):
        total = float(np.sum(m))
    if total <= 0.0:
        raise ValueError("masses must have a positive sum")
    if total == np.inf:
        raise ValueError("masses are out of range: their sum overflows double precision (exceeds 1.8e308 kg)")
    # weights scaled by a power of two near the total (exact): m @ r cannot overflow on the way to the mean
    j = np.frexp(total)[1]
    # (contiguous: a strided view takes another BLAS path and rounds differently)
    com = np.ldexp(m, -j) @ np.ascontiguousarray(r) / np.ldexp(total, -j)
    with np.errstate(over="ignore"):
        offsets = r - com
    if not np.isfinite(offsets).all():
        raise ValueError("positions are out of range: their distances from the centre of mass overflow double precision")
    return MassProperties(total, com, point_inertia(m, offsets))


def _as_part(entry: object, index: int) -> MassProperties:
    """(MassProperties, position, rotation) from one entry of ``combine``'s parts.

    A :class:`~kreisel.RigidBody` is recognised by its ``mass_properties``
    (the body layer sits above this module).
    """
    if isinstance(entry, MassProperties) or hasattr(entry, "mass_properties"):
        item, position, rotation = entry, None, None
    elif isinstance(entry, tuple) and 2 <= len(entry) <= 3:
        item, position, rotation = (*entry, None)[:3]
    else:
        raise TypeError(
            f"parts[{index}] must be a MassProperties, a RigidBody, or a tuple "
            "(part, position) / (part, position, rotation)"
        )
    if hasattr(item, "mass_properties"):
        item = item.mass_properties
    if not isinstance(item, MassProperties):
        raise TypeError(f"parts[{index}] must hold a MassProperties or RigidBody, got {type(item).__name__}")
    mass = as_float(item.mass, f"parts[{index}].mass")
    if mass == 0.0:
        raise ValueError(f"parts[{index}].mass must be nonzero")
    com = as_float_array(item.com, f"parts[{index}].com", tail=(3,)).reshape(3)
    inertia = check_inertia_tensor(item.inertia, f"parts[{index}].inertia")
    if inertia.shape != (3, 3):
        raise ValueError(f"parts[{index}].inertia must be a single (3, 3) tensor")
    return MassProperties(mass, com, inertia).transformed(position, rotation)


def combine(parts: Iterable[object]) -> MassProperties:
    """Mass properties of a body built from parts placed at poses.

    M = Σ m_i, C = Σ m_i c_i / M, I_C = Σ [R_i I_i R_iᵀ + m_i (d_i² 1 − d_i d_iᵀ)]
    with d_i = c_i − C (parallel-axis theorem, Theory §4.1).

    Parameters
    ----------
    parts : iterable
        Each entry is a :class:`MassProperties` or :class:`RigidBody` (whose
        centre of mass is taken at its body origin), optionally as a tuple
        ``(part, position)`` or ``(part, position, rotation)``: the part's own
        coordinate frame is placed with its origin at ``position`` and its
        axes rotated by ``rotation`` (3×3 matrix, scalar-first quaternion or
        rotation object, part → composite components). A part with negative
        mass and negated inertia subtracts material (a hole); the total must
        remain physical.

    Returns
    -------
    MassProperties
        About the composite centre of mass, in composite axes.

    Examples
    --------
    Two unit point-like spheres 2 m apart behave like a dumbbell.

    >>> import numpy as np, kreisel as kr
    >>> ball = kr.inertia.MassProperties(1.0, np.zeros(3), kr.inertia.solid_sphere(1.0, 0.1))
    >>> dumbbell = kr.inertia.combine([(ball, [-1.0, 0, 0]), (ball, [1.0, 0, 0])])
    >>> dumbbell.inertia.diagonal()
    array([0.008, 2.008, 2.008])
    """
    items = [_as_part(entry, k) for k, entry in enumerate(parts)]
    if not items:
        raise ValueError("parts must contain at least one part")
    masses = np.array([p.mass for p in items])
    coms = np.array([p.com for p in items])
    total = float(np.sum(masses))
    if total <= 0.0:
        raise ValueError(f"parts must have a positive total mass, got {total!r}")
    com = masses @ coms / total
    inertia = np.sum([p.inertia for p in items], axis=0) + np.sum(_outer_term(masses, coms - com), axis=0)
    check_principal_moments(np.linalg.eigvalsh(inertia), "combined inertia", definite=False)
    return MassProperties(total, com, inertia)
