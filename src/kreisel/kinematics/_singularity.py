"""Warnings for coordinate singularities of the rate maps.

Angular velocity is always well defined; what can fail is the *rate of a
parameterisation*: Euler-angle rates at gimbal lock (Theory §2.3, §3.6) and
rotation-vector rates where dexp⁻¹ has a pole, |ψ| = 2π, 4π, ... (Theory §3.5).
There the affected entries are returned as NaN, never as a large wrong
number, and one of these warnings is issued. Each rate function has a
``*_singular`` companion that returns the mask without warning.
"""

from __future__ import annotations

# Defined in so3, whose Rotation.as_euler and inverse Jacobians issue them too; re-exported here.
from ..so3.euler import GimbalLockWarning, KinematicSingularityWarning  # noqa: F401
from ..so3.jacobians import SINGULAR_TOL, RotationVectorSingularityWarning  # noqa: F401

__all__ = ["GimbalLockWarning", "KinematicSingularityWarning", "RotationVectorSingularityWarning", "SINGULAR_TOL"]
