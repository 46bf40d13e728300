"""Compiled integrators for Euler's dynamic equations with quaternion attitude.

State ``y = (ω′1, ω′2, ω′3, q0, q1, q2, q3)`` in the principal frame (seed 四.5,
principal-axis Euler equations), optionally followed by the centre of mass
position and velocity ``(r, v)`` in space (13 components, the 6-DOF body).
Every method is written once for one body; :func:`run` integrates one body
and :func:`run_batch` many in parallel (``prange``) with the same code.

Status codes returned by the drivers: 0 success, 1 adaptive step fell below
round-off, 2 non-finite state, 3 implicit iteration did not converge (step
too large for the fixed-point iteration).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..so3._kernels import qnormalize
from .forces import evaluate_force
from .torques import CALLBACK, DAMPING, evaluate_torque

_jit = njit(cache=True, nogil=True)

# method ids (the public names live in _simulate.METHODS)
DOP853, SPLITTING, SPLITTING4, DMV, RKMK4, MIDPOINT, RK4 = 0, 1, 2, 3, 4, 5, 6
OK, STEP_TOO_SMALL, NOT_FINITE, NO_CONVERGENCE = 0, 1, 2, 3

# Yoshida's triple jump: composing a symmetric 2nd-order step gives order 4
_CBRT2 = 2.0 ** (1.0 / 3.0)
YOSHIDA_OUTER = 1.0 / (2.0 - _CBRT2)
YOSHIDA_INNER = -_CBRT2 / (2.0 - _CBRT2)
_EPS = 2.220446049250313e-16
_MAX_ITER = 100


@_jit
def rhs(t, y, inertia, mass, rows, frows, dy, scratch):
    """dy/dt: Euler's equations I ω̇′ = (Iω′) × ω′ + M′, q̇ = ½ q ⊗ (0, ω′), r̈ = F/m."""
    w0, w1, w2 = y[0], y[1], y[2]
    q0, q1, q2, q3 = y[3], y[4], y[5], y[6]
    m = scratch[7:10]
    evaluate_torque(rows, t, y[3:7], y[0:3], m, scratch[0:7])
    i0, i1, i2 = inertia[0], inertia[1], inertia[2]
    dy[0] = ((i1 - i2) * w1 * w2 + m[0]) / i0
    dy[1] = ((i2 - i0) * w2 * w0 + m[1]) / i1
    dy[2] = ((i0 - i1) * w0 * w1 + m[2]) / i2
    dy[3] = -0.5 * (q1 * w0 + q2 * w1 + q3 * w2)
    dy[4] = 0.5 * (q0 * w0 + q2 * w2 - q3 * w1)
    dy[5] = 0.5 * (q0 * w1 + q3 * w0 - q1 * w2)
    dy[6] = 0.5 * (q0 * w2 + q1 * w1 - q2 * w0)
    if y.shape[0] == 13:
        f = scratch[10:13]
        evaluate_force(frows, t, y, f, scratch[0:7])
        for k in range(3):
            dy[7 + k] = y[10 + k]
            dy[10 + k] = f[k] / mass


# ----------------------------------------------------------------------------
# adaptive Dormand-Prince 8(5,3) with 7th-order dense output (Hairer-Norsett-Wanner II.10)


@_jit
def _rms(x, scale):
    s = 0.0
    for i in range(x.size):
        v = x[i] / scale[i]
        s += v * v
    return math.sqrt(s / x.size)


@_jit
def _initial_step(t0, y0, f0, span, inertia, mass, rows, frows, rtol, atol, tmp, f1, scratch):
    ny = y0.size
    scale = np.empty(ny)
    for i in range(ny):
        scale[i] = atol[i] + abs(y0[i]) * rtol
    d0 = _rms(y0, scale)
    d1 = _rms(f0, scale)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, span)
    for i in range(ny):
        tmp[i] = y0[i] + h0 * f0[i]
    rhs(t0 + h0, tmp, inertia, mass, rows, frows, f1, scratch)
    for i in range(ny):
        tmp[i] = f1[i] - f0[i]
    d2 = _rms(tmp, scale) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, span)


