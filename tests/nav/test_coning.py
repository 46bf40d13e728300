"""Coning motion and the classical drift table (Theory §3.5)."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import kreisel as kr

nav = kr.nav
OMEGA = 2 * np.pi  # 1 Hz coning


def body_rate(alpha, big_omega, t):
    """ω′ of Theory §3.5, written out independently of the library."""
    t = np.asarray(t, float)
    return np.stack([np.full_like(t, -2 * big_omega * np.sin(alpha / 2) ** 2),
                     -big_omega * np.sin(alpha) * np.sin(big_omega * t),
                     big_omega * np.sin(alpha) * np.cos(big_omega * t)], axis=-1)


def test_increments_are_integrals_of_the_body_rate():
    alpha, ts = np.radians(7.0), 0.013
    m = nav.coning_motion(alpha, OMEGA, ts, 200)
    nodes, weights = np.polynomial.legendre.leggauss(12)
    t0 = m.t[:-1, None]
    tq = t0 + 0.5 * ts * (nodes + 1.0)
    quadrature = 0.5 * ts * np.einsum("j,ijk->ik", weights, body_rate(alpha, OMEGA, tq))
    np.testing.assert_allclose(m.dtheta, quadrature, rtol=0, atol=1e-16)
    np.testing.assert_allclose(m.omega, body_rate(alpha, OMEGA, m.t), rtol=0, atol=1e-14)


def test_true_attitude_solves_the_quaternion_equation(quat):
    alpha, ts, n = np.radians(20.0), 0.01, 150
    m = nav.coning_motion(alpha, OMEGA, ts, n)

    def rhs(t, q):  # Theory §3.3: q̇ = ½ q ω′
        return 0.5 * quat.mul(q, np.concatenate([[0.0], body_rate(alpha, OMEGA, t)]))

    sol = solve_ivp(rhs, (0, m.t[-1]), m.q[0], method="DOP853", t_eval=m.t, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(sol.y.T, m.q, rtol=0, atol=1e-11)


@pytest.mark.parametrize("n, order", [(1, 2), (2, 4)])
def test_finer_increments_converge_to_the_true_attitude(quat, n, order):
    # the same motion sampled r times finer: the whole attitude history converges at the
    # algorithm's order (N = 1: summed increments, 2nd order; N = 2: 4th order)
    alpha, ts = np.radians(10.0), 0.05
    coarse = nav.coning_motion(alpha, OMEGA, ts, 40)
    errors = []
    for r in (32, 64, 128):
        fine = nav.coning_motion(alpha, OMEGA, ts / r, 40 * r)
        q = nav.attitude_from_increments(coarse.q[0], fine.dtheta, n)[:: r // n]
        errors.append(np.abs(quat.error(coarse.q, q)).max())
    ratios = np.array(errors[:-1]) / errors[1:]
    np.testing.assert_allclose(ratios, 2.0**order, rtol=0.05)
    assert errors[-1] < (2e-7 if n == 1 else 1e-12)


def test_attitude_returns_after_a_cone_period():
    m = nav.coning_motion(np.radians(30.0), 3.0, 2 * np.pi / 3.0 / 50, 50)
    np.testing.assert_allclose(m.q[-1], m.q[0], atol=1e-15)
    np.testing.assert_allclose(np.linalg.norm(m.q, axis=-1), 1.0, atol=1e-15)
    # and yet the increments sum to a steady rotation about -x
    assert m.dtheta.sum(axis=0)[0] < 0


def test_drift_coefficients_match_the_table():
    alpha, ts = 0.02, 0.03
    lam = OMEGA * ts
    table = {1: 1 / 12, 2: 1 / 60, 3: 1 / 280, 4: 1 / 1260}
    for n, c in table.items():
        assert nav.coning_drift(alpha, OMEGA, ts, n) == pytest.approx(alpha**2 * OMEGA * lam ** (2 * n) * c,
                                                                      rel=1e-14)


# (alpha in degrees, N, samples per cone period, cone periods, tolerance)
DRIFT_CASES = [(1.0, 1, 60, 20, 0.03), (1.0, 2, 60, 20, 0.03), (1.0, 3, 24, 40, 0.03),
               (0.1, 4, 16, 100, 0.15)]


@pytest.mark.parametrize("alpha_deg, n, per_period, periods, tol", DRIFT_CASES)
def test_coning_drift_table(quat, alpha_deg, n, per_period, periods, tol):
    # λ = 2π/per_period is large enough that the drift over the run exceeds the
    # accumulated round-off by > 100x; whole cone periods cancel the periodic error.
    alpha, ts = np.radians(alpha_deg), 1.0 / per_period
    m = nav.coning_motion(alpha, OMEGA, ts, per_period * periods)
    q = nav.attitude_from_increments(m.q[0], m.dtheta, n)
    error = quat.error(m.q[::n], q)
    per_cone = error[:: per_period // n]
    drift = np.polyfit(m.t[:: per_period][: len(per_cone)], per_cone, 1)[0]
    expected = nav.coning_drift(alpha, OMEGA, ts, n)
    assert -drift[0] == pytest.approx(expected, rel=tol)
    # along -x of the body: the cone axis, tilted by α from body x
    cos_angle = -drift[0] / np.linalg.norm(drift)
    assert cos_angle >= np.cos(1.01 * alpha)


def test_drift_shrinks_with_the_algorithm_order(quat):
    alpha, ts = np.radians(1.0), 1.0 / 24
    m = nav.coning_motion(alpha, OMEGA, ts, 24 * 10)
    final = [abs(quat.error(m.q[-1], nav.attitude_from_increments(m.q[0], m.dtheta, n)[-1])[0])
             for n in (1, 2, 3)]
    assert final[0] > 30 * final[1] > 30 * 30 * final[2]


def test_coning_motion_broadcasts():
    m = nav.coning_motion([0.1, 0.2], OMEGA, [[0.01], [0.02]], 10)
    assert m.dtheta.shape == (2, 2, 10, 3) and m.q.shape == (2, 2, 11, 4) and m.t.shape == (2, 2, 11)
    single = nav.coning_motion(0.2, OMEGA, 0.02, 10)
    np.testing.assert_array_equal(m.dtheta[1, 1], single.dtheta)


@pytest.mark.parametrize("kwargs, match", [
    (dict(half_angle=-0.1), "half_angle must be > 0, got -0.1"),
    (dict(rate=0.0), "rate must be > 0, got 0.0"),
    (dict(sample_time=np.nan), "sample_time must be finite"),
    (dict(n_samples=0), "n_samples must be a positive integer"),
    (dict(n_samples=2.5), "n_samples must be a positive integer"),
])
def test_coning_motion_rejects_bad_input(kwargs, match):
    args = dict(half_angle=0.1, rate=1.0, sample_time=0.01, n_samples=10) | kwargs
    with pytest.raises(ValueError, match=match):
        nav.coning_motion(**args)


def test_coning_drift_rejects_bad_n():
    with pytest.raises(ValueError, match="samples_per_update must be 1, 2, 3 or 4"):
        nav.coning_drift(0.1, 1.0, 0.01, 5)
    with pytest.raises(TypeError, match="samples_per_update"):
        nav.coning_drift(0.1, 1.0, 0.01, 2.0)


def test_coning_drift_at_extreme_magnitudes_against_mpmath():
    # α ~1e-200 squares to 0 and λ^(2N) ~1e320 overflows on their own; ε itself is representable
    mpmath = pytest.importorskip("mpmath")
    for alpha, rate, ts, n in [(1e-200, 1e60, 1e-20, 2), (1e-3, 1e100, 1e-99, 4), (0.5, 1e-80, 1e10, 3)]:
        c = mpmath.factorial(n) / (2 ** (n + 1) * mpmath.fac2(2 * n + 1))
        exact = c * mpmath.mpf(alpha) ** 2 * mpmath.mpf(rate) ** (2 * n + 1) * mpmath.mpf(ts) ** (2 * n)
        assert nav.coning_drift(alpha, rate, ts, n) == pytest.approx(float(exact), rel=1e-14)
    with pytest.raises(ValueError, match="out of range"):
        nav.coning_drift(0.1, 1e65, 0.01, 2)
