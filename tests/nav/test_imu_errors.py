"""Gyro error models: units, reproducibility and Allan-deviation signatures (Theory §3.5)."""

from decimal import Decimal, getcontext

import numpy as np
import pytest

import kreisel as kr

nav = kr.nav


def log_slope(taus, adev, lo, hi):
    sel = (taus >= lo) & (taus <= hi)
    return np.polyfit(np.log(taus[sel]), np.log(adev[sel]), 1)[0]


def test_unit_conversions():
    assert nav.DEG_PER_SQRT_HOUR == pytest.approx(np.radians(1.0) / np.sqrt(3600.0), rel=1e-15)
    assert nav.DEG_PER_HOUR == pytest.approx(np.radians(1.0) / 3600.0, rel=1e-15)
    assert nav.DEG_PER_HOUR_PER_SQRT_HOUR == pytest.approx(np.radians(1.0) / 3600.0 / 60.0, rel=1e-15)
    m = nav.GyroErrorModel.from_datasheet(angle_random_walk=0.2, bias_instability=5.0, correlation_time=100.0,
                                          rate_random_walk=3.0, bias=10.0)
    assert m.angle_random_walk == pytest.approx(0.2 * np.pi / 180 / 60, rel=1e-15)
    assert m.bias_instability == pytest.approx(5.0 * np.pi / 180 / 3600, rel=1e-15)
    assert m.rate_random_walk == pytest.approx(3.0 * np.pi / 180 / 3600 / 60, rel=1e-15)
    assert m.bias == pytest.approx(10.0 * np.pi / 180 / 3600, rel=1e-15)
    assert m.correlation_time == 100.0


def test_draws_are_seeded_and_shaped():
    m = nav.GyroErrorModel(angle_random_walk=1e-3, bias_instability=1e-4, correlation_time=5.0,
                           rate_random_walk=1e-5)
    a = m.rate_error(500, 0.01, seed=42)
    np.testing.assert_array_equal(a, m.rate_error(500, 0.01, seed=np.random.default_rng(42)))
    assert not np.array_equal(a, m.rate_error(500, 0.01, seed=43))
    assert m.rate_error(10, 0.1, shape=(2, 3)).shape == (10, 2, 3)
    d = np.zeros((4, 100, 3))
    assert not np.array_equal(m.corrupt_increments(d, 0.01, seed=1)[0], m.corrupt_increments(d, 0.01, seed=1)[1])


def test_constant_bias_integrates_into_increments():
    m = nav.GyroErrorModel.from_datasheet(bias=36.0)   # 36 deg/h = 0.01 deg/s
    d = m.corrupt_increments(np.zeros((100, 3)), 0.5, seed=0)
    np.testing.assert_allclose(d.sum(axis=0), np.radians(0.01) * 50.0, rtol=1e-13)


def test_angle_random_walk_signature():
    # white rate noise: σ_A = N/√τ, slope −1/2; level read at τ = 1 s is N (N in rad/√s)
    n_arw = 0.3 * nav.DEG_PER_SQRT_HOUR
    dt = 0.01
    e = nav.GyroErrorModel(angle_random_walk=n_arw).rate_error(200_000, dt, shape=(2,), seed=5)
    taus, adev = nav.allan_deviation(e, dt)
    assert adev.shape == (taus.size, 2)
    assert log_slope(taus, adev.mean(axis=1), 0.01, 100.0) == pytest.approx(-0.5, abs=0.02)
    level = nav.allan_deviation(e, dt, taus=[1.0])[1][0]
    np.testing.assert_allclose(level, n_arw, rtol=0.03)


def test_rate_random_walk_signature():
    # σ_A = K √(τ/3), slope +1/2
    k = 2.0 * nav.DEG_PER_HOUR_PER_SQRT_HOUR
    dt = 0.1
    e = nav.GyroErrorModel(rate_random_walk=k).rate_error(100_000, dt, shape=(8,), seed=6)
    taus, adev = nav.allan_deviation(e, dt, taus=np.geomspace(1.0, 300.0, 15))
    avg = np.sqrt(np.mean(adev**2, axis=1))
    assert log_slope(taus, avg, 1.0, 300.0) == pytest.approx(0.5, abs=0.05)
    np.testing.assert_allclose(avg, k * np.sqrt(taus / 3.0), rtol=0.1)


