"""Inertia tensors as arrays: point sets, the parallel-axis theorem, rotation
into other axes, principal axes, moments about an axis, radius of gyration and
the inertia ellipsoid (Theory §4.1–3).

Every function broadcasts over leading axes: a tensor is ``(..., 3, 3)``, a
vector ``(..., 3)``, a mass ``(...)``.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .._validation import as_float_array, check_inertia_tensor, check_principal_moments, positive_array
from ..so3._coercion import as_rotation_matrix
from .._norms import unit

__all__ = [
    "points",
    "parallel_axis",
    "parallel_axis_to_center_of_mass",
    "rotate",
    "principal_axes",
    "moment_about_axis",
    "radius_of_gyration",
    "inertia_ellipsoid",
    "InertiaEllipsoid",
]



def _outer_term(mass, r):
    """M (r² 1 − r rᵀ), the inertia of a point mass M at r about the origin; refused when it overflows."""
    return point_inertia(np.asarray(mass)[..., None], np.asarray(r)[..., None, :], "r_c is")


def _binary_exponent(x, axis):
    """e with max |x| over ``axis`` in [2^(e-1), 2^e) (0 where all are zero): dividing by 2^e is exact."""
    return np.frexp(np.max(np.abs(x), axis=axis))[1]


def _out_of_range(value, names):
    """``value`` scaled back by :func:`numpy.ldexp`: refused naming ``names`` where it overflows."""
    if not np.isfinite(value).all():
        raise ValueError(f"{names} out of range: the moment of inertia would overflow double precision "
                         "(exceed 1.8e308 kg m²)")
    return value


def point_inertia(masses, positions, names="masses and positions are"):
    """Σ m (r² 1 − r rᵀ) over axis -2 of ``positions`` (``(..., N, 3)``), for any finite magnitudes.

    Masses and positions are divided by powers of two (exact) that bring the total mass and the
    largest position near 1 before any product is taken, and the tensor is scaled back at the end:
    the result is the plain sum wherever that does not overflow or underflow, and a result too
    large for double precision is refused naming ``names``.
    """
    m, r = np.broadcast_arrays(np.asarray(masses)[..., None], positions)
    with np.errstate(over="ignore"):
        j = np.frexp(np.sum(m[..., 0], axis=-1))[1]
        k = _binary_exponent(r, axis=(-2, -1))
        m_scaled = np.ldexp(m[..., 0], -j[..., None])
        r_scaled = np.ldexp(r, -k[..., None, None])
        second_moment = np.einsum("...n,...ni,...nj->...ij", m_scaled, r_scaled, r_scaled)
        return _out_of_range(np.ldexp(second_moment_to_inertia(second_moment), (j + 2 * k)[..., None, None]), names)


def second_moment_to_inertia(second_moment):
    """Inertia I = tr(S) 1 − S from the second moment S = ∫ ρ r rᵀ dV (Theory §4.1)."""
    trace = np.trace(second_moment, axis1=-2, axis2=-1)
    return trace[..., None, None] * np.eye(3) - second_moment


def points(masses, positions):
    """Inertia tensor of point masses about the origin (Theory §4.1).

    I = Σ_P m_P (r_P² 1 − r_P r_Pᵀ).

    Parameters
    ----------
    masses : (..., N) array_like
        Point masses, kg, each >= 0.
    positions : (..., N, 3) array_like
        Positions seen from the reference point, m.

    Returns
    -------
    (..., 3, 3) ndarray
        Inertia tensor about the origin of ``positions``, kg m².

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.points([1.0, 1.0], [[1.0, 0, 0], [-1.0, 0, 0]])
    array([[0., 0., 0.],
           [0., 2., 0.],
           [0., 0., 2.]])
    """
    m = positive_array(masses, "masses", allow_zero=True)
    r = as_float_array(positions, "positions", tail=(3,))
    if r.ndim < 2:
        raise ValueError(f"positions must have shape (..., N, 3), got {r.shape}")
    try:
        np.broadcast_shapes(m.shape, r.shape[:-1])
    except ValueError:
        raise ValueError(
            f"masses {m.shape} and positions {r.shape} do not broadcast as (..., N) and (..., N, 3)"
        ) from None
    return point_inertia(m, r)


def parallel_axis(I_cm, mass, r_c):
    """Move an inertia tensor from the centre of mass to another point (Theory §4.1).

    I = I_C + M (r_C² 1 − r_C r_Cᵀ), with r_C the centre of mass seen from
    the new reference point.

    Parameters
    ----------
    I_cm : (..., 3, 3) array_like
        Inertia tensor about the centre of mass, kg m².
    mass : (...) array_like
        Total mass M > 0, kg.
    r_c : (..., 3) array_like
        Position of the centre of mass relative to the new point, m.

    Returns
    -------
    (..., 3, 3) ndarray
        Inertia tensor about the new point, same axes.

    See Also
    --------
    parallel_axis_to_center_of_mass : the inverse shift.

    Examples
    --------
    A rod of length 2 about its end: m L²/12 + m (L/2)² = m L²/3.

    >>> import kreisel as kr
    >>> I = kr.inertia.parallel_axis(kr.inertia.thin_rod(3.0, 2.0), 3.0, [0, 0, 1.0])
    >>> I.diagonal()
    array([4., 4., 0.])
    """
    I_c = check_inertia_tensor(I_cm, "I_cm")
    m = positive_array(mass, "mass")
    r = as_float_array(r_c, "r_c", tail=(3,))
    return I_c + _outer_term(m, r)


def parallel_axis_to_center_of_mass(I_point, mass, r_c):
    """Inverse of :func:`parallel_axis`: I_C = I_O − M (r_C² 1 − r_C r_Cᵀ).

    Parameters
    ----------
    I_point : (..., 3, 3) array_like
        Inertia tensor about a point O, kg m².
    mass : (...) array_like
        Total mass M > 0, kg.
    r_c : (..., 3) array_like
        Position of the centre of mass relative to O, m.

    Returns
    -------
    (..., 3, 3) ndarray
        Inertia tensor about the centre of mass. Note the subtraction loses
        relative accuracy when M r_C² dominates I_O.

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.parallel_axis_to_center_of_mass([[4.0, 0, 0], [0, 4, 0], [0, 0, 0]], 3.0, [0, 0, 1])
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 0.]])
    """
    I_o = check_inertia_tensor(I_point, "I_point")
    m = positive_array(mass, "mass")
    r = as_float_array(r_c, "r_c", tail=(3,))
    return I_o - _outer_term(m, r)


def rotate(I, rotation):
    """Express an inertia tensor in rotated axes: I′ = R I Rᵀ.

    With ``R`` mapping body components to space components (a = R a′),
    ``rotate(I_body, R)`` is the tensor in space axes — equivalently the
    tensor, in unchanged axes, of the body after rotating it actively by R.
    Use the transpose (or the inverse quaternion) for the opposite direction.

    Parameters
    ----------
    I : (..., 3, 3) array_like
        Symmetric inertia tensor.
    rotation : (..., 3, 3) or (..., 4) array_like or rotation object
        Rotation matrix, scalar-first quaternion, or an object with ``as_matrix()``.

    Returns
    -------
    (..., 3, 3) ndarray

    Examples
    --------
    A quarter turn about z swaps the x and y moments.

    >>> import numpy as np, kreisel as kr
    >>> q = [np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)]
    >>> np.round(kr.inertia.rotate(np.diag([1.0, 2.0, 3.0]), q), 12).diagonal()
    array([2., 1., 3.])
    """
    tensor = check_inertia_tensor(I, "I")
    R = as_rotation_matrix(rotation)
    out = R @ tensor @ np.swapaxes(R, -1, -2)
    return 0.5 * (out + np.swapaxes(out, -1, -2))


def principal_axes(I: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Principal moments and principal axes of an inertia tensor (Theory §4.2).

    Parameters
    ----------
    I : (..., 3, 3) array_like
        Symmetric tensor.

    Returns
    -------
    moments : (..., 3) ndarray
        Principal moments in ascending order.
    R : (..., 3, 3) ndarray
        Proper rotation (det +1) whose columns are the principal axes, so that
        I = R diag(moments) Rᵀ. Signs are fixed: the largest component of the
        first two axes is positive and the third is their cross product. For
        repeated moments (symmetric top, sphere) any orthonormal basis of the
        degenerate plane is a valid answer; the one returned is orthonormal to
        rounding and reconstructs I to rounding, and an already diagonal tensor
        gives a permutation of the coordinate axes.

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> moments, R = kr.inertia.principal_axes(np.diag([3.0, 1.0, 2.0]))
    >>> moments
    array([1., 2., 3.])
    >>> R
    array([[0., 0., 1.],
           [1., 0., 0.],
           [0., 1., 0.]])
    """
    tensor = check_inertia_tensor(I, "I")
    moments, vectors = np.linalg.eigh(tensor)
    first_two = vectors[..., :, :2]
    index = np.argmax(np.abs(first_two), axis=-2)[..., None, :]
    sign = np.where(np.take_along_axis(first_two, index, axis=-2) < 0, -1.0, 1.0)
    first_two = first_two * sign
    third = np.cross(first_two[..., :, 0], first_two[..., :, 1])
    R = np.concatenate([first_two, third[..., :, None]], axis=-1)
    return moments, R


