"""Mass properties: inertia tensors, principal axes, inertia ellipsoid (Theory §4.1–3).

Tensors are ``(..., 3, 3)`` arrays in kg m², about the centre of mass unless a
function says otherwise; every function broadcasts over leading axes.
:class:`RigidBody` bundles a validated tensor and mass for the dynamics.
"""

from . import primitive_meshes
from .body import *  # noqa: F401,F403
from .mesh_properties import *  # noqa: F401,F403
from .properties import *  # noqa: F401,F403
from .solids import *  # noqa: F401,F403
from .tensors import *  # noqa: F401,F403

# Literal, so that every type checker reads it (mypy reads neither `+=` nor `*` of another module's list);
# tests/test_public_surface.py checks that it holds exactly the names of the modules imported above.
__all__ = [
    # body
    "RigidBody",
    # properties
    "MassProperties", "from_points", "combine",
    # mesh_properties
    "from_mesh",
    # submodule
    "primitive_meshes",
    # solids
    "box", "solid_sphere", "hollow_sphere", "solid_cylinder", "hollow_cylinder", "solid_cone", "solid_ellipsoid",
    "thin_rod", "thin_disk", "thin_ring", "torus",
    # tensors
    "points", "parallel_axis", "parallel_axis_to_center_of_mass", "rotate", "principal_axes", "moment_about_axis",
    "radius_of_gyration", "inertia_ellipsoid", "InertiaEllipsoid",
]
