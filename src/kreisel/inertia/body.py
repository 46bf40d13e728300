"""The :class:`RigidBody`: mass and inertia tensor in body axes, validated once."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._html import html_table, number
from .._validation import as_float, as_float_array, check_inertia_tensor, check_principal_moments
from . import solids
from .mesh_properties import from_mesh
from .properties import MassProperties, combine, from_points
from .tensors import principal_axes

__all__ = ["RigidBody"]


def _read_only(a: ArrayLike) -> NDArray[np.float64]:
    a = np.array(a, dtype=np.float64)
    a.setflags(write=False)
    return a


class RigidBody:
    """A rigid body for Euler's equations: its mass and inertia tensor in body axes.

    The body axes have their origin at the reference point of the tensor —
    the centre of mass for a free body, the fixed point for a top with a
    fixed point (Theory §4.1, §4.4).

    Parameters
    ----------
    inertia : (3,) or (3, 3) array_like
        Either the three principal moments (the body axes are then principal
        axes, in the given order) or a symmetric tensor in body axes, kg m².
    mass : float
        Mass m > 0, kg.

    Raises
    ------
    ValueError
        If the tensor is not symmetric, not finite, not positive definite
        (Euler's equations need I⁻¹, so a thin rod with a zero moment is
        refused), violates a triangle inequality I_i <= I_j + I_k of its
        principal moments (equality, a thin plate, is accepted to within
        rounding), or if the mass is not a positive finite number.

    Attributes
    ----------
    inertia : (3, 3) ndarray
        Inertia tensor in body axes (read-only).
    mass : float
    principal_moments : (3,) ndarray
        Ascending principal moments.
    principal_axes : (3, 3) ndarray
        Proper rotation whose columns are the principal axes in body
        components: ``inertia = principal_axes @ diag(principal_moments) @ principal_axes.T``.
    is_principal : bool
        True when the tensor is diagonal (exactly) in body axes.

    Examples
    --------
    >>> import kreisel as kr
    >>> body = kr.RigidBody([3.0, 1.0, 2.0], mass=2.0)
    >>> body.principal_moments
    array([1., 2., 3.])
    >>> body.is_principal
    True
    >>> kr.RigidBody.box(12.0, (1.0, 2.0, 3.0)).inertia.diagonal()
    array([13., 10.,  5.])
    """

    __slots__ = ("_inertia", "_mass", "_moments", "_axes")

    def __init__(self, inertia: ArrayLike, mass: float = 1.0) -> None:
        if not np.isscalar(mass) and np.ndim(mass) != 0:
            raise ValueError(f"mass must be a scalar, got shape {np.shape(mass)}")
        m = as_float(mass, "mass")
        if m <= 0.0:
            raise ValueError(f"mass must be > 0, got {m!r}")
        a = as_float_array(inertia, "inertia")
        if a.shape == (3,):
            tensor = np.diag(a)
        elif a.shape == (3, 3):
            tensor = check_inertia_tensor(a, "inertia")
        else:
            raise ValueError(
                f"inertia must be 3 principal moments (3,) or a tensor (3, 3), got shape {a.shape}"
            )
        moments, axes = principal_axes(tensor)
        check_principal_moments(moments, "inertia")
        self._inertia = _read_only(tensor)
        self._mass = m
        self._moments = _read_only(moments)
        self._axes = _read_only(axes)

    @property
    def inertia(self) -> NDArray[np.float64]:
        """(3, 3) inertia tensor in body axes, kg m² (read-only)."""
        return self._inertia

    @property
    def mass(self) -> float:
        """Mass, kg."""
        return self._mass

    @property
    def principal_moments(self) -> NDArray[np.float64]:
        """(3,) principal moments in ascending order, kg m²."""
        return self._moments

    @property
    def principal_axes(self) -> NDArray[np.float64]:
        """(3, 3) proper rotation whose columns are the principal axes in body components."""
        return self._axes

    @property
    def mass_properties(self) -> MassProperties:
        """The body's :class:`~kreisel.inertia.MassProperties`: centre of mass at the body origin.

        Examples
        --------
        >>> import kreisel as kr
        >>> p = kr.RigidBody([1.0, 2.0, 3.0], mass=2.0).mass_properties
        >>> p.mass, p.com.tolist(), p.inertia.diagonal().tolist()
        (2.0, [0.0, 0.0, 0.0], [1.0, 2.0, 3.0])
        """
        return MassProperties(self._mass, np.zeros(3), self._inertia)

    @property
    def is_principal(self) -> bool:
        """Whether the body axes are principal axes (tensor exactly diagonal)."""
        return bool(np.count_nonzero(self._inertia - np.diag(np.diagonal(self._inertia))) == 0)

    @classmethod
    def from_properties(cls, properties: MassProperties) -> RigidBody:
        """Rigid body of a :class:`MassProperties`: body origin at its centre of mass, same axes.

        Examples
        --------
        A 3 kg cylinder (radius 0.5 m, height 2 m along z) described with its
        centre at (0, 0, 1): the body origin is its centre of mass, so the moments
        are the central ones, m r²/2 and m (3r² + h²)/12, not those about the base:

        >>> import numpy as np, kreisel as kr
        >>> cylinder = kr.inertia.MassProperties(3.0, np.array([0, 0, 1.0]), kr.inertia.solid_cylinder(3.0, 0.5, 2.0))
        >>> body = kr.RigidBody.from_properties(cylinder)
        >>> body.mass, body.principal_moments.round(12).tolist()
        (3.0, [0.375, 1.1875, 1.1875])
        >>> cylinder.about([0, 0, 0]).diagonal().round(12).tolist()
        [4.1875, 4.1875, 0.375]
        """
        return cls(properties.inertia, properties.mass)

    @classmethod
    def from_mesh(cls, vertices: ArrayLike, faces: ArrayLike, density: float = 1.0) -> RigidBody:
        """Rigid body of a homogeneous closed triangle mesh (:func:`kreisel.inertia.from_mesh`).

        The body origin is the mesh's centre of mass, the body axes are the
        mesh's axes (use :attr:`principal_axes` for the principal frame).

        Examples
        --------
        >>> import kreisel as kr
        >>> v, f = kr.inertia.primitive_meshes.box_mesh((1.0, 2.0, 3.0))
        >>> body = kr.RigidBody.from_mesh(v, f, density=2.0)
        >>> body.mass, body.principal_moments.round(12)
        (12.0, array([ 5., 10., 13.]))
        """
        return cls.from_properties(from_mesh(vertices, faces, density))

    @classmethod
    def from_parts(cls, parts: Iterable[Any]) -> RigidBody:
        """Rigid body assembled from parts at poses (:func:`kreisel.inertia.combine`).

        The body origin is the composite centre of mass, the body axes those
        in which the parts were placed.

        Examples
        --------
        >>> import kreisel as kr
        >>> ball = kr.RigidBody.solid_sphere(1.0, 0.1)
        >>> dumbbell = kr.RigidBody.from_parts([(ball, [-1.0, 0, 0]), (ball, [1.0, 0, 0])])
        >>> dumbbell.principal_moments
        array([0.008, 2.008, 2.008])
        """
        return cls.from_properties(combine(parts))

    @classmethod
    def from_points(cls, masses: ArrayLike, positions: ArrayLike) -> RigidBody:
        """Rigid body of point masses, body origin at their centre of mass (:func:`kreisel.inertia.from_points`).

        Examples
        --------
        Two 1 kg masses 2 m apart on x, a third of 2 kg on y: the body origin moves
        to their centre of mass, and the tensor is taken about it:

        >>> import kreisel as kr
        >>> body = kr.RigidBody.from_points([1.0, 1.0, 2.0], [[-1.0, 0, 0], [1.0, 0, 0], [0, 1.0, 0]])
        >>> body.mass, body.inertia.diagonal().round(12).tolist()
        (4.0, [1.0, 2.0, 3.0])
        """
        return cls.from_properties(from_points(masses, positions))

    @classmethod
    def box(cls, mass: float, size: ArrayLike) -> RigidBody:
        """Rigid body of a homogeneous box: :func:`kreisel.inertia.box` (same arguments and axes).

        Examples
        --------
        A 1 × 2 × 3 m box: each moment sums the squared edges across its axis:

        >>> import numpy as np, kreisel as kr
        >>> m, a, b, c = 12.0, 1.0, 2.0, 3.0
        >>> body = kr.RigidBody.box(m, (a, b, c))
        >>> body.inertia.diagonal().round(6).tolist()
        [13.0, 10.0, 5.0]
        >>> bool(np.allclose(body.inertia.diagonal(), [m / 12 * (b**2 + c**2), m / 12 * (a**2 + c**2), m / 12 * (a**2 + b**2)], rtol=1e-12, atol=0))
        True
        """
        return cls(solids.box(mass, size), mass)

    @classmethod
    def solid_sphere(cls, mass: float, radius: float) -> RigidBody:
        """Rigid body of a homogeneous solid sphere: :func:`kreisel.inertia.solid_sphere` (same arguments and axes).

        Examples
        --------
        A ball is isotropic, I = 2/5 m r² about every axis:

        >>> import numpy as np, kreisel as kr
        >>> m, r = 5.0, 0.2
        >>> body = kr.RigidBody.solid_sphere(m, r)
        >>> body.inertia.diagonal().round(6).tolist()
        [0.08, 0.08, 0.08]
        >>> bool(np.allclose(body.inertia.diagonal(), [2 / 5 * m * r**2] * 3, rtol=1e-12, atol=0))
        True
        """
        return cls(solids.solid_sphere(mass, radius), mass)

    @classmethod
    def hollow_sphere(cls, mass: float, radius: float, inner_radius: float | None = None) -> RigidBody:
        """Rigid body of a homogeneous hollow sphere: :func:`kreisel.inertia.hollow_sphere` (same arguments and axes).

        Examples
        --------
        A thin shell keeps all its mass at r, so I = 2/3 m r² exceeds the ball's 2/5 m r²:

        >>> import numpy as np, kreisel as kr
        >>> m, r = 3.0, 0.5
        >>> body = kr.RigidBody.hollow_sphere(m, r)
        >>> body.inertia.diagonal().round(6).tolist()
        [0.5, 0.5, 0.5]
        >>> bool(np.allclose(body.inertia.diagonal(), [2 / 3 * m * r**2] * 3, rtol=1e-12, atol=0))
        True
        """
        return cls(solids.hollow_sphere(mass, radius, inner_radius=inner_radius), mass)

    @classmethod
    def solid_cylinder(cls, mass: float, radius: float, height: float) -> RigidBody:
        """Rigid body of a homogeneous solid cylinder: :func:`kreisel.inertia.solid_cylinder` (same arguments and axes).

        Examples
        --------
        A cylinder longer than √3 r spins more easily about its axis (I_z = m r²/2) than end over end:

        >>> import numpy as np, kreisel as kr
        >>> m, r, h = 6.0, 0.5, 2.0
        >>> body = kr.RigidBody.solid_cylinder(m, r, h)
        >>> body.inertia.diagonal().round(6).tolist()
        [2.375, 2.375, 0.75]
        >>> bool(np.allclose(body.inertia.diagonal(), [m * (3 * r**2 + h**2) / 12] * 2 + [m * r**2 / 2], rtol=1e-12, atol=0))
        True
        """
        return cls(solids.solid_cylinder(mass, radius, height), mass)

    @classmethod
    def hollow_cylinder(cls, mass: float, radius: float, height: float,
                        inner_radius: float | None = None) -> RigidBody:
        """Rigid body of a homogeneous hollow cylinder: :func:`kreisel.inertia.hollow_cylinder` (same arguments and axes).

        Examples
        --------
        A thick tube: the radii enter only through R² + r²:

        >>> import numpy as np, kreisel as kr
        >>> m, R, r, h = 4.0, 0.5, 0.3, 1.0
        >>> body = kr.RigidBody.hollow_cylinder(m, R, h, inner_radius=r)
        >>> body.inertia.diagonal().round(6).tolist()
        [0.673333, 0.673333, 0.68]
        >>> bool(np.allclose(body.inertia.diagonal(), [m * (3 * (R**2 + r**2) + h**2) / 12] * 2 + [m * (R**2 + r**2) / 2], rtol=1e-12, atol=0))
        True
        """
        return cls(solids.hollow_cylinder(mass, radius, height, inner_radius=inner_radius), mass)

    @classmethod
    def solid_cone(cls, mass: float, radius: float, height: float, about: str = 'center_of_mass') -> RigidBody:
        """Rigid body of a homogeneous solid cone: :func:`kreisel.inertia.solid_cone` (same arguments and axes).

        Examples
        --------
        A cone about its apex, the fixed point of a top: the transverse moment is the central one plus m (3h/4)² (parallel axes):

        >>> import numpy as np, kreisel as kr
        >>> m, r, h = 2.0, 0.5, 1.0
        >>> body = kr.RigidBody.solid_cone(m, r, h, about='apex')
        >>> body.inertia.diagonal().round(6).tolist()
        [1.275, 1.275, 0.15]
        >>> bool(np.allclose(body.inertia.diagonal(), [3 / 20 * m * r**2 + 3 / 80 * m * h**2 + m * (3 * h / 4) ** 2] * 2 + [3 / 10 * m * r**2], rtol=1e-12, atol=0))
        True
        """
        return cls(solids.solid_cone(mass, radius, height, about=about), mass)

    @classmethod
    def solid_ellipsoid(cls, mass: float, semi_axes: ArrayLike) -> RigidBody:
        """Rigid body of a homogeneous solid ellipsoid: :func:`kreisel.inertia.solid_ellipsoid` (same arguments and axes).

        Examples
        --------
        An ellipsoid: the box formula with m/5 a² in place of m/12 a²:

        >>> import numpy as np, kreisel as kr
        >>> m, a, b, c = 5.0, 1.0, 2.0, 3.0
        >>> body = kr.RigidBody.solid_ellipsoid(m, (a, b, c))
        >>> body.inertia.diagonal().round(6).tolist()
        [13.0, 10.0, 5.0]
        >>> bool(np.allclose(body.inertia.diagonal(), [m / 5 * (b**2 + c**2), m / 5 * (a**2 + c**2), m / 5 * (a**2 + b**2)], rtol=1e-12, atol=0))
        True
        """
        return cls(solids.solid_ellipsoid(mass, semi_axes), mass)

    @classmethod
    def thin_disk(cls, mass: float, radius: float) -> RigidBody:
        """Rigid body of a homogeneous thin disk: :func:`kreisel.inertia.thin_disk` (same arguments and axes).

        Examples
        --------
        A thin disk obeys the perpendicular-axis theorem, I_z = I_x + I_y:

        >>> import numpy as np, kreisel as kr
        >>> m, r = 2.0, 0.3
        >>> body = kr.RigidBody.thin_disk(m, r)
        >>> body.inertia.diagonal().round(6).tolist()
        [0.045, 0.045, 0.09]
        >>> bool(np.allclose(body.inertia.diagonal(), [m * r**2 / 4] * 2 + [m * r**2 / 2], rtol=1e-12, atol=0))
        True
        """
        return cls(solids.thin_disk(mass, radius), mass)

    @classmethod
    def thin_ring(cls, mass: float, radius: float) -> RigidBody:
        """Rigid body of a homogeneous thin ring: :func:`kreisel.inertia.thin_ring` (same arguments and axes).

        Examples
        --------
        A hoop has all its mass at r from its axis (I_z = m r²) and is a plate, I_z = I_x + I_y:

        >>> import numpy as np, kreisel as kr
        >>> m, r = 2.0, 0.3
        >>> body = kr.RigidBody.thin_ring(m, r)
        >>> body.inertia.diagonal().round(6).tolist()
        [0.09, 0.09, 0.18]
        >>> bool(np.allclose(body.inertia.diagonal(), [m * r**2 / 2] * 2 + [m * r**2], rtol=1e-12, atol=0))
        True
        """
        return cls(solids.thin_ring(mass, radius), mass)

    @classmethod
    def torus(cls, mass: float, major_radius: float, minor_radius: float) -> RigidBody:
        """Rigid body of a homogeneous torus: :func:`kreisel.inertia.torus` (same arguments and axes).

        Examples
        --------
        A torus (tube radius a around a circle of radius R) tends to the hoop as a → 0:

        >>> import numpy as np, kreisel as kr
        >>> m, R, a = 3.0, 0.4, 0.1
        >>> body = kr.RigidBody.torus(m, R, a)
        >>> body.inertia.diagonal().round(6).tolist()
        [0.25875, 0.25875, 0.5025]
        >>> bool(np.allclose(body.inertia.diagonal(), [m * (R**2 / 2 + 5 / 8 * a**2)] * 2 + [m * (R**2 + 3 / 4 * a**2)], rtol=1e-12, atol=0))
        True
        """
        return cls(solids.torus(mass, major_radius, minor_radius), mass)

    def __repr__(self) -> str:
        if self.is_principal:
            body = np.array2string(np.diagonal(self._inertia), separator=", ")
        else:
            body = np.array2string(self._inertia, separator=", ").replace("\n", "")
        return f"RigidBody({body}, mass={self._mass!r})"

    def _repr_html_(self) -> str:
        rows = [("mass", number(self._mass) + " kg"),
                ("principal moments", number(self.principal_moments) + " kg m²")]
        if not self.is_principal:
            rows.append(("inertia tensor (body axes)", number(self._inertia.ravel()) + " kg m², row by row"))
        return html_table("RigidBody", rows, note="body origin at the centre of mass; SI units")