def _unit(axis, name="axis"):
    return unit(as_float_array(axis, name, tail=(3,)), name)


def moment_about_axis(I, axis):
    """Moment of inertia about an axis through the reference point: I_n = nᵀ I n (Theory §4.3).

    Parameters
    ----------
    I : (..., 3, 3) array_like
        Inertia tensor.
    axis : (..., 3) array_like
        Axis direction (need not be unit: it is normalised).

    Returns
    -------
    (...) ndarray

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> round(float(kr.inertia.moment_about_axis(np.diag([1.0, 2.0, 3.0]), [1.0, 1.0, 0.0])), 12)
    1.5
    """
    tensor = check_inertia_tensor(I, "I")
    n = _unit(axis)
    return np.einsum("...i,...ij,...j->...", n, tensor, n)


def radius_of_gyration(I, mass, axis):
    """Radius of gyration k = sqrt(I_n / m) about an axis (Theory §4.3).

    Parameters
    ----------
    I : (..., 3, 3) array_like
        Inertia tensor about a point on the axis.
    mass : (...) array_like
        Mass m > 0.
    axis : (..., 3) array_like
        Axis direction (normalised).

    Returns
    -------
    (...) ndarray
        k in metres.

    Examples
    --------
    A thin ring about its axis has k equal to its radius.

    >>> import kreisel as kr
    >>> float(kr.inertia.radius_of_gyration(kr.inertia.thin_ring(2.0, 0.5), 2.0, [0, 0, 1]))
    0.5
    """
    m = positive_array(mass, "mass")
    moment = moment_about_axis(I, axis)
    # rounding can leave a zero moment slightly negative
    return np.sqrt(np.maximum(moment, 0.0) / m)


