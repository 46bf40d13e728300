"""Rigid displacements SE(3) (Theory §1.3 Chasles' theorem, §3.8 screw motion).

:class:`RigidTransform` holds batched poses (R, r_C); :func:`change_base_point`
re-expresses a displacement about another body point (R unchanged);
:class:`Screw` carries the Chasles/Mozzi screw of finite displacements;
``kreisel.se3.lie`` has twists ``ξ = (ω, v)``, exp/log and the SE(3)
Jacobians; :func:`sclerp` interpolates along screws. The package builds on
:mod:`kreisel.so3` only (the SE(3) Jacobians are built on the kernels of those of :mod:`kreisel.so3.jacobians`).
"""

from .lie import *  # noqa: F401,F403
from .motion import *  # noqa: F401,F403
from .screw import *  # noqa: F401,F403
from .transform import *  # noqa: F401,F403

# Literal, so that every type checker reads it (mypy reads neither `+=` nor `*` of another module's list);
# tests/test_public_surface.py checks that it holds exactly the names of the modules imported above.
__all__ = [
    # transform
    "RigidTransform", "change_base_point",
    # screw
    "Screw",
    # lie
    "se3_hat", "se3_vee", "se3_left_jacobian", "se3_right_jacobian", "se3_left_jacobian_inverse",
    "se3_right_jacobian_inverse",
    # motion
    "sclerp",
]