@_jit
def dop853(t_out, y0, inertia, mass, rows, frows, rtol, atol, tab_a, tab_b, tab_c, tab_e3, tab_e5,
           tab_d, out):
    """Integrate from ``t_out[0]`` and write the state at every ``t_out`` into ``out``."""
    ny = y0.size
    n_out = t_out.size
    k = np.empty((16, ny))
    y = y0.copy()
    y_new = np.empty(ny)
    tmp = np.empty(ny)
    dense = np.empty((7, ny))
    scale = np.empty(ny)
    scratch = np.empty(13)
    out[0, :] = y
    if n_out == 1:
        return OK
    t = t_out[0]
    t_end = t_out[n_out - 1]
    rhs(t, y, inertia, mass, rows, frows, k[0], scratch)
    h = _initial_step(t, y, k[0], t_end - t, inertia, mass, rows, frows, rtol, atol, tmp, k[1], scratch)
    j = 1
    while j < n_out:
        rejected = False
        while True:
            min_step = 10.0 * _EPS * max(abs(t), 1e-300)
            if h < min_step:
                return STEP_TOO_SMALL
            t_new = t + h
            if t_new >= t_end:
                t_new = t_end
            h = t_new - t
            for s in range(1, 12):
                for i in range(ny):
                    acc = 0.0
                    for r in range(s):
                        acc += tab_a[s, r] * k[r, i]
                    tmp[i] = y[i] + h * acc
                rhs(t + tab_c[s] * h, tmp, inertia, mass, rows, frows, k[s], scratch)
            for i in range(ny):
                acc = 0.0
                for r in range(12):
                    acc += tab_b[r] * k[r, i]
                y_new[i] = y[i] + h * acc
            rhs(t_new, y_new, inertia, mass, rows, frows, k[12], scratch)
            e5 = 0.0
            e3 = 0.0
            for i in range(ny):
                scale[i] = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
                a5 = 0.0
                a3 = 0.0
                for r in range(13):
                    a5 += tab_e5[r] * k[r, i]
                    a3 += tab_e3[r] * k[r, i]
                e5 += (a5 / scale[i]) ** 2
                e3 += (a3 / scale[i]) ** 2
            if e5 == 0.0 and e3 == 0.0:
                err = 0.0
            else:
                err = h * e5 / math.sqrt((e5 + 0.01 * e3) * ny)
            if not math.isfinite(err):
                err = 1e300
            if err < 1.0:
                factor = 10.0 if err == 0.0 else min(10.0, 0.9 * err ** (-1.0 / 8.0))
                if rejected:
                    factor = min(1.0, factor)
                h_next = h * factor
                break
            h *= max(0.2, 0.9 * err ** (-1.0 / 8.0))
            rejected = True
        if t_out[j] <= t_new:
            # three extra stages make the interpolant 7th order
            for s in range(13, 16):
                for i in range(ny):
                    acc = 0.0
                    for r in range(s):
                        acc += tab_a[s, r] * k[r, i]
                    tmp[i] = y[i] + h * acc
                rhs(t + tab_c[s] * h, tmp, inertia, mass, rows, frows, k[s], scratch)
            for i in range(ny):
                dy = y_new[i] - y[i]
                dense[0, i] = dy
                dense[1, i] = h * k[0, i] - dy
                dense[2, i] = 2.0 * dy - h * (k[12, i] + k[0, i])
                for p in range(4):
                    acc = 0.0
                    for r in range(16):
                        acc += tab_d[p, r] * k[r, i]
                    dense[3 + p, i] = h * acc
            while j < n_out and t_out[j] <= t_new:
                if t_out[j] == t_new:
                    out[j, :] = y_new
                else:
                    x = (t_out[j] - t) / h
                    for i in range(ny):
                        v = 0.0
                        for p in range(7):
                            v += dense[6 - p, i]
                            v *= x if p % 2 == 0 else 1.0 - x
                        out[j, i] = v + y[i]
                j += 1
        for i in range(ny):
            y[i] = y_new[i]
            k[0, i] = k[12, i]
            if not math.isfinite(y[i]):
                return NOT_FINITE
        t = t_new
        h = h_next
    return OK


