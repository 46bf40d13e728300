"""Mass properties: inertia tensors, principal axes, inertia ellipsoid (Theory §4.1–3).

Tensors are ``(..., 3, 3)`` arrays in kg m², about the centre of mass unless a
function says otherwise; every function broadcasts over leading axes.
:class:`RigidBody` bundles a validated tensor and mass for the dynamics.
"""

from . import primitive_meshes
from .body import RigidBody
from .mesh_properties import from_mesh
from .properties import MassProperties, combine, from_points
from .solids import (
    box,
    hollow_cylinder,
    hollow_sphere,
    solid_cone,
    solid_cylinder,
    solid_ellipsoid,
    solid_sphere,
    thin_disk,
    thin_ring,
    thin_rod,
    torus,
)
from .tensors import (
    InertiaEllipsoid,
    inertia_ellipsoid,
    moment_about_axis,
    parallel_axis,
    parallel_axis_to_center_of_mass,
    points,
    principal_axes,
    radius_of_gyration,
    rotate,
)

__all__ = [
    "RigidBody",
    "MassProperties",
    "points",
    "from_points",
    "from_mesh",
    "combine",
    "primitive_meshes",
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
    "parallel_axis",
    "parallel_axis_to_center_of_mass",
    "rotate",
    "principal_axes",
    "moment_about_axis",
    "radius_of_gyration",
    "inertia_ellipsoid",
    "InertiaEllipsoid",
]
