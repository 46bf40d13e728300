"""Rotation group SO(3) (seed 一, 二 and the appendix): every representation of a
rotation, conversions between them, the exponential map and the ``Rotation`` class.

Conventions: scalar-first Hamilton quaternions, active rotations with ``R``
mapping body to space components, rotation vectors with |ψ| <= π from logs,
uppercase Euler sequences intrinsic and lowercase extrinsic.
"""

from . import euler, matrix, quaternion, rotvec
from .euler import *  # noqa: F401,F403
from .matrix import *  # noqa: F401,F403
from .quaternion import *  # noqa: F401,F403
from .rotvec import *  # noqa: F401,F403

__all__ = [*quaternion.__all__, *matrix.__all__, *rotvec.__all__, *euler.__all__]
