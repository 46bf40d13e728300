import numpy as np
import pytest
from scipy import integrate, special

from kreisel.tops import complete_elliptic_pi, elliptic_f, elliptic_k, elliptic_pi, jacobi_elliptic


def _pi_quad(phi, n, m):
    f = lambda x: 1.0 / ((1.0 - n * np.sin(x) ** 2) * np.sqrt(1.0 - m * np.sin(x) ** 2))
    return integrate.quad(f, 0.0, phi, epsabs=0.0, epsrel=1e-13, limit=500)[0]


@pytest.mark.parametrize("phi", [-7.3, -2.0, -0.4, 0.0, 0.3, 1.2, np.pi / 2, 1.9, 4.0, 11.0])
@pytest.mark.parametrize("n", [-3.0, -0.4, 0.0, 0.35, 0.9])
@pytest.mark.parametrize("m", [0.0, 0.2, 0.7, 0.99])
def test_incomplete_pi_matches_quadrature(phi, n, m):
    assert elliptic_pi(phi, n, m) == pytest.approx(_pi_quad(phi, n, m), rel=2e-13, abs=1e-14)


@pytest.mark.parametrize("n", [-2.0, 0.0, 0.5])
@pytest.mark.parametrize("m", [0.0, 0.5, 0.999])
def test_complete_pi_matches_quadrature(n, m):
    assert complete_elliptic_pi(n, m) == pytest.approx(_pi_quad(np.pi / 2, n, m), rel=2e-13)


def test_special_values_and_broadcasting():
    phi = np.linspace(-5, 5, 11)
    m = np.array([[0.1], [0.6]])
    np.testing.assert_allclose(elliptic_pi(phi, 0.0, m), special.ellipkinc(phi, m), rtol=1e-14, atol=1e-15)
    # m = 1 below pi/2: the integral of sec(θ)/(1 - n sin²θ) is finite
    assert elliptic_pi(1.0, -0.5, 1.0) == pytest.approx(_pi_quad(1.0, -0.5, 1.0), rel=1e-13)
    # n = m: Π(φ, m | m) has the closed form of DLMF 19.6.E13 at φ = π/2: E(m)/(1 - m)
    assert complete_elliptic_pi(0.3, 0.3) == pytest.approx(special.ellipe(0.3) / 0.7, rel=1e-14)


def test_bad_parameters_are_refused():
    with pytest.raises(ValueError, match="n must be < 1"):
        elliptic_pi(0.3, 1.5, 0.2)
    with pytest.raises(ValueError, match="m must be <= 1"):
        elliptic_pi(0.3, 0.5, 1.2)
    with pytest.raises(ValueError, match="diverges"):
        elliptic_pi(2.0, 0.5, 1.0)
    with pytest.raises(TypeError, match="phi"):
        elliptic_pi("x", 0.5, 0.2)


# ---- against mpmath at 30 digits, parameter given as m1 = 1 - m -----------------------------------
mp = pytest.importorskip("mpmath")
EPS = np.finfo(float).eps
M1_VALUES = [1.0, 0.7, 0.3, 1e-2, 1e-4, 1e-8, 1e-12, 1e-16, 1e-17, 1e-20, 1e-40, 1e-300]


def _mp_parameter(m1):
    # 30 correct digits of m = 1 - m1 need 30 + |log10 m1| working digits
    mp.mp.dps = 30 + int(max(0.0, -np.log10(m1)))
    return 1 - mp.mpf(m1)


@pytest.mark.parametrize("m1", M1_VALUES)
def test_jacobi_functions_match_mpmath(m1):
    m = _mp_parameter(m1)
    K = float(elliptic_k(m1=m1))
    assert K == pytest.approx(float(mp.ellipk(m)), rel=2 * EPS)
    u = np.concatenate([np.linspace(-3.7, 3.7, 23), [0.5, 0.999, 1.0, 1.001, 2.0, 2.5]]) * K
    sn, cn, dn = jacobi_elliptic(u, m1=m1)
    for i, x in enumerate(u):
        X = mp.mpf(x)
        S, C, D = (mp.ellipfun(kind, X, m=m) for kind in ("sn", "cn", "dn"))
        # error relative to the value plus what the rounding of u itself moves it (|u f'| eps);
        # 1e-30 is the reference's own resolution (mpmath returns sn(0) = ±1e-38)
        for value, exact, slope in ((sn[i], S, C * D), (cn[i], C, S * D), (dn[i], D, m * S * C)):
            scale = abs(exact) + abs(X * slope)
            assert abs(value - exact) <= 4 * EPS * scale + 1e-30, (x, value, exact)


@pytest.mark.parametrize("m1", M1_VALUES)
def test_first_and_third_kind_match_mpmath(m1):
    m = _mp_parameter(m1)
    for phi in (0.3, 1.2, np.pi / 2 - 1e-9, 1.9, -4.0):
        if m1 < 1e-16 and abs(phi) > np.pi / 2:
            continue  # K ~ ln(4/√m1): fine, but mpmath's reduction needs more digits than is useful
        F = mp.ellipf(mp.mpf(phi), m)
        assert float(elliptic_f(phi, m1=m1)) == pytest.approx(float(F), rel=8 * EPS)
        for n in (-3.0, -0.4, 0.5, 0.9):
            P = mp.ellippi(mp.mpf(n), mp.mpf(phi), m)
            assert float(elliptic_pi(phi, n, m1=m1)) == pytest.approx(float(P), rel=8 * EPS), (phi, n)
    if m1 > 0.0:
        for n in (-3.0, -0.4, 0.5, 0.9):
            P = mp.ellippi(mp.mpf(n), m)
            assert float(complete_elliptic_pi(n, m1=m1)) == pytest.approx(float(P), rel=8 * EPS), n


