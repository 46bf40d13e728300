"""Earth examples of Theory §8.2–§8.3 against the chapter's numbers, closed forms and references."""

import warnings

import numpy as np
import mpmath as mp
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import expm

import kreisel as kr

E = kr.earth
CHAPTER_OMEGA = 7.27221e-5
HEFEI = 31.8584
HEFEI_G = 9.7947


def test_contract_constant():
    assert E.OMEGA_EARTH == 7.2921159e-5


def test_chapter_hefei_drop_analytic_and_simulated():
    analytic = E.eastward_deflection(100.0, HEFEI, g=HEFEI_G, omega=CHAPTER_OMEGA)
    east, north = E.simulate_drop(100.0, HEFEI, g=HEFEI_G, omega=CHAPTER_OMEGA)
    assert round(float(analytic), 4) == 0.0186
    assert round(float(east), 4) == 0.0186
    # east has no O(ω²) correction: only the O(ω³) remainder separates them
    assert east == pytest.approx(analytic, rel=1e-6)
    assert -1e-5 < north < 0  # second-order southward drift in the north


def test_chapter_hefei_foucault_period():
    T = float(E.foucault_period(HEFEI, omega=CHAPTER_OMEGA))
    hours, minutes = divmod(T / 60.0, 60.0)
    assert (int(hours), int(minutes)) == (45, 28)


def test_deflection_scales_as_h_to_three_halves():
    h = np.array([1.0, 4.0, 100.0, 2500.0])
    d = E.eastward_deflection(h, 40.0)
    np.testing.assert_allclose(d / d[0], h**1.5, rtol=1e-13)
    east, _ = E.simulate_drop(h[1:3], 40.0)
    np.testing.assert_allclose(east[1] / east[0], (h[2] / h[1]) ** 1.5, rtol=1e-5)


def test_poles_and_equator():
    assert E.eastward_deflection(50.0, 90.0) == 0.0
    assert E.eastward_deflection(50.0, -90.0) == 0.0
    east, north = E.simulate_drop(50.0, np.array([90.0, -90.0, 0.0]))
    assert np.all(np.abs(east[:2]) < 1e-15) and np.all(np.abs(north) < 1e-15)
    assert east[2] == pytest.approx(E.eastward_deflection(50.0, 0.0), rel=1e-6)
    sidereal_day = 2 * np.pi / E.OMEGA_EARTH
    np.testing.assert_allclose(E.foucault_period([90.0, -90.0]), sidereal_day, rtol=1e-15)
    for latitude in (0.0, -0.0, [10.0, 0.0]):
        with pytest.raises(ValueError, match=r"at the equator \(latitude 0\) the swing plane .* does not turn"):
            E.foucault_period(latitude)
    with warnings.catch_warnings():
        warnings.simplefilter("error")   # no overflow warning: a message in words instead
        with pytest.raises(ValueError, match=r"latitude 1e-310°, this close to the equator.*exceeds the largest"):
            E.foucault_period(1e-310)
        assert np.isfinite(E.foucault_period(1e-300))
    assert E.foucault_precession_rate(0.0) == 0.0


def test_hemispheres():
    e_n, n_n = E.simulate_drop(200.0, 35.0)
    e_s, n_s = E.simulate_drop(200.0, -35.0)
    assert e_n == pytest.approx(e_s, rel=1e-12) and e_n > 0
    assert n_n == pytest.approx(-n_s, rel=1e-9) and n_n < 0
    assert E.foucault_precession_rate(35.0) < 0 < E.foucault_precession_rate(-35.0)


@pytest.mark.parametrize("lat", [-60.0, 0.0, 31.8584, 75.0])
def test_drop_matches_exact_linear_solution(lat):
    # r̈ = -g z - ω×(ω×r) - 2ω×ṙ is linear: solve by the matrix exponential
    g, h, w = 9.80665, 300.0, E.angular_velocity_enu(lat)
    W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
    M = np.zeros((7, 7))
    M[:3, 3:6] = np.eye(3)
    M[3:6, :3] = -W @ W
    M[3:6, 3:6] = -2 * W
    M[5, 6] = -g
    state = lambda t: expm(M * t) @ np.array([0, 0, h, 0, 0, 0, 1.0])
    t = np.sqrt(2 * h / g)
    for _ in range(30):
        s = state(t)
        t -= s[2] / s[5]
    east, north = E.simulate_drop(h, lat, g=g)
    ref = state(t)
    assert east == pytest.approx(ref[0], rel=1e-8, abs=1e-14)
    assert north == pytest.approx(ref[1], rel=1e-6, abs=1e-14)


