import numpy as np
import pytest

import kreisel as kr
from kreisel.so3 import quat_apply

TOP = kr.KovalevskayaTop(0.7, 1.3)
Q0 = np.array([np.cos(0.4), np.sin(0.4) * 0.6, np.sin(0.4) * 0.8, 0.0])
OMEGA0 = np.array([0.5, -0.2, 1.1])


def _spread(x):
    return np.ptp(x) / max(1.0, np.abs(x).max())


def test_four_integrals_conserved_along_independent_integration(reference):
    t = np.linspace(0.0, 60.0, 601)
    omega, q = reference(TOP.moments, OMEGA0, Q0, t, weight=TOP.mgl, lever=(1.0, 0.0, 0.0))
    gamma = quat_apply(q, [0.0, 0.0, 1.0], inverse=True)
    integrals = TOP.integrals(omega, gamma)
    for name in ("energy", "area", "geometric", "kovalevskaya"):
        assert _spread(getattr(integrals, name)) < 1e-11, name
    # γ taken along gravity (downward) flips the sign of c: that K is not conserved
    p, q_, _ = omega.T
    wrong = (p * p - q_ * q_ + TOP.c * gamma[:, 0]) ** 2 + (2 * p * q_ + TOP.c * gamma[:, 1]) ** 2
    assert _spread(wrong) > 1e-2
    # and for a generic heavy top (I1 != 2 I3) Kovalevskaya's K is not an integral
    omega, q = reference((1.5, 1.5, 0.7), OMEGA0, Q0, t, weight=TOP.mgl, lever=(1.0, 0.0, 0.0))
    gamma = quat_apply(q, [0.0, 0.0, 1.0], inverse=True)
    assert _spread(TOP.integrals(omega, gamma).kovalevskaya) > 1e-2


def test_euler_poisson_form_of_the_equations(reference):
    # 2ṗ = qr, 2q̇ = −pr + cγ3, ṙ = −cγ2 (Theory §7), by differentiating the reference
    t = np.array([0.0, 1e-4, 2e-4])
    omega, q = reference(TOP.moments, OMEGA0, Q0, t, weight=TOP.mgl, lever=(1.0, 0.0, 0.0))
    gamma = quat_apply(q, [0.0, 0.0, 1.0], inverse=True)
    rate = (omega[2] - omega[0]) / 2e-4
    p, q_, r = omega[1]
    g = gamma[1]
    np.testing.assert_allclose(rate, [q_ * r / 2, (-p * r + TOP.c * g[2]) / 2, -TOP.c * g[1]], atol=1e-7)


def test_simulate_conserves_kovalevskaya_integral():
    t = np.linspace(0.0, 100.0, 201)
    tr = TOP.simulate(t, OMEGA0, Q0, rtol=1e-13)
    np.testing.assert_allclose(tr.gamma, quat_apply(tr.q, [0.0, 0.0, 1.0], inverse=True), atol=1e-15)
    integrals = TOP.integrals(tr.omega, tr.gamma)
    for name in ("energy", "area", "geometric", "kovalevskaya"):
        assert _spread(getattr(integrals, name)) < 1e-10, name


def test_bad_input():
    with pytest.raises(ValueError, match="mgl"):
        kr.KovalevskayaTop(1.0, 0.0)
    with pytest.raises(ValueError, match="gamma"):
        TOP.integrals([1.0, 2.0, 3.0], [1.0, 0.0])


@pytest.mark.parametrize("omega", [[1e200, 0.0, 0.0], [0.0, 2e77, 0.0], [1.0, 0.0, 1e160]])
def test_integrals_beyond_double_precision_are_refused_without_a_warning(omega, recwarn):
    with pytest.raises(ValueError, match=r"omega and gamma are out of range for the \w+ integral"):
        TOP.integrals(omega, [0.0, 0.6, 0.8])
    assert not recwarn.list


def test_integrals_just_inside_double_precision_stay_finite_and_exact():
    # (p² − q²)² with p = 1e76, q = γ = 0 is 1e304: representable, and K equals it to rounding
    ints = TOP.integrals([1e76, 0.0, 0.0], [0.0, 0.0, 1.0])
    assert ints.kovalevskaya == pytest.approx(1e304, rel=1e-14)
