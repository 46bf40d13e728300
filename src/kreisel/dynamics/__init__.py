"""Dynamics: torque-driven rigid bodies, geometric integrators, trajectories (Theory §4.4–7).

:func:`simulate` integrates Euler's dynamic equations dJ′/dt + ω′ × J′ = M′
(Theory §4.5) with quaternion attitude under built-in torque models or any
callable; :func:`simulate_batch` runs many bodies in parallel;
:func:`simulate_6dof` adds the centre-of-mass translation. Every result is a
:class:`Trajectory`.
"""

from .engine import simulate, simulate_6dof, simulate_batch
from .forces import *  # noqa: F403
from .torques import *  # noqa: F403
from .trajectory import Trajectory

# Literal, so that every type checker reads it (mypy reads neither `+=` nor `*` of another module's list);
# tests/test_public_surface.py checks that it holds exactly the names of the modules imported above.
__all__ = [
    # engine, trajectory
    "simulate", "simulate_batch", "simulate_6dof", "Trajectory",
    # torques
    "TorqueModel", "GravityTorque", "ConstantTorque", "MagneticTorque", "LinearDamping", "TorqueSum",
    # forces
    "ForceModel", "ConstantForce", "LinearDrag", "ForceSum",
]
