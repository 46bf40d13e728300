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

# Literal, so that every type checker reads it (mypy reads neither `+=` nor `*` of another module's list);
# tests/test_public_surface.py checks that it holds exactly the names of the modules imported above.
__all__ = [
    # quaternion
    "quat_multiply", "quat_conjugate", "quat_inverse", "quat_norm", "quat_normalize", "quat_apply", "quat_identity",
    "quat_power",
    # matrix
    "quat_to_matrix", "matrix_to_quat", "orthonormalize",
    # rotvec
    "generators", "hat", "vee", "rotvec_to_matrix", "matrix_to_rotvec", "rotvec_to_quat", "quat_to_rotvec",
    "rotvec_to_axis_angle", "axis_angle_to_rotvec", "compose_rotvec", "bch", "adjoint_action",
    # jacobians
    "left_jacobian", "right_jacobian", "left_jacobian_inverse", "right_jacobian_inverse",
    # euler
    "parse_sequence", "euler_to_quat", "quat_to_euler", "euler_to_matrix", "matrix_to_euler", "gimbal_lock",
    # su2
    "quat_to_su2", "su2_to_quat", "quat_to_cayley_klein", "cayley_klein_to_quat", "quat_to_euler_parameters",
    "euler_parameters_to_quat", "euler_parameters_to_matrix",
    # rodrigues
    "quat_to_gibbs", "gibbs_to_quat", "quat_to_mrp", "mrp_to_quat",
    # interpolation
    "quat_slerp", "quat_mean",
    # alignment
    "align_vectors",
    # davenport
    "davenport_to_quat", "quat_to_davenport", "davenport_gimbal_lock",
    # groups
    "create_group", "reduce_quat",
    # rotation
    "Rotation",
    # spline
    "RotationSpline", "Slerp",
]
