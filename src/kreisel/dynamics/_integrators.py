"""Compiled integrators for Euler's dynamic equations with quaternion attitude.

State ``y = (ω′1, ω′2, ω′3, q0, q1, q2, q3)`` in the principal frame (Theory §4.5,
principal-axis Euler equations), optionally followed by the centre of mass
position and velocity ``(r, v)`` in space (13 components, the 6-DOF body).
Every method is written once for one body: :func:`run_dop853` and
the fixed-step runners (:func:`runners`) integrate one body, :func:`run_dop853_batch` and the
runners' ``many`` many in parallel (``prange``) with the same code.

Status codes returned by the drivers: 0 success, 1 adaptive step fell below
round-off, 2 non-finite state, 3 implicit iteration did not converge (step
too large for the fixed-point iteration), 4 paused.

The drivers take at most ``budget`` steps per call and then return
:data:`PAUSED` with everything needed to continue in their state
(:class:`Steps`; DOP853: :class:`~kreisel._compiled.dop853.Runs`): the
Python caller calls again until done, so a long run returns to Python often
enough to be interrupted (Ctrl-C) and to report progress. Continuing is exact: a run gives the same bits for any budget.
"""

from __future__ import annotations

import math
from types import FunctionType
from typing import Any, NamedTuple

import numpy as np
from numba import prange
from numpy.typing import NDArray

from .._compiled import cached, generic, inlined, parallel
from .._compiled.dop853 import NOT_FINITE, OK, PAUSED, Runs, advance, new_work, no_crossing, no_record
from .._compiled.kernels import rotated
from .._compiled.kernels import quat_product, quat_unit, rotvec_quat
from ._model_tables import CALLBACK
from .forces import evaluate_force
from .torques import DAMPING, evaluate_torque

# method ids (the public names live in engine.METHODS)
DOP853, SPLITTING, SPLITTING4, DMV, RKMK4, MIDPOINT, RK4 = 0, 1, 2, 3, 4, 5, 6
NO_CONVERGENCE = 3

# Yoshida's triple jump: composing a symmetric 2nd-order step gives order 4
_CBRT2 = 2.0 ** (1.0 / 3.0)
YOSHIDA_OUTER = 1.0 / (2.0 - _CBRT2)
YOSHIDA_INNER = -_CBRT2 / (2.0 - _CBRT2)
_EPS = 2.220446049250313e-16
_MAX_ITER = 100

# for type checkers: a model table (None: no model) and the DOP853 coefficient tables
_Rows = NDArray[np.float64] | None
_Tables = tuple[NDArray[np.float64], ...]


# inlined into the DOP853 stage loop: a call per stage would pass its arrays through reference counting
@inlined
def rhs(t: float, y: NDArray[np.float64], ny: int, inertia: NDArray[np.float64], mass: float, rows: _Rows, frows: _Rows, dy: NDArray[np.float64],
        offset: int, scratch: NDArray[np.float64]) -> None:
    """dy[offset:offset+ny] = Euler's equations I ω̇′ = (Iω′) × ω′ + M′, q̇ = ½ q ⊗ (0, ω′), r̈ = F/m.

    Arrays are addressed by index (never sliced) so the hot loops create no
    array views; ``scratch`` (13,) receives the torque in [7:10], force in [10:13].
    ``rows``/``frows`` are None for no torque/force: numba then compiles a
    specialisation without the model evaluation.
    """
    evaluate_torque(rows, t, y, scratch)
    dy[offset], dy[offset + 1], dy[offset + 2], dy[offset + 3], dy[offset + 4], dy[offset + 5], dy[offset + 6] = \
        _euler_rates(inertia[0], inertia[1], inertia[2], scratch[7], scratch[8], scratch[9],
                     y[0], y[1], y[2], y[3], y[4], y[5], y[6])
    if ny == 13:
        evaluate_force(frows, t, y, scratch)
        for k in range(3):
            dy[offset + 7 + k] = y[10 + k]
            dy[offset + 10 + k] = scratch[10 + k] / mass


# inlined: as a call, LLVM left it out of the DOP853 stage loop
@inlined
def _euler_rates(i0, i1, i2, m0, m1, m2, w0, w1, w2, q0, q1, q2, q3):
    """(ω̇′, q̇) of the principal moments ``i``, the body torque ``m`` and the state ``(ω′, q)``, as numbers."""
    d0, d1, d2, d3 = quat_product(q0, q1, q2, q3, 0.0, w0, w1, w2)
    return (((i1 - i2) * w1 * w2 + m0) / i0, ((i2 - i0) * w2 * w0 + m1) / i1, ((i0 - i1) * w0 * w1 + m2) / i2,
            0.5 * d0, 0.5 * d1, 0.5 * d2, 0.5 * d3)


@inlined
def _model_rhs(t, y, model, dy, offset):
    """:func:`rhs` in the calling convention of :mod:`kreisel._compiled.dop853`; ``model = (inertia, mass, rows, frows, scratch)``."""
    rhs(t, y, y.size, model[0], model[1], model[2], model[3], dy, offset, model[4])


# ----------------------------------------------------------------------------
# fixed-step methods; each advances the rotation part y[0:7] in place by one step h. They share one
# signature, (t, h, inertia, rows, y, wa, wb, wc, wd, scratch) -> status, with the driver's work arrays
# wa (8), wb (8), wc (28), wd (12) and scratch (13) of :func:`rhs`; each uses those it needs.