def test_angular_velocity_matches_enu_basis():
    lat = np.array([-70.0, -10.0, 0.0, 31.8584, 89.0])
    lon = np.array([10.0, -100.0, 0.0, 117.0, 45.0])
    M = E.enu_to_ecef_matrix(lat, lon)
    np.testing.assert_allclose(M @ np.swapaxes(M, -1, -2), np.broadcast_to(np.eye(3), M.shape), atol=1e-15)
    np.testing.assert_allclose(np.linalg.det(M), 1.0, rtol=1e-14)
    w_ecef = np.array([0.0, 0.0, E.OMEGA_EARTH])
    np.testing.assert_allclose(
        np.einsum("...ji,j->...i", M, w_ecef), E.angular_velocity_enu(lat), rtol=1e-14, atol=1e-22
    )


@pytest.mark.parametrize("speed,elev,az,lat", [(800.0, 45.0, 90.0, 45.0), (300.0, 30.0, 200.0, -30.0), (600.0, 70.0, 0.0, 10.0)])
def test_shell_deviation_against_first_order_estimate(speed, elev, az, lat):
    east, north = E.shell_deviation(speed, elev, az, lat)
    e1, n1 = E.shell_deviation_estimate(speed, elev, az, lat)
    flight = 2 * speed * np.sin(np.deg2rad(elev)) / 9.80665
    size = np.hypot(e1, n1)
    # neglected terms are O(ωT) relative to the first-order deviation
    assert np.hypot(east - e1, north - n1) < 3 * E.OMEGA_EARTH * flight * size


def test_shell_deviation_against_scipy():
    speed, elev, az, lat, g = 400.0, 50.0, 120.0, 52.0, 9.81
    w = E.angular_velocity_enu(lat)

    def rhs(t, y):
        r, v = y[:3], y[3:]
        return np.concatenate([v, [0, 0, -g] - np.cross(w, np.cross(w, r)) - 2 * np.cross(w, v)])

    ground = lambda t, y: y[2]
    ground.terminal, ground.direction = True, -1
    e, a = np.deg2rad(elev), np.deg2rad(az)
    v0 = speed * np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    sol = solve_ivp(rhs, (0, 200), np.concatenate([np.zeros(3), v0]), method="DOP853",
                    rtol=1e-12, atol=1e-12, events=ground)
    land = sol.y_events[0][0]
    reach = speed**2 * np.sin(2 * e) / g
    east, north = E.shell_deviation(speed, elev, az, lat, g=g)
    assert east == pytest.approx(land[0] - reach * np.cos(a), abs=1e-6)
    assert north == pytest.approx(land[1] - reach * np.sin(a), abs=1e-6)


@pytest.mark.parametrize("lat", [0.0, 40.0, -65.0])
def test_vertical_shot_lands_west(lat):
    # classic result: a body shot straight up lands (4/3) ω cos λ v³/g² to the west
    v, g = 100.0, 9.80665
    west = 4.0 / 3.0 * E.OMEGA_EARTH * np.cos(np.deg2rad(lat)) * v**3 / g**2
    east, north = E.shell_deviation_estimate(v, 90.0, 0.0, lat)
    assert east == pytest.approx(-west, rel=1e-12) and abs(north) < 1e-12
    east, north = E.shell_deviation(v, 90.0, 0.0, lat)
    assert east == pytest.approx(-west, rel=1e-4)


# Foucault pendulum: a 1 m pendulum (period 2 s) on a fast planet, ω = 0.02 rad/s,
# so that a few hundred swings show the precession; the chapter-scale run uses
# the real rate with a 10 m pendulum over 2 hours.
FAST = 0.02


@pytest.mark.parametrize("lat", [45.0, -45.0, 80.0, -20.0])
def test_foucault_rate_measured_in_both_hemispheres(lat):
    res = E.foucault_pendulum(1.0, lat, 300.0, 0.05, omega=FAST, azimuth_deg=30.0)
    expected = E.foucault_precession_rate(lat, omega=FAST)
    assert res.precession_rate == pytest.approx(expected, rel=0.02)
    # direction: clockwise in the north, counter-clockwise in the south
    assert np.sign(res.swing_azimuth[-1] - res.swing_azimuth[0]) == np.sign(expected)
    assert res.t[0] == 0 and res.swing_azimuth[0] == pytest.approx(np.deg2rad(30.0))
    assert np.all(np.abs(np.diff(res.swing_azimuth)) < 0.1)  # unwrapped, continuous
    assert res.jacobi[1] == pytest.approx(res.jacobi[0], rel=1e-8)


