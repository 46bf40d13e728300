"""Exact mass properties of homogeneous polyhedra given as closed triangle meshes."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .._validation import as_float_array, out_of_range
from .properties import MassProperties
from .tensors import second_moment_to_inertia

__all__ = ["from_mesh"]


def _as_faces(faces, n_vertices):
    f = np.asarray(faces)
    if f.dtype.kind not in "iu":
        raise TypeError(f"faces must be an integer array of vertex indices, got dtype {f.dtype}")
    if f.ndim != 2 or f.shape[1] != 3:
        raise ValueError(f"faces must have shape (F, 3), got {f.shape}")
    if f.shape[0] < 4:
        raise ValueError(f"a closed triangle mesh needs at least 4 faces, got {f.shape[0]}")
    f = f.astype(np.int64)
    if f.min() < 0 or f.max() >= n_vertices:
        raise ValueError(f"faces must index vertices 0..{n_vertices - 1}, got indices {f.min()}..{f.max()}")
    repeated = (f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 2] == f[:, 0])
    if np.any(repeated):
        k = int(np.flatnonzero(repeated)[0])
        raise ValueError(f"face {k} {f[k].tolist()} repeats a vertex (degenerate triangle)")
    return f


def check_closed_oriented(faces, n_vertices):
    """Refuse a triangle mesh that is open or not consistently oriented.

    In a closed, consistently oriented (2-manifold) mesh every directed edge
    i → j occurs exactly once and its reverse j → i occurs exactly once (in
    the neighbouring face).

    Parameters
    ----------
    faces : (F, 3) ndarray of int
        Vertex indices of each triangle.
    n_vertices : int
        Number of vertices.

    Raises
    ------
    ValueError
        Naming an offending edge.
    """
    edges = np.stack([faces, np.roll(faces, -1, axis=1)], axis=-1).reshape(-1, 2)
    code = edges[:, 0] * n_vertices + edges[:, 1]
    reverse = edges[:, 1] * n_vertices + edges[:, 0]
    order = np.sort(code)
    twice = order[1:][order[1:] == order[:-1]]
    if twice.size:
        i, j = divmod(int(twice[0]), n_vertices)
        raise ValueError(
            f"mesh is inconsistently oriented or non-manifold: edge {i} -> {j} occurs in two faces "
            "with the same direction (neighbouring faces must traverse a shared edge in opposite "
            "directions)"
        )
    position = np.minimum(np.searchsorted(order, reverse), order.size - 1)
    missing = order[position] != reverse
    if np.any(missing):
        i, j = (int(v) for v in edges[np.flatnonzero(missing)[0]])
        raise ValueError(
            f"mesh is open: edge {i} -> {j} has no neighbouring face with edge {j} -> {i} "
            "(a closed surface is required to enclose a volume)"
        )


def _tetrahedron_moments(vertices, faces, origin):
    """Volume, first and second moments of the cones from ``origin`` over every face.

    For the tetrahedron (origin, a, b, c) with signed volume V = a·(b×c)/6:
    ∫ r dV = V (a + b + c)/4 and ∫ r rᵀ dV = V/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ),
    s = a + b + c. Summed over a closed, outward-oriented surface these are
    the exact moments of the enclosed polyhedron (divergence theorem).
    """
    a, b, c = (vertices[faces[:, k]] - origin for k in range(3))
    six_volume = np.einsum("ni,ni->n", a, np.cross(b, c))
    s = a + b + c
    volume = six_volume.sum() / 6.0
    first = six_volume @ s / 24.0
    weight = (six_volume / 120.0)[:, None]
    second = sum((weight * x).T @ x for x in (a, b, c, s))
    return volume, first, second


def from_mesh(vertices: ArrayLike, faces: ArrayLike, density: float = 1.0) -> MassProperties:
    """Mass, centre of mass and central inertia of a homogeneous closed triangle mesh.

    Exact for the polyhedron the mesh bounds (up to rounding): the solid is
    decomposed into signed tetrahedra from a reference point, whose moments
    have closed forms. The reference point is first the mean face vertex and
    then the centre of mass itself, so the second moments are summed about
    the centre of mass and no large parallel-axis cancellation occurs.

    Parameters
    ----------
    vertices : (N, 3) array_like
        Vertex positions, m.
    faces : (F, 3) array_like of int
        Triangles as vertex indices, ordered counter-clockwise seen from
        outside (outward normals by the right-hand rule). The mesh must be
        closed and consistently oriented; several closed components are
        added together. Self-intersections are not detected.
    density : float
        Mass per volume, kg/m³.

    Returns
    -------
    MassProperties
        ``mass``, ``com`` and ``inertia`` about the centre of mass, in the
        mesh's axes.

    Raises
    ------
    ValueError
        For an open or inconsistently oriented mesh (naming an edge), an
        inside-out mesh (negative enclosed volume: reverse each face,
        ``faces[:, ::-1]``), a mesh enclosing no volume, or a bad density.

    Examples
    --------
    The unit cube has volume 1 and I = 1/6 about its centre.

    >>> import numpy as np, kreisel as kr
    >>> v, f = kr.inertia.primitive_meshes.box_mesh((1.0, 1.0, 1.0))
    >>> p = kr.inertia.from_mesh(v + 0.5, f, density=6.0)
    >>> p.mass, p.com
    (6.0, array([0.5, 0.5, 0.5]))
    >>> np.round(p.inertia, 12)
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    v = as_float_array(vertices, "vertices", tail=(3,))
    if v.ndim != 2:
        raise ValueError(f"vertices must have shape (N, 3), got {v.shape}")
    rho = as_float_array(density, "density")
    if rho.ndim != 0 or not rho > 0:
        raise ValueError(f"density must be a positive scalar, got {density!r}")
    f = _as_faces(faces, v.shape[0])
    check_closed_oriented(f, v.shape[0])

    # vertices divided by a power of two (exact) near their largest coordinate: volume (~L³) and second
    # moments (~L⁵) of a 1e-108 m or 1e62 m mesh neither underflow nor overflow; scaled back at the end
    e = int(np.frexp(np.max(np.abs(v[f])))[1]) if f.size else 0
    v = np.ldexp(v, -e)
    origin = v[f].mean(axis=(0, 1))
    volume, first, _ = _tetrahedron_moments(v, f, origin)
    extent = np.ptp(v[f].reshape(-1, 3), axis=0).max()
    if not abs(volume) > 1e-12 * extent**3:
        raise ValueError("vertices: the mesh encloses no volume (flat or degenerate)")
    if volume < 0:
        raise ValueError(
            "mesh is inside out: enclosed volume is negative, so its faces are ordered clockwise "
            "seen from outside; reverse every face (faces[:, ::-1])"
        )
    com = origin + first / volume
    volume, first, second = _tetrahedron_moments(v, f, com)
    # first is zero up to rounding; remove its tiny residual exactly
    offset = first / volume
    second = second - volume * np.outer(offset, offset)
    rho = float(rho)
    with out_of_range("vertices and density", "the mass or the moment of inertia") as guard:
        mass = guard.check(np.ldexp(rho * volume, 3 * e))
        inertia = guard.check(np.ldexp(rho * second_moment_to_inertia(second), 5 * e))
    # a body with volume has positive mass and diagonal moments: zeros are values below the smallest double
    for value, scaled, power, what in ((mass, rho * volume, 3, "the mass"),
                                       (np.diag(inertia).min(), rho * np.diag(second_moment_to_inertia(second)).min(),
                                        5, "the smallest moment of inertia")):
        if not value > 0.0:
            decade = np.log10(scaled) + power * e * np.log10(2.0)
            raise ValueError(f"vertices and density are out of range: {what}, about 1e{decade:.0f} (SI), is below the "
                             "smallest double (4.9e-324)")
    return MassProperties(float(mass), np.ldexp(com + offset, e), inertia)
