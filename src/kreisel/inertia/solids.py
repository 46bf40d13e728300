"""Inertia tensors of homogeneous primitive solids, shells and thin bodies.

Each function returns the ``(..., 3, 3)`` tensor about the centre of mass (the
cone can also be taken about its apex or base) in the body axes documented on
it; bodies of revolution have their symmetry axis along z. Arguments
broadcast over leading axes. Formulas are the textbook integrals of
I = ∫ ρ (r² 1 − r rᵀ) dV (Theory §4.1).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validation import as_float_array, positive_array
from .tensors import _binary_exponent, _out_of_range

__all__ = [
    "box",
    "solid_sphere",
    "hollow_sphere",
    "solid_cylinder",
    "hollow_cylinder",
    "solid_cone",
    "solid_ellipsoid",
    "thin_rod",
    "thin_disk",
    "thin_ring",
    "torus",
]


def _radii(outer, outer_name, inner, inner_name, allow_zero=True, reason=""):
    """An outer length and an inner one that must not exceed it (``inner=None``: equal to it)."""
    big = positive_array(outer, outer_name)
    small = big if inner is None else positive_array(inner, inner_name, allow_zero=allow_zero)
    if np.any(small > big):
        raise ValueError(f"{inner_name} must not exceed {outer_name}{reason}")
    return big, small


def _diagonal(xx, yy, zz):
    """Diagonal tensors ``(..., 3, 3)`` from broadcastable moments."""
    xx, yy, zz = np.broadcast_arrays(xx, yy, zz)
    out = np.zeros(xx.shape + (3, 3))
    out[..., 0, 0] = xx
    out[..., 1, 1] = yy
    out[..., 2, 2] = zz
    return out


def _axisymmetric(transverse, axial):
    """diag(I_⊥, I_⊥, I_z): the tensor of a body of revolution about z."""
    return _diagonal(transverse, transverse, axial)


def _moment(mass, terms, names):
    """m Σ_k w_k l_k² for the (weight, length) pairs ``terms``, for any finite magnitudes.

    The mass and the lengths are divided by powers of two (exact) that bring the mass and the
    largest length near 1 and the product is scaled back at the end: the plain formula's value
    wherever that does not overflow or underflow; a moment too large for double precision is
    refused naming ``names`` (e.g. ``"mass and radius are"``).
    """
    weights = [w for w, _ in terms]
    lengths = np.stack(np.broadcast_arrays(*[length for _, length in terms]))
    j = np.frexp(mass)[1]
    k = _binary_exponent(lengths, axis=0)
    scaled = np.ldexp(lengths, -k)
    total = sum(w * x * x for w, x in zip(weights, scaled))
    with np.errstate(over="ignore"):
        return _out_of_range(np.ldexp(np.ldexp(mass, -j) * total, j + 2 * k), names)


def _from_extents(mass, lengths, weight, names):
    """m w diag(b² + c², a² + c², a² + b²) for per-axis lengths (a, b, c) = ``lengths``."""
    m = positive_array(mass, "mass")
    a, b, c = np.moveaxis(lengths, -1, 0)
    return _diagonal(*(_moment(m, [(weight, x), (weight, y)], names) for x, y in ((b, c), (a, c), (a, b))))


def _round(mass, radius, transverse, axial):
    """m r² diag(transverse, transverse, axial): a body of revolution whose moments scale with r² alone."""
    m = positive_array(mass, "mass")
    r = positive_array(radius, "radius")
    names = "mass and radius are"
    return _axisymmetric(_moment(m, [(transverse, r)], names), _moment(m, [(axial, r)], names))


def box(mass: ArrayLike, size: ArrayLike) -> NDArray[np.float64]:
    """Solid rectangular box centred on the origin, edges along the axes.

    I = m/12 diag(b² + c², a² + c², a² + b²) for full edge lengths (a, b, c).

    Parameters
    ----------
    mass : (...) array_like
        Mass, kg.
    size : (..., 3) array_like
        Full edge lengths along x, y, z, m, each >= 0 (a zero edge gives a
        thin rectangular plate, two zero edges a thin rod).

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.box(12.0, (1.0, 2.0, 3.0))
    array([[13.,  0.,  0.],
           [ 0., 10.,  0.],
           [ 0.,  0.,  5.]])
    """
    edges = as_float_array(size, "size", tail=(3,))
    positive_array(edges, "size", allow_zero=True)
    return _from_extents(mass, edges, 1.0 / 12.0, "mass and size are")


def solid_ellipsoid(mass: ArrayLike, semi_axes: ArrayLike) -> NDArray[np.float64]:
    """Solid ellipsoid x²/a² + y²/b² + z²/c² <= 1.

    I = m/5 diag(b² + c², a² + c², a² + b²).

    Parameters
    ----------
    mass : (...) array_like
        Mass, kg.
    semi_axes : (..., 3) array_like
        Semi-axes (a, b, c) along x, y, z, m.

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.solid_ellipsoid(5.0, (1.0, 2.0, 3.0)).diagonal()
    array([13., 10.,  5.])
    """
    semi = as_float_array(semi_axes, "semi_axes", tail=(3,))
    positive_array(semi, "semi_axes")
    return _from_extents(mass, semi, 0.2, "mass and semi_axes are")


def solid_sphere(mass: ArrayLike, radius: ArrayLike) -> NDArray[np.float64]:
    """Solid ball: I = 2/5 m r² 1.

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.solid_sphere(5.0, 1.0).diagonal()
    array([2., 2., 2.])
    """
    return _round(mass, radius, 0.4, 0.4)


def hollow_sphere(mass: ArrayLike, radius: ArrayLike, inner_radius: ArrayLike | None = None) -> NDArray[np.float64]:
    """Spherical shell: thin (``inner_radius=None``) or thick (inner <= r <= radius).

    Thin shell: I = 2/3 m r². Thick shell: I = 2/5 m (R⁵ − r⁵)/(R³ − r³),
    evaluated as 2/5 m (R⁴ + R³r + R²r² + Rr³ + r⁴)/(R² + Rr + r²), which has
    no cancellation as r → R and tends to the thin-shell value there.

    Parameters
    ----------
    mass : (...) array_like
        Mass, kg.
    radius : (...) array_like
        Outer radius R of the shell, m.
    inner_radius : (...) array_like, optional
        Inner radius r, 0 <= r <= R; ``None`` means a thin shell (r = R).

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.hollow_sphere(3.0, 1.0).diagonal()
    array([2., 2., 2.])
    >>> kr.inertia.hollow_sphere(5.0, 1.0, 0.0).diagonal()   # the solid ball
    array([2., 2., 2.])
    """
    m = positive_array(mass, "mass")
    R, r = _radii(radius, "radius", inner_radius, "inner_radius")
    x = r / R  # in [0, 1]: the ratio of polynomials in R and r is R² times one in x, free of overflow
    ratio = (1.0 + x * (1.0 + x * (1.0 + x * (1.0 + x)))) / (1.0 + x * (1.0 + x))
    moment = _moment(m, [(0.4 * ratio, R)], "mass and radius are")
    return _diagonal(moment, moment, moment)


def solid_cylinder(mass: ArrayLike, radius: ArrayLike, height: ArrayLike) -> NDArray[np.float64]:
    """Solid circular cylinder, axis z, centred on the origin.

    I_z = m r²/2, I_x = I_y = m (3 r² + h²)/12.

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.solid_cylinder(12.0, 1.0, 3.0).diagonal()
    array([12., 12.,  6.])
    """
    return hollow_cylinder(mass, radius, height, inner_radius=0.0)


def hollow_cylinder(mass: ArrayLike, radius: ArrayLike, height: ArrayLike,
                    inner_radius: ArrayLike | None = None) -> NDArray[np.float64]:
    """Cylindrical tube, axis z, centred on the origin.

    I_z = m (R² + r²)/2, I_x = I_y = m (3 (R² + r²) + h²)/12, with outer
    radius R and inner radius r; ``inner_radius=None`` is a thin-walled tube
    (r = R: I_z = m R², I_x = m (6 R² + h²)/12).

    Parameters
    ----------
    mass : (...) array_like
        Mass, kg.
    radius : (...) array_like
        Outer radius R of the tube, m.
    height : (...) array_like
        Length along z, m.
    inner_radius : (...) array_like, optional
        Inner radius r, 0 <= r <= R.

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.hollow_cylinder(12.0, 1.0, 2.0).diagonal()
    array([10., 10., 12.])
    """
    m = positive_array(mass, "mass")
    R, r = _radii(radius, "radius", inner_radius, "inner_radius")
    h = positive_array(height, "height")
    names = "mass, radius and height are"
    return _axisymmetric(_moment(m, [(0.25, R), (0.25, r), (1.0 / 12.0, h)], names),
                         _moment(m, [(0.5, R), (0.5, r)], names))


_CONE_REFERENCE = {"center_of_mass": 0.0, "apex": 0.75, "base": -0.25}


def solid_cone(mass: ArrayLike, radius: ArrayLike, height: ArrayLike, about: str = "center_of_mass") -> NDArray[np.float64]:
    """Solid right circular cone, axis z.

    The centre of mass lies on the axis 3h/4 from the apex and h/4 from the
    centre of the base. I_z = 3/10 m r² about any point of the axis; the
    transverse moment is

    - about the centre of mass: 3/20 m r² + 3/80 m h²,
    - about the apex: 3/20 m r² + 3/5 m h²,
    - about the centre of the base: 3/20 m r² + 1/10 m h².

    Parameters
    ----------
    mass : (...) array_like
        Mass, kg.
    radius : (...) array_like
        Base radius, m.
    height : (...) array_like
        Apex-to-base height, m.
    about : {"center_of_mass", "apex", "base"}
        Reference point of the tensor (all on the z axis, so the tensor stays
        diagonal; which way the apex points does not change it).

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.solid_cone(20.0, 1.0, 1.0, about="apex").diagonal()
    array([15., 15.,  6.])
    """
    if about not in _CONE_REFERENCE:
        raise ValueError(f"about must be one of {sorted(_CONE_REFERENCE)}, got {about!r}")
    m = positive_array(mass, "mass")
    r = positive_array(radius, "radius")
    h = positive_array(height, "height")
    # distance from the reference point to the centre of mass along z, in units of h
    offset = _CONE_REFERENCE[about]
    names = "mass, radius and height are"
    return _axisymmetric(_moment(m, [(3.0 / 20.0, r), (3.0 / 80.0 + offset**2, h)], names),
                         _moment(m, [(0.3, r)], names))


def thin_rod(mass: ArrayLike, length: ArrayLike) -> NDArray[np.float64]:
    """Thin straight rod along z, centred on the origin: I = m L²/12 diag(1, 1, 0).

    The tensor is only semi-definite (no moment about the rod's own axis).
    For the tensor about an end use :func:`parallel_axis` with r_c = (0, 0, L/2).

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.thin_rod(3.0, 2.0).diagonal()
    array([1., 1., 0.])
    """
    m = positive_array(mass, "mass")
    L = positive_array(length, "length")
    transverse = _moment(m, [(1.0 / 12.0, L)], "mass and length are")
    return _axisymmetric(transverse, np.zeros_like(transverse))


def thin_disk(mass: ArrayLike, radius: ArrayLike) -> NDArray[np.float64]:
    """Thin uniform disk in the xy plane, centred on the origin.

    I_z = m r²/2, I_x = I_y = m r²/4 (a thin plate: I_z = I_x + I_y).

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.thin_disk(4.0, 1.0).diagonal()
    array([1., 1., 2.])
    """
    return _round(mass, radius, 0.25, 0.5)


def thin_ring(mass: ArrayLike, radius: ArrayLike) -> NDArray[np.float64]:
    """Thin circular hoop in the xy plane, centred on the origin.

    I_z = m r², I_x = I_y = m r²/2.

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.thin_ring(2.0, 1.0).diagonal()
    array([1., 1., 2.])
    """
    return _round(mass, radius, 0.5, 1.0)


def torus(mass: ArrayLike, major_radius: ArrayLike, minor_radius: ArrayLike) -> NDArray[np.float64]:
    """Solid torus about the z axis, centred on the origin.

    I_z = m (R² + 3/4 a²), I_x = I_y = m (R²/2 + 5/8 a²), with R the distance
    from the axis to the centre of the tube and a <= R the tube radius.

    Examples
    --------
    >>> import kreisel as kr
    >>> kr.inertia.torus(8.0, 1.0, 1.0).diagonal()
    array([ 9.,  9., 14.])
    """
    m = positive_array(mass, "mass")
    R, a = _radii(
        major_radius, "major_radius", minor_radius, "minor_radius", allow_zero=False, reason=" (a self-intersecting torus)"
    )
    names = "mass, major_radius and minor_radius are"
    return _axisymmetric(_moment(m, [(0.5, R), (0.625, a)], names), _moment(m, [(1.0, R), (0.75, a)], names))
