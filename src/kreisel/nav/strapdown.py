"""Strapdown attitude: body-frame gyro data to attitude quaternions (Theory §3.3, §3.5).

Two kinds of gyro exist and they need different algorithms:

* **Increment-output (integrating) gyros** deliver Δθ_i = ∫ω′ dt over each
  sample exactly. :func:`attitude_from_increments` combines N of them into
  the rotation vector of one update with the optimal coning correction and
  applies it as q ← q ⊗ exp(φ/2). Coning algorithms rest on this: the
  increments carry the exact integral of ω′ and the correction recovers the
  non-commutativity *inside* the update from the increments alone.
* **Rate-output gyros** deliver samples ω′(t_k). What happens between
  samples is unknown; :func:`attitude_from_rates` assumes ω′ linear between
  samples and integrates q̇ = ½ q ω′ or the Bortz equation by RK4. No
  integrator can restore what sampling lost: under coning, linear
  interpolation shrinks the apparent cone by about λ²/12 (λ = ΩT_s), and the
  attitude drifts about as fast as plain summation of exact increments
  (N = 1) does, whatever the integrator order — see the notes of
  :func:`attitude_from_rates` for the numbers.
"""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array
from ..so3._coercion import as_quaternion
from .._norms import norm
from . import _kernels
from .coning import coning_coefficients

__all__ = ["attitude_from_increments", "attitude_from_rates"]

_RATE_METHODS = ("quaternion", "bortz")


def _batched(q0, data, name):
    """Broadcast q0 (..., 4) against data (..., n, 3); return flattened C arrays and batch shape."""
    try:
        batch = np.broadcast_shapes(q0.shape[:-1], data.shape[:-2])
    except ValueError:
        raise ValueError(f"q0 batch shape {q0.shape[:-1]} does not broadcast with {name} batch shape "
                         f"{data.shape[:-2]}") from None
    n = data.shape[-2]
    # the batch size spelled out: reshape cannot infer it (-1) from data without samples (n = 0)
    size = int(np.prod(batch, dtype=np.int64))
    q0b = np.ascontiguousarray(np.broadcast_to(q0, batch + (4,)).reshape(size, 4))
    datab = np.ascontiguousarray(np.broadcast_to(data, batch + (n, 3)).reshape(size, n, 3))
    return q0b, datab, batch


