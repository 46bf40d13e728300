"""Argument checks shared by the kinematics functions (raised before any work).

Types, trailing shapes and batch shapes are checked here, naming the
arguments; what the values must hold (finite, a rotation, a nonzero
quaternion) is checked by the array operation, in the pass that computes it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validation import as_float_array, check_frame


def vectors(x: ArrayLike, name: str, length: int = 3) -> NDArray[np.float64]:
    """Float64 array of shape ``(..., length)``."""
    return as_float_array(x, name, (length,), finite=False)


def batch_shape(*items: tuple[str, NDArray[np.float64], int]) -> tuple[int, ...]:
    """Common batch shape of ``(name, array, core_ndim)`` items, or ValueError naming them."""
    shapes = [a.shape[: a.ndim - core] for _, a, core in items]
    try:
        return np.broadcast_shapes(*shapes)
    except ValueError:
        described = ", ".join(f"{name} {a.shape}" for name, a, _ in items)
        names = " and ".join(name for name, _, _ in items)
        raise ValueError(f"{names} have batch shapes that do not broadcast: {described}") from None


def same_batch(core_ndim: int, **arrays: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """The validated ``arrays``, in order, once their batch shapes (all but ``core_ndim`` trailing axes) broadcast."""
    batch_shape(*((name, a, core_ndim) for name, a in arrays.items()))
    return tuple(arrays.values())


def vector_batch(length: int = 3, **named: ArrayLike) -> tuple[NDArray[np.float64], ...]:
    """``(..., length)`` arrays of the keyword arguments, in order, with broadcastable batch shapes."""
    return same_batch(1, **{name: vectors(x, name, length) for name, x in named.items()})


def matrix_batch(**named: ArrayLike) -> tuple[NDArray[np.float64], ...]:
    """``(..., 3, 3)`` arrays of the keyword arguments, in order, with broadcastable batch shapes."""
    return same_batch(2, **{name: as_float_array(x, name, (3, 3), finite=False) for name, x in named.items()})


def frame_sign(frame: str) -> float:
    """+1 for space components, −1 for body components: the sign that tells the two rate maps apart."""
    return -1.0 if check_frame(frame) else 1.0
