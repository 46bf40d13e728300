"""Compiled strapdown loops: one time loop per batch element.

Every loop works on flattened batches, ``(B, n, 3)`` gyro data and ``(B, 4)``
initial attitudes, and calls the scalar quaternion kernels of
:mod:`kreisel._compiled.kernels`. Nothing here is compiled at import time; the
first call compiles and caches to disk.
"""

from __future__ import annotations

import math

import numpy as np

from .._compiled import cached
from .._compiled.kernels import qmul, qnormalize, rotvec_quat


@cached
def _buffer():
    """A scratch 4-vector (or 3-vector in its first slots) with numba's layout 'A'.

    Buffers of one layout keep the shared kernels (qmul, qnormalize)
    compiled, and cached on disk, for one signature only.
    """
    return np.empty((1, 4))[0, ::1]


@cached
def _start(q0, b, q, out):
    """Load the normalised initial attitude of batch element ``b`` into ``q`` and ``out[b, 0]``."""
    for c in range(4):
        q[c] = q0[b, c]
    qnormalize(q)
    for c in range(4):
        out[b, 0, c] = q[c]


@cached
def _advance(qn, q, out, b, j):
    """Renormalise the updated attitude ``qn`` (against drift), make it current and store it as sample ``j``."""
    qnormalize(qn)
    for c in range(4):
        q[c] = qn[c]
        out[b, j, c] = qn[c]


@cached
def integrate_increments(q0, dtheta, k, out):
    """Strapdown update from angle increments with the compressed coning correction.

    For each update of N = len(k) + 1 increments, φ = Σ Δθ_i + (Σ_{i<N} k_i Δθ_i) × Δθ_N
    and q ← q ⊗ exp(φ/2), renormalised. ``out`` is ``(B, n/N + 1, 4)``.
    """
    n_batch = dtheta.shape[0]
    per_update = k.shape[0] + 1
    n_updates = dtheta.shape[1] // per_update
    q = _buffer()
    dq = _buffer()
    qn = _buffer()
    phi = _buffer()
    for b in range(n_batch):
        _start(q0, b, q, out)
        for j in range(n_updates):
            base = j * per_update
            s0 = 0.0
            s1 = 0.0
            s2 = 0.0
            w0 = 0.0
            w1 = 0.0
            w2 = 0.0
            for i in range(per_update):
                s0 += dtheta[b, base + i, 0]
                s1 += dtheta[b, base + i, 1]
                s2 += dtheta[b, base + i, 2]
            for i in range(per_update - 1):
                w0 += k[i] * dtheta[b, base + i, 0]
                w1 += k[i] * dtheta[b, base + i, 1]
                w2 += k[i] * dtheta[b, base + i, 2]
            last = base + per_update - 1
            l0 = dtheta[b, last, 0]
            l1 = dtheta[b, last, 1]
            l2 = dtheta[b, last, 2]
            phi[0] = s0 + (w1 * l2 - w2 * l1)
            phi[1] = s1 + (w2 * l0 - w0 * l2)
            phi[2] = s2 + (w0 * l1 - w1 * l0)
            dq[0], dq[1], dq[2], dq[3] = rotvec_quat(phi[0], phi[1], phi[2])
            qmul(q, dq, qn)
            _advance(qn, q, out, b, j + 1)


@cached
def _quat_derivative(q, w0, w1, w2, out):
    """``out = ½ q ⊗ (0, ω′)`` (Theory §3.3)."""
    q0, q1, q2, q3 = q[0], q[1], q[2], q[3]
    out[0] = 0.5 * (-q1 * w0 - q2 * w1 - q3 * w2)
    out[1] = 0.5 * (q0 * w0 + q2 * w2 - q3 * w1)
    out[2] = 0.5 * (q0 * w1 - q1 * w2 + q3 * w0)
    out[3] = 0.5 * (q0 * w2 + q1 * w1 - q2 * w0)