@cached
def _axis_turn(c2, s2, mi, mj, q0, qk, qi, qj):
    """:func:`_axis_rotation` by the half angle whose cosine and sine are ``c2``, ``s2``."""
    # double angle from the half-angle pair: the momentum turns by twice the quaternion's half angle
    c = (c2 - s2) * (c2 + s2)
    s = 2.0 * s2 * c2
    return (c * mi + s * mj, c * mj - s * mi,
            c2 * q0 - s2 * qk, c2 * qk + s2 * q0, c2 * qi + s2 * qj, c2 * qj - s2 * qi)


@cached
def _axis_rotation(half, mi, mj, q0, qk, qi, qj):
    """One exact sub-flow about body axis k, on the components that change.

    (mi, mj), the momentum components after k in cyclic order, turn by
    −2·``half``; q ← q ⊗ (cos half, sin half e_k), a body-axis rotation
    applied on the right. Returns the new (mi, mj, q0, qk, qi, qj).
    """
    return _axis_turn(math.cos(half), math.sin(half), mi, mj, q0, qk, qi, qj)


@cached
def _axis_flow(k, h, i0, i1, i2, m0, m1, m2, q0, q1, q2, q3):
    """Exact flow of H_k = m_k²/(2 I_k) for a time h: m turns about body axis k by −h ω_k, q by +h ω_k.

    The state and the principal moments (i0, i1, i2) travel as scalars (m = I ω′
    and q), so a run of flows keeps them in registers and hands no array over
    (whose reference count every flow would update); ``k`` is a constant at
    every call, which selects the branch at compile time.
    """
    if k == 0:
        m1, m2, q0, q1, q2, q3 = _axis_rotation(0.5 * h / i0 * m0, m1, m2, q0, q1, q2, q3)
    elif k == 1:
        m2, m0, q0, q2, q3, q1 = _axis_rotation(0.5 * h / i1 * m1, m2, m0, q0, q2, q3, q1)
    else:
        m0, m1, q0, q3, q1, q2 = _axis_rotation(0.5 * h / i2 * m2, m0, m1, q0, q3, q1, q2)
    return m0, m1, m2, q0, q1, q2, q3


@cached
def _strang_free(h, inertia, y):
    # symmetric, hence second order; each flow keeps |m| and the space J exactly.
    # The flows act on m = I ω′ so that ω′ <-> m round trips happen once per step.
    i = (inertia[0], inertia[1], inertia[2])
    s = (i[0] * y[0], i[1] * y[1], i[2] * y[2], y[3], y[4], y[5], y[6])
    s = _axis_flow(0, 0.5 * h, *i, *s)
    s = _axis_flow(1, 0.5 * h, *i, *s)
    s = _axis_flow(2, h, *i, *s)
    s = _axis_flow(1, 0.5 * h, *i, *s)
    s = _axis_flow(0, 0.5 * h, *i, *s)
    for a in range(3):
        y[a] = s[a] / inertia[a]
    y[3], y[4], y[5], y[6] = s[3], s[4], s[5], s[6]
    return OK


@cached
def _kick(t, h, inertia, rows, y, scratch):
    """Explicit kick ω′ += h I⁻¹ M′(t, q, ω′): the exact flow when M′ does not depend on ω′."""
    evaluate_torque(rows, t, y, scratch)
    for a in range(3):
        y[a] += h * scratch[7 + a] / inertia[a]


@cached
def _depends_on_omega(rows):
    for i in range(rows.shape[0]):
        kind = int(rows[i, 0])
        if kind == DAMPING or kind == CALLBACK:
            return True
    return False


@cached
def _iterate_omega(y, n0, n1, n2, size, previous):
    """Store the fixed-point iterate ω′ = n; return (converged, change).

    Converged at round-off: the change is a few ulps of ``size`` = |ω′|₁, or it
    no longer shrinks once it is that small.
    """
    change = abs(n0 - y[0]) + abs(n1 - y[1]) + abs(n2 - y[2])
    y[0], y[1], y[2] = n0, n1, n2
    return change <= 4.0 * _EPS * size or (change >= previous and change <= 1e-13 * size), change


@cached
def _closing_kick(t, h, inertia, rows, y, scratch):
    """Implicit kick ω′_new = ω′ + h I⁻¹ M′(t, q, ω′_new), the adjoint of :func:`_kick`.

    Closing the step with the adjoint keeps kick–drift–kick symmetric, hence
    second order, also for torques that depend on ω′ (damping, callables).
    """
    if not _depends_on_omega(rows):
        _kick(t, h, inertia, rows, y, scratch)
        return OK
    w0, w1, w2 = y[0], y[1], y[2]
    size = abs(w0) + abs(w1) + abs(w2) + 1e-300
    previous = np.inf
    for _ in range(_MAX_ITER):
        evaluate_torque(rows, t, y, scratch)
        n0 = w0 + h * scratch[7] / inertia[0]
        n1 = w1 + h * scratch[8] / inertia[1]
        n2 = w2 + h * scratch[9] / inertia[2]
        converged, previous = _iterate_omega(y, n0, n1, n2, size, previous)
        if converged:
            return OK
    return NO_CONVERGENCE