def attitude_from_increments(q0, dtheta, samples_per_update=1):
    """Attitude from gyro angle increments with the optimal coning correction.

    Each update takes N consecutive increments Δθ_1 … Δθ_N (exact integrals of
    ω′ over a sample, body frame) and forms the update rotation vector

        φ = Σ Δθ_i + δφ,   δφ = (Σ_{i<N} k_i Δθ_i) × Δθ_N

    with k = (2/3) for N = 2, (9/20, 27/20) for N = 3 and (54/105, 92/105,
    214/105) for N = 4 (Theory §3.5; δφ approximates the Bortz term ½∫ψ×ω′,
    Theory §3.5). Then q ← q ⊗ exp(φ/2), renormalised (the quaternion form of
    q̇ = ½ q ω′, Theory §3.3). Under coning of half angle α at rate Ω the result
    drifts about −x of the body at :func:`coning_drift` (α²Ωλ²/12 for N = 1,
    α²Ωλ⁴/60 for N = 2, α²Ωλ⁶/280 for N = 3, λ = ΩT_s); the tests confirm
    this within 3 % (N = 4 within 15 % at α = 0.1°).

    Parameters
    ----------
    q0 : Rotation or array_like
        Initial attitude, body → reference: a ``Rotation``, rotation matrices
        ``(..., 3, 3)`` or quaternions ``(..., 4)`` (normalised), as every
        kreisel rotation argument.
    dtheta : (..., n, 3) array_like
        Angle increments in rad, body components; n divisible by N.
    samples_per_update : int
        N = 1, 2, 3 or 4.

    Returns
    -------
    (..., n/N + 1, 4) ndarray
        Attitude after 0, 1, …, n/N updates (the first row is q0).

    Examples
    --------
    >>> import numpy as np
    >>> q = attitude_from_increments([1, 0, 0, 0], np.tile([0, 0, np.pi / 100], (100, 1)), 2)
    >>> q.shape
    (51, 4)
    >>> np.round(q[-1], 12) + 0.0      # a half turn about z
    array([0., 0., 0., 1.])
    """
    k = coning_coefficients(samples_per_update)
    q0 = as_quaternion(q0, "q0")
    dtheta = as_float_array(dtheta, "dtheta", tail=(3,), finite=False)
    if dtheta.ndim < 2:
        raise ValueError(f"dtheta must have shape (..., n, 3), got {dtheta.shape}")
    bad = ~np.isfinite(dtheta)
    if bad.any():
        raise ValueError(f"dtheta must be finite; first bad sample at index {np.argwhere(bad)[0][:-1].tolist()}")
    n = dtheta.shape[-2]
    per_update = k.size + 1
    if n % per_update:
        raise ValueError(f"dtheta has {n} samples, not divisible by samples_per_update={per_update} "
                         f"({n % per_update} left over)")
    q0b, data, batch = _batched(q0, dtheta, "dtheta")
    out = np.empty((data.shape[0], n // per_update + 1, 4))
    _kernels.integrate_increments(q0b, data, k, out)
    return out.reshape(batch + out.shape[1:])


def attitude_from_rates(q0, t, omega_body, method="quaternion"):
    """Attitude from sampled body rates of a rate-output gyro (Theory §3.3, §3.5).

    ω′ is taken as linear between samples and integrated over each interval
    by classical RK4, either on q̇ = ½ q ω′ (``method="quaternion"``, then
    renormalised) or on the Bortz equation ψ̇ = ω′ + ½ψ×ω′ +
    (1/ψ²)(1 − (ψ/2)cot(ψ/2)) ψ×(ψ×ω′) for the rotation vector of the
    interval followed by q ← q ⊗ exp(ψ/2) (``method="bortz"``). For truly
    linear rates both are fourth-order accurate in the sample interval.

    Notes
    -----
    Coning algorithms (:func:`attitude_from_increments`) assume
    increment-output gyros. A rate-output gyro only reveals ω′ at the
    samples, and the interpolation between them is where the accuracy goes:
    for coning (α = 1°, Ω = 2π rad/s) linear interpolation shrinks the cone
    by ≈ λ²/12 and both methods drift along −x of the body at α²Ωλ²/12 —
    the drift of plain summation of exact increments (N = 1), and 5/λ²
    times (500× at λ = 0.1) that of the two-sample coning algorithm on
    increments (``tests/nav/test_strapdown.py::test_rate_sampling_cost``).

    Parameters
    ----------
    q0 : Rotation or array_like
        Initial attitude body → reference, as in :func:`attitude_from_increments`.
    t : (n,) array_like
        Strictly increasing sample times in s.
    omega_body : (..., n, 3) array_like
        Body angular velocity ω′ at ``t`` in rad/s.
    method : {"quaternion", "bortz"}
        Equation integrated within each sample interval.

    Returns
    -------
    (..., n, 4) ndarray
        Attitude at ``t`` (the first row is q0).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 11)
    >>> q = attitude_from_rates([1, 0, 0, 0], t, np.tile([0.0, 0.0, np.pi], (11, 1)), method="bortz")
    >>> np.round(q[-1], 12) + 0.0       # a half turn about z
    array([0., 0., 0., 1.])
    """
    if method not in _RATE_METHODS:
        raise ValueError(f"method must be one of {_RATE_METHODS}, got {method!r}")
    q0 = as_quaternion(q0, "q0")
    t = as_float_array(t, "t")
    if t.ndim != 1 or t.size < 2:
        raise ValueError(f"t must be one-dimensional with at least 2 samples, got shape {t.shape}")
    step = np.diff(t)
    if np.any(step <= 0):
        i = int(np.argmax(step <= 0)) + 1
        raise ValueError(f"t must be strictly increasing: t[{i}] = {float(t[i])!r} follows "
                         f"t[{i - 1}] = {float(t[i - 1])!r}")
    omega_body = as_float_array(omega_body, "omega_body", tail=(t.size, 3), finite=False)
    bad = ~np.isfinite(omega_body)
    if bad.any():
        raise ValueError(f"omega_body must be finite; first bad sample at index {np.argwhere(bad)[0][:-1].tolist()}")
    # a turn of more than π within one interval is aliased (the samples cannot tell it from a shorter one
    # the other way round) and far outside RK4's accuracy: refused, not integrated into a wrong attitude
    speed = norm(omega_body)
    with np.errstate(over="ignore"):
        turn = np.maximum(speed[..., :-1], speed[..., 1:]) * step
    if np.any(turn > np.pi):
        worst = np.unravel_index(np.argmax(turn), turn.shape)
        raise ValueError(f"omega_body turns the body by {float(turn[worst]):.3g} rad between samples {worst[-1]} "
                         f"and {worst[-1] + 1} of t, more than π: sample faster (the rates do not determine the "
                         "attitude between such samples)")
    q0b, data, batch = _batched(q0, omega_body, "omega_body")
    out = np.empty((data.shape[0], t.size, 4))
    _kernels.integrate_rates(q0b, np.ascontiguousarray(t), data, method == "bortz", out)
    return out.reshape(batch + out.shape[1:])
