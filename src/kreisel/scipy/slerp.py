"""scipy's ``Slerp`` over kreisel's: interpolates :class:`kreisel.scipy.Rotation` objects."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..so3.spline import Slerp as _Slerp
from ._interpolation import Interpolation
from .rotation import Rotation

__all__ = ["Slerp"]


class Slerp(Interpolation):
    """Piecewise slerp through rotations at given times: ``from kreisel.scipy import Slerp``.

    Parameters
    ----------
    times : array_like, shape (N,)
        Strictly increasing knot times.
    rotations : Rotation, shape (N,)

    Examples
    --------
    >>> from kreisel.scipy import Rotation, Slerp
    >>> s = Slerp([0, 1], Rotation.from_rotvec([[0, 0, 0], [0, 0, 1]]))
    >>> s([0.25, 0.5]).as_rotvec().round(12).tolist()
    [[0.0, 0.0, 0.25], [0.0, 0.0, 0.5]]
    """

    kind = _Slerp
    _interpolant: _Slerp

    @property
    def timedelta(self) -> NDArray[np.float64]:
        """Durations of the segments."""
        return self._interpolant.timedelta

    @property
    def rotvecs(self) -> NDArray[np.float64]:
        """Rotation vectors of the segments, from each knot to the next."""
        return self._interpolant.rotvecs

    def __call__(self, times: ArrayLike) -> Rotation:
        """Interpolated rotations at ``times`` (a scalar or 1-D, within the knots)."""
        if np.ndim(times) > 1:
            raise ValueError(f"times must be a scalar or 1-D, got shape {np.shape(times)}")
        return Rotation.from_kreisel(self._interpolant(times))
