"""Torque models for :func:`kreisel.simulate` (seed 四.4: dJ/dt = M).

Every built-in model is encoded as rows of a small float table that the
compiled integrators read inside their time loop, so a simulation under
gravity, a magnetic field, damping or any sum of them never leaves machine
code. A plain Python callable ``torque(t, q, omega_body) -> (3,)`` is also
accepted by :func:`kreisel.simulate`; it is called back from the compiled loop
(through numba's object mode), which costs a few microseconds per evaluation.

Table layout: one row of ``ROW_SIZE`` floats per model, ``row[0]`` the kind,
``row[1:]`` its parameters, all in the frame the integrator works in (the
principal frame of the body).
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from numba import njit, objmode

from .._validation import as_float_array
from ..so3._kernels import qnormalize, qrotate_inverse

__all__ = [
    "TorqueModel",
    "GravityTorque",
    "ConstantTorque",
    "MagneticTorque",
    "LinearDamping",
    "TorqueSum",
]

ROW_SIZE = 10
BODY, SPACE, CROSS, DAMPING, CALLBACK = 0, 1, 2, 3, 4

_jit = njit(cache=True, nogil=True)


class TorqueModel:
    """Base class of the compiled torque models; models add with ``+``.

    A model is also callable, ``model(t, q, omega_body)`` returning the body
    torque ``M′`` in N m, which is what the integrators evaluate.
    """

    def rows(self):
        """The model's table rows in body coordinates, shape ``(k, ROW_SIZE)``."""
        raise NotImplementedError

    def __add__(self, other):
        if not isinstance(other, TorqueModel):
            return NotImplemented
        return TorqueSum(self, other)

    def __call__(self, t, q, omega_body):
        q = as_float_array(q, "q", tail=(4,))
        w = as_float_array(omega_body, "omega_body", tail=(3,))
        if q.ndim != 1 or w.ndim != 1:
            raise ValueError("a torque model is evaluated for one state: q (4,), omega_body (3,)")
        out = np.empty(3)
        evaluate_torque(self.rows(), float(t), q, w, out, np.empty(7))
        return out


def _vector(x, name):
    a = as_float_array(x, name, tail=(3,))
    if a.ndim != 1:
        raise ValueError(f"{name} must have shape (3,), got {a.shape}")
    return a


def _row(kind, *vectors):
    r = np.zeros(ROW_SIZE)
    r[0] = kind
    flat = np.concatenate([np.ravel(v) for v in vectors]) if vectors else np.zeros(0)
    r[1:1 + flat.size] = flat
    return r[None, :]


class GravityTorque(TorqueModel):
    """Uniform gravity on a body turning about a fixed pivot (heavy top, seed 六).

    Gravity points along space −z. The body torque about the pivot is
    ``M′ = lever × Rᵀ (0, 0, −weight)``.

    Parameters
    ----------
    weight : float
        m g in newtons (>= 0).
    lever : (3,) array_like
        Body-frame vector from the pivot to the centre of mass, metres.

    Examples
    --------
    >>> import numpy as np
    >>> g = GravityTorque(2.0, [0.0, 0.0, 0.5])
    >>> q = [np.cos(0.25), np.sin(0.25), 0.0, 0.0]   # tilted 0.5 rad about x
    >>> np.round(g(0.0, q, [0, 0, 0]), 6)             # 1 N m * sin(0.5) about +x
    array([0.479426, 0.      , 0.      ])
    """

    def __init__(self, weight, lever):
        weight = float(weight)
        if not (math.isfinite(weight) and weight >= 0.0):
            raise ValueError(f"weight must be a finite number >= 0 (m g in newtons), got {weight}")
        self.weight = weight
        self.lever = _vector(lever, "lever")

    def rows(self):
        return _row(CROSS, self.lever, np.array([0.0, 0.0, -self.weight]))

    def __repr__(self):
        return f"GravityTorque(weight={self.weight!r}, lever={self.lever.tolist()!r})"


class MagneticTorque(TorqueModel):
    """Magnetic dipole fixed in the body in a uniform field: ``M′ = m′ × Rᵀ B``.

    Parameters
    ----------
    dipole : (3,) array_like
        Magnetic moment in body coordinates, A m².
    field : (3,) array_like
        Uniform flux density in space coordinates, tesla.

    Examples
    --------
    >>> m = MagneticTorque([1.0, 0.0, 0.0], [0.0, 2.0, 0.0])
    >>> m(0.0, [1, 0, 0, 0], [0, 0, 0])
    array([0., 0., 2.])
    """

    def __init__(self, dipole, field):
        self.dipole = _vector(dipole, "dipole")
        self.field = _vector(field, "field")

    def rows(self):
        return _row(CROSS, self.dipole, self.field)

    def __repr__(self):
        return f"MagneticTorque(dipole={self.dipole.tolist()!r}, field={self.field.tolist()!r})"


class ConstantTorque(TorqueModel):
    """A torque fixed in the body (``frame="body"``) or in space (``frame="space"``).

    Parameters
    ----------
    torque : (3,) array_like
        N m, components in ``frame``.
    frame : {"body", "space"}

    Examples
    --------
    >>> c = ConstantTorque([0.0, 0.0, 1.0], frame="space")
    >>> q = [np.cos(np.pi / 4), np.sin(np.pi / 4), 0.0, 0.0]   # body x-axis turned 90°
    >>> np.round(c(0.0, q, [0, 0, 0]), 12) + 0.0
    array([0., 1., 0.])
    """

    def __init__(self, torque, frame="body"):
        if frame not in ("body", "space"):
            raise ValueError(f"frame must be 'space' or 'body', got {frame!r}")
        self.torque = _vector(torque, "torque")
        self.frame = frame

    def rows(self):
        return _row(BODY if self.frame == "body" else SPACE, self.torque)

    def __repr__(self):
        return f"ConstantTorque({self.torque.tolist()!r}, frame={self.frame!r})"