@cached
def _dmv_free(h, inertia, y):
    """Discrete Moser-Veselov step: solve h m = 2 q0 I v + 2 v × I v for Ω = (q0, v)."""
    m0 = inertia[0] * y[0]
    m1 = inertia[1] * y[1]
    m2 = inertia[2] * y[2]
    v0 = 0.5 * h * y[0]
    v1 = 0.5 * h * y[1]
    v2 = 0.5 * h * y[2]
    size = abs(v0) + abs(v1) + abs(v2)
    converged = size == 0.0
    for _ in range(_MAX_ITER):
        if converged:
            break
        nv = v0 * v0 + v1 * v1 + v2 * v2
        if nv >= 1.0:
            return NO_CONVERGENCE
        c = math.sqrt(1.0 - nv)
        a0, a1, a2 = inertia[0] * v0, inertia[1] * v1, inertia[2] * v2
        n0 = (0.5 * h * m0 - (v1 * a2 - v2 * a1)) / (inertia[0] * c)
        n1 = (0.5 * h * m1 - (v2 * a0 - v0 * a2)) / (inertia[1] * c)
        n2 = (0.5 * h * m2 - (v0 * a1 - v1 * a0)) / (inertia[2] * c)
        change = abs(n0 - v0) + abs(n1 - v1) + abs(n2 - v2)
        v0, v1, v2 = n0, n1, n2
        converged = change <= 4.0 * _EPS * size
    if not converged:
        return NO_CONVERGENCE
    c = math.sqrt(1.0 - (v0 * v0 + v1 * v1 + v2 * v2))
    # m_{k+1} = Ωᵀ m_k  (rotate the body momentum back by Ω), q_{k+1} = q_k ⊗ Ω
    n0, n1, n2 = rotated(c, -v0, -v1, -v2, m0, m1, m2)
    y[0] = n0 / inertia[0]
    y[1] = n1 / inertia[1]
    y[2] = n2 / inertia[2]
    y[3], y[4], y[5], y[6] = quat_product(y[3], y[4], y[5], y[6], c, v0, v1, v2)
    return OK


@generic
def _kick_drift_kick(drift, t, h, inertia, rows, y, scratch):
    """The torque's kick for h/2, the torque-free step ``drift(h, inertia, y) -> status``, the closing kick."""
    if rows is not None:
        _kick(t, 0.5 * h, inertia, rows, y, scratch)
    status = drift(h, inertia, y)
    if rows is not None and status == OK:
        status = _closing_kick(t + h, 0.5 * h, inertia, rows, y, scratch)
    return status


@cached
def _splitting(t, h, inertia, rows, y, wa, wb, wc, wd, scratch):
    """Lie–Poisson splitting: the Strang step of the free body, a torque by kick–drift–kick."""
    return _kick_drift_kick(_strang_free, t, h, inertia, rows, y, scratch)


@cached
def _splitting4(t, h, inertia, rows, y, wa, wb, wc, wd, scratch):
    """Yoshida's triple jump of :func:`_splitting`: order 4."""
    status = _splitting(t, YOSHIDA_OUTER * h, inertia, rows, y, wa, wb, wc, wd, scratch)
    t1 = t + YOSHIDA_OUTER * h
    status += _splitting(t1, YOSHIDA_INNER * h, inertia, rows, y, wa, wb, wc, wd, scratch)
    t2 = t1 + YOSHIDA_INNER * h
    status += _splitting(t2, YOSHIDA_OUTER * h, inertia, rows, y, wa, wb, wc, wd, scratch)
    return status


@cached
def _dmv(t, h, inertia, rows, y, wa, wb, wc, wd, scratch):
    """Discrete Moser–Veselov, a torque by kick–drift–kick."""
    return _kick_drift_kick(_dmv_free, t, h, inertia, rows, y, scratch)


@cached
def _rates_at(t, i0, i1, i2, rows, stage, scratch, y):
    """:func:`_euler_rates` at the state ``y`` (a 7-tuple) under the torque table ``rows``.

    No torque (``rows`` None): numba prunes the model branch at compile
    time and the state never leaves the registers; a model reads the state
    from the array ``stage`` (``scratch`` as in :func:`rhs`).
    """
    m0 = m1 = m2 = 0.0
    if rows is not None:
        stage[0], stage[1], stage[2], stage[3], stage[4], stage[5], stage[6] = y
        evaluate_torque(rows, t, stage, scratch)
        m0, m1, m2 = scratch[7], scratch[8], scratch[9]
    return _euler_rates(i0, i1, i2, m0, m1, m2, y[0], y[1], y[2], y[3], y[4], y[5], y[6])


@cached
def _shifted(y, a, k):
    """``y + a k`` for 7-tuples."""
    return (y[0] + a * k[0], y[1] + a * k[1], y[2] + a * k[2], y[3] + a * k[3], y[4] + a * k[4], y[5] + a * k[5],
            y[6] + a * k[6])


@cached
def _rk4_sum(y, c, k1, k2, k3, k4, i):
    return y[i] + c * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@cached
def _rk4_step(t, h, i0, i1, i2, rows, stage, scratch, y):
    """Classical RK4 on the 7-tuple ``y = (ω′, q)``, q renormalised; the new state as a tuple (see :func:`_rates_at`)."""
    k1 = _rates_at(t, i0, i1, i2, rows, stage, scratch, y)
    k2 = _rates_at(t + 0.5 * h, i0, i1, i2, rows, stage, scratch, _shifted(y, 0.5 * h, k1))
    k3 = _rates_at(t + 0.5 * h, i0, i1, i2, rows, stage, scratch, _shifted(y, 0.5 * h, k2))
    k4 = _rates_at(t + h, i0, i1, i2, rows, stage, scratch, _shifted(y, h, k3))
    c = h / 6.0
    q0, q1, q2, q3 = quat_unit(_rk4_sum(y, c, k1, k2, k3, k4, 3), _rk4_sum(y, c, k1, k2, k3, k4, 4),
                               _rk4_sum(y, c, k1, k2, k3, k4, 5), _rk4_sum(y, c, k1, k2, k3, k4, 6))
    return (_rk4_sum(y, c, k1, k2, k3, k4, 0), _rk4_sum(y, c, k1, k2, k3, k4, 1), _rk4_sum(y, c, k1, k2, k3, k4, 2),
            q0, q1, q2, q3)


