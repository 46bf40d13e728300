"""Attitude interpolators: :class:`RotationSpline` (C², scipy's curve) and :class:`Slerp`.

``RotationSpline`` is scipy's construction: between knots ``t_i`` the
attitude is ``R(t) = R_i exp(ψ(t))`` with a cubic rotation vector ``ψ(t)``,
``ψ(t_i) = 0`` and ``ψ(t_{i+1}) = log(R_iᵀ R_{i+1})``; the knot rates are
solved for (with scipy's end conditions and fixed-point iteration) so that
angular velocity and angular acceleration are continuous. The angular
velocity of the curve is the dexp map of Theory §3.4,

.. math::

   \\omega' = J_r(\\psi)\\,\\dot\\psi
   = \\dot\\psi - A\\,\\psi\\times\\dot\\psi + B\\,\\psi\\times(\\psi\\times\\dot\\psi),
   \\qquad A = \\frac{1-\\cos\\psi}{\\psi^2},\\ B = \\frac{\\psi-\\sin\\psi}{\\psi^3},

which is the **body** angular velocity (``hat ω' = Rᵀ Ṙ``): that is what
scipy's ``RotationSpline(t, 1)`` returns. Here the frame is explicit:
``spline(t, 1, frame="body")`` is scipy's value and ``frame="space"`` gives
``ω = R ω'``; the angular accelerations are ``dω'/dt`` and ``dω/dt = R dω'/dt``.
Evaluation runs in compiled code, on both cores for long time arrays.
"""

from __future__ import annotations

from typing import Literal, overload

import numpy as np
from numba import types
from numpy.typing import ArrayLike, NDArray

from .._compiled import dexp, kernels
from .._compiled.checks import VECTOR, finite_array
from .._compiled.elementwise import Input, Parameter, declare, kernel
from .._compiled.outputs import takes_out
from .._norms import norm
from .._validation import check_frame, out_of_range, refuse_long_angle
from .rotation import Rotation

__all__ = ["RotationSpline", "Slerp"]


_BODY = -1.0  # the sign of the right Jacobian J_r, which maps ψ̇ to ω′


# A segment of the curve, gathered per time: its start time, the coefficients c₀, c₁, c₂ of
# ψ(τ) = ((c₀ τ + c₁) τ + c₂) τ and the knot's quaternion (14 numbers).


@kernel
def _psi(tau: float, c0x: float, c0y: float, c0z: float, c1x: float, c1y: float, c1z: float, c2x: float, c2y: float,
         c2z: float) -> tuple[float, float, float]:
    return ((c0x * tau + c1x) * tau + c2x) * tau, ((c0y * tau + c1y) * tau + c2y) * tau, ((c0z * tau + c1z) * tau + c2z) * tau


@kernel
def _attitude(t: float, ts: float, c0x: float, c0y: float, c0z: float, c1x: float, c1y: float, c1z: float, c2x: float,
              c2y: float, c2z: float, q0: float, q1: float, q2: float, q3: float) -> tuple[float, float, float, float]:
    # R_i exp(ψ(τ))
    x, y, z = _psi(t - ts, c0x, c0y, c0z, c1x, c1y, c1z, c2x, c2y, c2z)
    e0, e1, e2, e3 = kernels.rotvec_quat(x, y, z)
    r0, r1, r2, r3 = kernels.quat_product(q0, q1, q2, q3, e0, e1, e2, e3)
    return kernels.quat_unit(r0, r1, r2, r3)


@kernel
def _rate(t: float, ts: float, c0x: float, c0y: float, c0z: float, c1x: float, c1y: float, c1z: float, c2x: float,
          c2y: float, c2z: float, q0: float, q1: float, q2: float, q3: float, order: int,
          space: int) -> tuple[float, float, float]:
    # the body rate J_r(ψ) ψ̇ (order 1) or its derivative (order 2), turned by R_i exp(ψ(τ)) for space components
    tau = t - ts
    x, y, z = _psi(tau, c0x, c0y, c0z, c1x, c1y, c1z, c2x, c2y, c2z)
    vx = (3.0 * c0x * tau + 2.0 * c1x) * tau + c2x
    vy = (3.0 * c0y * tau + 2.0 * c1y) * tau + c2y
    vz = (3.0 * c0z * tau + 2.0 * c1z) * tau + c2z
    if order == 1:
        wx, wy, wz = dexp.jacobian_times(x, y, z, vx, vy, vz, _BODY)
    else:
        wx, wy, wz = dexp.jacobian_rate_times(
            x, y, z, vx, vy, vz, 6.0 * c0x * tau + 2.0 * c1x, 6.0 * c0y * tau + 2.0 * c1y, 6.0 * c0z * tau + 2.0 * c1z, _BODY
        )
    if space:
        e0, e1, e2, e3 = kernels.rotvec_quat(x, y, z)
        r0, r1, r2, r3 = kernels.quat_product(q0, q1, q2, q3, e0, e1, e2, e3)
        wx, wy, wz = kernels.rotated(r0, r1, r2, r3, wx, wy, wz)
    return wx, wy, wz


