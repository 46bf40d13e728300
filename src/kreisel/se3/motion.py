"""Screw interpolation between poses (Theory §3.8 in finite form).

Trajectories of body points of a moving body are
:func:`kreisel.kinematics.point_trajectory`.
"""

from __future__ import annotations

from numpy.typing import ArrayLike

from .._compiled.elementwise import uses
from .._validation import as_float_array
from ..so3.quaternion import check_angle_multiple
from . import _kernels
from .transform import RigidTransform

__all__ = ["sclerp"]

#: Powers of the relative poses, refused naming the fraction.
_scaled = _kernels.power.renamed(p="fraction")


def _transform(x: object, name: str) -> RigidTransform:
    if not isinstance(x, RigidTransform):
        raise TypeError(f"{name} must be a RigidTransform, got {type(x).__name__}")
    return x


@uses(_scaled)
def sclerp(start: RigidTransform, end: RigidTransform, fraction: ArrayLike) -> RigidTransform:
    """Screw linear interpolation ``T(s) = T₀ exp(s log(T₀⁻¹ T₁))`` between poses.

    The body moves from ``start`` to ``end`` along the single screw motion
    (constant twist in body components) that joins them: the rotation is
    SLERP, and every body point moves on a helix about the fixed screw axis
    of the relative displacement (Theory §3.8 in finite form). Equivalent to
    dual-quaternion ScLERP for the relative rotation angle ≤ π.

    Parameters
    ----------
    start, end : RigidTransform
        Poses at ``fraction = 0`` and ``1`` (batch shapes broadcast).
    fraction : array_like
        Interpolation parameter(s), broadcast against the batch shape;
        values outside [0, 1] extrapolate along the same screw, as far as
        1e8 rad of turn (see :func:`~kreisel.so3.rotvec_to_quat`).

    Returns
    -------
    RigidTransform
        The interpolated poses, with the broadcast batch shape.

    Examples
    --------
    >>> import numpy as np
    >>> a = RigidTransform.identity()
    >>> b = RigidTransform.from_screw([0, 0, 1], [0, 0, 0], np.pi / 2, 1.0)
    >>> mid = sclerp(a, b, 0.5)
    >>> bool(np.allclose((mid * mid).as_matrix(), b.as_matrix()))
    True
    """
    start = _transform(start, "start")
    end = _transform(end, "end")
    fraction = as_float_array(fraction, "fraction")
    relative = start.inv() * end
    check_angle_multiple(fraction, lambda: relative._q, "fraction", "|fraction| times the rotation angle")
    return start * RigidTransform._from_pose(_scaled(relative._pose, fraction))
