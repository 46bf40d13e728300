"""Gyro error models for simulation and their Allan-deviation signatures (Theory §3.5).

Datasheets quote gyro noise in navigation units; the model works in SI:

=========================  ===============  ===========================  ===================
term                       datasheet unit   SI unit                      Allan deviation
=========================  ===============  ===========================  ===================
angle random walk N        deg/√h           rad/√s  (× π/180/60)         N/√τ (slope −1/2)
bias instability σ, T_c    deg/h, s         rad/s   (× π/180/3600)       peak ≈ 0.617σ at 1.89 T_c
rate random walk K         deg/h/√h         rad/s/√s (× π/180/3600/60)   K√(τ/3) (slope +1/2)
=========================  ===============  ===========================  ===================

Bias instability is modelled as a first-order Gauss–Markov process of
stationary standard deviation σ and correlation time T_c, whose Allan
variance is σ²T_c²/τ² (2x − 3 + 4e^{−x} − e^{−2x}), x = τ/T_c: flat near
its maximum ≈ 0.6174σ at τ ≈ 1.89 T_c. (A datasheet "bias instability" B is
the Allan floor divided by 0.664, so σ ≈ 1.075 B reproduces it.)
"""

from __future__ import annotations

import numpy as np

from .._validation import as_float, as_float_array

__all__ = [
    "DEG_PER_SQRT_HOUR",
    "DEG_PER_HOUR",
    "DEG_PER_HOUR_PER_SQRT_HOUR",
    "GyroErrorModel",
    "allan_deviation",
    "gauss_markov_allan_deviation",
]

#: one deg/√h in rad/√s (angle random walk)
DEG_PER_SQRT_HOUR = np.pi / 180.0 / 60.0
#: one deg/h in rad/s (bias, bias instability)
DEG_PER_HOUR = np.pi / 180.0 / 3600.0
#: one deg/h/√h in rad/s/√s (rate random walk)
DEG_PER_HOUR_PER_SQRT_HOUR = np.pi / 180.0 / 3600.0 / 60.0


def _nonnegative(value, name):
    a = as_float_array(value, name)
    if a.ndim != 0 or a < 0:
        raise ValueError(f"{name} must be a non-negative scalar, got {value!r}")
    return float(a)


