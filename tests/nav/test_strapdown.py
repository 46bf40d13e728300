"""Strapdown updates: increments and sampled rates (Theory §3.3, §3.5)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

import kreisel as kr
from kreisel.nav._kernels import bortz_coefficient_from_square

nav = kr.nav
OMEGA = 2 * np.pi


def random_unit_quaternions(rng, shape):
    q = rng.normal(size=shape + (4,))
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


@pytest.mark.parametrize("n", [1, 2, 3, 4])
def test_fixed_axis_rotation_is_exact(n):
    # no coning: every increment is parallel, the correction vanishes, q is exp of the sum
    rng = np.random.default_rng(1)
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    steps = rng.uniform(0.0, 0.05, size=240)
    q0 = random_unit_quaternions(rng, ())
    q = nav.attitude_from_increments(q0, steps[:, None] * axis, n)
    total = np.cumsum(steps)[n - 1:: n]
    expected = (Rotation.from_quat(q0, scalar_first=True) * Rotation.from_rotvec(total[:, None] * axis))
    np.testing.assert_allclose(Rotation.from_quat(q[1:], scalar_first=True).inv().__mul__(expected).magnitude(),
                               0.0, atol=1e-13)


@settings(max_examples=50, deadline=None)
@given(arrays(np.float64, (12, 3), elements=st.floats(-0.5, 0.5)), st.sampled_from([1, 2, 3, 4]))
def test_updates_compose_like_scipy(d, n):
    # property: the state after each update is q0 ⊗ exp(φ_1/2) ⊗ exp(φ_2/2) ⊗ … (scipy composes)
    k = nav.coning_coefficients(n)
    blocks = d.reshape(-1, n, 3)
    phi = blocks.sum(axis=1)
    if n > 1:
        phi += np.cross(np.tensordot(k, blocks[:, :-1], axes=(0, 1)), blocks[:, -1])
    r = Rotation.identity()
    expected = [r]
    for p in phi:
        r = r * Rotation.from_rotvec(p)
        expected.append(r)
    q = nav.attitude_from_increments([1.0, 0, 0, 0], d, n)
    gap = (Rotation.concatenate(expected).inv() * Rotation.from_quat(q, scalar_first=True)).magnitude()
    assert gap.max() < 1e-14


@pytest.mark.parametrize("n", [2, 3, 4])
def test_one_update_matches_the_written_formula(quat, n):
    rng = np.random.default_rng(n)
    d = rng.normal(scale=0.01, size=(n, 3))
    k = {2: [2 / 3], 3: [9 / 20, 27 / 20], 4: [54 / 105, 92 / 105, 214 / 105]}[n]
    phi = d.sum(axis=0) + np.cross(np.tensordot(k, d[:-1], axes=1), d[-1])
    expected = Rotation.from_rotvec(phi).as_quat(scalar_first=True)
    q = nav.attitude_from_increments([1.0, 0, 0, 0], d, n)
    assert np.abs(quat.error(expected, q[-1])).max() < 1e-17 + 1e-15 * np.abs(phi).max()
    np.testing.assert_allclose(nav.coning_coefficients(n), k, rtol=1e-15)


def test_increments_broadcast_over_batches():
    rng = np.random.default_rng(7)
    q0 = random_unit_quaternions(rng, (2, 1))
    d = rng.normal(scale=0.02, size=(3, 12, 3))
    q = nav.attitude_from_increments(q0, d, 3)
    assert q.shape == (2, 3, 5, 4)
    for i in range(2):
        for j in range(3):
            np.testing.assert_array_equal(q[i, j], nav.attitude_from_increments(q0[i, 0], d[j], 3))
    np.testing.assert_allclose(np.linalg.norm(q, axis=-1), 1.0, atol=1e-15)


@pytest.mark.parametrize("n", [1, 2, 3, 4])
def test_no_increments_leave_q0(n):
    # zero increments are zero updates: the attitude after them is q0 alone (this raised numpy's "cannot
    # reshape array of size 0 into shape (0,3)", which names neither argument)
    q0 = random_unit_quaternions(np.random.default_rng(5), (2,))
    # (q0 as given, renormalised to rounding)
    np.testing.assert_allclose(nav.attitude_from_increments(q0[0], np.zeros((0, 3)), n), q0[:1], atol=1e-15)
    np.testing.assert_allclose(nav.attitude_from_increments(q0[:, None], np.zeros((3, 0, 3)), n),
                               np.broadcast_to(q0[:, None, None], (2, 3, 1, 4)), atol=1e-15)


def test_increments_bad_input():
    d = np.zeros((10, 3))
    with pytest.raises(ValueError, match=r"10 samples, not divisible by samples_per_update=3 \(1 left over\)"):
        nav.attitude_from_increments([1, 0, 0, 0], d, 3)
    d[7, 1] = np.nan
    with pytest.raises(ValueError, match=r"dtheta must be finite; first bad sample at index \[7\]"):
        nav.attitude_from_increments([1, 0, 0, 0], d, 1)
    with pytest.raises(ValueError, match="q0 must be nonzero quaternions"):
        nav.attitude_from_increments([0, 0, 0, 0], np.zeros((4, 3)))
    with pytest.raises(ValueError, match=r"dtheta must have shape \(\.\.\., 3\)"):
        nav.attitude_from_increments([1, 0, 0, 0], np.zeros((4, 2)))
    with pytest.raises(ValueError, match="does not broadcast"):
        nav.attitude_from_increments(np.tile([1.0, 0, 0, 0], (2, 1)), np.zeros((3, 4, 3)))
    with pytest.raises(ValueError, match="samples_per_update must be 1, 2, 3 or 4"):
        nav.attitude_from_increments([1, 0, 0, 0], np.zeros((10, 3)), 5)


def test_bortz_coefficient_from_square_series_and_closed_form_agree():
    # the switch at ψ = 0.1 is seamless, and ψ → 0 gives the chapter's 1/12
    below, above = bortz_coefficient_from_square(np.nextafter(1e-2, 0)), bortz_coefficient_from_square(1e-2)
    assert above == pytest.approx(below, rel=1e-15)
    assert bortz_coefficient_from_square(0.0) == 1 / 12
    psi = 1.3
    assert bortz_coefficient_from_square(psi**2) == pytest.approx((1 - psi / 2 / np.tan(psi / 2)) / psi**2, rel=1e-14)
    assert bortz_coefficient_from_square(psi**2) == pytest.approx(kr.kinematics.bortz_coefficient(psi), rel=1e-14)


def smooth_rate(t):
    """A body rate with no special structure (all three axes, several frequencies)."""
    t = np.asarray(t, float)
    return np.stack([0.7 * np.sin(1.3 * t) + 0.2, 0.5 * np.cos(2.1 * t), 0.9 * np.sin(0.7 * t + 0.4)], axis=-1)


def linear_rate(t):
    """ω′ linear in time: exactly what the rate integrator assumes between samples."""
    t = np.asarray(t, float)[..., None]
    return np.array([0.2, -0.5, 0.3]) + t * np.array([0.4, 0.3, -0.6])


@pytest.mark.parametrize("method", ["quaternion", "bortz"])
@pytest.mark.parametrize("rate, order", [(linear_rate, 4), (smooth_rate, 2)])
def test_rate_integration_order(quat, method, rate, order):
    # linear rates: RK4 order 4; smooth rates: linear interpolation between samples limits to 2
    q0 = np.array([0.5, 0.5, -0.5, 0.5])
    t_end = 4.0
    ref = solve_ivp(lambda t, q: 0.5 * quat.mul(q, np.concatenate([[0.0], rate(t)])),
                    (0, t_end), q0, method="DOP853", rtol=1e-13, atol=1e-15)
    q_end = ref.y[:, -1] / np.linalg.norm(ref.y[:, -1])
    errors = []
    for n in (25, 50, 100):
        t = np.linspace(0.0, t_end, n + 1)
        q = nav.attitude_from_rates(q0, t, rate(t), method=method)
        errors.append(np.linalg.norm(quat.error(q_end, q[-1])))
    ratios = np.array(errors[:-1]) / errors[1:]
    np.testing.assert_allclose(ratios, 2.0**order, rtol=0.1)


def test_constant_rate_is_exact_with_bortz():
    # ψ stays parallel to ω′, so the Bortz equation reduces to ψ̇ = ω′ and RK4 is exact
    # (RK4 on q̇ = ½ q ω′ only truncates exp at fourth order: covered by the order test)
    t = np.sort(np.random.default_rng(3).uniform(0, 2, 50))
    w = np.array([0.3, -1.1, 0.8])
    q = nav.attitude_from_rates([1, 0, 0, 0], t, np.tile(w, (50, 1)), method="bortz")
    expected = Rotation.from_rotvec((t - t[0])[:, None] * w).as_quat(scalar_first=True)
    np.testing.assert_allclose(q * np.sign(q[:, :1]), expected, atol=1e-12)


def test_rate_sampling_cost(quat):
    # rate-output gyros under coning (α = 1°, 1 Hz, λ = 2π/60): RK4 on linearly interpolated
    # rates drifts like plain summation of exact increments (N = 1), ~λ²·60/12 times the
    # two-sample coning algorithm on increments; documented in attitude_from_rates
    alpha, ts = np.radians(1.0), 1.0 / 60
    m = nav.coning_motion(alpha, OMEGA, ts, 60 * 10)
    eps1 = nav.coning_drift(alpha, OMEGA, ts, 1)
    for method in ("quaternion", "bortz"):
        q = nav.attitude_from_rates(m.q[0], m.t, m.omega, method=method)
        drift = quat.error(m.q[-1], q[-1]) / m.t[-1]
        assert -drift[0] == pytest.approx(eps1, rel=0.01)
    q2 = nav.attitude_from_increments(m.q[0], m.dtheta, 2)
    drift2 = quat.error(m.q[-1], q2[-1]) / m.t[-1]
    assert -drift[0] / -drift2[0] > 400


def test_rates_bad_input():
    t = np.array([0.0, 0.1, 0.1, 0.3])
    w = np.zeros((4, 3))
    with pytest.raises(ValueError, match=r"t must be strictly increasing: t\[2\] = 0.1 follows t\[1\] = 0.1"):
        nav.attitude_from_rates([1, 0, 0, 0], t, w)
    t[2] = 0.2
    w[3, 2] = np.inf
    with pytest.raises(ValueError, match=r"omega_body must be finite; first bad sample at index \[3\]"):
        nav.attitude_from_rates([1, 0, 0, 0], t, w)
    with pytest.raises(ValueError, match="method must be one of"):
        nav.attitude_from_rates([1, 0, 0, 0], t, np.zeros((4, 3)), method="euler")
    with pytest.raises(ValueError, match=r"omega_body must have shape \(\.\.\., 4, 3\)"):
        nav.attitude_from_rates([1, 0, 0, 0], t, np.zeros((5, 3)))


def test_q0_is_any_rotation_input_as_for_simulate():
    """One coercion (kreisel.so3): a Rotation, a matrix or a quaternion of any norm give the same attitude."""
    q0 = np.array([0.5, 0.5, -0.5, 0.5])
    d = np.tile([0.01, -0.02, 0.03], (8, 1))
    want = nav.attitude_from_increments(q0, d, 2)
    for same in (3.0 * q0, kr.Rotation.from_quat(q0), kr.quat_to_matrix(q0)):
        np.testing.assert_allclose(nav.attitude_from_increments(same, d, 2), want, rtol=0, atol=1e-15)


def test_attitude_from_rates_refuses_turns_beyond_half_a_turn_per_sample():
    # more than π between samples is aliased; rates ~1e80 used to give NaN attitudes without an error
    t = np.linspace(0.0, 1.0, 5)
    for scale in (20.0, 1e80, 1e300):
        with pytest.raises(ValueError, match=r"omega_body turns the body by .* between samples 0 and 1 of t, more than π"):
            kr.nav.attitude_from_rates([1, 0, 0, 0], t, np.tile([0.0, 0.0, scale], (5, 1)))
    with pytest.raises(ValueError, match="more than π"):
        kr.nav.attitude_from_rates([1, 0, 0, 0], t * 1e100, np.tile([0.0, 0.0, 1.0], (5, 1)))
    # just under half a turn per sample still integrates: the exact turn about a fixed axis
    q = kr.nav.attitude_from_rates([1, 0, 0, 0], t, np.tile([0.0, 0.0, 12.0], (5, 1)), method="bortz")
    np.testing.assert_allclose(q[-1], [np.cos(6.0), 0, 0, np.sin(6.0)], atol=1e-12)
    # tiny rates over tiny or huge spans are fine
    q = kr.nav.attitude_from_rates([1, 0, 0, 0], t * 1e200, np.tile([0.0, 0.0, 1e-200], (5, 1)), method="bortz")
    np.testing.assert_allclose(q[-1], [np.cos(0.5), 0, 0, np.sin(0.5)], atol=1e-15)
