import mpmath as mp
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import kreisel as kr

TOP = kr.LagrangeTop(1.0, 0.5, 1.0)
MOMENTS = (1.0, 1.0, 0.5)
# (label, euler0, rates0): cusp = released from rest, loop = pushed backwards, monotone = pushed forwards
STATES = {
    "cusp": ([0.3, 0.5, 0.2], [0.0, 0.0, 10.0]),
    "loop": ([0.3, 0.5, 0.2], [-0.6, 0.7, 10.0]),
    "loop_low": ([0.3, 1.2, 0.2], [-0.5, -0.3, 6.0]),
    "monotone": ([0.3, 0.9, 0.2], [7.8, 0.4, 5.15]),
    "below_horizontal": ([0.0, 2.0, 0.0], [0.3, 0.1, -5.0]),
}


def _reference_from(reference, tr, t):
    return reference(MOMENTS, tr.omega[0], tr.q[0], t, weight=TOP.mgl, lever=(0.0, 0.0, 1.0))


def _cubic_roots_numpy(constants):
    I1, I3, mgl = TOP.I1, TOP.I3, TOP.mgl
    a, b = constants.J3 / I1, constants.Jz / I1
    alpha, beta = (2 * constants.E - constants.J3**2 / I3) / I1, 2 * mgl / I1
    # (1 - u²)(α - βu) - (b - au)² expanded by numpy polynomial algebra
    f = np.polysub(np.polymul([-1.0, 0.0, 1.0], [-beta, alpha]), np.polymul([-a, b], [-a, b]))
    return np.sort(np.roots(f).real)


@pytest.mark.parametrize("label", STATES)
def test_exact_solution_matches_reference(reference, label):
    euler0, rates0 = STATES[label]
    t = np.linspace(0.0, 20.0, 201)
    tr = TOP.solve(t, euler0, rates0)
    np.testing.assert_allclose(tr.zxz_angles[0], euler0, atol=1e-15)
    omega_ref, q_ref = _reference_from(reference, tr, t)
    np.testing.assert_allclose(tr.omega, omega_ref, atol=1e-10)
    np.testing.assert_allclose(tr.q, q_ref, atol=1e-10)
    # the reference's own Euler angles agree with the exact ones
    angles = Rotation.from_quat(q_ref[:, [1, 2, 3, 0]]).as_euler("ZXZ")
    np.testing.assert_allclose(angles[:, 1], tr.zxz_angles[:, 1], atol=1e-10)