def _swing_maxima(budget, room):
    # the compiled swing of foucault_pendulum, called again and again: budgets of ``budget`` steps, a record
    # grown by ``room`` columns whenever it is full
    from kreisel._compiled import dop853
    from kreisel.earth import foucault

    lat = np.deg2rad(40.0)
    p = np.array([0.0, FAST * np.cos(lat), FAST * np.sin(lat), 9.80665, 1.0])
    runs = dop853.new_runs(np.array([[np.sin(0.05), 0.0, -np.cos(0.05), 0.0, 0.0, 0.0]]))
    record = np.empty((3, room))
    while (status := foucault._swing(p, runs, 20.0, 1e-10, np.full(6, 1e-12), 0.1, dop853.tableau(), record,
                                     budget)) == dop853.PAUSED:
        if runs.found[0] == record.shape[1]:
            record = np.concatenate([record, np.empty((3, room))], axis=1)
    assert status == dop853.OK and runs.t[0] == 20.0
    return record[:, :runs.found[0]], runs.y[0]


def test_foucault_maxima_do_not_depend_on_chunks_or_a_full_record():
    # a run paused by its budget, or before a step whose maximum finds the record full, continues bit for bit
    whole, end = _swing_maxima(2**40, 64)
    assert whole.shape[1] > 15
    for budget, room in ((1, 64), (7, 1), (2**40, 1), (3, 2)):
        maxima, y = _swing_maxima(budget, room)
        assert np.array_equal(maxima, whole) and np.array_equal(y, end)


def test_foucault_equator_does_not_precess():
    res = E.foucault_pendulum(1.0, 0.0, 200.0, 0.05, omega=FAST)
    # only Airy/anisotropy effects of O(amplitude² ω, ω²/ω0) remain
    assert abs(res.precession_rate) < 1e-3 * FAST


def test_foucault_hefei_real_rate():
    res = E.foucault_pendulum(10.0, HEFEI, 7200.0, 0.05, g=HEFEI_G, omega=CHAPTER_OMEGA)
    expected = E.foucault_precession_rate(HEFEI, omega=CHAPTER_OMEGA)
    assert res.precession_rate == pytest.approx(expected, rel=0.02)
    turn_time = 2 * np.pi / abs(res.precession_rate)
    assert turn_time == pytest.approx(float(E.foucault_period(HEFEI, omega=CHAPTER_OMEGA)), rel=0.02)


def test_foucault_period_broadcasts_and_validates():
    lat = np.array([[10.0, -10.0], [45.0, 90.0]])
    assert E.foucault_period(lat).shape == (2, 2)
    with pytest.raises(ValueError, match="latitude_deg"):
        E.foucault_period(91.0)
    with pytest.raises(ValueError, match="omega"):
        E.eastward_deflection(10.0, 10.0, omega=-1.0)
    with pytest.raises(ValueError, match="height"):
        E.simulate_drop(0.0, 10.0)
    with pytest.raises(ValueError, match="amplitude"):
        E.foucault_pendulum(1.0, 10.0, 10.0, 2.0)
    # a 1670 m pendulum (period 82 s) over 20 s reaches no excursion: it once returned a NaN precession rate
    with pytest.raises(ValueError, match=r"duration and length: in 20 s .* \(period 82 s\) reached no excursion"):
        E.foucault_pendulum(1670.0, 40.0, 20.0, 0.1)
    # 1e-158 rad ended in a ZeroDivisionError (squared excursions underflow), 1e-164 rad in a misleading refusal
    with pytest.raises(ValueError, match=r"amplitude = 1e-158 rad is out of range: below 1e-150 rad"):
        E.foucault_pendulum(1.0, 40.0, 20.0, 1e-158)
    assert E.foucault_pendulum(1.0, 40.0, 20.0, 1e-140).precession_rate == pytest.approx(
        E.foucault_pendulum(1.0, 40.0, 20.0, 1e-3).precession_rate, rel=1e-3)
    # 1e-143 m swings 1.5e73 rad in 20 s: refused before work, not a 'step fell below round-off' failure
    with pytest.raises(ValueError, match=r"length and duration are out of range: .* phase of 1.53e\+73 rad"):
        E.foucault_pendulum(1.67e-143, 40.0, 20.0, 0.1)
    with pytest.raises(ValueError, match="elevation_deg"):
        E.shell_deviation(100.0, 0.0, 0.0, 10.0)


