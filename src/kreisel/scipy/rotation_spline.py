"""scipy's ``RotationSpline`` over kreisel's: rates in the body frame, as scipy returns them."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..so3.spline import RotationSpline as _RotationSpline
from ._interpolation import Interpolation
from .rotation import Rotation

__all__ = ["RotationSpline"]


class RotationSpline(Interpolation):
    """C² attitude spline through rotations at given times: ``from kreisel.scipy import RotationSpline``.

    The curve is kreisel's :class:`~kreisel.so3.RotationSpline`, which is
    scipy's; derivatives are body-frame angular velocity and acceleration.

    Parameters
    ----------
    times : array_like, shape (N,)
        Strictly increasing knot times.
    rotations : Rotation, shape (N,)

    Examples
    --------
    >>> from kreisel.scipy import Rotation, RotationSpline
    >>> spline = RotationSpline([0, 1, 2], Rotation.from_rotvec([[0, 0, 0], [0, 0, 1], [0, 0, 2]]))
    >>> spline(0.5, 1).round(12).tolist()
    [0.0, 0.0, 1.0]
    """

    kind = _RotationSpline
    _interpolant: _RotationSpline

    def __call__(self, times: ArrayLike, order: int = 0) -> Any:
        """Rotations (``order=0``), body angular velocities (1) or accelerations (2) at ``times``."""
        if np.ndim(times) > 1:
            raise ValueError(f"times must be a scalar or 1-D, got shape {np.shape(times)}")
        if order == 0:
            return Rotation.from_kreisel(self._interpolant(times))
        return self._interpolant(times, order, frame="body")
