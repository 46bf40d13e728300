"""Torque models for :func:`kreisel.simulate` (Theory §4.4: dJ/dt = M).

Every built-in model is encoded as rows of a small float table that the
compiled integrators read inside their time loop, so a simulation under
gravity, a magnetic field, damping or any sum of them never leaves machine
code. A plain Python callable ``torque(t, q, omega_body) -> (3,)`` is also
accepted by :func:`kreisel.simulate`; it is called back from the compiled loop
(through numba's object mode), far slower than a built-in model.

Table layout (:mod:`kreisel.dynamics._model_tables`): one row of ``ROW_SIZE`` floats
per model, ``row[0]`` the kind, ``row[1:]`` its parameters, all in the frame
the integrator works in (the principal frame of the body).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import cached, inlined
from .._compiled.kernels import rotated
from .._validation import as_float_array
from ._model_tables import RowModel, RowSum, in_principal_axes, row, sum_rows

__all__ = [
    "TorqueModel",
    "GravityTorque",
    "ConstantTorque",
    "MagneticTorque",
    "LinearDamping",
    "TorqueSum",
]

BODY, SPACE, CROSS, DAMPING = 0, 1, 2, 3


class TorqueModel(RowModel["TorqueSum"]):
    """Base class of the compiled torque models; models add with ``+``.

    A model is also callable, ``model(t, q, omega_body)`` returning the body
    torque ``M′`` in N m, which is what the integrators evaluate.

    Examples
    --------
    A top standing upright feels no gravity torque (lever parallel to the
    weight), only the damping −C ω′ of its spin:

    >>> from kreisel.dynamics import GravityTorque, LinearDamping, TorqueModel
    >>> model = GravityTorque(9.81, [0.0, 0.0, 0.1]) + LinearDamping(0.01)
    >>> isinstance(model, TorqueModel), len(model.rows())
    (True, 2)
    >>> model(0.0, [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 10.0]).tolist()
    [0.0, 0.0, -0.1]
    """

    _sum: type[TorqueSum]  # set once TorqueSum exists, below

    def rows(self) -> NDArray[np.float64]:
        """The model's table rows in body coordinates, shape ``(k, ROW_SIZE)``.

        Column 0 is the kind, the rest its parameters; a sum stacks the rows of
        its terms, which the compiled integrators add up.

        Examples
        --------
        Gravity on a top is the torque on a dipole: both are a body vector crossed
        with a fixed space vector (lever × m g, dipole × B), so they share one row kind:

        >>> from kreisel.dynamics import GravityTorque, MagneticTorque, LinearDamping
        >>> gravity = GravityTorque(2.0, [0.0, 0.0, 0.5])
        >>> gravity.rows()[0].tolist()
        [2.0, 0.0, 0.0, 0.5, 0.0, 0.0, -2.0, 0.0, 0.0, 0.0]
        >>> bool((gravity.rows() == MagneticTorque([0.0, 0.0, 0.5], [0.0, 0.0, -2.0]).rows()).all())
        True
        >>> (gravity + LinearDamping(0.1)).rows().shape
        (2, 10)
        """
        raise NotImplementedError

    def __call__(self, t: float, q: ArrayLike, omega_body: ArrayLike) -> NDArray[np.float64]:
        q = as_float_array(q, "q", tail=(4,))
        w = as_float_array(omega_body, "omega_body", tail=(3,))
        if q.ndim != 1 or w.ndim != 1:
            raise ValueError("a torque model is evaluated for one state: q (4,), omega_body (3,)")
        scratch = np.zeros(13)
        evaluate_torque(self.rows(), float(t), np.concatenate([w, q]), scratch)
        return scratch[7:10].copy()


def _vector(x: ArrayLike, name: str) -> NDArray[np.float64]:
    a = as_float_array(x, name, tail=(3,))
    if a.ndim != 1:
        raise ValueError(f"{name} must have shape (3,), got {a.shape}")
    return a


class GravityTorque(TorqueModel):
    """Uniform gravity on a body turning about a fixed pivot (heavy top, Theory §6).

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

    def __init__(self, weight: float, lever: ArrayLike) -> None:
        weight = float(weight)
        if not (math.isfinite(weight) and weight >= 0.0):
            raise ValueError(f"weight must be a finite number >= 0 (m g in newtons), got {weight}")
        self.weight = weight
        self.lever = _vector(lever, "lever")

    def rows(self) -> NDArray[np.float64]:
        return row(CROSS, self.lever, np.array([0.0, 0.0, -self.weight]))

    def __repr__(self) -> str:
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

    def __init__(self, dipole: ArrayLike, field: ArrayLike) -> None:
        self.dipole = _vector(dipole, "dipole")
        self.field = _vector(field, "field")

    def rows(self) -> NDArray[np.float64]:
        return row(CROSS, self.dipole, self.field)

    def __repr__(self) -> str:
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

    def __init__(self, torque: ArrayLike, frame: str = "body") -> None:
        if frame not in ("body", "space"):
            raise ValueError(f"frame must be 'space' or 'body', got {frame!r}")
        self.torque = _vector(torque, "torque")
        self.frame = frame

    def rows(self) -> NDArray[np.float64]:
        return row(BODY if self.frame == "body" else SPACE, self.torque)

    def __repr__(self) -> str:
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

    def __init__(self, coefficient: ArrayLike) -> None:
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

    def rows(self) -> NDArray[np.float64]:
        return row(DAMPING, self.coefficient)

    def __repr__(self) -> str:
        return f"LinearDamping({self.coefficient.tolist()!r})"