# ----------------------------------------------------------------------------
# fixed-step methods; each advances y[0:7] in place by one step h


@_jit
def _quat_times_axis(q, k, c, s):
    """q ← q ⊗ (c, s e_k): a body-axis rotation applied on the right."""
    i = (k + 1) % 3
    j = (k + 2) % 3
    q0, qk, qi, qj = q[0], q[1 + k], q[1 + i], q[1 + j]
    q[0] = c * q0 - s * qk
    q[1 + k] = c * qk + s * q0
    q[1 + i] = c * qi + s * qj
    q[1 + j] = c * qj - s * qi


@_jit
def _axis_flow(k, h, inertia, m, q):
    """Exact flow of H_k = m_k²/(2 I_k): m turns about body axis k by −h ω_k, q by +h ω_k."""
    i = (k + 1) % 3
    j = (k + 2) % 3
    half = 0.5 * h * m[k] / inertia[k]
    s2 = math.sin(half)
    c2 = math.cos(half)
    c = math.cos(2.0 * half)
    s = math.sin(2.0 * half)
    mi = m[i]
    mj = m[j]
    m[i] = c * mi + s * mj
    m[j] = c * mj - s * mi
    _quat_times_axis(q, k, c2, s2)


@_jit
def _strang_free(h, inertia, y, m):
    # symmetric, hence second order; each flow keeps |m| and the space J exactly.
    # The flows act on m = I ω′ so that ω′ <-> m round trips happen once per step.
    q = y[3:7]
    for a in range(3):
        m[a] = inertia[a] * y[a]
    _axis_flow(0, 0.5 * h, inertia, m, q)
    _axis_flow(1, 0.5 * h, inertia, m, q)
    _axis_flow(2, h, inertia, m, q)
    _axis_flow(1, 0.5 * h, inertia, m, q)
    _axis_flow(0, 0.5 * h, inertia, m, q)
    for a in range(3):
        y[a] = m[a] / inertia[a]


@_jit
def _kick(t, h, inertia, rows, y, scratch):
    """Explicit kick ω′ += h I⁻¹ M′(t, q, ω′): the exact flow when M′ does not depend on ω′."""
    m = scratch[7:10]
    evaluate_torque(rows, t, y[3:7], y[0:3], m, scratch[0:7])
    for a in range(3):
        y[a] += h * m[a] / inertia[a]


@_jit
def _depends_on_omega(rows):
    for i in range(rows.shape[0]):
        kind = int(rows[i, 0])
        if kind == DAMPING or kind == CALLBACK:
            return True
    return False


@_jit
def _closing_kick(t, h, inertia, rows, y, scratch):
    """Implicit kick ω′_new = ω′ + h I⁻¹ M′(t, q, ω′_new), the adjoint of :func:`_kick`.

    Closing the step with the adjoint keeps kick–drift–kick symmetric, hence
    second order, also for torques that depend on ω′ (damping, callables).
    """
    if not _depends_on_omega(rows):
        _kick(t, h, inertia, rows, y, scratch)
        return OK
    m = scratch[7:10]
    w0, w1, w2 = y[0], y[1], y[2]
    size = abs(w0) + abs(w1) + abs(w2) + 1e-300
    previous = np.inf
    for _ in range(_MAX_ITER):
        evaluate_torque(rows, t, y[3:7], y[0:3], m, scratch[0:7])
        n0 = w0 + h * m[0] / inertia[0]
        n1 = w1 + h * m[1] / inertia[1]
        n2 = w2 + h * m[2] / inertia[2]
        change = abs(n0 - y[0]) + abs(n1 - y[1]) + abs(n2 - y[2])
        y[0], y[1], y[2] = n0, n1, n2
        if change <= 4.0 * _EPS * size or (change >= previous and change <= 1e-13 * size):
            return OK
        previous = change
    return NO_CONVERGENCE


