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

# Literal, so that every type checker reads it (mypy reads neither `+=` nor `*` of another module's list);
# tests/test_public_surface.py checks that it holds exactly the names of the modules imported above.
__all__ = [
    # rates
    "angular_velocity", "quat_rate", "angular_velocity_from_quat_rate",
    # rotvec
    "bortz_coefficient", "angular_velocity_from_rotvec_rate", "rotvec_rate", "rotvec_rate_singular",
    # euler
    "euler_rate_matrix", "euler_rate_matrix_inverse", "angular_velocity_from_euler_rates", "euler_rates",
    "euler_rates_singular",
    # acceleration
    "angular_acceleration", "angular_acceleration_from_quat", "angular_acceleration_from_rotvec",
    "angular_acceleration_from_euler",
    # motion
    "point_velocity", "point_acceleration", "relative_derivative", "VelocityTerms", "AccelerationTerms",
    "three_term_velocity", "five_term_acceleration",
    # point_motion
    "PointMotion", "point_trajectory",
    # screw
    "ScrewAxis", "screw_axis", "instantaneous_centre", "Centrodes", "centrodes",
    # _singularity
    "KinematicSingularityWarning", "GimbalLockWarning", "RotationVectorSingularityWarning",
]
