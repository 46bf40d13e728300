"""The :class:`RigidBody`: mass and inertia tensor in body axes, validated once."""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array
from . import solids
from .mesh_properties import from_mesh
from .properties import MassProperties, combine, from_points
from .tensors import as_symmetric_tensor, check_moments, principal_axes


def _read_only(a):
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

    def __init__(self, inertia, mass=1.0):
        if not np.isscalar(mass) and np.ndim(mass) != 0:
            raise ValueError(f"mass must be a scalar, got shape {np.shape(mass)}")
        m = float(as_float_array(mass, "mass"))
        if m <= 0.0:
            raise ValueError(f"mass must be > 0, got {m!r}")
        a = as_float_array(inertia, "inertia")
        if a.shape == (3,):
            tensor = np.diag(a)
        elif a.shape == (3, 3):
            tensor = as_symmetric_tensor(a, "inertia")
        else:
            raise ValueError(
                f"inertia must be 3 principal moments (3,) or a tensor (3, 3), got shape {a.shape}"
            )
        moments, axes = principal_axes(tensor)
        check_moments(moments, "inertia", definite=True)
        self._inertia = _read_only(tensor)
        self._mass = m
        self._moments = _read_only(moments)
        self._axes = _read_only(axes)

    @property
    def inertia(self):
        """(3, 3) inertia tensor in body axes, kg m² (read-only)."""
        return self._inertia

    @property
    def mass(self):
        """Mass, kg."""
        return self._mass

    @property
    def principal_moments(self):
        """(3,) principal moments in ascending order, kg m²."""
        return self._moments

    @property
    def principal_axes(self):
        """(3, 3) proper rotation whose columns are the principal axes in body components."""
        return self._axes

    @property
    def mass_properties(self):
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
    def is_principal(self):
        """Whether the body axes are principal axes (tensor exactly diagonal)."""
        return bool(np.count_nonzero(self._inertia - np.diag(np.diagonal(self._inertia))) == 0)

    @classmethod
    def from_properties(cls, properties):
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
    def from_mesh(cls, vertices, faces, density=1.0):
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
    def from_parts(cls, parts):
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
    def from_points(cls, masses, positions):
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

    def __repr__(self):
        if self.is_principal:
            body = np.array2string(np.diagonal(self._inertia), separator=", ")
        else:
            body = np.array2string(self._inertia, separator=", ").replace("\n", "")
        return f"RigidBody({body}, mass={self._mass!r})"


