"""Argument checks shared by the kinematics functions (raised before any work)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled.gufunc import finite_array, matrix_array
from .._validation import as_float_array, check_frame


def vectors(x: ArrayLike, name: str, length: int = 3) -> NDArray[np.float64]:
    """Finite float64 array of shape ``(..., length)`` (one compiled pass, no temporaries).

    C-contiguous, so that a strided view gives bit for bit the result of a plain array (numpy's
    reductions sum in another order over other layouts).
    """
    return np.ascontiguousarray(finite_array(x, name, (length,)))


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
    """Finite ``(..., length)`` arrays of the keyword arguments, in order, with broadcastable batch shapes."""
    return same_batch(1, **{name: vectors(x, name, length) for name, x in named.items()})


def rotation_batch(R: ArrayLike, **derivatives: ArrayLike) -> tuple[NDArray[np.float64], ...]:
    """``R`` as rotation matrices and its ``derivatives`` as float ``(..., 3, 3)`` arrays, with broadcastable batch shapes.

    ``R`` is checked like every rotation matrix of kreisel (orthogonal to
    within ``ORTHOGONALITY_TOLERANCE``, det > 0): a scaled matrix or a
    reflection would silently scale or flip the angular velocity.
    """
    return same_batch(2, R=matrix_array(R, "R"), **{name: as_float_array(x, name, (3, 3))
                                                    for name, x in derivatives.items()})


def frame_sign(frame: str) -> float:
    """+1 for space components, −1 for body components: the sign that tells the two rate maps apart."""
    return -1.0 if check_frame(frame) else 1.0