@_jit
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
    # m_{k+1} = Ωᵀ m_k  (rotate the body momentum back by Ω)
    t0 = 2.0 * (-v1 * m2 + v2 * m1)
    t1 = 2.0 * (-v2 * m0 + v0 * m2)
    t2 = 2.0 * (-v0 * m1 + v1 * m0)
    n0 = m0 + c * t0 - v1 * t2 + v2 * t1
    n1 = m1 + c * t1 - v2 * t0 + v0 * t2
    n2 = m2 + c * t2 - v0 * t1 + v1 * t0
    y[0] = n0 / inertia[0]
    y[1] = n1 / inertia[1]
    y[2] = n2 / inertia[2]
    q0, q1, q2, q3 = y[3], y[4], y[5], y[6]
    y[3] = q0 * c - q1 * v0 - q2 * v1 - q3 * v2
    y[4] = q0 * v0 + q1 * c + q2 * v2 - q3 * v1
    y[5] = q0 * v1 - q1 * v2 + q2 * c + q3 * v0
    y[6] = q0 * v2 + q1 * v1 - q2 * v0 + q3 * c
    return OK


@_jit
def _kick_drift_kick(method, t, h, inertia, rows, y, scratch):
    torqued = rows.shape[0] > 0
    if torqued:
        _kick(t, 0.5 * h, inertia, rows, y, scratch)
    status = OK
    if method == DMV:
        status = _dmv_free(h, inertia, y)
    else:
        _strang_free(h, inertia, y, scratch[10:13])
    if torqued and status == OK:
        status = _closing_kick(t + h, 0.5 * h, inertia, rows, y, scratch)
    return status


@_jit
def _rk4(t, h, inertia, rows, y, wk, scratch):
    y0, k1, k2, k3, k4, tmp = wk[0, :7], wk[1, :7], wk[2, :7], wk[3, :7], wk[4, :7], wk[5, :7]
    y0[:] = y[0:7]
    rhs(t, y0, inertia, 1.0, rows, rows, k1, scratch)
    for i in range(7):
        tmp[i] = y0[i] + 0.5 * h * k1[i]
    rhs(t + 0.5 * h, tmp, inertia, 1.0, rows, rows, k2, scratch)
    for i in range(7):
        tmp[i] = y0[i] + 0.5 * h * k2[i]
    rhs(t + 0.5 * h, tmp, inertia, 1.0, rows, rows, k3, scratch)
    for i in range(7):
        tmp[i] = y0[i] + h * k3[i]
    rhs(t + h, tmp, inertia, 1.0, rows, rows, k4, scratch)
    for i in range(7):
        y[i] = y0[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
    qnormalize(y[3:7])


@_jit
def _dexpinv_right(u, f, out):
    """Body-frame (right-trivialised) dexp⁻¹: u̇ = f + ½ u × f + (1/12) u × (u × f) + O(u⁴ f)."""
    c0 = u[1] * f[2] - u[2] * f[1]
    c1 = u[2] * f[0] - u[0] * f[2]
    c2 = u[0] * f[1] - u[1] * f[0]
    d0 = u[1] * c2 - u[2] * c1
    d1 = u[2] * c0 - u[0] * c2
    d2 = u[0] * c1 - u[1] * c0
    out[0] = f[0] + 0.5 * c0 + d0 / 12.0
    out[1] = f[1] + 0.5 * c1 + d1 / 12.0
    out[2] = f[2] + 0.5 * c2 + d2 / 12.0


@_jit
def _group_stage(q0, u, out):
    """out = q0 ⊗ exp(u): the Lie-group stage point of RKMK."""
    half = 0.5 * math.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])
    c = math.cos(half)
    s = 0.5 - half * half / 12.0 if half < 1e-4 else math.sin(half) / (2.0 * half)
    e0, e1, e2, e3 = c, s * u[0], s * u[1], s * u[2]
    out[0] = q0[0] * e0 - q0[1] * e1 - q0[2] * e2 - q0[3] * e3
    out[1] = q0[0] * e1 + q0[1] * e0 + q0[2] * e3 - q0[3] * e2
    out[2] = q0[0] * e2 - q0[1] * e3 + q0[2] * e0 + q0[3] * e1
    out[3] = q0[0] * e3 + q0[1] * e2 - q0[2] * e1 + q0[3] * e0