@cached
def _rk4(t, h, inertia, rows, y, stage, wb, wc, wd, scratch):
    """:func:`_rk4_step` on the array ``y`` (its first 7 components)."""
    y[0], y[1], y[2], y[3], y[4], y[5], y[6] = _rk4_step(t, h, inertia[0], inertia[1], inertia[2], rows, stage, scratch,
                                                         (y[0], y[1], y[2], y[3], y[4], y[5], y[6]))
    return OK


@cached
def _dexpinv_right(u0, u1, u2, f0, f1, f2):
    """Body-frame (right-trivialised) dexp⁻¹: u̇ = f + ½ u × f + (1/12) u × (u × f) + O(u⁴ f)."""
    c0 = u1 * f2 - u2 * f1
    c1 = u2 * f0 - u0 * f2
    c2 = u0 * f1 - u1 * f0
    d0 = u1 * c2 - u2 * c1
    d1 = u2 * c0 - u0 * c2
    d2 = u0 * c1 - u1 * c0
    return f0 + 0.5 * c0 + d0 / 12.0, f1 + 0.5 * c1 + d1 / 12.0, f2 + 0.5 * c2 + d2 / 12.0


@cached
def _group_stage(src, u0, u1, u2, dst):
    """dst[3:7] = src[3:7] ⊗ exp(u): the Lie-group stage point of RKMK."""
    e0, e1, e2, e3 = rotvec_quat(u0, u1, u2)
    dst[3], dst[4], dst[5], dst[6] = quat_product(src[3], src[4], src[5], src[6], e0, e1, e2, e3)


@cached
def _rkmk4(t, h, inertia, rows, y, y0, stage, deriv, ku, scratch):
    """Runge-Kutta-Munthe-Kaas with the classical RK4 tableau on SO(3) × R³.

    ``deriv`` holds ω̇′ of stage s at 7s, ``ku`` the dexp⁻¹ increments at 3s.
    """
    for i in range(7):
        y0[i] = y[i]
    u0 = u1 = u2 = 0.0
    for s in range(4):
        a = 0.0 if s == 0 else (h if s == 3 else 0.5 * h)
        if s > 0:
            u0, u1, u2 = a * ku[3 * s - 3], a * ku[3 * s - 2], a * ku[3 * s - 1]
        for i in range(3):
            stage[i] = y0[i] + (0.0 if s == 0 else a * deriv[7 * (s - 1) + i])
        _group_stage(y0, u0, u1, u2, stage)
        rhs(t + a, stage, 7, inertia, 1.0, rows, None, deriv, 7 * s, scratch)
        k0, k1, k2 = _dexpinv_right(u0, u1, u2, stage[0], stage[1], stage[2])
        ku[3 * s] = k0
        ku[3 * s + 1] = k1
        ku[3 * s + 2] = k2
    u0 = h / 6.0 * (ku[0] + 2.0 * ku[3] + 2.0 * ku[6] + ku[9])
    u1 = h / 6.0 * (ku[1] + 2.0 * ku[4] + 2.0 * ku[7] + ku[10])
    u2 = h / 6.0 * (ku[2] + 2.0 * ku[5] + 2.0 * ku[8] + ku[11])
    for i in range(3):
        y[i] = y0[i] + h / 6.0 * (deriv[i] + 2.0 * deriv[7 + i] + 2.0 * deriv[14 + i] + deriv[21 + i])
    _group_stage(y0, u0, u1, u2, y)
    y[3], y[4], y[5], y[6] = quat_unit(y[3], y[4], y[5], y[6])
    return OK


@cached
def _midpoint(t, h, inertia, rows, y, y0, mean, wc, wd, scratch):
    """Implicit midpoint on (ω′, q), solved by fixed-point iteration to round-off.

    The quaternion half is linear given the mean ω̄, so q1 = q0 ⊗ cay(h ω̄/2)
    in closed form (a unit quaternion); the momentum half is iterated.
    """
    for i in range(7):
        y0[i] = y[i]
    size = abs(y0[0]) + abs(y0[1]) + abs(y0[2]) + 1e-300
    previous = np.inf
    i0, i1, i2 = inertia[0], inertia[1], inertia[2]
    for _ in range(_MAX_ITER):
        for i in range(3):
            mean[i] = 0.5 * (y0[i] + y[i])
        a0, a1, a2 = 0.25 * h * mean[0], 0.25 * h * mean[1], 0.25 * h * mean[2]
        na = a0 * a0 + a1 * a1 + a2 * a2
        inv = 1.0 / (1.0 + na)
        c, s0, s1, s2 = (1.0 - na) * inv, 2.0 * a0 * inv, 2.0 * a1 * inv, 2.0 * a2 * inv
        y[3], y[4], y[5], y[6] = quat_product(y0[3], y0[4], y0[5], y0[6], c, s0, s1, s2)
        for i in range(3, 7):
            mean[i] = 0.5 * (y0[i] + y[i])
        evaluate_torque(rows, t + 0.5 * h, mean, scratch)
        m0, m1, m2 = scratch[7], scratch[8], scratch[9]
        w0, w1, w2 = mean[0], mean[1], mean[2]
        n0 = y0[0] + h * ((i1 - i2) * w1 * w2 + m0) / i0
        n1 = y0[1] + h * ((i2 - i0) * w2 * w0 + m1) / i1
        n2 = y0[2] + h * ((i0 - i1) * w0 * w1 + m2) / i2
        converged, previous = _iterate_omega(y, n0, n1, n2, size, previous)
        if converged:
            return OK
    return NO_CONVERGENCE


