"""Compiled adaptive Dormand–Prince 8(5,3) integrator for the frames and earth layers.

The stepping, error norm and step-size control follow Hairer, Nørsett & Wanner
(and scipy's ``DOP853``), with the Butcher tableau taken from
``scipy.integrate._ivp.dop853_coefficients`` so that the numbers are not
re-typed. Every routine receives the right-hand side ``rhs(t, y, params, out)``
as an argument so the same loop serves every model (free particle, spherical
pendulum, user forces).

Why these kernels are ``njit`` without ``cache=True``: numba cannot cache a
function whose arguments include another compiled function (each process would
append a new, never reused entry to ``__pycache__``). Compilation happens on the
first call of each model in a process (about a second) and never at import.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

_jit = njit(nogil=True)

_SAFETY = 0.9
_MIN_FACTOR = 0.2
_MAX_FACTOR = 10.0
_ERROR_EXPONENT = -1.0 / 8.0
_N_STAGES = 12

_TABLEAU = None


def tableau():
    """Return the DOP853 tableau ``(A, B, C, E3, E5)`` as contiguous float arrays."""
    global _TABLEAU
    if _TABLEAU is None:
        from scipy.integrate._ivp import dop853_coefficients as d

        n = _N_STAGES
        _TABLEAU = tuple(
            np.ascontiguousarray(a, dtype=np.float64)
            for a in (d.A[:n, :n], d.B, d.C[:n], d.E3, d.E5)
        )
    return _TABLEAU


@_jit
def rk_step(rhs, params, t, y, f, h, A, B, C, K, y_new, f_new):
    """One DOP853 step of size ``h`` from ``(t, y)`` with ``f = rhs(t, y)``.

    Writes ``y_new``, ``f_new = rhs(t + h, y_new)`` and the stages into ``K``
    (``K[12]`` holds ``f_new``, needed by the error estimate).
    """
    n = y.size
    ys = np.empty(n)
    K[0, :] = f
    for s in range(1, _N_STAGES):
        for i in range(n):
            acc = 0.0
            for j in range(s):
                acc += A[s, j] * K[j, i]
            ys[i] = y[i] + h * acc
        rhs(t + C[s] * h, ys, params, K[s])
    for i in range(n):
        acc = 0.0
        for j in range(_N_STAGES):
            acc += B[j] * K[j, i]
        y_new[i] = y[i] + h * acc
    rhs(t + h, y_new, params, f_new)
    K[_N_STAGES, :] = f_new


@_jit
def _error_norm(y, y_new, h, K, E3, E5, rtol, atol):
    n = y.size
    e5 = 0.0
    e3 = 0.0
    for i in range(n):
        scale = atol + max(abs(y[i]), abs(y_new[i])) * rtol
        a5 = 0.0
        a3 = 0.0
        for j in range(_N_STAGES + 1):
            a5 += E5[j] * K[j, i]
            a3 += E3[j] * K[j, i]
        e5 += (a5 / scale) ** 2
        e3 += (a3 / scale) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)


@_jit
def initial_step(rhs, params, t, y, f, rtol, atol, max_step):
    """Starting step of Hairer's algorithm (as scipy's ``select_initial_step``)."""
    n = y.size
    d0 = 0.0
    d1 = 0.0
    for i in range(n):
        scale = atol + abs(y[i]) * rtol
        d0 += (y[i] / scale) ** 2
        d1 += (f[i] / scale) ** 2
    d0 = math.sqrt(d0 / n)
    d1 = math.sqrt(d1 / n)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, max_step)
    y1 = y + h0 * f
    f1 = np.empty(n)
    rhs(t + h0, y1, params, f1)
    d2 = 0.0
    for i in range(n):
        scale = atol + abs(y[i]) * rtol
        d2 += ((f1[i] - f[i]) / scale) ** 2
    d2 = math.sqrt(d2 / n) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, max_step)


@_jit
def advance(rhs, params, t, y, f, h, t_end, rtol, atol, max_step, A, B, C, E3, E5, K, y_new, f_new):
    """Take one accepted adaptive step from ``t`` towards ``t_end`` (never past it).

    Returns ``(h_taken, h_next)``; the new state is in ``y_new``, ``f_new``.
    """
    rejected = False
    h = min(h, max_step)
    h_natural = h
    while True:
        clipped = h >= t_end - t
        if clipped:
            h = t_end - t
        rk_step(rhs, params, t, y, f, h, A, B, C, K, y_new, f_new)
        err = _error_norm(y, y_new, h, K, E3, E5, rtol, atol)
        if err < 1.0:
            if err == 0.0:
                factor = _MAX_FACTOR
            else:
                factor = min(_MAX_FACTOR, _SAFETY * err**_ERROR_EXPONENT)
            if rejected:
                return h, h * min(1.0, factor)
            # a step shortened only to land on t_end says nothing about the natural step
            return h, max(h * factor, h_natural) if clipped else h * factor
        if h < 1e-14 * max(1.0, abs(t)):
            raise RuntimeError("step size underflow: the equations are too stiff or singular")
        h *= max(_MIN_FACTOR, _SAFETY * err**_ERROR_EXPONENT)
        rejected = True


@_jit
def integrate(rhs, params, t_out, y0, rtol, atol, max_step, A, B, C, E3, E5):
    """States at the sorted output times ``t_out`` (``t_out[0]`` is the initial time)."""
    n = y0.size
    m = t_out.size
    out = np.empty((m, n))
    y = y0.copy()
    out[0, :] = y
    f = np.empty(n)
    t = t_out[0]
    rhs(t, y, params, f)
    K = np.empty((_N_STAGES + 1, n))
    y_new = np.empty(n)
    f_new = np.empty(n)
    h = initial_step(rhs, params, t, y, f, rtol, atol, max_step) if m > 1 else 0.0
    for k in range(1, m):
        while t < t_out[k]:
            h_taken, h_next = advance(
                rhs, params, t, y, f, h, t_out[k], rtol, atol, max_step, A, B, C, E3, E5, K, y_new, f_new
            )
            t = t_out[k] if h_taken == t_out[k] - t else t + h_taken
            h = h_next
            y[:] = y_new
            f[:] = f_new
        out[k, :] = y
    return out


@_jit
def land(rhs, params, t0, y0, rtol, atol, max_step, A, B, C, E3, E5):
    """Integrate until ``y[2]`` (height) comes down through zero; return ``(t, y)`` there.

    The crossing step is found by the adaptive loop, then its length is solved
    for by Newton's method on a single DOP853 step (dz/dτ = ``y[5]``), so the
    landing state has the integrator's full order.
    """
    n = y0.size
    y = y0.copy()
    f = np.empty(n)
    t = t0
    rhs(t, y, params, f)
    K = np.empty((_N_STAGES + 1, n))
    y_new = np.empty(n)
    f_new = np.empty(n)
    h = initial_step(rhs, params, t, y, f, rtol, atol, max_step)
    while True:
        h_taken, h_next = advance(rhs, params, t, y, f, h, np.inf, rtol, atol, max_step, A, B, C, E3, E5, K, y_new, f_new)
        if y_new[2] <= 0.0 and y_new[5] < 0.0:
            if y[2] > 0.0:
                break
            # a launch from the ground that is back below it after one step: shorten
            h = 0.5 * h_taken
            continue
        t += h_taken
        h = h_next
        y[:] = y_new
        f[:] = f_new
    # safeguarded Newton (bisection fallback) on the length of the last step
    lo, hi = 0.0, h_taken
    tau = h_taken * y[2] / (y[2] - y_new[2])
    for _ in range(100):
        rk_step(rhs, params, t, y, f, tau, A, B, C, K, y_new, f_new)
        if y_new[2] > 0.0:
            lo = tau
        else:
            hi = tau
        step = -y_new[2] / y_new[5] if y_new[5] != 0.0 else np.inf
        new_tau = tau + step
        if not (lo < new_tau < hi):
            new_tau = 0.5 * (lo + hi)
        converged = abs(new_tau - tau) <= 1e-15 * tau
        tau = new_tau
        if converged:
            break
    rk_step(rhs, params, t, y, f, tau, A, B, C, K, y_new, f_new)
    return t + tau, y_new
