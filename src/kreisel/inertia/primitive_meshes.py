"""Closed, outward-oriented triangle meshes of the primitive solids.

Each function returns ``(vertices, faces)`` — ``(N, 3)`` floats and ``(F, 3)``
vertex indices, counter-clockwise seen from outside — ready for
:func:`kreisel.inertia.from_mesh` or for drawing. Axes and placement match
the solids of :mod:`kreisel.inertia.solids` (centred on the origin, axis z),
except the cone, whose base lies in z = 0 with the apex at z = height.
Curved surfaces are polyhedral approximations: a regular n-gon in azimuth,
inscribed in the true surface.
"""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array

__all__ = ["box_mesh", "surface_of_revolution", "ellipsoid_mesh", "cylinder_mesh", "cone_mesh", "torus_mesh"]

_BOX_CORNERS = np.array(
    [[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]
)
# two triangles per side, counter-clockwise seen from outside
_BOX_FACES = np.array(
    [
        [0, 1, 3], [0, 3, 2],  # x = -1/2
        [4, 6, 7], [4, 7, 5],  # x = +1/2
        [0, 4, 5], [0, 5, 1],  # y = -1/2
        [2, 3, 7], [2, 7, 6],  # y = +1/2
        [0, 2, 6], [0, 6, 4],  # z = -1/2
        [1, 5, 7], [1, 7, 3],  # z = +1/2
    ]
)


def _count(n, name, minimum=3):
    if not isinstance(n, (int, np.integer)) or n < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {n!r}")
    return int(n)


def _positive_scalar(x, name):
    a = as_float_array(x, name)
    if a.ndim != 0 or not a > 0:
        raise ValueError(f"{name} must be a positive scalar, got {x!r}")
    return float(a)


def box_mesh(size):
    """Box centred on the origin with full edge lengths ``size`` (8 vertices, 12 triangles).

    Examples
    --------
    >>> import kreisel as kr
    >>> v, f = kr.inertia.primitive_meshes.box_mesh((1.0, 2.0, 3.0))
    >>> v.shape, f.shape
    ((8, 3), (12, 3))
    """
    edges = as_float_array(size, "size", tail=(3,))
    if edges.shape != (3,) or np.any(edges <= 0):
        raise ValueError(f"size must be three positive edge lengths, got {size!r}")
    return _BOX_CORNERS * edges, _BOX_FACES.copy()


def surface_of_revolution(profile, n_azimuth, closed=False):
    """Revolve a profile polyline about the z axis into a closed triangle mesh.

    Parameters
    ----------
    profile : (K, 2) array_like
        Points (ρ, z), ρ >= 0, traversed counter-clockwise in the (ρ, z)
        half-plane (the solid on the left). An open profile must start and
        end on the axis (ρ = 0), which become single pole vertices; a closed
        profile (``closed=True``, e.g. a torus tube) must stay off the axis.
    n_azimuth : int
        Number of azimuthal segments (>= 3).
    closed : bool
        Whether the last profile point connects back to the first.

    Returns
    -------
    vertices : (N, 3) ndarray
    faces : (F, 3) ndarray of int

    Examples
    --------
    A cone of radius 1 and height 2 as a pyramid over a regular 16-gon:

    >>> import kreisel as kr
    >>> v, f = kr.inertia.primitive_meshes.surface_of_revolution([[0, 0], [1, 0], [0, 2]], 16)
    >>> v.shape, f.shape
    ((18, 3), (32, 3))
    """
    p = as_float_array(profile, "profile", tail=(2,))
    n = _count(n_azimuth, "n_azimuth")
    if p.ndim != 2 or p.shape[0] < 3:
        raise ValueError(f"profile must have shape (K, 2) with K >= 3, got {p.shape}")
    rho, z = p[:, 0], p[:, 1]
    if np.any(rho < 0):
        raise ValueError("profile radii must be >= 0")
    on_axis = rho == 0.0
    if closed and np.any(on_axis):
        raise ValueError("a closed profile must stay off the axis (rho > 0)")
    if not closed and not (on_axis[0] and on_axis[-1] and not np.any(on_axis[1:-1])):
        raise ValueError("an open profile must start and end on the axis (rho = 0) and leave it between")

    phi = 2.0 * np.pi * np.arange(n) / n
    index = np.empty((p.shape[0], n), dtype=np.int64)
    vertices = []
    for k in range(p.shape[0]):
        start = len(vertices)
        if on_axis[k]:
            vertices.append([0.0, 0.0, z[k]])
            index[k] = start
        else:
            vertices.extend(np.stack([rho[k] * np.cos(phi), rho[k] * np.sin(phi), np.full(n, z[k])], axis=1))
            index[k] = start + np.arange(n)

    segments = [(k, k + 1) for k in range(p.shape[0] - 1)]
    if closed:
        segments.append((p.shape[0] - 1, 0))
    faces = []
    nxt = np.roll(np.arange(n), -1)
    for k, l in segments:
        a, b = index[k], index[k][nxt]
        c, d = index[l][nxt], index[l]
        if not on_axis[k]:
            faces.append(np.stack([a, b, c], axis=1))
        if not on_axis[l]:
            faces.append(np.stack([a, c, d], axis=1))
    return np.asarray(vertices, dtype=np.float64), np.concatenate(faces)


def ellipsoid_mesh(semi_axes, n_polar=32, n_azimuth=64):
    """Ellipsoid with semi-axes (a, b, c) along x, y, z: a scaled latitude–longitude sphere.

    Examples
    --------
    >>> import kreisel as kr
    >>> v, f = kr.inertia.primitive_meshes.ellipsoid_mesh((1.0, 2.0, 3.0), 8, 12)
    >>> v.shape, f.shape
    ((86, 3), (168, 3))
    """
    semi = as_float_array(semi_axes, "semi_axes", tail=(3,))
    if semi.shape != (3,) or np.any(semi <= 0):
        raise ValueError(f"semi_axes must be three positive lengths, got {semi_axes!r}")
    polar = np.linspace(np.pi, 0.0, _count(n_polar, "n_polar", 2) + 1)
    profile = np.stack([np.sin(polar), np.cos(polar)], axis=1)
    profile[[0, -1], 0] = 0.0
    vertices, faces = surface_of_revolution(profile, n_azimuth)
    return vertices * semi, faces


def cylinder_mesh(radius, height, n_azimuth=64, inner_radius=None):
    """Cylinder (or tube with ``inner_radius`` > 0), axis z, centred on the origin.

    Examples
    --------
    >>> import kreisel as kr
    >>> v, f = kr.inertia.primitive_meshes.cylinder_mesh(1.0, 2.0, 16, inner_radius=0.5)
    >>> v.shape, f.shape
    ((64, 3), (128, 3))
    """
    R = _positive_scalar(radius, "radius")
    h = 0.5 * _positive_scalar(height, "height")
    if inner_radius is None:
        return surface_of_revolution([[0.0, -h], [R, -h], [R, h], [0.0, h]], n_azimuth)
    r = _positive_scalar(inner_radius, "inner_radius")
    if r >= R:
        raise ValueError("inner_radius must be smaller than radius")
    return surface_of_revolution([[r, -h], [R, -h], [R, h], [r, h]], n_azimuth, closed=True)


def cone_mesh(radius, height, n_azimuth=64):
    """Cone, axis z, base disk of ``radius`` in z = 0, apex at z = ``height``.

    Examples
    --------
    >>> import kreisel as kr
    >>> v, f = kr.inertia.primitive_meshes.cone_mesh(1.0, 2.0, 16)
    >>> v.shape, f.shape
    ((18, 3), (32, 3))
    """
    R = _positive_scalar(radius, "radius")
    h = _positive_scalar(height, "height")
    return surface_of_revolution([[0.0, 0.0], [R, 0.0], [0.0, h]], n_azimuth)


def torus_mesh(major_radius, minor_radius, n_major=64, n_minor=32):
    """Torus about the z axis, centred on the origin, tube radius ``minor_radius`` < ``major_radius``.

    Examples
    --------
    >>> import kreisel as kr
    >>> v, f = kr.inertia.primitive_meshes.torus_mesh(1.0, 0.25, 16, 8)
    >>> v.shape, f.shape
    ((128, 3), (256, 3))
    """
    R = _positive_scalar(major_radius, "major_radius")
    a = _positive_scalar(minor_radius, "minor_radius")
    if a >= R:
        raise ValueError("minor_radius must be smaller than major_radius")
    angle = 2.0 * np.pi * np.arange(_count(n_minor, "n_minor")) / n_minor
    # counter-clockwise around the tube centre in the (rho, z) plane
    profile = np.stack([R + a * np.cos(angle), a * np.sin(angle)], axis=1)
    return surface_of_revolution(profile, n_major, closed=True)