_SEGMENT = [Input("times", (), VECTOR), Input("segments", (14,), VECTOR)]
_attitudes = declare(_attitude, _SEGMENT, (4,), name="rotation_spline")
_rates = declare(_rate, _SEGMENT, (3,), [Parameter("order", types.int64), Parameter("space", types.int64)],
                 name="rotation_spline_rates").refusing(out_of_range("times", "the angular rate").message)


def _block_tridiagonal(lower: NDArray[np.float64], upper: NDArray[np.float64], diagonal: NDArray[np.float64]) -> NDArray[np.float64]:
    """Banded form (5, 5) of the block matrix with blocks d·1 on the diagonal, ``lower`` below, ``upper`` above."""
    m = len(diagonal)
    banded = np.zeros((11, 3 * m))
    rows, cols, values = [np.arange(3 * m)], [np.arange(3 * m)], [np.repeat(diagonal, 3)]
    r, c = np.meshgrid(np.arange(3), np.arange(3), indexing="ij")
    for blocks, row_shift, col_shift in ((lower, 1, 0), (upper, 0, 1)):
        for b, block in enumerate(blocks):
            rows.append((r + 3 * (b + row_shift)).ravel())
            cols.append((c + 3 * (b + col_shift)).ravel())
            values.append(block.ravel())
    i, j, v = np.concatenate(rows), np.concatenate(cols), np.concatenate(values)
    banded[5 + i - j, j] = v
    return banded


