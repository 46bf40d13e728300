"""Rotation group SO(3) (Theory §1, §2 and the appendix): every representation of a
rotation, conversions between them, the exponential map and the ``Rotation`` class.

Conventions: scalar-first Hamilton quaternions, active rotations with ``R``
mapping body to space components, rotation vectors with |ψ| <= π from logs,
uppercase Euler sequences intrinsic and lowercase extrinsic. Every array
function broadcasts over leading axes and takes a keyword-only ``out=``, an
array of the result's shape and dtype to fill and return, which may be one of
the inputs (see :ref:`out-arrays`).

Modules: ``quaternion`` (algebra, Theory §2.4), ``matrix`` (DCM, §2.1),
``rotvec`` (generators, exp/log, BCH, adjoint action, §2.2),
``jacobians`` (left/right Jacobians and their inverses, §3.4–5),
``euler`` (§2.3), ``su2`` (SU(2), Cayley–Klein, Euler parameters,
appendix), ``rodrigues`` (Gibbs vector, MRPs), ``interpolation``
(slerp, mean), ``alignment`` (Wahba's problem), ``davenport``
(Davenport angles), ``groups`` (point groups, reduction), ``rotation`` (the ``Rotation`` class), ``spline``
(``RotationSpline``, ``Slerp``).
"""

from . import (
    alignment, davenport, euler, groups, interpolation, jacobians, matrix, quaternion, rodrigues, rotation, rotvec, spline, su2,
)
from .alignment import *  # noqa: F401,F403
from .davenport import *  # noqa: F401,F403
from .euler import *  # noqa: F401,F403
from .groups import *  # noqa: F401,F403
from .interpolation import *  # noqa: F401,F403
from .jacobians import *  # noqa: F401,F403
from .matrix import *  # noqa: F401,F403
from .quaternion import *  # noqa: F401,F403
from .rodrigues import *  # noqa: F401,F403
from .rotation import *  # noqa: F401,F403
from .rotvec import *  # noqa: F401,F403
from .spline import *  # noqa: F401,F403
from .su2 import *  # noqa: F401,F403
from .._compiled.outputs import release_memory

# built with += so that type checkers read it (they do not read a list with * unpacking)
__all__: list[str] = []
__all__ += quaternion.__all__
__all__ += matrix.__all__
__all__ += rotvec.__all__
__all__ += jacobians.__all__
__all__ += euler.__all__
__all__ += su2.__all__
__all__ += rodrigues.__all__
__all__ += interpolation.__all__
__all__ += alignment.__all__
__all__ += davenport.__all__
__all__ += groups.__all__
__all__ += rotation.__all__
__all__ += spline.__all__
__all__ += ["release_memory"]  # the memory kept for large results of so3, kinematics and se3