class GyroErrorModel:
    """Additive gyro error: white noise, Gauss–Markov bias, rate random walk, constant bias.

    The rate error of sample k (the mean over a sample of length Δt) is

        e_k = N/√Δt w_k + b_k + r_k + b₀,
        b_{k+1} = e^{−Δt/T_c} b_k + σ √(1 − e^{−2Δt/T_c}) w′_k   (b stationary from k = 0),
        r_{k+1} = r_k + K √Δt w″_k,   r_0 = 0,

    with independent standard normal w, w′, w″ (Theory §3.5). All parameters
    are SI; :meth:`from_datasheet` takes the usual navigation units.

    Parameters
    ----------
    angle_random_walk : float
        N in rad/√s (white rate noise density).
    bias_instability : float
        σ, stationary standard deviation of the Gauss–Markov bias, rad/s.
    correlation_time : float
        T_c of the Gauss–Markov bias in s (required when σ > 0).
    rate_random_walk : float
        K in rad/s/√s.
    bias : float
        Constant bias b₀ in rad/s.

    Examples
    --------
    >>> model = GyroErrorModel.from_datasheet(angle_random_walk=0.1)   # 0.1 deg/√h
    >>> e = model.rate_error(1000, 0.01, seed=1)
    >>> e.shape
    (1000, 3)
    >>> bool(abs(e.std() / (0.1 * DEG_PER_SQRT_HOUR / np.sqrt(0.01)) - 1) < 0.05)
    True
    """

    def __init__(self, angle_random_walk=0.0, bias_instability=0.0, correlation_time=None,
                 rate_random_walk=0.0, bias=0.0):
        self.angle_random_walk = _nonnegative(angle_random_walk, "angle_random_walk")
        self.bias_instability = _nonnegative(bias_instability, "bias_instability")
        self.rate_random_walk = _nonnegative(rate_random_walk, "rate_random_walk")
        b = as_float_array(bias, "bias")
        if b.ndim != 0:
            raise ValueError(f"bias must be a scalar, got shape {b.shape}")
        self.bias = float(b)
        if self.bias_instability > 0:
            if correlation_time is None:
                raise ValueError("correlation_time is required when bias_instability > 0")
            correlation_time = _nonnegative(correlation_time, "correlation_time")
            if correlation_time == 0:
                raise ValueError("correlation_time must be positive")
        elif correlation_time is not None:
            correlation_time = _nonnegative(correlation_time, "correlation_time")
        self.correlation_time = correlation_time

    @classmethod
    def from_datasheet(cls, angle_random_walk=0.0, bias_instability=0.0, correlation_time=None,
                       rate_random_walk=0.0, bias=0.0):
        """Build from datasheet units: deg/√h, deg/h (with T_c in s), deg/h/√h, deg/h.

        Examples
        --------
        >>> m = GyroErrorModel.from_datasheet(angle_random_walk=0.15, bias=3.0)
        >>> round(m.angle_random_walk * 60 * 180 / np.pi, 12), round(m.bias * 3600 * 180 / np.pi, 12)
        (0.15, 3.0)
        """
        return cls(angle_random_walk=_nonnegative(angle_random_walk, "angle_random_walk") * DEG_PER_SQRT_HOUR,
                   bias_instability=_nonnegative(bias_instability, "bias_instability") * DEG_PER_HOUR,
                   correlation_time=correlation_time,
                   rate_random_walk=_nonnegative(rate_random_walk, "rate_random_walk") * DEG_PER_HOUR_PER_SQRT_HOUR,
                   bias=as_float_array(bias, "bias") * DEG_PER_HOUR)

    def __repr__(self):
        return (f"GyroErrorModel(angle_random_walk={self.angle_random_walk!r}, "
                f"bias_instability={self.bias_instability!r}, correlation_time={self.correlation_time!r}, "
                f"rate_random_walk={self.rate_random_walk!r}, bias={self.bias!r})")

    def rate_error(self, n_samples, sample_time, shape=(3,), seed=None):
        """Draw the rate error of ``n_samples`` consecutive samples.

        Parameters
        ----------
        n_samples : int
            Number of samples.
        sample_time : float
            Δt in s.
        shape : tuple of int
            Channel shape after the time axis (default three axes).
        seed : int, numpy.random.Generator or None
            Passed to :func:`numpy.random.default_rng`; an int makes the draw reproducible.

        Returns
        -------
        ndarray of shape ``(n_samples, *shape)``
            Rate error in rad/s.

        Examples
        --------
        A constant bias is the same in every sample; a seed makes the white noise
        reproducible, and its standard deviation is N/√Δt:

        >>> GyroErrorModel(bias=1e-3).rate_error(2, 0.01).tolist()
        [[0.001, 0.001, 0.001], [0.001, 0.001, 0.001]]
        >>> model = GyroErrorModel(angle_random_walk=1e-3)
        >>> bool(np.array_equal(model.rate_error(5, 0.01, seed=7), model.rate_error(5, 0.01, seed=7)))
        True
        >>> e = model.rate_error(20_000, 0.01, shape=(), seed=1)
        >>> bool(abs(e.std() / (1e-3 / np.sqrt(0.01)) - 1) < 0.03)
        True
        """
        if isinstance(n_samples, bool) or not isinstance(n_samples, (int, np.integer)) or n_samples < 1:
            raise ValueError(f"n_samples must be a positive integer, got {n_samples!r}")
        dt = _nonnegative(sample_time, "sample_time")
        if dt == 0:
            raise ValueError("sample_time must be positive")
        rng = np.random.default_rng(seed)
        size = (int(n_samples),) + tuple(shape)
        error = np.full(size, self.bias)
        if self.angle_random_walk > 0:
            error += self.angle_random_walk / np.sqrt(dt) * rng.standard_normal(size)
        if self.bias_instability > 0:
            from scipy.signal import lfilter  # heavy import, needed only here

            decay = np.exp(-dt / self.correlation_time)
            drive = self.bias_instability * np.sqrt(-np.expm1(-2.0 * dt / self.correlation_time)) \
                * rng.standard_normal(size)
            drive[0] = self.bias_instability * rng.standard_normal(size[1:])
            error += lfilter([1.0], [1.0, -decay], drive, axis=0)
        if self.rate_random_walk > 0:
            steps = self.rate_random_walk * np.sqrt(dt) * rng.standard_normal(size)
            steps[0] = 0.0
            error += np.cumsum(steps, axis=0)
        return error

    def corrupt_rates(self, omega_body, sample_time, seed=None):
        """Add the rate error to ideal rate samples ``(..., n, 3)`` (rad/s).

        Examples
        --------
        A gyro at rest with a 1 mrad/s bias reads 1 mrad/s on every axis:

        >>> still = np.zeros((4, 3))
        >>> GyroErrorModel(bias=1e-3).corrupt_rates(still, 0.01).tolist()[0]
        [0.001, 0.001, 0.001]
        """
        omega_body = as_float_array(omega_body, "omega_body")
        return omega_body + self._error_like(omega_body, sample_time, seed)

    def corrupt_increments(self, dtheta, sample_time, seed=None):
        """Add the integrated error (rate error × Δt) to ideal increments ``(..., n, 3)`` (rad).

        Examples
        --------
        The same bias adds b Δt to each increment, so the integrated angle error
        grows like b t (here 1 mrad after 1 s):

        >>> still = np.zeros((100, 3))
        >>> dtheta = GyroErrorModel(bias=1e-3).corrupt_increments(still, 0.01)
        >>> dtheta.sum(axis=0).round(12).tolist()
        [0.001, 0.001, 0.001]
        """
        dtheta = as_float_array(dtheta, "dtheta")
        return dtheta + self._error_like(dtheta, sample_time, seed) * sample_time

    def _error_like(self, data, sample_time, seed):
        if data.ndim < 2:
            raise ValueError(f"data must have shape (..., n, 3), got {data.shape}")
        e = self.rate_error(data.shape[-2], sample_time, shape=data.shape[:-2] + data.shape[-1:], seed=seed)
        return np.moveaxis(e, 0, -2)