@cached
def bortz_coefficient_from_square(angle2):
    """The Bortz coefficient (2 sin ψ − ψ(1 + cos ψ)) / (2ψ² sin ψ) of Theory §3.5, from ψ² = ``angle2``.

    The function of :func:`kreisel.kinematics.bortz_coefficient` (which takes
    ψ), cut down for the inner loop of the Bortz RK4 integration, where every
    stage has ψ² at hand: below ψ = 0.1 four terms of its series
    1/12 + ψ²/720 + ψ⁴/30240 + ψ⁶/1209600, with no square root, above it the
    closed form. Near ψ = 0.1 both lose digits (up to about 3e-13 relative),
    which the rate does not notice: the term the coefficient scales is ψ²
    times smaller than ω′. The general kernel, accurate to a few ulp
    everywhere, would cost the loop a square root and a twelve-term series at
    every stage.
    """
    if angle2 < 1e-2:
        return 1.0 / 12.0 + angle2 * (1.0 / 720.0 + angle2 * (1.0 / 30240.0 + angle2 / 1209600.0))
    a = math.sqrt(angle2)
    return (2.0 * math.sin(a) - a * (1.0 + math.cos(a))) / (2.0 * angle2 * math.sin(a))


@cached
def _bortz_rate(p, w0, w1, w2, out):
    """``out = ψ̇ = ω′ + ½ ψ × ω′ + c(ψ) ψ × (ψ × ω′)`` (Bortz equation, Theory §3.5)."""
    c = bortz_coefficient_from_square(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])
    x0 = p[1] * w2 - p[2] * w1
    x1 = p[2] * w0 - p[0] * w2
    x2 = p[0] * w1 - p[1] * w0
    out[0] = w0 + 0.5 * x0 + c * (p[1] * x2 - p[2] * x1)
    out[1] = w1 + 0.5 * x1 + c * (p[2] * x0 - p[0] * x2)
    out[2] = w2 + 0.5 * x2 + c * (p[0] * x1 - p[1] * x0)


@cached
def integrate_rates(q0, t, omega, use_bortz, out):
    """Classical RK4 over each sample interval with ω′ linear between samples.

    ``use_bortz`` False: RK4 on q̇ = ½ q ω′ then renormalise. True: RK4 on
    the Bortz equation for the interval's rotation vector, started at ψ = 0,
    then q ← q ⊗ exp(ψ/2). ``out`` is ``(B, n, 4)``.
    """
    n_batch = omega.shape[0]
    n = t.shape[0]
    y, ys, dq, qn = _buffer(), _buffer(), _buffer(), _buffer()
    k1, k2, k3, k4 = _buffer(), _buffer(), _buffer(), _buffer()  # the RK4 stages
    for b in range(n_batch):
        _start(q0, b, y, out)
        for j in range(n - 1):
            h = t[j + 1] - t[j]
            a0, a1, a2 = omega[b, j, 0], omega[b, j, 1], omega[b, j, 2]
            e0, e1, e2 = omega[b, j + 1, 0], omega[b, j + 1, 1], omega[b, j + 1, 2]
            m0, m1, m2 = 0.5 * (a0 + e0), 0.5 * (a1 + e1), 0.5 * (a2 + e2)
            if use_bortz:
                # ψ is a 3-vector; slot 3 stays zero so the same stage buffers serve
                for c in range(4):
                    ys[c] = 0.0
                _bortz_rate(ys, a0, a1, a2, k1)
                for c in range(3):
                    ys[c] = 0.5 * h * k1[c]
                _bortz_rate(ys, m0, m1, m2, k2)
                for c in range(3):
                    ys[c] = 0.5 * h * k2[c]
                _bortz_rate(ys, m0, m1, m2, k3)
                for c in range(3):
                    ys[c] = h * k3[c]
                _bortz_rate(ys, e0, e1, e2, k4)
                for c in range(3):
                    ys[c] = h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c])
                dq[0], dq[1], dq[2], dq[3] = rotvec_quat(ys[0], ys[1], ys[2])
                qmul(y, dq, qn)
            else:
                _quat_derivative(y, a0, a1, a2, k1)
                for c in range(4):
                    ys[c] = y[c] + 0.5 * h * k1[c]
                _quat_derivative(ys, m0, m1, m2, k2)
                for c in range(4):
                    ys[c] = y[c] + 0.5 * h * k2[c]
                _quat_derivative(ys, m0, m1, m2, k3)
                for c in range(4):
                    ys[c] = y[c] + h * k3[c]
                _quat_derivative(ys, e0, e1, e2, k4)
                for c in range(4):
                    qn[c] = y[c] + h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c])
            _advance(qn, y, out, b, j + 1)
