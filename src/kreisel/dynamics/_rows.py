"""What torque and force models share: one row of floats per model, and sums of models.

A model is encoded as rows of a small float table (``row[0]`` the kind,
``row[1:]`` its parameters) that the compiled integrators read inside their
time loop; models of one family add with ``+`` into a flat sum.
"""

from __future__ import annotations

import numpy as np

ROW_SIZE = 10


def row(kind, *vectors):
    """One table row ``(1, ROW_SIZE)``: the kind, then the flattened parameter vectors."""
    r = np.zeros(ROW_SIZE)
    r[0] = kind
    flat = np.concatenate([np.ravel(v) for v in vectors]) if vectors else np.zeros(0)
    r[1:1 + flat.size] = flat
    return r[None, :]


class RowModel:
    """Base of a model family; subclasses set ``_sum`` to the family's sum class."""

    _sum = None

    def rows(self):
        """The model's table rows (body vectors in body coordinates), shape ``(k, ROW_SIZE)``."""
        raise NotImplementedError

    def __add__(self, other):
        family = self._sum.family
        if not (isinstance(self, family) and isinstance(other, family)):
            return NotImplemented
        return self._sum(self, other)


class RowSum:
    """Flat sum of models of the family ``family`` (named ``noun`` in messages)."""

    family = None
    noun = ""

    def __init__(self, *models):
        flat = []
        for m in models:
            if not isinstance(m, self.family):
                raise TypeError(f"{type(self).__name__} takes {self.noun} models, got {type(m).__name__}")
            flat.extend(m.models if isinstance(m, RowSum) else [m])
        self.models = tuple(flat)

    def rows(self):
        if not self.models:
            return np.zeros((0, ROW_SIZE))
        return np.concatenate([m.rows() for m in self.models])