@cached
def _translation_kick(t, h, mass, frows, y, scratch):
    if frows is None:
        return
    evaluate_force(frows, t, y, scratch)
    for k in range(3):
        y[10 + k] += h * scratch[10 + k] / mass


class Steps(NamedTuple):
    """The resumable states of fixed-step runs (:func:`runners`), one row per body.

    Attributes
    ----------
    interval : (n,) ndarray of int64
        Output interval in progress; −1 before the first call.
    step : (n,) ndarray of int64
        Steps taken in it.
    pending : (n,) ndarray
        The deferred flow of a run whose state stays in registers (:func:`_register_run`).
    registers : (n, 7) ndarray
        The state of such a run, in the method's own variables.
    y : (n, ny) ndarray
        The state of the other runs (ω′, q, …); of every run before the first call.
    """

    interval: NDArray[np.int64]
    step: NDArray[np.int64]
    pending: NDArray[np.float64]
    registers: NDArray[np.float64]
    y: NDArray[np.float64]


def new_state(y0: NDArray[np.float64]) -> Steps:
    """The resumable states of fixed-step runs for bodies starting at ``y0 (count, ny)``: one :class:`Steps`."""
    count = y0.shape[0]
    return Steps(np.full(count, -1, dtype=np.int64), np.zeros(count, dtype=np.int64), np.zeros(count),
                 np.zeros((count, 7)), np.array(y0, dtype=np.float64, order="C"))


def reached(t_out: NDArray[np.float64], dt: float, state: Steps, paused: NDArray[np.bool_]) -> float:
    """The earliest time reached by the bodies ``paused`` (a mask) of ``state``."""
    k = np.clip(state.interval[paused], 0, t_out.size - 2)
    span = t_out[k + 1] - t_out[k]
    return float(np.min(t_out[k] + state.step[paused] * span / substeps(span, dt)))


def substeps(span: NDArray[np.float64], dt: float) -> NDArray[np.float64]:
    """Steps of the fixed-step drivers over intervals ``span``: ``ceil(span/dt)``, as floats (they may not fit an int)."""
    steps: NDArray[np.float64] = np.maximum(1.0, np.ceil(span / dt * (1.0 - 1e-12)))
    return steps


def step_grid(t_out: NDArray[np.float64], dt: float) -> NDArray[np.float64]:
    """The steps of the fixed-step drivers, per output interval: their size (row 0) and count (row 1, :func:`substeps`).

    Computed once per run, not per body and interval: a division and a
    rounding per interval cost as much as storing a sample.
    """
    span = np.diff(t_out)
    counts = substeps(span, dt)
    return np.stack([span / counts, counts])


@cached
def _sample(w0, w1, w2, q0, q1, q2, q3):
    """The output sample ``(ω′, q/|q|)``: its attitude as a unit quaternion.

    The squares are summed in numpy's order (``np.linalg.norm`` over the last
    axis), so the samples carry the same bits as normalising the whole output
    afterwards would give, without a second pass over it. The drivers write
    the tuple into the output themselves: no helper is handed the output
    array, whose reference count (shared by every body of a parallel batch,
    hence by both cores) numba would otherwise update per sample.
    """
    q0, q1, q2, q3 = quat_unit(q0, q1, q2, q3)
    return w0, w1, w2, q0, q1, q2, q3


@cached
def _next_sample(k, every):
    """(j, wait) at output time ``k``: the last sample stored is ``out[j]``, the next one ``wait`` intervals on.

    The drivers count down to the next sample instead of dividing by ``every``
    at each interval (an integer division costs as much as a step's arithmetic).
    """
    return k // every, every - k % every


@cached
def _finite(s, v):
    """Whether every number of the tuples ``s`` and ``v`` is finite, with one test instead of one per number.

    ``x - x`` is 0 for a finite ``x`` and NaN otherwise, and a sum with a NaN is NaN.
    """
    total = 0.0
    for x in s:
        total += x - x
    for x in v:
        total += x - x
    return total == 0.0


