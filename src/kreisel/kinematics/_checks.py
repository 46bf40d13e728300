"""Argument checks shared by the kinematics functions (raised before any work)."""

from __future__ import annotations

import numpy as np

from ..so3._gufunc import finite_array


def vectors(x, name, length=3):
    """Finite float64 array of shape ``(..., length)`` (one compiled pass, no temporaries)."""
    return finite_array(x, name, (length,))


def batch_shape(*items):
    """Common batch shape of ``(name, array, core_ndim)`` items, or ValueError naming them."""
    shapes = [a.shape[: a.ndim - core] for _, a, core in items]
    try:
        return np.broadcast_shapes(*shapes)
    except ValueError:
        described = ", ".join(f"{name} {a.shape}" for name, a, _ in items)
        names = " and ".join(name for name, _, _ in items)
        raise ValueError(f"{names} have batch shapes that do not broadcast: {described}") from None


def tolerance(tol, name="tol"):
    t = float(tol)
    if not (0.0 <= t < 1.0):
        raise ValueError(f"{name} must be in [0, 1), got {tol!r}")
    return t
