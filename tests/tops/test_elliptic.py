import numpy as np
import pytest
from scipy import integrate, special

from kreisel.tops import complete_elliptic_pi, elliptic_pi


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
