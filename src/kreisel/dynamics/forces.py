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
from numpy.typing import ArrayLike, NDArray

from .._compiled import cached, inlined
from .._compiled.kernels import rotated
from .._validation import as_float_array
from ._model_tables import RowModel, RowSum, in_principal_axes, row, sum_rows

__all__ = ["ForceModel", "ConstantForce", "LinearDrag", "ForceSum"]

F_SPACE, F_BODY, F_DRAG = 0, 1, 2


class ForceModel(RowModel["ForceSum"]):
    """Base class of the compiled force models; models add with ``+``.

    Examples
    --------
    A 2 kg body thrown horizontally at 3 m/s under gravity and linear drag
    c = 0.5 N s/m: m v̇ = m g − c v relaxes v to the terminal velocity m g/c with
    time constant m/c, v(t) = v_T + (v0 − v_T) e^(−c t/m):

    >>> import numpy as np, kreisel as kr
    >>> from kreisel.dynamics import ConstantForce, LinearDrag
    >>> m, c, g = 2.0, 0.5, 9.81
    >>> air = ConstantForce([0.0, 0.0, -m * g]) + LinearDrag(c)
    >>> t = np.array([0.0, 1.0, 2.0])
    >>> tr = kr.simulate_6dof(kr.RigidBody([1.0, 2.0, 3.0], mass=m), t, [0.0, 0.0, 0.0],
    ...                       velocity0=[3.0, 0.0, 0.0], force=air)
    >>> terminal = np.array([0.0, 0.0, -m * g / c])
    >>> closed_form = terminal + ([3.0, 0.0, 0.0] - terminal) * np.exp(-c * t / m)[:, None]
    >>> tr.velocity[-1].round(6).tolist()
    [1.819592, 0.0, -15.439737]
    >>> bool(np.allclose(tr.velocity, closed_form, rtol=0.0, atol=1e-10))
    True
    """

    _sum: type[ForceSum]  # set once ForceSum exists, below

    def rows(self) -> NDArray[np.float64]:
        """The model's table rows (body vectors in body coordinates), shape ``(k, ROW_SIZE)``.

        Column 0 is the kind (space force, body force, drag), the rest its
        parameters; a sum stacks the rows of its terms.

        Examples
        --------
        A thruster fixed in the body and the weight fixed in space carry the same
        numbers but different kinds: only the thruster turns with the body.

        >>> from kreisel.dynamics import ConstantForce, LinearDrag
        >>> weight = ConstantForce([0.0, 0.0, -9.81])
        >>> thrust = ConstantForce([0.0, 0.0, -9.81], frame="body")
        >>> weight.rows()[0, :4].tolist(), thrust.rows()[0, :4].tolist()
        ([0.0, 0.0, 0.0, -9.81], [1.0, 0.0, 0.0, -9.81])
        >>> (weight + thrust + LinearDrag(0.2)).rows()[:, :2].tolist()
        [[0.0, 0.0], [1.0, 0.0], [2.0, 0.2]]
        """
        raise NotImplementedError


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

    def __init__(self, force: ArrayLike, frame: str = "space") -> None:
        if frame not in ("body", "space"):
            raise ValueError(f"frame must be 'space' or 'body', got {frame!r}")
        f = as_float_array(force, "force", tail=(3,))
        if f.ndim != 1:
            raise ValueError(f"force must have shape (3,), got {f.shape}")
        self.force = f
        self.frame = frame

    def rows(self) -> NDArray[np.float64]:
        return row(F_SPACE if self.frame == "space" else F_BODY, self.force)


class LinearDrag(ForceModel):
    """Linear drag on the centre of mass, ``F = −c v`` (c >= 0 in N s/m).

    Examples
    --------
    >>> LinearDrag(0.1).coefficient
    0.1
    """

    def __init__(self, coefficient: float) -> None:
        c = float(coefficient)
        if not (np.isfinite(c) and c >= 0.0):
            raise ValueError(f"coefficient must be a finite number >= 0, got {coefficient!r}")
        self.coefficient = c

    def rows(self) -> NDArray[np.float64]:
        return row(F_DRAG, [self.coefficient])


class ForceSum(RowSum, ForceModel):
    """Sum of force models (what ``model_a + model_b`` returns).

    Nested sums are flattened, so the compiled loop sees one row per force.

    Examples
    --------
    >>> from kreisel.dynamics import ConstantForce, ForceSum, LinearDrag
    >>> total = (ConstantForce([0.0, 0.0, -9.81]) + LinearDrag(0.1)) + ConstantForce([1.0, 0.0, 0.0])
    >>> isinstance(total, ForceSum), [type(f).__name__ for f in total.models]
    (True, ['ConstantForce', 'LinearDrag', 'ConstantForce'])
    >>> total.rows().shape
    (3, 10)
    """

    family = ForceModel
    noun = "force"


ForceModel._sum = ForceSum


def to_principal(rows: NDArray[np.float64], axes: NDArray[np.float64] | None) -> NDArray[np.float64]:
    """Force rows in principal axes: the body forces turn, the space ones and drag do not."""
    return in_principal_axes(rows, axes, (F_BODY,))


@inlined
def _force_term(rows: NDArray[np.float64], i: int, q0: float, q1: float, q2: float, q3: float, y: NDArray[np.float64]) -> tuple[float, float, float]:
    """Space force of row ``i`` at the unit attitude ``q`` and the state ``y = (ω′, q, r, v)``."""
    kind = int(rows[i, 0])
    if kind == F_SPACE:
        return rows[i, 1], rows[i, 2], rows[i, 3]
    if kind == F_BODY:
        return rotated(q0, q1, q2, q3, rows[i, 1], rows[i, 2], rows[i, 3])
    if kind == F_DRAG:
        return -rows[i, 1] * y[10], -rows[i, 1] * y[11], -rows[i, 1] * y[12]
    return 0.0, 0.0, 0.0


@cached
def evaluate_force(rows: NDArray[np.float64] | None, t: float, y: NDArray[np.float64], scratch: NDArray[np.float64]) -> None:
    """Space force on the centre of mass (None: no force) for ``y = (ω′, q, r, v)`` into ``scratch[10:13]``."""
    if rows is None:
        scratch[10] = scratch[11] = scratch[12] = 0.0
    else:
        sum_rows(_force_term, rows, t, y, scratch, 10)