def allan_deviation(rate, sample_time, taus=None, axis=None):
    """Overlapping Allan deviation of a rate signal.

    With θ_k = Δt Σ_{i<k} y_i the integrated signal and τ = mΔt,
    σ²(τ) = Σ_k (θ_{k+2m} − 2θ_{k+m} + θ_k)² / (2τ²(n − 2m + 1)).

    Parameters
    ----------
    rate : array_like
        Samples y_k (any unit; the deviation has the same unit). Time runs
        along ``axis``: by default axis 0 of a 1-D array, axis −2 otherwise
        (the ``(..., n, 3)`` layout of gyro data).
    sample_time : float
        Δt in s.
    taus : array_like, optional
        Averaging times; rounded to whole multiples m of Δt, 1 ≤ m ≤ (n − 1)/2.
        Default: about 10 per decade from Δt to the longest allowed.
    axis : int, optional
        Time axis.

    Returns
    -------
    taus : (k,) ndarray
        The averaging times used (s).
    adev : ndarray
        Allan deviation, ``rate``'s shape with the time axis replaced by k.

    Examples
    --------
    >>> y = np.random.default_rng(0).standard_normal(100_000)   # white noise, unit density at Δt = 1
    >>> taus, adev = allan_deviation(y, 1.0, taus=[1.0, 100.0])
    >>> np.round(adev * np.sqrt(taus), 1)
    array([1., 1.])
    """
    y = as_float_array(rate, "rate")
    dt = _nonnegative(sample_time, "sample_time")
    if dt == 0:
        raise ValueError("sample_time must be positive")
    if y.ndim == 0:
        raise ValueError("rate must have a time axis")
    axis = (0 if y.ndim == 1 else -2) if axis is None else axis
    y = np.moveaxis(y, axis, 0)
    n = y.shape[0]
    m_max = (n - 1) // 2
    if m_max < 1:
        raise ValueError(f"rate needs at least 3 samples along the time axis, got {n}")
    if taus is None:
        m = np.unique(np.round(np.logspace(0, np.log10(m_max), int(10 * np.log10(m_max)) + 1)).astype(int))
    else:
        with np.errstate(over="ignore", under="ignore"):
            ratio = np.round(as_float_array(taus, "taus").ravel() / dt)
        if not np.all((ratio >= 1) & (ratio <= m_max)):
            raise ValueError(f"taus must lie between {dt!r} and {m_max * dt!r} s for {n} samples, got {taus!r}")
        m = ratio.astype(int)
    with np.errstate(over="ignore"):
        used = m * dt
    if not np.isfinite(used).all():
        raise ValueError(f"sample_time is out of range: the averaging times up to {m.max()} × sample_time "
                         "overflow double precision")
    # σ(τ = mΔt) = |θ_{k+2m} − 2θ_{k+m} + θ_k|_rms / (√2 m Δt) with θ in units of Δt: Δt cancels, and the
    # rate is divided by a power of two (exact) that brings its largest sample near 1 before it is summed
    # and squared, its scale restored at the end (no overflow or underflow at any magnitude); the mean does
    # not change the Allan variance, and removing it keeps θ small and its differences exact
    k = np.frexp(np.max(np.abs(y), axis=0))[1]
    y = np.ldexp(y, -k)
    theta = np.concatenate([np.zeros((1,) + y.shape[1:]), np.cumsum(y - y.mean(axis=0), axis=0)])
    adev = np.empty((m.size,) + y.shape[1:])
    for j, mj in enumerate(m):
        d = theta[2 * mj:] - 2.0 * theta[mj:n + 1 - mj] + theta[:n + 1 - 2 * mj]
        adev[j] = np.sqrt(np.mean(d * d, axis=0) / 2.0) / mj
    return used, np.moveaxis(np.ldexp(adev, k), 0, axis)