def test_deflection_formulas_scale_without_overflow_or_refuse():
    # h √(2h/g) ∝ h^1.5 and the shell estimate's T, T², T³ terms: h³ or T³ alone overflowed where the
    # result is representable
    base = E.eastward_deflection(100.0, 31.8584)
    for scale in (1e100, 1e-100):
        assert E.eastward_deflection(100.0 * scale, 31.8584) == pytest.approx(base * scale**1.5, rel=1e-15)
    with pytest.raises(ValueError, match="height, g and omega are out of range: the deflection exceeds"):
        E.eastward_deflection(1e300, 31.8584)
    east, north = E.shell_deviation_estimate(1e102, 45.0, 30.0, 40.0)
    assert np.isfinite(east) and np.isfinite(north)
    with pytest.raises(ValueError, match="speed, g and omega are out of range: the deviation exceeds"):
        E.shell_deviation_estimate(1e200, 45.0, 30.0, 40.0)
    # the integrated deviation grows as speed² far out (a landing-time estimate squared vz from 1e154 m/s)
    near, far = np.array(E.shell_deviation(1e140, 30.0, 20.0, 40.0)), np.array(E.shell_deviation(1e150, 30.0, 20.0, 40.0))
    np.testing.assert_allclose(far / 1e300, near / 1e280, rtol=1e-8)
    with pytest.raises(ValueError, match="speed, g and omega are out of range: the range of the shell exceeds"):
        E.shell_deviation(1e202, 30.0, 20.0, 40.0)


def test_drop_from_far_out_is_scale_free():
    # far above g/ω² the drop is the inertial straight line seen from the turning Earth frame, so the
    # deviations grow as the height; from 5e149 m the integrator's error norm once overflowed its squares
    base = np.array(E.simulate_drop(5e100, 40.0)) / 5e100
    np.testing.assert_allclose(np.array(E.simulate_drop(5e149, 40.0)) / 5e149, base, rtol=1e-8)


def _closed_form_deviation(speed, elev, az, lat, g, omega):
    """The shell's deviation from the exact solution of the linear equations, at 50+ digits (mpmath).

    In the inertial frame that coincides with ENU at t = 0, ρ̈ = R(ω t) g: the part of g along the
    axis n stays, the perpendicular part turns, so ρ = v0 t + g∥ t²/2 + g⊥ (1 - cos θ)/ω²
    + n×g⊥ (θ - sin θ)/ω² with θ = ω t, and r = R(-θ) ρ. The landing is a root of r_z.
    """
    mp.mp.dps = 50 + int(-3 * mp.log10(omega * speed / g))  # (θ - sin θ) keeps its digits
    speed, elev, az, lat, g, omega = (mp.mpf(x) for x in (speed, elev, az, lat, g, omega))
    e, a, lam = mp.radians(elev), mp.radians(az), mp.radians(lat)
    n = mp.matrix([0, mp.cos(lam), mp.sin(lam)])
    v0 = speed * mp.matrix([mp.cos(e) * mp.cos(a), mp.cos(e) * mp.sin(a), mp.sin(e)])
    grav = mp.matrix([0, 0, -g])
    g_par = (grav.T * n)[0] * n
    g_perp = grav - g_par

    def cross(p, q):
        return mp.matrix([p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]])

    def position(t):
        th = omega * t
        rho = v0 * t + g_par * t**2 / 2 + g_perp * (1 - mp.cos(th)) / omega**2 + cross(n, g_perp) * (th - mp.sin(th)) / omega**2
        # Rodrigues, angle -θ about n
        return rho * mp.cos(th) - cross(n, rho) * mp.sin(th) + n * (n.T * rho)[0] * (1 - mp.cos(th))

    land = mp.findroot(lambda t: position(t)[2], 2 * v0[2] / g)
    r = position(land)
    reach = speed**2 * mp.sin(2 * e) / g
    return float(r[0] - reach * mp.cos(a)), float(r[1] - reach * mp.sin(a))


