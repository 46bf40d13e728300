"""Coning motion: the classical test of strapdown attitude algorithms (Theory §3.5).

A body whose axis x sweeps a cone of half angle α at rate Ω has body rate
ω′ = (−2Ω sin²(α/2), −Ω sin α sin Ωt, Ω sin α cos Ωt). Its attitude returns
to the start after every cone period, yet the sum of its gyro increments
grows linearly along −x: the non-commuting y and z rotations (the coning
effect) rectify into a steady rotation about x that any update algorithm
must reproduce. What it misses over an update shows up as a steady drift
along −x of the body.
"""

from __future__ import annotations

from math import factorial

import numpy as np

from .._validation import positive_array

__all__ = ["ConingMotion", "coning_motion", "coning_drift", "coning_coefficients"]

# compressed optimal coefficients k_i of δφ = (Σ_{i<N} k_i Δθ_i) × Δθ_N (Theory §3.5)
_CONING_COEFFICIENTS = {
    1: (),
    2: (2.0 / 3.0,),
    3: (9.0 / 20.0, 27.0 / 20.0),
    4: (54.0 / 105.0, 92.0 / 105.0, 214.0 / 105.0),
}


def coning_coefficients(samples_per_update):
    """Coefficients k_i of the optimal N-sample coning correction, compressed form.

    The correction added to the summed increments of one update is
    δφ = (Σ_{i<N} k_i Δθ_i) × Δθ_N (Theory §3.5).

    Parameters
    ----------
    samples_per_update : int
        N, the number of gyro increments per attitude update, 1 to 4.

    Returns
    -------
    (N - 1,) ndarray
        k_1 … k_{N−1}; empty for N = 1 (plain summation).

    Examples
    --------
    >>> coning_coefficients(2)
    array([0.66666667])
    """
    n = _check_samples_per_update(samples_per_update)
    return np.array(_CONING_COEFFICIENTS[n], dtype=np.float64)


def _check_samples_per_update(samples_per_update):
    if isinstance(samples_per_update, bool) or not isinstance(samples_per_update, (int, np.integer)):
        raise TypeError(f"samples_per_update must be an integer 1..4, got {samples_per_update!r}")
    if int(samples_per_update) not in _CONING_COEFFICIENTS:
        raise ValueError(f"samples_per_update must be 1, 2, 3 or 4, got {samples_per_update}")
    return int(samples_per_update)


class ConingMotion:
    """Sampled coning motion: times, exact gyro increments, true attitude.

    Attributes
    ----------
    t : (..., n + 1) ndarray
        Sample instants k T_s, k = 0 … n (seconds).
    dtheta : (..., n, 3) ndarray
        Exact angle increments ∫ω′ dt over [t_k, t_{k+1}] (body, rad).
    q : (..., n + 1, 4) ndarray
        True attitude body → reference at ``t``.
    omega : (..., n + 1, 3) ndarray
        Body angular velocity ω′ at ``t`` (what a rate gyro would sample).
    half_angle, rate, sample_time : ndarray
        The parameters α, Ω, T_s (broadcast batch shape).

    Examples
    --------
    In coning the body rate has a constant part −2Ω sin²(α/2) along x (the
    source of coning drift) while the attitude itself returns after one period;
    a second-order coning algorithm integrates the exact increments back to
    the true attitude:

    >>> from kreisel.nav import attitude_from_increments
    >>> alpha, rate = 0.05, 2 * np.pi
    >>> m = coning_motion(alpha, rate, 0.01, 100)
    >>> m.t.shape, m.dtheta.shape, m.q.shape
    ((101,), (100, 3), (101, 4))
    >>> bool(np.allclose(m.omega[:, 0], -2 * rate * np.sin(alpha / 2) ** 2))
    True
    >>> q = attitude_from_increments(m.q[0], m.dtheta, 2)
    >>> bool(np.allclose(q[-1], m.q[-1], atol=1e-8))
    True
    """

    def __init__(self, t, dtheta, q, omega, half_angle, rate, sample_time):
        self.t = t
        self.dtheta = dtheta
        self.q = q
        self.omega = omega
        self.half_angle = half_angle
        self.rate = rate
        self.sample_time = sample_time

    def __repr__(self):
        return (f"ConingMotion(n_samples={self.dtheta.shape[-2]}, batch={self.dtheta.shape[:-2]}, "
                f"half_angle={self.half_angle!r}, rate={self.rate!r}, sample_time={self.sample_time!r})")


def _positive_scalars(**kwargs):
    return np.broadcast_arrays(*(positive_array(value, name) for name, value in kwargs.items()))


