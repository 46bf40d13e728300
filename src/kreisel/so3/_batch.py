"""The batch protocol of the classes that hold unit quaternions ``(..., 4)``: ``Rotation`` and ``RigidTransform``.

Both keep their rotations as scalar-first unit quaternions in ``_q`` and are
batched like numpy arrays: a single element has batch shape ``()`` and is
neither sized, iterable nor indexable. Each class indexes its own arrays.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__: list[str] = []


class QuaternionBatch:
    """Batch shape, ``single`` and ``len`` of a batch of unit quaternions held in ``_q``."""

    __slots__ = ("_q",)

    _q: NDArray[np.float64]

    @property
    def shape(self) -> tuple[int, ...]:
        """Batch shape (``()`` for a single element)."""
        return self._q.shape[:-1]

    @property
    def single(self) -> bool:
        """True for a single element (batch shape ``()``)."""
        return self._q.ndim == 1

    def _single_error(self, what: str) -> TypeError:
        # The TypeError numpy and scipy give for what a scalar cannot do, e.g. "has no len()".
        return TypeError(f"a single {type(self).__name__} {what}")

    def __len__(self) -> int:
        if self._q.ndim == 1:
            raise self._single_error("has no len()")
        return self._q.shape[0]