@_jit
def _rkmk4(t, h, inertia, rows, y, wk, scratch):
    """Runge-Kutta-Munthe-Kaas with the classical RK4 tableau on SO(3) × R³."""
    y0 = wk[0, :7]
    stage = wk[1, :7]
    dw = wk[2:6, :3]     # ω̇ at the four stages
    ku = wk[6:10, :3]    # dexp⁻¹ at the four stages
    u = wk[10, :3]
    deriv = wk[11, :7]
    y0[:] = y[0:7]
    coef = (0.0, 0.5, 0.5, 1.0)
    for s in range(4):
        a = coef[s] * h
        for i in range(3):
            u[i] = 0.0 if s == 0 else a * ku[s - 1, i]
            stage[i] = y0[i] + (0.0 if s == 0 else a * dw[s - 1, i])
        _group_stage(y0[3:7], u, stage[3:7])
        rhs(t + a, stage, inertia, 1.0, rows, rows, deriv, scratch)
        for i in range(3):
            dw[s, i] = deriv[i]
        _dexpinv_right(u, stage[0:3], ku[s])
    for i in range(3):
        u[i] = h / 6.0 * (ku[0, i] + 2.0 * ku[1, i] + 2.0 * ku[2, i] + ku[3, i])
        y[i] = y0[i] + h / 6.0 * (dw[0, i] + 2.0 * dw[1, i] + 2.0 * dw[2, i] + dw[3, i])
    _group_stage(y0[3:7], u, y[3:7])
    qnormalize(y[3:7])


@_jit
def _midpoint(t, h, inertia, rows, y, wk, scratch):
    """Implicit midpoint on (ω′, q), solved by fixed-point iteration to round-off.

    The quaternion half is linear given the mean ω̄, so q1 = q0 ⊗ cay(h ω̄/2)
    in closed form (a unit quaternion); the momentum half is iterated.
    """
    y0 = wk[0, :7]
    mean = wk[1, :7]
    torque = scratch[7:10]
    y0[:] = y[0:7]
    size = abs(y0[0]) + abs(y0[1]) + abs(y0[2]) + 1e-300
    converged = False
    previous = np.inf
    for _ in range(_MAX_ITER):
        for i in range(3):
            mean[i] = 0.5 * (y0[i] + y[i])
        a0, a1, a2 = 0.25 * h * mean[0], 0.25 * h * mean[1], 0.25 * h * mean[2]
        na = a0 * a0 + a1 * a1 + a2 * a2
        inv = 1.0 / (1.0 + na)
        c, s0, s1, s2 = (1.0 - na) * inv, 2.0 * a0 * inv, 2.0 * a1 * inv, 2.0 * a2 * inv
        p0, p1, p2, p3 = y0[3], y0[4], y0[5], y0[6]
        y[3] = p0 * c - p1 * s0 - p2 * s1 - p3 * s2
        y[4] = p0 * s0 + p1 * c + p2 * s2 - p3 * s1
        y[5] = p0 * s1 - p1 * s2 + p2 * c + p3 * s0
        y[6] = p0 * s2 + p1 * s1 - p2 * s0 + p3 * c
        for i in range(3, 7):
            mean[i] = 0.5 * (y0[i] + y[i])
        evaluate_torque(rows, t + 0.5 * h, mean[3:7], mean[0:3], torque, scratch[0:7])
        w0, w1, w2 = mean[0], mean[1], mean[2]
        i0, i1, i2 = inertia[0], inertia[1], inertia[2]
        n0 = y0[0] + h * ((i1 - i2) * w1 * w2 + torque[0]) / i0
        n1 = y0[1] + h * ((i2 - i0) * w2 * w0 + torque[1]) / i1
        n2 = y0[2] + h * ((i0 - i1) * w0 * w1 + torque[2]) / i2
        change = abs(n0 - y[0]) + abs(n1 - y[1]) + abs(n2 - y[2])
        y[0], y[1], y[2] = n0, n1, n2
        # stop at round-off: the change no longer shrinks once it reaches a few ulps
        if change <= 4.0 * _EPS * size or (change >= previous and change <= 1e-13 * size):
            converged = True
            break
        previous = change
    if not converged:
        return NO_CONVERGENCE
    return OK


