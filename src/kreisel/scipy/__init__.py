"""scipy's ``scipy.spatial.transform`` interface on kreisel's kernels: a drop-in for scipy code.

``from kreisel.scipy import Rotation, Slerp, RotationSpline, RigidTransform``
gives classes that follow scipy's conventions and defaults — quaternions
scalar last ``[x, y, z, w]``, the gimbal-lock warning of ``as_euler``,
non-orthogonal matrices projected onto the nearest rotation — so that code
written for scipy runs unchanged. The rest of kreisel keeps its own
convention (scalar-first quaternions); ``to_kreisel()`` and
``from_kreisel()`` convert between the two without copying.

Modules: ``rotation`` (``Rotation``), ``slerp`` (``Slerp``),
``rotation_spline`` (``RotationSpline``), ``rigid_transform``
(``RigidTransform``).
"""

from .rigid_transform import RigidTransform
from .rotation import Rotation
from .rotation_spline import RotationSpline
from .slerp import Slerp

__all__ = ["Rotation", "Slerp", "RotationSpline", "RigidTransform"]
