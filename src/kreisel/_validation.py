"""Input checking shared by every layer.

Each public function validates its arguments *before* any work starts and
raises ``ValueError``/``TypeError`` naming the argument and the expectation.
"""

from __future__ import annotations

import numpy as np

FRAMES = ("space", "body")


def as_float_array(x, name, tail=None, finite=True):
    """Return ``x`` as a float64 array, checking its trailing shape.

    Parameters
    ----------
    x : array_like
        The user's input.
    name : str
        Argument name used in error messages.
    tail : tuple of int, optional
        Required trailing shape, e.g. ``(4,)`` for quaternions or ``(3, 3)``
        for matrices.
    finite : bool
        Refuse NaN and infinities.
    """
    try:
        a = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a real numeric array, got {type(x).__name__}") from exc
    if tail is not None:
        k = len(tail)
        if a.ndim < k or a.shape[a.ndim - k:] != tuple(tail):
            want = "(..., " + ", ".join(str(n) for n in tail) + ")"
            raise ValueError(f"{name} must have shape {want}, got {a.shape}")
    if finite and not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite (no NaN or inf)")
    return a


def check_frame(frame):
    """Return True for ``frame="body"``, False for ``"space"``; refuse anything else."""
    if frame not in FRAMES:
        raise ValueError(f"frame must be 'space' or 'body', got {frame!r}")
    return frame == "body"


def batch_shape(shape, name="shape"):
    """Return ``shape`` (``None``, a non-negative int or a sequence of them) as a tuple.

    Floats such as ``2.5`` (or ``2.0``), strings and negative sizes raise
    ``ValueError`` naming the argument, instead of numpy's ``TypeError``.
    """
    if shape is None:
        return ()
    items = (shape,) if np.ndim(shape) == 0 else shape
    try:
        items = tuple(items)
    except TypeError:
        items = None
    if items is None or not all(isinstance(n, (int, np.integer)) and not isinstance(n, bool) for n in items):
        raise ValueError(f"{name} must be None, a non-negative int or a tuple of them, got {shape!r}")
    if any(n < 0 for n in items):
        raise ValueError(f"{name} must have non-negative entries, got {shape!r}")
    return tuple(int(n) for n in items)