@pytest.mark.parametrize("speed,elev,az,lat,omega,rel_north", [
    (500.0, 45.0, 90.0, 45.0, E.OMEGA_EARTH, 1e-9),    # north is of third order in ω here: 1e-13 of the east
    (300.0, 30.0, 200.0, -30.0, E.OMEGA_EARTH, 1e-12),
    (100.0, 90.0, 0.0, 40.0, E.OMEGA_EARTH, 1e-12),
    (600.0, 10.0, 45.0, 60.0, 1e-9, 1e-12),         # the Earth turns 1e-10 rad: was refused
    (50.0, 60.0, 135.0, -20.0, 2e-3, 1e-12),         # a fast planet: turns 0.35 rad, O(1) corrections
])
def test_shell_deviation_against_high_precision_closed_form(speed, elev, az, lat, omega, rel_north):
    """Each component to near the integrator's tolerance of itself, however small against the range.

    The difference of two integrated ranges left 1e-16 of the range, 3e-12 m for the first case:
    1e-5 of its north deviation (-3.0e-7 m) and 1e5 times the deviations of the fourth.
    """
    east, north = E.shell_deviation(speed, elev, az, lat, omega=omega)
    ref_east, ref_north = _closed_form_deviation(speed, elev, az, lat, 9.80665, omega)
    assert east == pytest.approx(ref_east, rel=1e-12)
    assert north == pytest.approx(ref_north, rel=rel_north)


def test_shell_deviation_first_order_in_omega_and_exact_zero():
    """Against the first-order closed form as ω → 0: the remainder is of relative order ω T, down to 1e-300 rad."""
    case = (400.0, 35.0, 160.0, 50.0)
    rates = np.array([1e-4, 1e-6, 1e-8, 1e-100, 1e-290])
    east, north = E.shell_deviation(*case, omega=rates)
    e1, n1 = E.shell_deviation_estimate(*case, omega=rates)
    remainder = np.hypot(east - e1, north - n1) / np.hypot(e1, n1)
    flight = 2 * 400.0 * np.sin(np.deg2rad(35.0)) / 9.80665
    ratio = remainder / (rates * flight)
    # O(ωT) with a steady coefficient (not round-off: the old subtraction gave 1e-16 of the range / ω T)
    # and the coefficient itself converges at rate ω T
    assert 0.05 < ratio[1] < 2 and ratio[0] == pytest.approx(ratio[1], rel=1e-2) and ratio[2] == pytest.approx(ratio[1], rel=1e-4)
    assert np.all(remainder[3:] < 1e-15)
    assert E.shell_deviation(*case, omega=0.0) == (0.0, 0.0)
    with pytest.raises(ValueError, match=r"speed, elevation_deg, g and omega are out of range: the Earth turns .* rad, less "
                                         r"than 1e-300 rad, during the flight of a speed = 400 m/s shell"):
        E.shell_deviation(*case, omega=1e-305)
    # 1.6e-161 m/s once failed inside the integrator (a subnormal range): the deviation underflows to 0
    assert E.shell_deviation(1.6e-161, 45.0, 90.0, 45.0) == (0.0, 0.0)


@pytest.mark.parametrize("length, omega", [(1e300, 7.29e-5), (1e30, 7.29e-5), (1.0, 1e300), (1.0, 1e10), (1.0, 3.2)])
def test_foucault_pendulum_refuses_a_frame_turning_as_fast_as_the_swing(length, omega):
    """Huge lengths or rates gave a ZeroDivisionError or a failed integration; ω²·l >= g has no rest state.

    (1 m under 9.80665 m/s²: √(g/l) = 3.13 rad/s, so ω = 3.2 rad/s is just beyond.)
    """
    with pytest.raises(ValueError, match=r"omega and length: .* not slower than the pendulum's own frequency"):
        kr.earth.foucault_pendulum(length, 45.0, 1e16 if length == 1e30 else 100.0, 0.05, omega=omega)


def test_foucault_pendulum_just_inside_the_limit_runs():
    swing = kr.earth.foucault_pendulum(1.0, 90.0, 20.0, 0.05, omega=0.5)
    assert np.all(np.isfinite(swing.swing_azimuth)) and swing.t.size > 5


def test_foucault_period_of_a_vanishing_rate_blames_omega_not_the_latitude():
    with pytest.raises(ValueError, match=r"omega = 1e-310 rad/s: .* exceeds the largest float"):
        kr.earth.foucault_period(45.0, 1e-310)
    assert kr.earth.foucault_period(45.0, 1e300) == pytest.approx(2 * np.pi / (1e300 * np.sin(np.pi / 4)), rel=1e-15)