@_jit
def _rotation_step(method, t, h, inertia, rows, y, wk, scratch):
    if method == SPLITTING or method == DMV:
        return _kick_drift_kick(method, t, h, inertia, rows, y, scratch)
    if method == SPLITTING4:
        status = _kick_drift_kick(SPLITTING, t, YOSHIDA_OUTER * h, inertia, rows, y, scratch)
        t1 = t + YOSHIDA_OUTER * h
        status += _kick_drift_kick(SPLITTING, t1, YOSHIDA_INNER * h, inertia, rows, y, scratch)
        t2 = t1 + YOSHIDA_INNER * h
        status += _kick_drift_kick(SPLITTING, t2, YOSHIDA_OUTER * h, inertia, rows, y, scratch)
        return status
    if method == RK4:
        _rk4(t, h, inertia, rows, y, wk, scratch)
        return OK
    if method == RKMK4:
        _rkmk4(t, h, inertia, rows, y, wk, scratch)
        return OK
    return _midpoint(t, h, inertia, rows, y, wk, scratch)


@_jit
def _translation_kick(t, h, mass, frows, y, scratch):
    f = scratch[10:13]
    evaluate_force(frows, t, y, f, scratch[0:7])
    for k in range(3):
        y[10 + k] += h * f[k] / mass


@_jit
def fixed_step(method, t_out, dt, y0, inertia, mass, rows, frows, out):
    """Fixed-step integration; each output interval is split into ceil(Δt/dt) equal steps."""
    ny = y0.size
    y = y0.copy()
    wk = np.empty((12, 7))
    scratch = np.empty(13)
    out[0, :] = y
    for k in range(t_out.size - 1):
        span = t_out[k + 1] - t_out[k]
        n_sub = max(1, int(math.ceil(span / dt * (1.0 - 1e-12))))
        h = span / n_sub
        for s in range(n_sub):
            t = t_out[k] + s * h
            if ny == 13:
                # velocity Verlet for the centre of mass around the rotation step
                _translation_kick(t, 0.5 * h, mass, frows, y, scratch)
                for c in range(3):
                    y[7 + c] += h * y[10 + c]
            status = _rotation_step(method, t, h, inertia, rows, y, wk, scratch)
            if status != OK:
                return NO_CONVERGENCE
            if ny == 13:
                _translation_kick(t + h, 0.5 * h, mass, frows, y, scratch)
        for i in range(ny):
            if not math.isfinite(y[i]):
                return NOT_FINITE
        out[k + 1, :] = y
    return OK


@_jit
def run(method, t_out, dt, y0, inertia, mass, rows, frows, rtol, atol, tables, out):
    """One body: dispatch to DOP853 or a fixed-step method."""
    if method == DOP853:
        tab_a, tab_b, tab_c, tab_e3, tab_e5, tab_d = tables
        return dop853(t_out, y0, inertia, mass, rows, frows, rtol, atol, tab_a, tab_b, tab_c,
                      tab_e3, tab_e5, tab_d, out)
    return fixed_step(method, t_out, dt, y0, inertia, mass, rows, frows, out)


@njit(cache=True, parallel=True)
def run_batch(method, t_out, dt, y0, inertia, mass, rows, frows, rtol, atol, tables, out, status):
    """Many bodies, one per ``prange`` iteration: the same code as :func:`run`."""
    for b in prange(y0.shape[0]):
        status[b] = run(method, t_out, dt, y0[b], inertia[b], mass[b], rows, frows, rtol, atol[b],
                        tables, out[b])