class LinearDamping(TorqueModel):
    """Viscous damping ``M′ = −C ω′`` with C a scalar, per-axis (3,) or (3, 3) matrix.

    Parameters
    ----------
    coefficient : float or (3,) or (3, 3) array_like
        N m s, in body coordinates; must be positive semi-definite.

    Examples
    --------
    >>> LinearDamping(0.5)(0.0, [1, 0, 0, 0], [2.0, 0.0, -4.0])
    array([-1.,  0.,  2.])
    """

    def __init__(self, coefficient):
        c = as_float_array(coefficient, "coefficient")
        if c.ndim == 0:
            c = c * np.eye(3)
        elif c.shape == (3,):
            c = np.diag(c)
        elif c.shape != (3, 3):
            raise ValueError(f"coefficient must be a scalar, (3,) or (3, 3), got shape {c.shape}")
        if np.linalg.eigvalsh(0.5 * (c + c.T)).min() < -1e-12 * max(1.0, np.abs(c).max()):
            raise ValueError("coefficient must be positive semi-definite (damping cannot add energy)")
        self.coefficient = c

    def rows(self):
        return _row(DAMPING, self.coefficient)

    def __repr__(self):
        return f"LinearDamping({self.coefficient.tolist()!r})"


class TorqueSum(TorqueModel):
    """Sum of torque models (what ``model_a + model_b`` returns).

    Examples
    --------
    >>> s = ConstantTorque([1.0, 0, 0]) + LinearDamping(1.0)
    >>> s(0.0, [1, 0, 0, 0], [1.0, 0, 0])
    array([0., 0., 0.])
    """

    def __init__(self, *models):
        flat = []
        for m in models:
            if not isinstance(m, TorqueModel):
                raise TypeError(f"TorqueSum takes torque models, got {type(m).__name__}")
            flat.extend(m.models if isinstance(m, TorqueSum) else [m])
        self.models = tuple(flat)

    def rows(self):
        if not self.models:
            return np.zeros((0, ROW_SIZE))
        return np.concatenate([m.rows() for m in self.models])

    def __repr__(self):
        return " + ".join(repr(m) for m in self.models) or "TorqueSum()"


def to_principal(rows, axes):
    """Express body-frame table rows in principal axes ``a_principal = axesᵀ a_body``."""
    if axes is None:
        return rows
    out = rows.copy()
    for r in out:
        kind = int(r[0])
        if kind in (BODY, CROSS):
            r[1:4] = axes.T @ r[1:4]
        elif kind == DAMPING:
            r[1:10] = (axes.T @ r[1:10].reshape(3, 3) @ axes).ravel()
    return out


# Python callables are looked up by id from the compiled loop: a table row
# carries only numbers, so the registry maps that number back to the function.
_CALLBACKS = {}
_IDS = itertools.count(1)


def register_callback(function):
    """Store a torque callable; return its id for a ``CALLBACK`` row."""
    key = next(_IDS)
    _CALLBACKS[key] = function
    return key


def release_callback(key):
    _CALLBACKS.pop(key, None)


def callback_row(key):
    r = np.zeros((1, ROW_SIZE))
    r[0, 0] = CALLBACK
    r[0, 1] = key
    return r


def _call_registered(key, t, q, w):
    return np.ascontiguousarray(_CALLBACKS[int(key)](t, q.copy(), w.copy()), dtype=np.float64)


@njit(cache=True)
def _callback_torque(key, t, q, w, out):
    with objmode(r="float64[:]"):
        r = _call_registered(key, t, q, w)
    out[0] += r[0]
    out[1] += r[1]
    out[2] += r[2]


@_jit
def evaluate_torque(rows, t, q, w, out, scratch):
    """Body torque of the model table at (t, q, ω′) into ``out``; ``scratch`` is (7,)."""
    out[0] = 0.0
    out[1] = 0.0
    out[2] = 0.0
    n = rows.shape[0]
    if n == 0:
        return
    # stage states of explicit Runge-Kutta methods are not exactly unit
    qn = scratch[0:4]
    v = scratch[4:7]
    qn[0] = q[0]
    qn[1] = q[1]
    qn[2] = q[2]
    qn[3] = q[3]
    qnormalize(qn)
    for i in range(n):
        r = rows[i]
        kind = int(r[0])
        if kind == BODY:
            out[0] += r[1]
            out[1] += r[2]
            out[2] += r[3]
        elif kind == SPACE:
            qrotate_inverse(qn, r[1:4], v)
            out[0] += v[0]
            out[1] += v[1]
            out[2] += v[2]
        elif kind == CROSS:
            qrotate_inverse(qn, r[4:7], v)
            out[0] += r[2] * v[2] - r[3] * v[1]
            out[1] += r[3] * v[0] - r[1] * v[2]
            out[2] += r[1] * v[1] - r[2] * v[0]
        elif kind == DAMPING:
            out[0] -= r[1] * w[0] + r[2] * w[1] + r[3] * w[2]
            out[1] -= r[4] * w[0] + r[5] * w[1] + r[6] * w[2]
            out[2] -= r[7] * w[0] + r[8] * w[1] + r[9] * w[2]
        else:
            _callback_torque(r[1], t, qn, w, out)
