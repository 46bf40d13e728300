"""Kinematics of a rigid body (Theory §3 and §4.6–7).

Every map between a parameterisation's rates and the angular velocity, in
space (``frame="space"``, hat(ω) = Ṙ Rᵀ) or body components
(``frame="body"``, hat(ω′) = Rᵀ Ṙ): rotation matrices, quaternions, rotation
vectors (dexp and the Bortz equation; the SO(3) Jacobian matrices are
:mod:`kreisel.so3.jacobians`, also importable from here), Euler angles of all 24 conventions,
with NaN and a warning at coordinate singularities; angular acceleration;
velocity and acceleration of body points and of points moving on the body
(five-term acceleration), and of body points along sampled attitudes; screw axis of a twist; planar instantaneous
centre and centrodes.
"""

from . import acceleration, euler, motion, point_motion, rates, rotvec, screw
from ..so3.jacobians import left_jacobian, left_jacobian_inverse, right_jacobian, right_jacobian_inverse  # noqa: F401
from ._singularity import (
    GimbalLockWarning,
    KinematicSingularityWarning,
    RotationVectorSingularityWarning,
)
from .acceleration import *  # noqa: F401,F403
from .rates import *  # noqa: F401,F403
from .euler import *  # noqa: F401,F403
from .motion import *  # noqa: F401,F403
from .point_motion import *  # noqa: F401,F403
from .rotvec import *  # noqa: F401,F403
from .screw import *  # noqa: F401,F403

# built with += so that type checkers read it (they do not read a list with * unpacking)
__all__: list[str] = []
__all__ += rates.__all__
__all__ += rotvec.__all__
__all__ += euler.__all__
__all__ += acceleration.__all__
__all__ += motion.__all__
__all__ += point_motion.__all__
__all__ += screw.__all__
__all__ += ["KinematicSingularityWarning", "GimbalLockWarning", "RotationVectorSingularityWarning"]