class InertiaEllipsoid(NamedTuple):
    """The surface xᵀ I x = 1 (Theory §4.3): its semi-axes, axes and a sampled surface.

    Attributes
    ----------
    semi_axes : (..., 3) ndarray
        1/sqrt(I_k) for the ascending principal moments I_k (so descending).
    axes : (..., 3, 3) ndarray
        Columns are the principal directions matching ``semi_axes``.
    x, y, z : (..., n_polar, n_azimuth) ndarray
        Surface points for plotting (e.g. ``plot_surface(x, y, z)``).

    Examples
    --------
    Every sampled surface point x satisfies xᵀ I x = 1; the longest semi-axis
    lies along the axis of smallest moment:

    >>> import numpy as np, kreisel as kr
    >>> I = np.diag([3.0, 1.0, 2.0])
    >>> e = kr.inertia.inertia_ellipsoid(I)
    >>> e.semi_axes.round(6).tolist(), np.abs(e.axes[:, 0]).tolist()
    ([1.0, 0.707107, 0.57735], [0.0, 1.0, 0.0])
    >>> xyz = np.stack([e.x, e.y, e.z], -1)
    >>> bool(np.allclose(np.einsum("...i,ij,...j->...", xyz, I, xyz), 1.0))
    True
    """

    semi_axes: np.ndarray
    axes: np.ndarray
    x: np.ndarray
    y: np.ndarray
    z: np.ndarray


def inertia_ellipsoid(I, n_polar=25, n_azimuth=49):
    """Inertia ellipsoid xᵀ I x = 1 of a tensor (Theory §4.3).

    A point at distance ρ along a unit direction n lies on the surface when
    ρ = 1/sqrt(I_n), I_n the moment about n.

    Parameters
    ----------
    I : (..., 3, 3) array_like
        Positive definite inertia tensor (a zero moment would make the
        surface an unbounded cylinder and is refused).
    n_polar, n_azimuth : int
        Surface samples in polar angle (pole to pole) and azimuth (closed loop).

    Returns
    -------
    InertiaEllipsoid

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> e = kr.inertia.inertia_ellipsoid(np.diag([1.0, 4.0, 16.0]))
    >>> e.semi_axes
    array([1.  , 0.5 , 0.25])
    >>> e.x.shape
    (25, 49)
    """
    for value, label in ((n_polar, "n_polar"), (n_azimuth, "n_azimuth")):
        if not isinstance(value, (int, np.integer)) or value < 2:
            raise ValueError(f"{label} must be an integer >= 2, got {value!r}")
    moments, R = principal_axes(I)
    # the surface needs only I > 0; drawing it for a textbook body that breaks the triangle inequality is fine
    check_principal_moments(moments, "I", allow_unphysical=True)
    semi = 1.0 / np.sqrt(moments)
    polar = np.linspace(0.0, np.pi, n_polar)[:, None]
    azimuth = np.linspace(0.0, 2.0 * np.pi, n_azimuth)[None, :]
    unit = np.stack(
        np.broadcast_arrays(np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)),
        axis=-1,
    )  # (n_polar, n_azimuth, 3) in principal axes
    scaled = unit * semi[..., None, None, :]
    surface = np.einsum("...ij,...pqj->...pqi", R, scaled)
    return InertiaEllipsoid(semi, R, surface[..., 0], surface[..., 1], surface[..., 2])