def test_bias_instability_flat_region():
    sigma, tc, dt = 10.0 * nav.DEG_PER_HOUR, 5.0, 0.05
    e = nav.GyroErrorModel(bias_instability=sigma, correlation_time=tc).rate_error(200_000, dt, shape=(8,),
                                                                                   seed=7)
    taus, adev = nav.allan_deviation(e, dt, taus=np.geomspace(0.5, 50.0, 21))
    avg = np.sqrt(np.mean(adev**2, axis=1))
    np.testing.assert_allclose(avg, nav.gauss_markov_allan_deviation(taus, sigma, tc), rtol=0.05)
    # flat near the peak 0.617σ at 1.89 T_c, rising below and falling beyond it
    assert abs(log_slope(taus, avg, 0.9 * tc, 4.0 * tc)) < 0.15
    assert taus[np.argmax(avg)] == pytest.approx(1.89 * tc, rel=0.35)
    assert avg.max() == pytest.approx(0.6174 * sigma, rel=0.08)
    assert log_slope(taus, avg, 0.5, 1.0) > 0.3 and log_slope(taus, avg, 30.0, 50.0) < -0.3


def test_gauss_markov_closed_form_against_high_precision():
    getcontext().prec = 50
    x = np.array([1e-6, 1e-3, 0.3, 0.999, 1.0, 2.0, 40.0])

    def exact(xi):
        d = Decimal(float(xi))
        return float(((2 * d - 3 + 4 * (-d).exp() - (-2 * d).exp()) / d**2).sqrt())

    np.testing.assert_allclose(nav.gauss_markov_allan_deviation(x, 1.0, 1.0), [exact(v) for v in x], rtol=1e-14)


def test_allan_deviation_matches_cluster_averages():
    rng = np.random.default_rng(8)
    y = np.cumsum(rng.standard_normal(301)) * 0.1 + rng.standard_normal(301)
    taus, adev = nav.allan_deviation(y, 0.5, taus=[0.5, 2.0, 37.5])
    for tau, a in zip(taus, adev):
        m = int(round(tau / 0.5))
        means = np.array([y[j:j + m].mean() for j in range(y.size - m + 1)])
        assert a == pytest.approx(np.sqrt(0.5 * np.mean((means[m:] - means[:-m]) ** 2)), rel=1e-10)


def test_error_model_bad_input():
    with pytest.raises(ValueError, match="correlation_time is required"):
        nav.GyroErrorModel(bias_instability=1e-5)
    with pytest.raises(ValueError, match="angle_random_walk must be a non-negative scalar"):
        nav.GyroErrorModel(angle_random_walk=-1.0)
    with pytest.raises(ValueError, match="n_samples must be a positive integer"):
        nav.GyroErrorModel().rate_error(0, 0.1)
    with pytest.raises(ValueError, match="taus must lie between"):
        nav.allan_deviation(np.zeros(10), 1.0, taus=[5.0])
    with pytest.raises(ValueError, match="rate must be finite"):
        nav.allan_deviation([0.0, np.nan, 1.0, 2.0], 1.0)


def test_allan_deviation_at_extreme_magnitudes_scales_exactly():
    # the rate is scaled by powers of two inside: a rate scaled by 2^±900 gives exactly that scaled deviation
    y = np.random.default_rng(3).normal(size=(64, 3))
    taus, adev = nav.allan_deviation(y, 0.01)
    for k in (900, -900, -1000):
        scaled_taus, scaled = nav.allan_deviation(np.ldexp(y, k), 0.01)
        np.testing.assert_array_equal(scaled, np.ldexp(adev, k))
        np.testing.assert_array_equal(scaled_taus, taus)
    # Δt cancels from the deviation: only the averaging times carry it
    tiny_taus, tiny = nav.allan_deviation(y, 1e-300)
    np.testing.assert_allclose(tiny, adev, rtol=1e-14)
    np.testing.assert_allclose(tiny_taus, taus * 1e-298, rtol=1e-14)
    with pytest.raises(ValueError, match="sample_time is out of range"):
        nav.allan_deviation(y, 1e307)


@pytest.mark.parametrize("tau, correlation_time", [(1e-200, 1e100), (1e-300, 1e-5), (3e250, 1e-60), (2.0, 3.0),
                                                   (0.3, 1e-320)])
def test_gauss_markov_allan_deviation_at_extreme_ratios_against_mpmath(tau, correlation_time):
    # τ/T from 1e-300 to 1e310: the closed form, with 1000 digits for its x³ cancellation at small x
    mpmath = pytest.importorskip("mpmath")
    with mpmath.workdps(1000):
        x = mpmath.mpf(tau) / mpmath.mpf(correlation_time)
        bracket = 2 * x - 3 + 4 * mpmath.exp(-x) - mpmath.exp(-2 * x)
        exact = float(2.5 * mpmath.sqrt(bracket) / x)
    np.testing.assert_allclose(nav.gauss_markov_allan_deviation(tau, 2.5, correlation_time), exact, rtol=1e-14)