@generic
def _register_run(steps, at_output, from_omega, params, t_out, grid, state, b, inertia, out, budget, every):
    """A run of a torque-free body whose state stays in registers: one loop over numbers.

    ``steps(params, n, h, i0, i1, i2, s, pending) -> (s, pending)`` takes
    ``n`` steps of size ``h`` from the 7-tuple ``s``; ``at_output(params,
    h_next, i0, i1, i2, s, pending) -> (sample, s, pending)`` completes the
    state at an output time (``h_next``: the next interval's step, NaN after
    the last) and returns the sample ``(ω′, q)``; ``from_omega(params, i0,
    i1, i2, s)`` turns ``(ω′, q)`` into the method's state. ``pending``
    is a method's deferred work (see :func:`_splitting_free`). A pause keeps
    the state and ``pending`` in row ``b`` of ``state`` (:class:`Steps`).

    No array is handed to a helper in the loop: numba would update its
    reference count per interval, and the output's and the moments' counts
    are shared by every body of a parallel batch, hence contended by both
    cores.
    """
    i0, i1, i2 = inertia[0], inertia[1], inertia[2]
    k, s0, pending = state.interval[b], state.step[b], state.pending[b]
    r = state.registers
    s = (r[b, 0], r[b, 1], r[b, 2], r[b, 3], r[b, 4], r[b, 5], r[b, 6])
    if k < 0:
        y = state.y
        s = (y[b, 0], y[b, 1], y[b, 2], y[b, 3], y[b, 4], y[b, 5], y[b, 6])
        out[0, 0], out[0, 1], out[0, 2], out[0, 3], out[0, 4], out[0, 5], out[0, 6] = _sample(*s)
        s = from_omega(params, i0, i1, i2, s)
        k, pending = 0, 0.0
    j, wait = _next_sample(k, every)
    last = t_out.size - 1
    taken = 0
    while k < last:
        if taken >= budget:
            state.interval[b], state.step[b], state.pending[b] = k, s0, pending
            r[b, 0], r[b, 1], r[b, 2], r[b, 3], r[b, 4], r[b, 5], r[b, 6] = s
            return PAUSED
        h, n_sub = grid[0, k], int(grid[1, k])
        n = min(n_sub - s0, budget - taken)
        taken += n
        s, pending = steps(params, n, h, i0, i1, i2, s, pending)
        s0 += n
        if s0 < n_sub:
            continue
        k += 1
        s0 = 0
        wait -= 1
        v, s, pending = at_output(params, grid[0, k] if k < last else np.nan, i0, i1, i2, s, pending)
        if not _finite(s, v):
            return NOT_FINITE
        if wait == 0:
            j, wait = j + 1, every
            out[j, 0], out[j, 1], out[j, 2], out[j, 3], out[j, 4], out[j, 5], out[j, 6] = _sample(*v)
    return OK


# inlined, as _strang_output: called once per output interval, a call would pass the state through the stack
@inlined
def _strang_steps(weights, n, h, i0, i1, i2, s, pending):
    """``n`` steps of :func:`_splitting_free`, the flows about axis 0 merged; ``pending`` the one not yet applied."""
    for _ in range(n):
        for g in weights:
            pending += 0.5 * g * h
            if pending != 0.0:  # zero: the state is ahead by this half flow already
                s = _axis_flow(0, pending, i0, i1, i2, *s)
            s = _axis_flow(1, 0.5 * g * h, i0, i1, i2, *s)
            s = _axis_flow(2, g * h, i0, i1, i2, *s)
            s = _axis_flow(1, 0.5 * g * h, i0, i1, i2, *s)
            pending = 0.5 * g * h
    return s, pending


@inlined
def _strang_output(weights, h_next, i0, i1, i2, s, pending):
    """The sample of :func:`_splitting_free` at an output time (the pending flow applied) and the state.

    Before another interval the state is ahead by that interval's first half flow.
    """
    ahead = 0.5 * weights[0] * h_next
    if not math.isnan(ahead):
        v, s = _flows_at_output(pending, ahead, i0, s)
        pending = -ahead
    else:
        s = _axis_flow(0, pending, i0, i1, i2, *s)
        v = s
        pending = 0.0
    return (v[0] / i0, v[1] / i1, v[2] / i2, v[3], v[4], v[5], v[6]), s, pending


@cached
def _momentum(params, i0, i1, i2, s):
    """``(m = I ω′, q)`` from ``(ω′, q)``: the state of the splitting flows."""
    return i0 * s[0], i1 * s[1], i2 * s[2], s[3], s[4], s[5], s[6]


@generic
def _splitting_free(weights, t_out, grid, state, b, inertia, mass, rows, frows, out, budget, every):
    """A run of ``splitting``/``splitting4`` without torque, its state in registers.

    Each step is a composition of Strang steps of sizes ``weights·h``.
    Consecutive half-flows about axis 0 are merged into one (they commute and
    add: m_0 is their invariant), saving one flow in five; ``pending`` is
    the time of the half flow not yet applied. The flows act on m = I ω′, and
    the state stays m across output times (ω′ = m/I is formed for the
    samples only).

    At an output time before another interval the sample is the state
    advanced by the pending half flow, and the state is advanced by the next
    interval's first one too (:func:`_flows_at_output`); ``pending`` then
    turns negative (the state is ahead by the next half flow) and the next
    step skips its own. Between intervals of equal steps both flows come
    from one sine and cosine, so storing every step costs no flow that the
    end-state run does not take; steps that differ (if only in their last
    bits) take two, evaluated side by side. At the last time the pending
    flow is applied before the sample, as at the end of a run.
    """
    return _register_run(_strang_steps, _strang_output, _momentum, weights, t_out, grid, state, b, inertia, out,
                         budget, every)


@cached
def _rk4_steps(params, n, h, i0, i1, i2, s, pending):
    """``n`` torque-free :func:`_rk4_step` (which then depends on neither the time nor the arrays)."""
    for _ in range(n):
        s = _rk4_step(0.0, h, i0, i1, i2, None, None, None, s)
    return s, pending


@cached
def _rk4_output(params, h_next, i0, i1, i2, s, pending):
    return s, s, pending