def gauss_markov_allan_deviation(tau, sigma, correlation_time):
    """Allan deviation of a first-order Gauss–Markov rate, closed form.

    σ_A²(τ) = σ²T²/τ² (2x − 3 + 4e^{−x} − e^{−2x}), x = τ/T (from the
    autocovariance σ² e^{−|s|/T} integrated over two adjacent windows). The
    bracket cancels to x³ order at small x, so below x = 1 it is summed as its
    series Σ_{k≥3} (−1)^k (4 − 2^k) x^k / k! (2x³/3 − x⁴/2 + …; short τ looks
    like a rate random walk with K² = 2σ²/T).

    Examples
    --------
    >>> x = np.linspace(0.5, 5, 4000)
    >>> a = gauss_markov_allan_deviation(x, 1.0, 1.0)
    >>> round(float(x[np.argmax(a)]), 2), round(float(a.max()), 4)
    (1.89, 0.6174)
    """
    tau = as_float_array(tau, "tau")
    if np.any(tau <= 0):
        raise ValueError("tau must be positive")
    sigma = as_float(sigma, "sigma")
    correlation_time = _nonnegative(correlation_time, "correlation_time")
    # √x = √τ/√T cannot overflow or underflow where x = τ/T would; σ_A/σ <= 0.62 is formed from it first
    with np.errstate(divide="ignore", over="ignore", under="ignore"):
        root = np.sqrt(tau) / np.sqrt(correlation_time)
        x = root * root
    small = x < 1.0
    xs = np.where(small, x, 0.0)
    # below x = 1: σ_A/σ = √x √(bracket/x³), the series of bracket/x³ = 2/3 − x/2 + … summed term by term;
    # 25 terms leave < 1e-17 relative at x = 1
    series = np.zeros_like(xs)
    term = np.full_like(xs, 1.0 / 6.0)  # x^(k−3)/k! for k = 3
    for k in range(3, 26):
        series += (-1) ** k * (4.0 - 2.0**k) * term
        term = term * xs / (k + 1)
    # above: σ_A/σ = √(2/x) √(1 − (3 − 4e^{−x} + e^{−2x})/(2x)), which tends to √(2/x) as x → ∞
    xl = np.where(small, 1.0, x)
    with np.errstate(divide="ignore"):
        large = np.sqrt(2.0) / np.where(small, 1.0, root) * np.sqrt(1.0 - (3.0 - 4.0 * np.exp(-xl) + np.exp(-2.0 * xl)) / (2.0 * xl))
    return sigma * np.where(small, root * np.sqrt(series), large)
