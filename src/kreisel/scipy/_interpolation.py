"""What scipy's ``Slerp`` and ``RotationSpline`` share: kreisel's interpolant of the knots' rotations."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .rotation import Rotation


class Interpolation:
    """Knot times and rotations held as kreisel's interpolant ``kind(times, rotations)``."""

    kind: Any

    def __init__(self, times: ArrayLike, rotations: Rotation) -> None:
        if not isinstance(rotations, Rotation):
            raise TypeError(f"rotations must be a kreisel.scipy Rotation, got {type(rotations).__name__}")
        self._interpolant = self.kind(times, rotations.to_kreisel())
        self.rotations = rotations

    @property
    def times(self) -> NDArray[np.float64]:
        """The knot times."""
        return np.asarray(self._interpolant.times)