def test_separatrix_limit_and_parameter_checks():
    u = np.array([-30.0, -1.0, 0.0, 0.4, 25.0])
    sn, cn, dn = jacobi_elliptic(u, m1=0.0)
    np.testing.assert_allclose(sn, np.tanh(u), rtol=1e-15)
    np.testing.assert_allclose(cn, 1 / np.cosh(u), rtol=1e-15)
    np.testing.assert_array_equal(cn, dn)
    # m given as m or as m1 agree where 1 - m is exact
    np.testing.assert_array_equal(elliptic_pi(0.7, -0.3, 0.25), elliptic_pi(0.7, -0.3, m1=0.75))
    with pytest.raises(TypeError, match="exactly one of m and m1"):
        elliptic_pi(0.3, 0.5, 0.2, m1=0.8)
    with pytest.raises(ValueError, match="m must be <= 1"):
        jacobi_elliptic(0.3, m1=-1e-3)
    with pytest.raises(ValueError, match="diverges"):
        complete_elliptic_pi(0.5, m1=0.0)


def test_complete_pi_where_m_and_n_both_approach_one():
    # Π(n | m) with 1 − n and m1 both tiny and far apart (a Lagrange top passing next to the
    # vertical): the reference is the same Carlson form evaluated by mpmath at 100 digits, so
    # forming 1 − m and 1 − n in the reference costs nothing; Carlson's R_C term of R_J is where
    # double precision lost up to 1e-11 before its argument was formed without cancellation
    from kreisel.tops._elliptic import complete_pi

    mp.mp.dps = 100
    for one_minus_n in (0.5, 3.0, 1e-3, 1e-10, 1e-20, 1e-30, 1e-60, 1e-150, 1e-300):
        for ratio in (1e-300, 1e-100, 1e-40, 1e-13, 1e-11, 1e-9, 1e-6, 1e-3, 1.0, 1e3, 1e10):
            m1 = ratio * one_minus_n
            if not 0.0 < m1 < 1.0:
                continue
            n, M1 = 1 - mp.mpf(one_minus_n), mp.mpf(m1)
            exact = mp.elliprf(0, M1, 1) + n / 3 * mp.elliprj(0, M1, 1, mp.mpf(one_minus_n))
            value = complete_pi(1.0 - one_minus_n, one_minus_n, m1, np.sqrt(m1))
            assert value == pytest.approx(float(exact), rel=4 * EPS), (one_minus_n, m1)


@pytest.mark.parametrize("m1", [0.9997, 0.3, 1e-6, 1e-20, 1e-40, 1e-310])
def test_third_kind_for_characteristics_far_below_zero(m1):
    # n -> −∞ (a top passing next to the lower vertical): Π ~ π/(2√(1 − n)) is what is left of
    # F + (n/3) s³ R_J after F cancels; the form with R_C and R_J(q) loses nothing
    m = _mp_parameter(m1)
    for n in (-0.5, -1e3, -1e8, -3.1e27, -1e200):
        P = mp.ellippi(mp.mpf(n), m)
        assert float(complete_elliptic_pi(n, m1=m1)) == pytest.approx(float(P), rel=8 * EPS), n
        for phi in (1e-9, 0.3, 1.2, np.pi / 2 - 1e-9, -0.7):
            P = mp.ellippi(mp.mpf(n), mp.mpf(phi), m)
            assert float(elliptic_pi(phi, n, m1=m1)) == pytest.approx(float(P), rel=8 * EPS), (phi, n)


@pytest.mark.parametrize("m1", [0.9997, 0.3, 1e-6])
def test_split_phase_third_kind_next_to_n_one(m1):
    # Π(am(±K + r), n | m) with 1 − n down to 1e-28 (a top passing next to the upper vertical):
    # the reflected integral r/(1 − n) − (…)/(1 − n)² cancelled to a few digits; the reference is
    # mpmath's Π at the amplitude am(K + r) (the reflected integral is Π(am(K + r)) − Π(n | m)) at
    # 80 digits, compared relative to the size of the split's terms
    from kreisel.tops._elliptic import complete_k, complete_pi, jacobi_near, pi_split

    kc = np.sqrt(m1)
    K = complete_k(m1, kc)
    mp.mp.dps = 80
    m = 1 - mp.mpf(m1)
    for one_minus_n in (0.1, 1e-12, 1.8e-28):
        n, N = 1.0 - one_minus_n, 1 - mp.mpf(one_minus_n)
        complete = complete_pi(n, one_minus_n, m1, kc)
        exact_complete = mp.ellippi(N, m)
        for r in (-0.45 * K, -0.1, 1e-9, 0.3, 0.5 * K):
            s, c, _ = jacobi_near(r, m1, kc)
            v = mp.ellipk(m) + mp.mpf(r)
            amplitude = mp.atan2(mp.ellipfun("sn", v, m=m), mp.ellipfun("cn", v, m=m))
            reflected = mp.ellippi(N, amplitude, m) - exact_complete
            for quarter in (1, -1, 3):
                exact = quarter * exact_complete + reflected
                value = pi_split(quarter, r, s, c, m1, kc, n, one_minus_n, complete)
                assert abs(value - exact) <= 8 * EPS * (abs(exact) + 3 * abs(complete)), (one_minus_n, r, quarter)
