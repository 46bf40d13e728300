"""Rigid displacements SE(3) (Theory §1.3 Chasles' theorem, §3.8 screw motion).

:class:`RigidTransform` holds batched poses (R, r_C); :func:`change_base_point`
re-expresses a displacement about another body point (R unchanged);
:class:`Screw` carries the Chasles/Mozzi screw of finite displacements;
``kreisel.se3.lie`` has twists ``ξ = (ω, v)``, exp/log and the SE(3)
Jacobians; :func:`sclerp` interpolates along screws. The package builds on
:mod:`kreisel.so3` only (the SE(3) Jacobians are built on those of :mod:`kreisel.so3.jacobians`).
"""

from . import lie, motion, screw, transform
from .lie import *  # noqa: F401,F403
from .motion import *  # noqa: F401,F403
from .screw import *  # noqa: F401,F403
from .transform import *  # noqa: F401,F403

# built with += so that type checkers read it (they do not read a list with * unpacking)
__all__: list[str] = []
__all__ += transform.__all__
__all__ += screw.__all__
__all__ += lie.__all__
__all__ += motion.__all__