def coning_motion(half_angle, rate, sample_time, n_samples):
    """Exact coning motion sampled for a gyro simulation (Theory §3.5, Theory §3.3).

    The attitude is q(t) = (cos(α/2), 0, sin(α/2) cos Ωt, sin(α/2) sin Ωt), so
    q̇ = ½ q ω′ with ω′ = (−2Ω sin²(α/2), −Ω sin α sin Ωt, Ω sin α cos Ωt), and
    the increments are the closed-form integrals of ω′ over each sample, free
    of cancellation at small α and small ΩT_s.

    Parameters
    ----------
    half_angle : float or array_like
        Half-cone angle α in radians (> 0).
    rate : float or array_like
        Coning rate Ω in rad/s (> 0).
    sample_time : float or array_like
        Gyro sample interval T_s in seconds (> 0); broadcast with the other
        two to give a batch shape.
    n_samples : int
        Number of increments n.

    Returns
    -------
    ConingMotion
        With ``t`` (..., n+1), ``dtheta`` (..., n, 3), ``q`` (..., n+1, 4) and
        ``omega`` (..., n+1, 3); ``...`` is the broadcast shape of the three
        parameters.

    Examples
    --------
    >>> m = coning_motion(0.01, 2 * np.pi, 0.01, 100)
    >>> m.dtheta.shape, m.q.shape
    ((100, 3), (101, 4))
    >>> bool(np.allclose(m.q[-1], m.q[0]))   # one full cone period later
    True
    """
    alpha, big_omega, ts = _positive_scalars(half_angle=half_angle, rate=rate, sample_time=sample_time)
    if isinstance(n_samples, bool) or not isinstance(n_samples, (int, np.integer)) or n_samples < 1:
        raise ValueError(f"n_samples must be a positive integer, got {n_samples!r}")
    k = np.arange(n_samples + 1, dtype=np.float64)
    a = alpha[..., None]
    w = big_omega[..., None]
    h = ts[..., None]
    phase = w * h * k                      # Ω t_k
    s_half = np.sin(0.5 * a)
    q = np.stack(np.broadcast_arrays(np.cos(0.5 * a), 0.0 * phase, s_half * np.cos(phase),
                                     s_half * np.sin(phase)), axis=-1)
    omega = np.stack(np.broadcast_arrays(-2.0 * w * s_half**2, -w * np.sin(a) * np.sin(phase),
                                         w * np.sin(a) * np.cos(phase)), axis=-1)
    lam = w * h
    mid = phase[..., :-1] + 0.5 * lam
    chord = 2.0 * np.sin(a) * np.sin(0.5 * lam)
    dtheta = np.stack(np.broadcast_arrays(-2.0 * lam * s_half**2, -chord * np.sin(mid),
                                          chord * np.cos(mid)), axis=-1)
    t = h * k
    return ConingMotion(t, dtheta, q, omega, alpha[()], big_omega[()], ts[()])


def _double_factorial_odd(n):
    return float(np.prod(np.arange(1, 2 * n + 2, 2, dtype=np.float64)))


def coning_drift(half_angle, rate, sample_time, samples_per_update):
    """Classical coning drift rate of the optimal N-sample algorithm (Theory §3.5).

    ε_N = α² Ω λ^(2N) N! / (2^(N+1) (2N+1)!!), λ = Ω T_s: N = 1 gives
    α²Ωλ²/12, N = 2 α²Ωλ⁴/60, N = 3 α²Ωλ⁶/280, N = 4 α²Ωλ⁸/1260. The
    computed attitude drifts at this rate about −x of the body (precisely
    about the cone axis, which the body sees at angle α from its x axis). It is the
    leading term in α²: the next terms grow like α⁴ and take over for
    higher N at larger cones (at α = 1° the N = 4 drift is dominated by
    them; compare N = 4 at α ≤ 0.1°).

    Parameters
    ----------
    half_angle, rate, sample_time : float or array_like
        α (rad), Ω (rad/s), T_s (s); broadcast together.
    samples_per_update : int
        N, 1 to 4.

    Returns
    -------
    ndarray
        Drift magnitude in rad/s.

    Examples
    --------
    >>> eps = coning_drift(np.radians(1.0), 2 * np.pi, 0.01, 1)
    >>> bool(np.isclose(eps, np.radians(1.0)**2 * 2 * np.pi * (2 * np.pi * 0.01)**2 / 12))
    True
    """
    n = _check_samples_per_update(samples_per_update)
    alpha, big_omega, ts = _positive_scalars(half_angle=half_angle, rate=rate, sample_time=sample_time)
    coefficient = factorial(n) / (2.0 ** (n + 1) * _double_factorial_odd(n))
    # ε = c α² Ω^(2N+1) T_s^(2N) from the mantissas and binary exponents of α, Ω and T_s (exact splits):
    # no power overflows or underflows on the way to an ε that double precision holds
    (fa, ea), (fo, eo), (ft, et) = (np.frexp(x) for x in (alpha, big_omega, ts))
    mantissa = coefficient * fa**2 * fo ** (2 * n + 1) * ft ** (2 * n)
    with np.errstate(over="ignore"):
        eps = np.ldexp(mantissa, 2 * ea + (2 * n + 1) * eo + 2 * n * et)
    if not np.isfinite(eps).all():
        raise ValueError("half_angle, rate and sample_time are out of range: the drift rate α² Ω λ^(2N) … "
                         "overflows double precision")
    return eps[()]