@pytest.mark.parametrize("label", ["cusp", "loop"])
def test_long_run_integrals_and_turning_points(reference, label):
    euler0, rates0 = STATES[label]
    t = np.linspace(0.0, 120.0, 6001)
    tr = TOP.solve(t, euler0, rates0)
    omega_ref, q_ref = _reference_from(reference, tr, t)
    np.testing.assert_allclose(tr.q, q_ref, atol=2e-9)
    constants = TOP.constants(euler0, rates0)
    # integrals along the independent integration
    R = Rotation.from_quat(q_ref[:, [1, 2, 3, 0]])
    J_space = R.apply(np.array(MOMENTS) * omega_ref)
    axis_height = R.apply([0.0, 0.0, 1.0])[:, 2]
    energy = 0.5 * np.sum(np.array(MOMENTS) * omega_ref**2, axis=1) + TOP.mgl * axis_height
    np.testing.assert_allclose(MOMENTS[2] * omega_ref[:, 2], constants.J3, atol=1e-11)
    np.testing.assert_allclose(J_space[:, 2], constants.Jz, atol=1e-11)
    np.testing.assert_allclose(energy, constants.E, atol=1e-10)
    # turning points: numpy roots of the cubic and the extremes of a long integration
    u1, u2, u3 = _cubic_roots_numpy(constants)
    np.testing.assert_allclose(TOP.cubic_roots(euler0, rates0), (u1, u2, u3), rtol=1e-12, atol=1e-13)
    theta_min, theta_max = TOP.turning_points(euler0, rates0)
    assert theta_min == pytest.approx(np.arccos(u2), abs=1e-11)
    assert theta_max == pytest.approx(np.arccos(u1), abs=1e-11)
    theta = np.arccos(np.clip(axis_height, -1, 1))
    assert theta.min() == pytest.approx(theta_min, abs=1e-6) and theta.max() == pytest.approx(theta_max, abs=1e-6)
    assert theta.min() >= theta_min - 1e-9 and theta.max() <= theta_max + 1e-9
    # effective potential: ½ I1 θ̇² + V_eff(θ) = E, and V_eff = E at the turning points
    veff = TOP.effective_potential(tr.zxz_angles[:, 1], constants.J3, constants.Jz)
    np.testing.assert_allclose(0.5 * TOP.I1 * tr.zxz_rates[:, 1] ** 2 + veff, constants.E, rtol=1e-12)
    np.testing.assert_allclose(TOP.effective_potential([theta_min, theta_max], constants.J3, constants.Jz), constants.E, rtol=1e-11)
    # nutation period and mean precession against the long run
    period = TOP.nutation_period(euler0, rates0)
    n = int(t[-1] // period)
    late = TOP.solve(np.array([0.0, n * period]), euler0, rates0)
    np.testing.assert_allclose(late.zxz_angles[1, 1], euler0[1], atol=1e-10)
    phi = np.unwrap(R.as_euler("ZXZ")[:, 0])
    k = np.searchsorted(t, n * period)
    slope = (late.zxz_angles[1, 0] - late.zxz_angles[0, 0]) / (n * period)
    assert TOP.mean_precession_rate(euler0, rates0) == pytest.approx(slope, rel=1e-11)
    assert (phi[k] - phi[0]) / t[k] == pytest.approx(slope, rel=1e-3)


@pytest.mark.parametrize("label, kind", [("cusp", "cusp"), ("loop", "loop"), ("loop_low", "loop"), ("monotone", "monotone")])
def test_apex_locus_kinds(reference, label, kind):
    euler0, rates0 = STATES[label]
    assert TOP.apex_locus_kind(euler0, rates0) == kind
    # φ̇ along an independent integration: one sign (monotone), both signs (loop), zero at the cusps
    t = np.linspace(0.0, 2 * TOP.nutation_period(euler0, rates0), 4001)
    tr = TOP.solve(t[:1], euler0, rates0)
    omega_ref, q_ref = _reference_from(reference, tr, t)
    angles = Rotation.from_quat(q_ref[:, [1, 2, 3, 0]]).as_euler("ZXZ")
    theta, psi = angles[:, 1], angles[:, 2]
    phidot = (omega_ref[:, 0] * np.sin(psi) + omega_ref[:, 1] * np.cos(psi)) / np.sin(theta)
    scale = np.abs(phidot).max()
    if kind == "monotone":
        assert np.all(phidot > 0.05 * scale) or np.all(phidot < -0.05 * scale)
    elif kind == "loop":
        assert phidot.max() > 0.05 * scale and phidot.min() < -0.05 * scale
    else:
        assert phidot.min() > -1e-7 * scale or phidot.max() < 1e-7 * scale
        assert np.abs(phidot).min() < 1e-3 * scale


@pytest.mark.parametrize("theta0", [0.4, 1.0, 2.2])
def test_steady_precession_keeps_theta(reference, theta0):
    omega3 = 8.0
    for rate in TOP.steady_precession_rates(theta0, omega3):
        rates0 = [rate, 0.0, omega3 - np.cos(theta0) * rate]
        t = np.linspace(0.0, 10.0, 101)
        tr = TOP.solve(t[:1], [0.0, theta0, 0.0], rates0)
        omega_ref, q_ref = _reference_from(reference, tr, t)
        theta = Rotation.from_quat(q_ref[:, [1, 2, 3, 0]]).as_euler("ZXZ")[:, 1]
        np.testing.assert_allclose(theta, theta0, atol=1e-9)
        u1, u2, _ = TOP.cubic_roots([0.0, theta0, 0.0], rates0)
        assert u2 - u1 < 1e-7
    # θ equation I1 cos θ φ̇² − J3 φ̇ + mgl = 0, and no steady precession for a slow top tilted up
    slow, fast = TOP.steady_precession_rates(0.4, omega3)
    J3 = TOP.I3 * omega3
    for rate in (slow, fast):
        assert TOP.I1 * np.cos(0.4) * rate**2 - J3 * rate + TOP.mgl == pytest.approx(0.0, abs=1e-12)
    assert np.isnan(TOP.steady_precession_rates(0.1, 1.0)[0])
    # horizontal axis: only the slow precession mgl/J3 remains
    slow, fast = TOP.steady_precession_rates(np.pi / 2, omega3)
    assert slow == pytest.approx(TOP.mgl / J3, rel=1e-15) and abs(fast) > 1e15


def test_sleeping_top_threshold(reference):
    threshold = TOP.sleeping_top_threshold()
    assert threshold == pytest.approx(2 * np.sqrt(TOP.I1 * TOP.mgl) / TOP.I3)
    assert TOP.sleeping_top_stable(1.05 * threshold) and not TOP.sleeping_top_stable(0.95 * threshold)
    np.testing.assert_array_equal(TOP.sleeping_top_stable([0.5 * threshold, 2 * threshold]), [False, True])
    # the independent integration: a nearly upright top stays up only above the threshold
    t = np.linspace(0.0, 40.0, 401)
    for factor, stays_up in [(1.05, True), (0.95, False)]:
        omega3 = factor * threshold
        tr = TOP.solve(t[:1], [0.0, 1e-3, 0.0], [0.0, 0.0, omega3])
        omega_ref, q_ref = _reference_from(reference, tr, t)
        theta = Rotation.from_quat(q_ref[:, [1, 2, 3, 0]]).as_euler("ZXZ")[:, 1]
        assert (theta.max() < 0.05) == stays_up
        # the roots of f(u) say the same: θ_max = arccos(u1) with u1 → a²/β − 1 for the upright top
        theta_max = TOP.turning_points([0.0, 1e-3, 0.0], [0.0, 0.0, omega3])[1]
        assert (theta_max < 0.05) == stays_up
        assert 0.95 * theta_max < theta.max() <= theta_max + 1e-9


@pytest.mark.parametrize("theta0", [0.5, 1.3])
def test_fast_top_approaches_chapter_estimates(theta0):
    errors = []
    for omega3 in (50.0, 100.0, 200.0):
        ft = TOP.fast_top(theta0, omega3)
        J3 = TOP.I3 * omega3
        assert ft.approx_precession_rate == pytest.approx(TOP.mgl / J3)
        assert ft.approx_nutation_frequency == pytest.approx(J3 / TOP.I1)
        errors.append(
            [
                abs(ft.exact_precession_rate / ft.approx_precession_rate - 1),
                abs(ft.exact_nutation_frequency / ft.approx_nutation_frequency - 1),
                abs(ft.exact_nutation_amplitude / ft.approx_nutation_amplitude - 1),
            ]
        )
    errors = np.array(errors)
    # relative errors are O(1/p), p = J3²/(2 I1 mgl): a factor 4 per doubling of the spin
    assert np.all(errors[-1] < 1e-3)
    np.testing.assert_allclose(errors[:-1] / errors[1:], 4.0, rtol=0.05)
    # exact values are those of the quadrature
    ft = TOP.fast_top(theta0, 100.0)
    u1, u2, _ = TOP.cubic_roots([0.0, theta0, 0.0], [0.0, 0.0, 100.0])
    assert ft.exact_nutation_amplitude == pytest.approx(u2 - u1)
    assert ft.exact_nutation_frequency == pytest.approx(2 * np.pi / TOP.nutation_period([0.0, theta0, 0.0], [0.0, 0.0, 100.0]))


def test_larmor_precession_is_the_fast_top_limit():
    e, m, B = 1.602176634e-19, 9.1093837139e-31, 0.7
    assert kr.larmor_precession_rate(B) == pytest.approx(e * B / (2 * m), rel=1e-15)
    # orbiting charge: μ = e ω a²/2, J = m ω a²; as a fast top mgl -> μB, I3 ω3 -> J (scaled units)
    scale_e, scale_m, a = 1.0, 1.0, 1.0
    for omega in (200.0, 400.0):
        mu, J = scale_e * omega * a**2 / 2, scale_m * omega * a**2
        top = kr.LagrangeTop(1.0 * scale_m * a**2, scale_m * a**2, mu * B)
        rate = top.fast_top(1.0, J / (scale_m * a**2)).exact_precession_rate
        assert rate == pytest.approx(kr.larmor_precession_rate(B, scale_e, scale_m), rel=2 * (mu * B) / omega**2)


def test_larmor_rate_at_extreme_fields_rounds_once_or_is_refused():
    # e B/(2m) at 1e-293 T passed through a subnormal product (e B ~ 1e-312) and lost 11 digits;
    # the rate is linear in B, so the scaled field gives the scaled rate to rounding
    field = np.array([-0.7, 0.03, 0.4])
    for scale in (1e-293, 1e-300, 1e297):
        np.testing.assert_allclose(kr.larmor_precession_rate(field * scale), kr.larmor_precession_rate(field) * scale,
                                   rtol=4e-16, atol=0)
    with pytest.raises(ValueError, match="magnetic_field, charge and mass are out of range: .* exceeds 1.8e308"):
        kr.larmor_precession_rate(field * 1e298)


def test_simulate_agrees_with_exact_solution():
    euler0, rates0 = STATES["loop"]
    t = np.linspace(0.0, 30.0, 301)
    exact = TOP.solve(t, euler0, rates0)
    sim = TOP.simulate(t, euler0, rates0, rtol=1e-13)
    np.testing.assert_allclose(sim.q, exact.q, atol=1e-9)
    np.testing.assert_allclose(sim.omega, exact.omega, atol=1e-9)
    np.testing.assert_allclose(sim.zxz_angles, exact.zxz_angles, atol=1e-9)


def test_bad_input():
    # mgl is a weight times a length: the refusal used to call it a moment of inertia
    with pytest.raises(ValueError, match=r"^mgl must be a single positive number, got -1.0$"):
        kr.LagrangeTop(1.0, 0.5, -1.0)
    with pytest.raises(ValueError, match="theta"):
        TOP.turning_points([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    with pytest.raises(ValueError, match="rates0"):
        TOP.solve([0.0], [0.0, 0.5, 0.0], [0.0, 1.0])
    with pytest.raises(ValueError, match="theta must lie"):
        TOP.effective_potential(0.0, 1.0, 1.0)


def test_turning_points_of_a_top_that_reaches_the_vertical():
    # J3 = Jz to rounding: u = 1 is nearly a root (exactly, θ_min = 4.980071096e-16 for these
    # doubles, from mpmath at 60 digits); the computed u2 used to round above 1 (θ_min = NaN)
    euler0, rates0 = [0.0, np.radians(60.0), 0.0], [1.2000000000000002, 0.0, 3.0]
    theta_min, theta_max = TOP.turning_points(euler0, rates0)
    assert theta_min == pytest.approx(4.980071096e-16, rel=1e-9)
    assert theta_max == pytest.approx(np.radians(60.0), abs=1e-15)
    assert TOP.cubic_roots(euler0, rates0)[1] == 1.0  # 1 − 1.2e-31


def _mp_cubic(top, euler0, rates0, dps):
    """a, b, β, the roots u1 <= u2 <= u3 of f(u) (mpmath's ``polyroots``), u0 and sin θ0 · θ̇0 at
    ``dps`` digits from the exact values of the doubles given (Theory §6.3)."""
    mp.mp.dps = dps
    I1, I3, mgl = (mp.mpf(x) for x in (top.I1, top.I3, top.mgl))
    theta0 = mp.mpf(euler0[1])
    phidot, thetadot, psidot = (mp.mpf(x) for x in rates0)
    u0, s = mp.cos(theta0), mp.sin(theta0)
    J3 = I3 * (u0 * phidot + psidot)
    Jz = I1 * phidot * s**2 + J3 * u0
    E = (I1 * (thetadot**2 + phidot**2 * s**2) + J3**2 / I3) / 2 + mgl * u0
    a, b = J3 / I1, Jz / I1
    alpha, beta = (2 * E - J3**2 / I3) / I1, 2 * mgl / I1
    roots = mp.polyroots([beta, -(alpha + a * a), 2 * a * b - beta, alpha - b * b], maxsteps=500, extraprec=4 * dps)
    u1, u2, u3 = sorted(mp.re(r) for r in roots)
    return a, b, beta, u1, u2, u3, u0, s * thetadot


def _theta_reference(euler0, rates0, t, dps=60):
    """θ(t) and m1 at ``dps`` digits from the exact values of the doubles given (Theory §6.3).

    The roots of f(u) by mpmath's ``polyroots``, u = u1 + (u2 − u1) sn²(λt + v0 | m) by its
    ``ellipfun`` (q-series) and ``ellipf``: nothing shared with kreisel's root finding or its
    m1-carrying elliptic functions.
    """
    a, b, beta, u1, u2, u3, u0, udot_sign = _mp_cubic(TOP, euler0, rates0, dps)
    m = (u2 - u1) / (u3 - u1)
    lam = mp.sqrt(beta * (u3 - u1)) / 2
    v0 = mp.ellipf(mp.asin(mp.sqrt(min((u0 - u1) / (u2 - u1), 1))), m)
    v0 = -v0 if udot_sign > 0 else v0  # u̇0 = −sin θ0 θ̇0
    # u may pass u2 <= 1 by a unit of the 60th digit: acos gets an imaginary part of that size
    theta = [mp.re(mp.acos(u1 + (u2 - u1) * mp.ellipfun("sn", lam * mp.mpf(x) + v0, m=m) ** 2)) for x in t]
    return np.array([float(x) for x in theta]), float(1 - m)


def _just_reaching_the_vertical(theta0, relative):
    """Rates at the lower turning point θ0 (θ̇0 = 0) for b = a, α = β (J3 = Jz, the upright's energy),
    then φ̇0 moved by ``relative``: a² = β(1 + u0), φ̇0 = a/(1 + u0), ψ̇0 = a I1/I3 − u0 φ̇0."""
    u0 = np.cos(theta0)
    a = np.sqrt(2.0 * TOP.mgl / TOP.I1 * (1.0 + u0))
    phidot = a / (1.0 + u0)
    return [0.2, theta0, -0.1], [phidot * (1.0 + relative), 0.0, a * TOP.I1 / TOP.I3 - u0 * phidot]


# next to the separatrix of the upright top (ω3 = 2 is below the sleeping-top threshold 4):
# - started ε from the vertical at rest (it falls from its upper turning point, u2 = cos ε, u3 -> 1)
#   or kicked with θ̇0 = ε (above the upright's energy, u2 -> 1): m1 ≈ 4ε²/9;
# - started at θ0 = 2 with φ̇0 a relative 4δ above or below the rate that takes it exactly to the
#   vertical: m1 ≈ 2.4δ, J3 − Jz and E − E_upright cancel to O(m1) in their O(1) terms
SEPARATRIX_CASES = {
    f"{side}-{eps:g}": ([0.2, eps, -0.1], [0.0, eps if side == "kicked" else 0.0, 2.0], m1)
    for eps, m1 in [(1.5e-5, 1e-10), (1.5e-6, 1e-12), (1.5e-7, 1e-14)]
    for side in ("rest", "kicked")
} | {
    f"reaching{sign:+d}-{m1:g}": (*_just_reaching_the_vertical(2.0, sign * 0.4 * m1), m1)
    for m1 in (1e-10, 1e-12, 1e-14)
    for sign in (1, -1)
}


@pytest.mark.filterwarnings("ignore:Descending:DeprecationWarning")  # mpmath 1.4 polyroots; asc= is not in 1.3
@pytest.mark.parametrize("label", SEPARATRIX_CASES)
def test_next_to_the_separatrix_theta_agrees_with_a_60_digit_reference(label):
    euler0, rates0, m1 = SEPARATRIX_CASES[label]
    period = TOP.nutation_period(euler0, rates0)
    t = np.linspace(0.0, 3.0 * period, 25)
    theta_ref, m1_ref = _theta_reference(euler0, rates0, t)
    assert 0.5 * m1 < m1_ref < 1.1 * m1
    tr = TOP.solve(t, euler0, rates0)
    np.testing.assert_allclose(tr.zxz_angles[:, 1], theta_ref, rtol=0.0, atol=1e-11)
    # the top swings down to θ_max and back near the vertical, three times
    assert theta_ref.max() > 1.5 and theta_ref.min() < 1e-3


@pytest.mark.parametrize("thetadot0", [0.0, 0.8, -1.5, 2.9, -3.5])
def test_planar_pendulum_swings_through_the_vertical(reference, thetadot0):
    # J3 = Jz = 0: libration through the bottom (|θ̇0| small) or circulation over the top
    euler0, rates0 = [0.4, 2.0, -0.3], [0.0, thetadot0, 0.0]
    t = np.linspace(0.0, 12.0, 121)
    tr = TOP.solve(t, euler0, rates0)
    np.testing.assert_allclose(tr.zxz_angles[0], euler0, atol=1e-15)
    np.testing.assert_allclose(tr.zxz_rates[0], rates0, atol=1e-14)
    omega_ref, q_ref = _reference_from(reference, tr, t)
    np.testing.assert_allclose(tr.omega, omega_ref, atol=1e-10)
    dq = np.minimum(np.abs(tr.q - q_ref).max(axis=1), np.abs(tr.q + q_ref).max(axis=1))
    assert dq.max() < 1e-10
    constants = TOP.constants(euler0, rates0)
    energy = 0.5 * TOP.I1 * tr.zxz_rates[:, 1] ** 2 + TOP.mgl * np.cos(tr.zxz_angles[:, 1])
    np.testing.assert_allclose(energy, constants.E, rtol=1e-13)


def test_bundled_apex_sweep_grid_has_finite_turning_points():
    # the cells of kreisel's bundled lagrange_apex sweep (φ̇ × ψ̇ at θ0 = 60°), J3 = Jz among them
    for phidot in np.linspace(-3.0, 3.0, 25):
        for psidot in np.linspace(2.0, 12.0, 11):
            theta_min, theta_max = TOP.turning_points([0.0, np.radians(60.0), 0.0], [phidot, 0.0, psidot])
            assert 0.0 <= theta_min <= theta_max <= np.pi


@pytest.mark.filterwarnings("ignore:Descending:DeprecationWarning")
def test_passing_next_to_both_verticals():
    # hardly spinning, nudged 1e-12 from the top: it falls through to within 5e-9 rad of the bottom
    # and returns within 9e-17 rad of the top (m1 = 3.75e-33, Π at n -> 1 and m -> 1 together)
    euler0, rates0 = [0.1, 1e-12, 0.2], [-1e-8, 1e-12, 1e-12]
    period = TOP.nutation_period(euler0, rates0)
    t = np.linspace(0.0, 1.2 * period, 9)
    theta_ref, m1_ref = _theta_reference(euler0, rates0, t, dps=100)
    assert 3e-33 < m1_ref < 4e-33
    tr = TOP.solve(t, euler0, rates0)
    assert np.all(np.isfinite(tr.zxz_angles)) and np.all(np.isfinite(tr.zxz_rates))
    np.testing.assert_allclose(tr.zxz_angles[:, 1], theta_ref, rtol=0.0, atol=1e-11)
    constants = TOP.constants(euler0, rates0)
    energy = 0.5 * TOP.I1 * (tr.zxz_rates[:, 1] ** 2 + (tr.zxz_rates[:, 0] * np.sin(tr.zxz_angles[:, 1])) ** 2)
    energy += constants.J3**2 / (2 * TOP.I3) + TOP.mgl * np.cos(tr.zxz_angles[:, 1])
    np.testing.assert_allclose(energy, constants.E, rtol=1e-12)


def test_refuses_what_doubles_cannot_follow():
    with pytest.raises(ValueError, match="theta >= 1e-75"):
        TOP.solve([0.0, 1.0], [0.0, 1e-80, 0.0], [0.0, 0.0, 1.0])
    # passing within ~1e-150 rad of the vertical without reaching it: φ turns by π in ~1e-150 s
    with pytest.raises(ValueError, match="passes within 1e-75 rad of the vertical"):
        TOP.solve([0.0, 1.0], [0.0, 1e-74, 0.0], [0.3, 0.1, 1.0])


def _rigid_body_reference(euler0, rates0, t, dps=30):
    """q and body ω at ``dps`` digits: mpmath's Taylor integrator (odefun) on Euler's equations with
    the gravity torque −mgl e3 × R^T ẑ and q̇ = ½ q ⊗ ω, free of the ZXZ angles' singularity.
    The initial q and ω come from the exact values of the doubles given."""
    mp.mp.dps = dps
    I1, I3, mgl = (mp.mpf(x) for x in (TOP.I1, TOP.I3, TOP.mgl))
    phi, theta, psi = (mp.mpf(x) for x in euler0)
    phidot, thetadot, psidot = (mp.mpf(x) for x in rates0)
    c, s = mp.cos(theta / 2), mp.sin(theta / 2)
    q0 = [c * mp.cos((phi + psi) / 2), s * mp.cos((phi - psi) / 2), s * mp.sin((phi - psi) / 2),
          c * mp.sin((phi + psi) / 2)]
    w0 = [phidot * mp.sin(theta) * mp.sin(psi) + thetadot * mp.cos(psi),
          phidot * mp.sin(theta) * mp.cos(psi) - thetadot * mp.sin(psi), phidot * mp.cos(theta) + psidot]

    def rhs(_, y):
        a, b, c, d, w1, w2, w3 = y
        gx, gy = 2 * (b * d - a * c), 2 * (c * d + a * b)  # R^T ẑ, transverse part
        return [(-b * w1 - c * w2 - d * w3) / 2, (a * w1 + c * w3 - d * w2) / 2, (a * w2 - b * w3 + d * w1) / 2,
                (a * w3 + b * w2 - c * w1) / 2, ((I1 - I3) * w2 * w3 + mgl * gy) / I1,
                ((I3 - I1) * w3 * w1 - mgl * gx) / I1, mp.mpf(0)]

    solution = mp.odefun(rhs, 0, q0 + w0)
    rows = np.array([[float(x) for x in solution(mp.mpf(x))] for x in t])
    return rows[:, :4], rows[:, 4:]


# the reproducers: spinning (ψ̇ = 10) and precessing (φ̇ ≠ 0) next to either vertical
NEXT_TO_A_VERTICAL = {
    "below-1e-8": ([0.0, np.pi - 1e-8, 0.0], [0.3, 0.2, 10.0]),
    "above-1e-8": ([0.0, 1e-8, 0.0], [0.3, 0.2, 10.0]),
    "below-3e-9": ([0.4, np.pi - 3e-9, -1.0], [-0.7, -0.1, 6.0]),
    "above-5e-9": ([-0.2, 5e-9, 2.0], [1.5, 0.05, -8.0]),
}


@pytest.mark.parametrize("label", NEXT_TO_A_VERTICAL)
def test_next_to_a_vertical_agrees_with_a_30_digit_reference(label):
    euler0, rates0 = NEXT_TO_A_VERTICAL[label]
    t = np.linspace(0.0, 5.0, 6)
    q_ref, omega_ref = _rigid_body_reference(euler0, rates0, t)
    tr = TOP.solve(t, euler0, rates0)
    sign = np.sign(np.sum(tr.q * q_ref, axis=1))[:, None]
    np.testing.assert_allclose(tr.q, sign * q_ref, rtol=0.0, atol=1e-12)
    np.testing.assert_allclose(tr.omega, omega_ref, rtol=0.0, atol=1e-12)
    theta_ref = 2.0 * np.arctan2(np.hypot(q_ref[:, 1], q_ref[:, 2]), np.hypot(q_ref[:, 0], q_ref[:, 3]))
    np.testing.assert_allclose(tr.zxz_angles[:, 1], theta_ref, rtol=0.0, atol=1e-12)
    # ω3 is J3/I3 itself, not a difference of rates that grow like 1/sin θ
    assert np.all(tr.omega[:, 2] == tr.omega[0, 2])


def test_refuses_phases_beyond_what_a_double_resolves():
    # issue 33: two times one ulp apart at 1e17 s gave unrelated attitudes (ψ ≈ 1e18 rad), t = 1e300 finite values
    for t in ([0.0, 1e17, np.nextafter(1e17, 2e17)], [0.0, 1e300]):
        with pytest.raises(ValueError, match=r"t, euler0 and rates0 are out of range: .* more than 1e\+15 rad"):
            TOP.solve(t, [0.0, 1.0, 0.0], [0.3, 0.2, 10.0])
    with pytest.raises(ValueError, match="more than 1e\\+15 rad"):  # the planar pendulum too
        TOP.solve([0.0, 1e300], [0.0, 2.0, 0.0], [0.0, 0.1, 0.0])
    assert np.isfinite(TOP.solve([0.0, 1e12], [0.0, 1.0, 0.0], [0.3, 0.2, 10.0]).q).all()


def test_long_sample_arrays_are_solved_in_interruptible_calls_with_the_same_bits(monkeypatch):
    # issue 33: Ctrl-C took 2.6–5 s to stop solve on 1e7 samples (one compiled call); calls of
    # SAMPLES_PER_CALL samples give Ctrl-C its chance between them and change no bit
    from kreisel.tops import lagrange

    t = np.linspace(0.0, 30.0, 1001)
    whole = TOP.solve(t, [0.3, 0.5, 0.2], [-0.6, 0.7, 10.0])
    monkeypatch.setattr(lagrange, "SAMPLES_PER_CALL", 7)
    calls = []
    compiled = lagrange._lagrange_samples
    monkeypatch.setattr(lagrange, "_lagrange_samples", lambda t, *args: calls.append(t.size) or compiled(t, *args))
    chunked = TOP.solve(t, [0.3, 0.5, 0.2], [-0.6, 0.7, 10.0])
    assert len(calls) == 143 and max(calls) == 7
    np.testing.assert_array_equal(chunked.q, whole.q)
    np.testing.assert_array_equal(chunked.omega, whole.omega)


def _nutation_reference(top, euler0, rates0, dps=60):
    """u2 − u1, ⟨φ̇⟩ and b − a u at u1, u2 at ``dps`` digits (:func:`_mp_cubic`), the mean by
    mpmath's tanh–sinh quadrature of φ̇ = (b − a u)/(1 − u²) over the nutation,
    u = u1 + (u2 − u1) sin²x, du/√f = 2 dx/√(β (u3 − u))."""
    a, b, beta, u1, u2, u3, _, _ = _mp_cubic(top, euler0, rates0, dps)

    def weight(x):
        return 1 / mp.sqrt(beta * (u3 - u1 - (u2 - u1) * mp.sin(x) ** 2))

    def rate(x):
        u = u1 + (u2 - u1) * mp.sin(x) ** 2
        return (b - a * u) / (1 - u * u) * weight(x)

    mean = mp.quad(rate, [0, mp.pi / 2]) / mp.quad(weight, [0, mp.pi / 2])
    return float(u2 - u1), float(mean), float(b - a * u1), float(b - a * u2)


# released from rest (cusp) and pushed along (φ̇0 = 3 mgl/J3: a loop), spun up to J3 = 1e8:
# the nutation (u2 − u1 ~ 2 I1 mgl sin²θ0/J3², down to 1e-16) and the precession (~ mgl/J3)
# are far below the O(1) terms they used to be differences of
FAST_TOPS = {f"{kind}-{omega3:g}": ([0.1, 0.8, -0.2], [phidot, 0.0, omega3])
             for omega3 in (2e4, 2e6, 2e8) for kind, phidot in (("cusp", 0.0), ("loop", 6.0 / omega3))}


@pytest.mark.filterwarnings("ignore:Descending:DeprecationWarning")
@pytest.mark.parametrize("label", FAST_TOPS)
def test_fast_top_keeps_the_digits_of_its_nutation_and_precession(label):
    euler0, rates0 = FAST_TOPS[label]
    amplitude, mean, g1, g2 = _nutation_reference(TOP, euler0, rates0)
    assert TOP.mean_precession_rate(euler0, rates0) == pytest.approx(mean, rel=1e-12)
    assert TOP.apex_locus_kind(euler0, rates0) == label.split("-")[0]
    assert g1 * g2 < 0.0 if label.startswith("loop") else abs(g2) < 1e-9 * abs(g1)
    # the exact solution starts from the state given, φ̇0 included (b − a u of size mgl/J3, a of size J3)
    tr = TOP.solve([0.0, 1e-9], euler0, rates0)
    np.testing.assert_allclose(tr.zxz_rates[0], rates0, rtol=1e-13, atol=1e-300)
    if label.startswith("cusp"):
        fast = TOP.fast_top(euler0[1], rates0[2])
        assert fast.exact_nutation_amplitude == pytest.approx(amplitude, rel=1e-13)
        assert fast.exact_precession_rate == pytest.approx(mean, rel=1e-12)
        assert fast.exact_precession_rate == pytest.approx(fast.approx_precession_rate, rel=10.0 / rates0[2])


def test_a_weak_top_is_solved_or_refused_by_name(recwarn):
    # mgl -> 0: u3 ~ (J3/I1)²/β passes 1e154 (mgl ~ 1e-153) and overflows near mgl ~ 1e-307
    euler0, rates0 = [0.0, 1.0, 0.0], [0.3, 0.2, 10.0]
    free = kr.LagrangeTop(1.0, 0.5, 1e-100)
    for mgl in (1e-160, 1e-250, 1e-300):
        top = kr.LagrangeTop(1.0, 0.5, mgl)
        assert top.turning_points(euler0, rates0) == pytest.approx(free.turning_points(euler0, rates0), rel=1e-15)
        assert top.nutation_period(euler0, rates0) == pytest.approx(free.nutation_period(euler0, rates0), rel=1e-15)
        assert np.isfinite(top.solve([0.0, 1.0], euler0, rates0).q).all()
    with pytest.raises(ValueError, match=r"mgl is too small .* exceeds the largest double"):
        kr.LagrangeTop(1.0, 0.5, 1e-308).solve([0.0, 1.0], euler0, rates0)
    assert not recwarn.list