def _knot_rates(dt: NDArray[np.float64], rotvecs: NDArray[np.float64], max_iter: int, tol: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Body angular rates at the knots and ψ̇ at the segment starts (scipy's fixed-point scheme)."""
    from scipy.linalg import solve_banded

    rates = rotvecs / dt[:, None]
    if len(rotvecs) == 1:
        return rates, rates
    first = rates[0].copy()
    # J_r(ψ) (ψ̇ -> ω') and its inverse; no pole, as |ψ| <= π
    J_inv = dexp.jacobian_matrix(rotvecs, _BODY)
    J = dexp.jacobian_inverse_matrix(rotvecs, _BODY, 0.0)
    M = _block_tridiagonal(
        2.0 * J_inv[1:-1] / dt[1:-1, None, None], 2.0 * J[1:-1] / dt[1:-1, None, None], 4.0 * (1.0 / dt[:-1] + 1.0 / dt[1:])
    )
    b0 = 6.0 * (rotvecs[:-1] * dt[:-1, None] ** -2 + rotvecs[1:] * dt[1:, None] ** -2)
    b0[0] -= 2.0 / dt[0] * J_inv[0] @ first
    b0[-1] -= 2.0 / dt[-1] * J[-1] @ rates[-1]
    for _ in range(max_iter):
        rotvecs_dot = np.einsum("nij,nj->ni", J, rates)
        new = solve_banded((5, 5), M, (b0 - dexp.apply_jacobian_rate(rotvecs[:-1], rotvecs_dot[:-1], np.zeros(3), _BODY)).ravel()).reshape(-1, 3)
        done = np.all(np.abs(new - rates[:-1]) < tol * (1.0 + np.abs(new)))
        rates[:-1] = new
        if done:
            break
    rotvecs_dot = np.einsum("nij,nj->ni", J, rates)
    return np.vstack([first, rates[:-1]]), rotvecs_dot


def _rotations_quat(rotations: Rotation) -> NDArray[np.float64]:
    if not isinstance(rotations, Rotation):
        raise TypeError(f"rotations must be a kreisel Rotation, got {type(rotations).__name__}")
    if rotations.single or len(rotations.shape) != 1:
        raise ValueError(f"rotations must be a 1-D batch of rotations, got shape {rotations.shape}")
    return rotations.as_quat()


def _knot_times(times: ArrayLike, count: int) -> NDArray[np.float64]:
    t = finite_array(times, "times", None)
    if t.ndim != 1 or len(t) != count:
        raise ValueError(f"times must have shape ({count},), one per rotation, got {t.shape}")
    if count < 2:
        raise ValueError("times and rotations must hold at least 2 knots")
    if not np.all(np.diff(t) > 0):
        raise ValueError("times must be strictly increasing")
    return t


def _check_extrapolation(t: NDArray[np.float64], segments: NDArray[np.float64]) -> None:
    """Refuse ``times`` whose extrapolated rotation vector ψ(τ) is longer than ``ROTVEC_RANGE`` (1e8 rad)."""
    tau = (t - segments[..., 0])[..., None]
    with np.errstate(over="ignore", invalid="ignore"):
        psi = ((segments[..., 1:4] * tau + segments[..., 4:7]) * tau + segments[..., 7:10]) * tau
        longest = float(np.max(norm(psi), initial=0.0)) if np.isfinite(psi).all() else np.inf
    refuse_long_angle(longest, "times", "the extrapolated |psi|")


class RotationSpline:
    """C² attitude spline through rotations at given times (scipy's ``RotationSpline``).

    Parameters
    ----------
    times : array_like, shape (N,)
        Strictly increasing knot times, N >= 2.
    rotations : Rotation, shape (N,)
        Attitudes at the knots.

    Attributes
    ----------
    times : ndarray, shape (N,)
    rotations : Rotation

    Notes
    -----
    Same curve as scipy (same end conditions, ``MAX_ITER`` and ``TOL`` of the
    knot-rate iteration); see :mod:`kreisel.so3.spline` for the frames of the
    derivatives. Times outside the knots extrapolate the end segments (as far
    as their rotation vector stays within 1e8 rad, else they are refused). For
    large turns between knots scipy's 10 iterations may stop short of
    convergence, leaving jumps of the angular acceleration at the knots
    (~1e-4 rad/s² for random attitudes a second apart); a subclass with a
    larger ``MAX_ITER`` gives the converged, truly C² curve.

    Examples
    --------
    >>> import numpy as np
    >>> times = [0.0, 10.0, 20.0, 40.0]
    >>> knots = Rotation.from_euler("XYZ", [[-10, 20, 30], [0, 15, 40], [-30, 45, 30], [20, 45, 90]], degrees=True)
    >>> spline = RotationSpline(times, knots)
    >>> bool(spline(times).approx_equal(knots, atol=1e-12).all())
    True
    >>> spline([5.0, 15.0], 1, frame="body").shape                # angular velocity, rad/s
    (2, 3)
    """

    #: Iterations and relative tolerance of the knot-rate solve (scipy's values).
    MAX_ITER = 10
    TOL = 1e-9

    def __init__(self, times: ArrayLike, rotations: Rotation) -> None:
        q = _rotations_quat(rotations)
        self.times = _knot_times(times, len(q))
        self.rotations = rotations
        dt = np.diff(self.times)
        rotvecs = (rotations[:-1].inv() * rotations[1:]).as_rotvec()
        rates, rotvecs_dot = _knot_rates(dt, rotvecs, self.MAX_ITER, self.TOL)
        dt = dt[:, None]
        coeff = np.empty((len(dt), 3, 3))
        coeff[:, 0] = (-2.0 * rotvecs + dt * rates + dt * rotvecs_dot) / dt**3
        coeff[:, 1] = (3.0 * rotvecs - 2.0 * dt * rates - dt * rotvecs_dot) / dt**2
        coeff[:, 2] = rates
        self._segments = np.concatenate([self.times[:-1, None], coeff.reshape(-1, 9), q[:-1]], axis=1)

    @overload
    def __call__(self, times: ArrayLike, order: Literal[0] = 0, frame: str | None = None, *, out: None = None) -> Rotation: ...

    @overload
    def __call__(self, times: ArrayLike, order: Literal[1, 2], frame: str | None = None, *,
                 out: NDArray[np.float64] | None = None) -> NDArray[np.float64]: ...

    @overload
    def __call__(self, times: ArrayLike, order: int, frame: str | None = None, *,
                 out: NDArray[np.float64] | None = None) -> Rotation | NDArray[np.float64]: ...

    @takes_out(result="Result array for ``order`` 1 and 2, shape ``times.shape + (3,)``, may\n"
                      "share memory with ``times``; ``order=0`` returns a new :class:`Rotation`\n"
                      "and refuses it")
    def __call__(self, times: ArrayLike, order: int = 0, frame: str | None = None, *,
                 out: NDArray[np.float64] | None = None) -> Rotation | NDArray[np.float64]:
        """Attitudes (``order=0``), angular velocities (1) or angular accelerations (2) at ``times``.

        Parameters
        ----------
        times : float or array_like
            Any shape; the result has that batch shape.
        order : {0, 1, 2}
        frame : {"body", "space"}
            Required for ``order`` 1 and 2. ``"body"`` (``hat ω' = Rᵀ Ṙ``) is
            what scipy's ``RotationSpline`` returns; ``"space"`` is ``R ω'``.

        Returns
        -------
        Rotation or ndarray, shape (..., 3)

        Examples
        --------
        The rates are the derivative of the curve (here checked by a central difference):

        >>> import numpy as np
        >>> spline = RotationSpline([0.0, 1.0, 3.0], Rotation.random(3, rng=0))
        >>> h = 1e-6
        >>> Rdot = (spline(1.5 + h).as_matrix() - spline(1.5 - h).as_matrix()) / (2 * h)
        >>> W = spline(1.5).as_matrix().T @ Rdot
        >>> bool(np.allclose(spline(1.5, 1, frame="body"), [W[2, 1], W[0, 2], W[1, 0]], atol=1e-6))
        True
        """
        if order not in (0, 1, 2):
            raise ValueError(f"order must be 0, 1 or 2, got {order!r}")
        if order and frame is None:
            raise ValueError(
                "frame must be given for derivatives: 'body' (what scipy's RotationSpline returns) or 'space'"
            )
        if out is not None and order == 0:
            raise ValueError("out is for the angular rates (order 1 or 2); order 0 returns a new Rotation")
        space = order > 0 and not check_frame(frame)
        t = finite_array(times, "times", None)
        index = np.clip(np.searchsorted(self.times, t, side="right") - 1, 0, len(self.times) - 2)
        segments = self._segments[index]
        if t.size and (t.min() < self.times[0] or t.max() > self.times[-1]):
            _check_extrapolation(t, segments)
        if order == 0:
            return Rotation._wrap(_attitudes(t, segments))
        return _rates(t, segments, order, int(space), out=out)


class Slerp:
    """Piecewise slerp through rotations at given times (scipy's ``Slerp``).

    Constant angular velocity between knots, along the shortest arc; times
    outside ``[times[0], times[-1]]`` are refused, as in scipy.

    Parameters
    ----------
    times : array_like, shape (N,)
        Strictly increasing, N >= 2.
    rotations : Rotation, shape (N,)

    Examples
    --------
    >>> import numpy as np
    >>> slerp = Slerp([0.0, 2.0], Rotation.from_rotvec([[0.0, 0.0, 0.0], [0.0, 0.0, 1.0]]))
    >>> slerp([0.5, 1.0]).as_rotvec().round(12).tolist()
    [[0.0, 0.0, 0.25], [0.0, 0.0, 0.5]]
    """

    def __init__(self, times: ArrayLike, rotations: Rotation) -> None:
        q = _rotations_quat(rotations)
        self.times = _knot_times(times, len(q))
        self.rotations = rotations
        self.timedelta = np.diff(self.times)
        self.rotvecs = (rotations[:-1].inv() * rotations[1:]).as_rotvec()

    def __call__(self, times: ArrayLike) -> Rotation:
        """Interpolated rotations at ``times`` (any shape within the knot range).

        Examples
        --------
        >>> slerp = Slerp([0.0, 1.0, 2.0], Rotation.from_rotvec([[0, 0, 0], [0, 0, 1.0], [0, 1.0, 1.0]]))
        >>> slerp(1.0).as_rotvec().round(12).tolist()
        [0.0, 0.0, 1.0]
        """
        t = finite_array(times, "times", None)
        if t.size and (t.min() < self.times[0] or t.max() > self.times[-1]):
            raise ValueError(f"times must lie within [{self.times[0]}, {self.times[-1]}] (no extrapolation)")
        index = np.clip(np.searchsorted(self.times, t, side="right") - 1, 0, len(self.times) - 2)
        alpha = (t - self.times[index]) / self.timedelta[index]
        step = Rotation.from_rotvec(self.rotvecs[index] * alpha[..., None])
        return self.rotations[index] * step