@cached
def _same(params, i0, i1, i2, s):
    return s


@generic
def _rk4_free(params, t_out, grid, state, b, inertia, mass, rows, frows, out, budget, every):
    """A run of ``rk4`` without torque, its state ``(ω′, q)`` in registers."""
    return _register_run(_rk4_steps, _rk4_output, _same, None, t_out, grid, state, b, inertia, out, budget, every)


# inlined: LLVM kept it out of line, a call per output interval
@inlined
def _flows_at_output(p, ahead, i0, s):
    """(the state ``s`` after the flow of time ``p`` about axis 0, after that flow and the next of time ``ahead``).

    Equal flows (even steps) take one sine and cosine: the flow of 2p turns
    the quaternion by twice the half angle of the flow of p, whose cosine
    and sine follow by the double-angle formulas, as the momentum's do
    inside :func:`_axis_turn` (round-off as that of sin and cos). Unequal
    ones (steps that differ in their last bits, as those of most grids of
    ``np.linspace`` do) take the two flows of :func:`_axis_flow`; their
    angles depend on m_0 only, which neither flow changes, so the second
    sine and cosine need not wait for the first flow: the two evaluations
    overlap instead of following each other.
    """
    m0, m1, m2, q0, q1, q2, q3 = s
    half = 0.5 * p / i0 * m0
    c2, s2 = math.cos(half), math.sin(half)
    once = _axis_turn(c2, s2, m1, m2, q0, q1, q2, q3)
    if ahead == p:
        twice = _axis_turn((c2 - s2) * (c2 + s2), 2.0 * s2 * c2, m1, m2, q0, q1, q2, q3)
    else:
        half = 0.5 * ahead / i0 * m0
        twice = _axis_turn(math.cos(half), math.sin(half), *once)
    return (m0, once[0], once[1], once[2], once[3], once[4], once[5]), \
        (m0, twice[0], twice[1], twice[2], twice[3], twice[4], twice[5])


@generic
def _stepped(step, t_out: NDArray[np.float64], grid: NDArray[np.float64], state: Steps, b: int,
             inertia: NDArray[np.float64], mass: float, rows: _Rows, frows: _Rows, out: NDArray[np.float64],
             budget: int, every: int) -> int:
    """Fixed-step integration of body ``b`` of ``state``; interval k takes ``grid[1, k]`` steps of size ``grid[0, k]``.

    ``step`` is the method's step (see the fixed-step methods above).

    At most ``budget`` steps per call (see the module note). The grid comes
    from :func:`step_grid`, and the caller has checked that every step count
    fits an int. The state at ``t_out[k]`` is stored in ``out[k // every]``
    when ``every`` divides ``k`` (decimated output: the same steps, fewer
    samples kept).
    """
    ny = state.y.shape[1]
    y = np.empty(ny)
    for i in range(ny):
        y[i] = state.y[b, i]
    wa, wb, wc, wd, scratch = np.empty(8), np.empty(8), np.empty(28), np.empty(12), np.empty(13)
    k = state.interval[b]
    s0 = state.step[b]
    if k < 0:
        for i in range(7, ny):
            out[0, i] = y[i]
        out[0, 0], out[0, 1], out[0, 2], out[0, 3], out[0, 4], out[0, 5], out[0, 6] = \
            _sample(y[0], y[1], y[2], y[3], y[4], y[5], y[6])
        k = 0
    j, wait = _next_sample(k, every)
    taken = 0
    while k < t_out.size - 1:
        if taken >= budget:
            state.interval[b] = k
            state.step[b] = s0
            for i in range(ny):
                state.y[b, i] = y[i]
            return PAUSED
        h, n_sub = grid[0, k], int(grid[1, k])
        n = min(n_sub - s0, budget - taken)
        taken += n
        # the steps' loop is written here, not in an inlined helper: numba counted the references of the
        # seven arrays handed to the helper at every output interval
        for s in range(s0, s0 + n if ny == 7 else 0):
            if step(t_out[k] + s * h, h, inertia, rows, y, wa, wb, wc, wd, scratch) != OK:
                return NO_CONVERGENCE
        for s in range(s0, s0 + n if ny == 13 else 0):
            t = t_out[k] + s * h
            # velocity Verlet for the centre of mass around the rotation step
            _translation_kick(t, 0.5 * h, mass, frows, y, scratch)
            for c in range(3):
                y[7 + c] += h * y[10 + c]
            if step(t, h, inertia, rows, y, wa, wb, wc, wd, scratch) != OK:
                return NO_CONVERGENCE
            _translation_kick(t + h, 0.5 * h, mass, frows, y, scratch)
        s0 += n
        if s0 < n_sub:
            continue
        for i in range(ny):
            if not math.isfinite(y[i]):
                return NOT_FINITE
        k += 1
        s0 = 0
        wait -= 1
        if wait == 0:
            j, wait = j + 1, every
            for i in range(7, ny):
                out[j, i] = y[i]
            out[j, 0], out[j, 1], out[j, 2], out[j, 3], out[j, 4], out[j, 5], out[j, 6] = \
                _sample(y[0], y[1], y[2], y[3], y[4], y[5], y[6])
    return OK