# Per solid: what the example shows, the variables, the constructor's arguments after the
# mass, the textbook moments (I_x, I_y, I_z) as an expression in those variables, and the
# moments the constructor returns (rounded to 6 decimals), so each generated docstring
# checks the body against its closed form (Theory §4.1).
_SOLID_EXAMPLES = {
    "box": (
        "A 1 × 2 × 3 m box: each moment sums the squared edges across its axis",
        "m, a, b, c = 12.0, 1.0, 2.0, 3.0", "(a, b, c)",
        "[m / 12 * (b**2 + c**2), m / 12 * (a**2 + c**2), m / 12 * (a**2 + b**2)]",
        "[13.0, 10.0, 5.0]",
    ),
    "solid_sphere": (
        "A ball is isotropic, I = 2/5 m r² about every axis",
        "m, r = 5.0, 0.2", "r", "[2 / 5 * m * r**2] * 3", "[0.08, 0.08, 0.08]",
    ),
    "hollow_sphere": (
        "A thin shell keeps all its mass at r, so I = 2/3 m r² exceeds the ball's 2/5 m r²",
        "m, r = 3.0, 0.5", "r", "[2 / 3 * m * r**2] * 3", "[0.5, 0.5, 0.5]",
    ),
    "solid_cylinder": (
        "A cylinder longer than √3 r spins more easily about its axis (I_z = m r²/2)"
        " than end over end",
        "m, r, h = 6.0, 0.5, 2.0", "r, h",
        "[m * (3 * r**2 + h**2) / 12] * 2 + [m * r**2 / 2]", "[2.375, 2.375, 0.75]",
    ),
    "hollow_cylinder": (
        "A thick tube: the radii enter only through R² + r²",
        "m, R, r, h = 4.0, 0.5, 0.3, 1.0", "R, h, inner_radius=r",
        "[m * (3 * (R**2 + r**2) + h**2) / 12] * 2 + [m * (R**2 + r**2) / 2]",
        "[0.673333, 0.673333, 0.68]",
    ),
    "solid_cone": (
        "A cone about its apex, the fixed point of a top: the transverse moment is the"
        " central one plus m (3h/4)² (parallel axes)",
        "m, r, h = 2.0, 0.5, 1.0", "r, h, about='apex'",
        "[3 / 20 * m * r**2 + 3 / 80 * m * h**2 + m * (3 * h / 4) ** 2] * 2 + [3 / 10 * m * r**2]",
        "[1.275, 1.275, 0.15]",
    ),
    "solid_ellipsoid": (
        "An ellipsoid: the box formula with m/5 a² in place of m/12 a²",
        "m, a, b, c = 5.0, 1.0, 2.0, 3.0", "(a, b, c)",
        "[m / 5 * (b**2 + c**2), m / 5 * (a**2 + c**2), m / 5 * (a**2 + b**2)]",
        "[13.0, 10.0, 5.0]",
    ),
    "thin_disk": (
        "A thin disk obeys the perpendicular-axis theorem, I_z = I_x + I_y",
        "m, r = 2.0, 0.3", "r", "[m * r**2 / 4] * 2 + [m * r**2 / 2]", "[0.045, 0.045, 0.09]",
    ),
    "thin_ring": (
        "A hoop has all its mass at r from its axis (I_z = m r²) and is a plate, I_z = I_x + I_y",
        "m, r = 2.0, 0.3", "r", "[m * r**2 / 2] * 2 + [m * r**2]", "[0.09, 0.09, 0.18]",
    ),
    "torus": (
        "A torus (tube radius a around a circle of radius R) tends to the hoop as a → 0",
        "m, R, a = 3.0, 0.4, 0.1", "R, a",
        "[m * (R**2 / 2 + 5 / 8 * a**2)] * 2 + [m * (R**2 + 3 / 4 * a**2)]",
        "[0.25875, 0.25875, 0.5025]",
    ),
}


def _solid_constructor(solid):
    def constructor(cls, mass, *args, **kwargs):
        return cls(solid(mass, *args, **kwargs), mass)

    name = solid.__name__
    remark, variables, arguments, textbook, moments = _SOLID_EXAMPLES[name]
    constructor.__name__ = name
    constructor.__qualname__ = f"RigidBody.{name}"
    constructor.__doc__ = f"""Rigid body of the homogeneous solid of :func:`kreisel.inertia.{name}`.

    Same arguments, body axes and reference point as that function; the body's
    inertia tensor is the closed form given there (Theory §4.1).

    Examples
    --------
    {remark}:

    >>> import numpy as np, kreisel as kr
    >>> {variables}
    >>> body = kr.RigidBody.{name}(m, {arguments})
    >>> body.inertia.diagonal().round(6).tolist()
    {moments}
    >>> bool(np.allclose(body.inertia.diagonal(), {textbook}, rtol=1e-12, atol=0))
    True
    """
    return classmethod(constructor)


for _solid in (
    solids.box,
    solids.solid_sphere,
    solids.hollow_sphere,
    solids.solid_cylinder,
    solids.hollow_cylinder,
    solids.solid_cone,
    solids.solid_ellipsoid,
    solids.thin_disk,
    solids.thin_ring,
    solids.torus,
):
    setattr(RigidBody, _solid.__name__, _solid_constructor(_solid))
del _solid
