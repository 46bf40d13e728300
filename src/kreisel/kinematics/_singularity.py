"""Warnings for coordinate singularities of the rate maps.

Angular velocity is always well defined; what can fail is the *rate of a
parameterisation*: Euler-angle rates at gimbal lock (Theory §2.3, §3.6) and
rotation-vector rates where dexp⁻¹ has a pole, |ψ| = 2π, 4π, ... (Theory §3.5).
There the affected entries are returned as NaN, never as a large wrong
number, and one of these warnings is issued. Each rate function has a
``*_singular`` companion that returns the mask without warning.
"""

from __future__ import annotations

import warnings

# Defined in so3 so that Rotation.as_euler can issue it too; re-exported here.
from ..so3.euler import GimbalLockWarning, KinematicSingularityWarning  # noqa: F401

#: Default singularity threshold on the determinant of the rate map
#: (|sin β| or |cos β| for Euler angles, |sin(ψ/2)| for rotation vectors).
#: Away from it the rates are returned with relative error ≲ 1e-16/|det|,
#: i.e. at worst ~1e-8.
SINGULAR_TOL = 1e-8


class RotationVectorSingularityWarning(KinematicSingularityWarning):
    """Rotation-vector rates requested at |ψ| = 2πk (k >= 1): those rates are NaN."""


def warn_if_any(mask, category, message):
    """Issue ``category`` once when any entry of ``mask`` is set."""
    if mask.any():
        count = int(mask.sum())
        warnings.warn(f"{message} ({count} of {mask.size} samples; entries set to NaN)", category, stacklevel=3)