@cached
def run_dop853(t_out: NDArray[np.float64], runs: Runs, b: int, inertia: NDArray[np.float64], mass: float, rows: _Rows,
               frows: _Rows, rtol: float, atol: NDArray[np.float64], tables: _Tables, out: NDArray[np.float64],
               budget: int) -> int:
    """Body ``b`` of ``runs``, at most ``budget`` DOP853 steps on: :func:`kreisel._compiled.dop853.advance`.

    ``out[k]`` receives the state at ``t_out[k]`` with its attitude as a unit
    quaternion. Decimated output takes the decimated times: the steps depend
    on the first and last output time only, so ``t_out[::every]`` gives the
    same steps, hence the same bits.
    """
    model = (inertia, mass, rows, frows, np.empty(13))
    return advance(_model_rhs, model, no_crossing, no_record, None, t_out, runs, b, new_work(runs.y.shape[1]), rtol,
                   atol, np.inf, tables, out, False, budget, 3, True)


@parallel
def run_dop853_batch(t_out: NDArray[np.float64], runs: Runs, inertia: NDArray[np.float64], mass: NDArray[np.float64],
                     rows: _Rows, frows: _Rows, rtol: float, atol: NDArray[np.float64], tables: _Tables,
                     out: NDArray[np.float64], status: NDArray[np.int64], budget: int) -> None:
    """Many bodies, one per ``prange`` iteration: the same code as :func:`run_dop853`.

    Bodies whose ``status`` is no longer :data:`PAUSED` (finished or failed) are skipped.
    """
    for b in prange(status.size):
        if status[b] == PAUSED:
            # np.int64: a prange index is unsigned, and run_dop853 would be compiled again for it
            status[b] = run_dop853(t_out, runs, np.int64(b), inertia[b], mass[b], rows, frows, rtol, atol[b], tables,
                                   out[b], budget)


# ----------------------------------------------------------------------------
# The runners. numba caches no function that takes another compiled function as an argument (its type holds
# the callee's address), so each fixed-step method gets compiled runners of its own, made from the two
# templates below by :func:`_declare`: a run compiles the method it uses and no other.

def _one_body(t_out, grid, state, b, inertia, mass, rows, frows, out, budget, every):
    """Body ``b``: the method's run ``RUN(PARAMETER, ...)`` (globals of each runner, see :func:`_declare`)."""
    return RUN(PARAMETER, t_out, grid, state, b, inertia, mass, rows, frows, out, budget, every)  # noqa: F821


def _many_bodies(t_out, grid, state, inertia, mass, rows, frows, out, status, budget, every):
    """Many bodies, one per ``prange`` iteration: the same code, the one-body runner ``ONE``, as for one.

    Bodies whose ``status`` is no longer :data:`PAUSED` (finished or failed) are skipped.
    """
    for b in prange(status.size):
        if status[b] == PAUSED:
            # np.int64: a prange index is unsigned, and ONE would be compiled again for it
            status[b] = ONE(t_out, grid, state, np.int64(b), inertia[b], mass[b], rows, frows,  # noqa: F821
                            out[b], budget, every)


class Runners(NamedTuple):
    """The compiled runners of a fixed-step method: ``one`` body (returns its status) and ``many`` (in parallel).

    ``one(t_out, grid, state, b, inertia, mass, rows, frows, out, budget, every)`` takes the arguments of
    :func:`_stepped`; ``many(t_out, grid, state, inertia, mass, rows, frows, out, status, budget, every)``
    the bodies' moments, masses, outputs and statuses as arrays.
    """

    one: Any
    many: Any


def _declare(name: str, run: Any, parameter: Any) -> Runners:
    """The runners of the method whose run of one body is ``run(parameter, t_out, grid, state, b, ...)``.

    Each is a template's code made a function of its own, named after the
    method (the name keys its cache entry), whose globals give ``RUN``,
    ``PARAMETER`` and ``ONE`` the method's.
    """
    def made(flavour: Any, template: Any, suffix: str, **constants: Any) -> Any:
        function = FunctionType(template.__code__, {**globals(), **constants}, f"{name}_{suffix}")
        function.__qualname__ = function.__name__
        return flavour(function)

    one = made(cached, _one_body, "one", RUN=run, PARAMETER=parameter)
    return Runners(one, made(parallel, _many_bodies, "many", ONE=one))


_RUNNERS = {SPLITTING: _declare("splitting", _stepped, _splitting),
            SPLITTING4: _declare("splitting4", _stepped, _splitting4),
            DMV: _declare("dmv", _stepped, _dmv),
            RKMK4: _declare("rkmk4", _stepped, _rkmk4),
            MIDPOINT: _declare("midpoint", _stepped, _midpoint),
            RK4: _declare("rk4", _stepped, _rk4)}
# a torque-free rotation (state (ω′, q), no torque) whose state stays in registers
_FREE_RUNNERS = {SPLITTING: _declare("splitting_free", _splitting_free, (1.0,)),
                 SPLITTING4: _declare("splitting4_free", _splitting_free, (YOSHIDA_OUTER, YOSHIDA_INNER, YOSHIDA_OUTER)),
                 RK4: _declare("rk4_free", _rk4_free, None)}


def runners(method: int, free: bool) -> Runners:
    """The runners of fixed-step ``method``; ``free``: a torque-free rotation alone (state (ω′, q), no torque).

    Examples
    --------
    >>> runners(SPLITTING, free=True) == runners(SPLITTING, free=False)
    False
    >>> runners(DMV, free=True) == runners(DMV, free=False)  # no torque-free runner of its own
    True
    """
    return _FREE_RUNNERS.get(method, _RUNNERS[method]) if free else _RUNNERS[method]
