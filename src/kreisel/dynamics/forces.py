"""Force models for the six-degree-of-freedom free body (:func:`kreisel.dynamics.simulate_6dof`).

Encoded like the torque models (:mod:`kreisel.dynamics.torques`): rows of a
float table read by the compiled integrators. The force acts at the centre
of mass, so it moves the body without turning it; forces applied elsewhere
enter through a torque model. Python callables
``force(t, q, omega_body, position, velocity) -> space force (3,)`` are
accepted too (called back from the compiled loop, slower).
"""

from __future__ import annotations

import numpy as np
from numba import njit, objmode

from .._validation import as_float_array
from ..so3._kernels import qnormalize, qrotate
from .torques import ROW_SIZE, _CALLBACKS

__all__ = ["ForceModel", "ConstantForce", "LinearDrag", "ForceSum"]

F_SPACE, F_BODY, F_DRAG, F_CALLBACK = 0, 1, 2, 3

_jit = njit(cache=True, nogil=True)


class ForceModel:
    """Base class of the compiled force models; models add with ``+``."""

    def rows(self):
        """The model's table rows (body vectors in body coordinates)."""
        raise NotImplementedError

    def __add__(self, other):
        if not isinstance(other, ForceModel):
            return NotImplemented
        return ForceSum(self, other)


class ConstantForce(ForceModel):
    """A force fixed in space (``frame="space"``, e.g. weight) or in the body (a thruster).

    Parameters
    ----------
    force : (3,) array_like
        Newtons, components in ``frame``.
    frame : {"space", "body"}

    Examples
    --------
    >>> ConstantForce([0.0, 0.0, -9.81]).force
    array([ 0.  ,  0.  , -9.81])
    """

    def __init__(self, force, frame="space"):
        if frame not in ("body", "space"):
            raise ValueError(f"frame must be 'space' or 'body', got {frame!r}")
        f = as_float_array(force, "force", tail=(3,))
        if f.ndim != 1:
            raise ValueError(f"force must have shape (3,), got {f.shape}")
        self.force = f
        self.frame = frame

    def rows(self):
        r = np.zeros((1, ROW_SIZE))
        r[0, 0] = F_SPACE if self.frame == "space" else F_BODY
        r[0, 1:4] = self.force
        return r


class LinearDrag(ForceModel):
    """Linear drag on the centre of mass, ``F = −c v`` (c >= 0 in N s/m).

    Examples
    --------
    >>> LinearDrag(0.1).coefficient
    0.1
    """

    def __init__(self, coefficient):
        c = float(coefficient)
        if not (np.isfinite(c) and c >= 0.0):
            raise ValueError(f"coefficient must be a finite number >= 0, got {coefficient!r}")
        self.coefficient = c

    def rows(self):
        r = np.zeros((1, ROW_SIZE))
        r[0, 0] = F_DRAG
        r[0, 1] = self.coefficient
        return r


class ForceSum(ForceModel):
    """Sum of force models (what ``model_a + model_b`` returns)."""

    def __init__(self, *models):
        flat = []
        for m in models:
            if not isinstance(m, ForceModel):
                raise TypeError(f"ForceSum takes force models, got {type(m).__name__}")
            flat.extend(m.models if isinstance(m, ForceSum) else [m])
        self.models = tuple(flat)

    def rows(self):
        if not self.models:
            return np.zeros((0, ROW_SIZE))
        return np.concatenate([m.rows() for m in self.models])


def to_principal(rows, axes):
    """Express body vectors of force rows in principal axes."""
    if axes is None:
        return rows
    out = rows.copy()
    for r in out:
        if int(r[0]) == F_BODY:
            r[1:4] = axes.T @ r[1:4]
    return out


def _call_registered(key, t, q, w, r, v):
    return np.ascontiguousarray(
        _CALLBACKS[int(key)](t, q.copy(), w.copy(), r.copy(), v.copy()), dtype=np.float64
    )


@njit(cache=True)
def _callback_force(key, t, q, w, r, v, out):
    with objmode(f="float64[:]"):
        f = _call_registered(key, t, q, w, r, v)
    out[0] += f[0]
    out[1] += f[1]
    out[2] += f[2]


@_jit
def evaluate_force(rows, t, y, out, scratch):
    """Space force on the centre of mass for the 13-state ``y = (ω′, q, r, v)``."""
    out[0] = 0.0
    out[1] = 0.0
    out[2] = 0.0
    n = rows.shape[0]
    if n == 0:
        return
    qn = scratch[0:4]
    f = scratch[4:7]
    for i in range(4):
        qn[i] = y[3 + i]
    qnormalize(qn)
    for i in range(n):
        row = rows[i]
        kind = int(row[0])
        if kind == F_SPACE:
            out[0] += row[1]
            out[1] += row[2]
            out[2] += row[3]
        elif kind == F_BODY:
            qrotate(qn, row[1:4], f)
            out[0] += f[0]
            out[1] += f[1]
            out[2] += f[2]
        elif kind == F_DRAG:
            out[0] -= row[1] * y[10]
            out[1] -= row[1] * y[11]
            out[2] -= row[1] * y[12]
        else:
            _callback_force(row[1], t, qn, y[0:3], y[7:10], y[10:13], out)
