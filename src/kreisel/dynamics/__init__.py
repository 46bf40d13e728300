"""Dynamics: torque-driven rigid bodies, geometric integrators, trajectories (Theory §4.4–7).

:func:`simulate` integrates Euler's dynamic equations dJ′/dt + ω′ × J′ = M′
(Theory §4.5) with quaternion attitude under built-in torque models or any
callable; :func:`simulate_batch` runs many bodies in parallel;
:func:`simulate_6dof` adds the centre-of-mass translation. Every result is a
:class:`Trajectory`.
"""

from . import forces, torques
from .engine import simulate, simulate_6dof, simulate_batch
from .forces import *  # noqa: F403
from .torques import *  # noqa: F403
from .trajectory import Trajectory

# built with += so that type checkers read it (they do not read a list with * unpacking)
__all__: list[str] = ["simulate", "simulate_batch", "simulate_6dof", "Trajectory"]
__all__ += torques.__all__
__all__ += forces.__all__