class TorqueSum(RowSum, TorqueModel):
    """Sum of torque models (what ``model_a + model_b`` returns).

    Examples
    --------
    >>> s = ConstantTorque([1.0, 0, 0]) + LinearDamping(1.0)
    >>> s(0.0, [1, 0, 0, 0], [1.0, 0, 0])
    array([0., 0., 0.])
    """

    family = TorqueModel
    noun = "torque"

    def __repr__(self) -> str:
        return " + ".join(repr(m) for m in self.models) or "TorqueSum()"


TorqueModel._sum = TorqueSum


def to_principal(rows: NDArray[np.float64], axes: NDArray[np.float64] | None) -> NDArray[np.float64]:
    """Torque rows in principal axes: body torques, the body arm of a cross torque and the damping matrix turn."""
    return in_principal_axes(rows, axes, (BODY, CROSS), (DAMPING,))


@inlined
def _torque_term(rows: NDArray[np.float64], i: int, q0: float, q1: float, q2: float, q3: float, y: NDArray[np.float64]) -> tuple[float, float, float]:
    """Body torque of row ``i`` at the unit attitude ``q`` and the state ``y = (ω′, q, ...)``."""
    kind = int(rows[i, 0])
    if kind == SPACE:
        return rotated(q0, -q1, -q2, -q3, rows[i, 1], rows[i, 2], rows[i, 3])
    if kind == BODY:
        return rows[i, 1], rows[i, 2], rows[i, 3]
    if kind == CROSS:
        a0, a1, a2 = rows[i, 1], rows[i, 2], rows[i, 3]
        v0, v1, v2 = rotated(q0, -q1, -q2, -q3, rows[i, 4], rows[i, 5], rows[i, 6])
        return a1 * v2 - a2 * v1, a2 * v0 - a0 * v2, a0 * v1 - a1 * v0
    if kind == DAMPING:
        w0, w1, w2 = y[0], y[1], y[2]
        return (-(rows[i, 1] * w0 + rows[i, 2] * w1 + rows[i, 3] * w2),
                -(rows[i, 4] * w0 + rows[i, 5] * w1 + rows[i, 6] * w2),
                -(rows[i, 7] * w0 + rows[i, 8] * w1 + rows[i, 9] * w2))
    return 0.0, 0.0, 0.0


@cached
def evaluate_torque(rows: NDArray[np.float64] | None, t: float, y: NDArray[np.float64], scratch: NDArray[np.float64]) -> None:
    """Body torque of the model table (None: no torque) at ``y = (ω′, q, ...)`` into ``scratch[7:10]``.

    A separate (not inlined) function, so that numba compiles the None case
    to three stores: inside inlined code it no longer prunes on argument types.
    """
    if rows is None:
        scratch[7] = scratch[8] = scratch[9] = 0.0
    else:
        sum_rows(_torque_term, rows, t, y, scratch, 7)
