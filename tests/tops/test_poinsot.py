import numpy as np
import pytest

import kreisel as kr


@pytest.mark.parametrize("moments, omega0", [((1.0, 2.0, 3.0), [0.3, 0.2, 1.0]), ((2.0, 3.0, 1.0), [1.0, -0.2, 0.3])])
def test_polhode_herpolhode_and_plane(moments, omega0):
    top = kr.EulerTop(*moments)
    period = top.omega_period(omega0)
    q0 = np.array([0.5, 0.5, -0.5, 0.5])
    g = kr.poinsot(top, np.linspace(0.0, period, 400), omega0, q0)
    I = np.array(moments)
    T = top.energy(omega0)
    J = top.angular_momentum(omega0)
    # on the inertia ellipsoid and on the momentum ellipsoid, closed after one period
    np.testing.assert_allclose(g.polhode**2 @ I, 1.0, rtol=1e-13)
    np.testing.assert_allclose(g.polhode**2 @ I**2, J**2 / (2 * T), rtol=1e-13)
    np.testing.assert_allclose(g.polhode[-1], g.polhode[0], atol=1e-12)
    # the herpolhode stays on the invariable plane at distance √(2T)/|J|, normal to the space J
    np.testing.assert_allclose(g.herpolhode_space @ g.plane_normal, np.sqrt(2 * T) / J, rtol=1e-13)
    assert g.plane_distance == pytest.approx(np.sqrt(2 * T) / J)
    J_space = kr.quat_apply(q0, I * np.asarray(omega0))
    np.testing.assert_allclose(g.plane_normal, J_space / J, atol=1e-15)
    # the tangent plane of the ellipsoid at the contact point is the invariable plane: its normal ∝ I r
    normal_body = I * g.polhode
    tr = top.solve(g.t, omega0, q0)
    normal_space = kr.quat_apply(tr.q, normal_body)
    np.testing.assert_allclose(normal_space / np.linalg.norm(normal_space, axis=1)[:, None], np.broadcast_to(g.plane_normal, normal_space.shape), atol=1e-13)
    # in-plane coordinates reproduce the distance from the foot of the perpendicular
    radius = np.linalg.norm(g.herpolhode, axis=1)
    expected = np.sqrt(np.sum(g.herpolhode_space**2, axis=1) - g.plane_distance**2)
    np.testing.assert_allclose(radius, expected, atol=1e-12)
    assert g.herpolhode[0, 1] == pytest.approx(0.0, abs=1e-15)
    np.testing.assert_allclose(np.linalg.norm(normal_body, axis=1), J / np.sqrt(2 * T), rtol=1e-13)


def test_bad_input():
    with pytest.raises(TypeError, match="EulerTop"):
        kr.poinsot(object(), [0.0], [1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="nonzero"):
        kr.poinsot(kr.EulerTop(1.0, 2.0, 3.0), [0.0], [0.0, 0.0, 0.0])


def test_poinsot_at_extreme_rates_is_the_time_scaled_geometry():
    # ω0 × s traces the same polhode and herpolhode at times t / s (Euler's equations are homogeneous);
    # its energy (~s²) and momentum once overflowed or underflowed
    top = kr.EulerTop(1.0, 2.0, 3.0)
    t = np.linspace(0.0, 5.0, 11)
    base = kr.tops.poinsot(top, t, [0.3, 0.2, 1.0])
    for s in (1e-300, 1e-160, 1e160, 1e300):
        g = kr.tops.poinsot(top, t / s, np.array([0.3, 0.2, 1.0]) * s)
        np.testing.assert_allclose(g.polhode, base.polhode, rtol=1e-12, atol=1e-14)
        np.testing.assert_allclose(g.herpolhode, base.herpolhode, rtol=1e-12, atol=1e-14)
        np.testing.assert_allclose(g.plane_distance, base.plane_distance, rtol=1e-14)
    with pytest.raises(ValueError, match="t and omega0 are out of range"):
        kr.tops.poinsot(top, t * 1e20, [0.3, 0.2, 1.0])
