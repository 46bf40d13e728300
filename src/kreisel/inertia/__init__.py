"""Mass properties: inertia tensors, principal axes, inertia ellipsoid (Theory §4.1–3).

Tensors are ``(..., 3, 3)`` arrays in kg m², about the centre of mass unless a
function says otherwise; every function broadcasts over leading axes.
:class:`RigidBody` bundles a validated tensor and mass for the dynamics.
"""

from . import body, mesh_properties, primitive_meshes, properties, solids, tensors
from .body import *  # noqa: F401,F403
from .mesh_properties import *  # noqa: F401,F403
from .properties import *  # noqa: F401,F403
from .solids import *  # noqa: F401,F403
from .tensors import *  # noqa: F401,F403

__all__ = [
    *body.__all__,
    *properties.__all__,
    *mesh_properties.__all__,
    "primitive_meshes",
    *solids.__all__,
    *tensors.__all__,
]
