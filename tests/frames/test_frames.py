"""Moving-frame mechanics (Theory §4.7, §8.1) against identities and an inertial-frame reference."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

import kreisel as kr

F = kr.frames

vec = st.lists(st.floats(-3, 3), min_size=3, max_size=3).map(np.array)


def hat(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


@settings(max_examples=60, deadline=None)
@given(vec, vec, vec, vec, vec, st.floats(0.1, 5))
def test_lagrangian_is_inertial_kinetic_energy_up_to_a_gauge(r, v, w, v0, a0, m):
    # ½m|ṙ + ω×r + v0|² = L + V + d/dt(m r·v0) + ½ m v0², with d(v0')/dt = a0 - ω×v0
    L = F.lagrangian(r, v, w, a0=a0, potential=1.5, mass=m)
    inertial = 0.5 * m * np.sum((v + np.cross(w, r) + v0) ** 2)
    gauge = m * (v @ v0 + r @ (a0 - np.cross(w, v0)))
    assert L + 1.5 + gauge + 0.5 * m * v0 @ v0 == pytest.approx(inertial, rel=1e-12, abs=1e-10)


@settings(max_examples=60, deadline=None)
@given(vec, vec, vec, vec, st.floats(0.1, 5))
def test_legendre_transform_and_hamilton_equations(r, v, w, a0, m):
    L = F.lagrangian(r, v, w, a0=a0, potential=0.7, mass=m)
    p = F.canonical_momentum(r, v, w, mass=m)
    H = F.hamiltonian(r, p, w, a0=a0, potential=0.7, mass=m)
    assert H == pytest.approx(p @ v - L, rel=1e-12, abs=1e-10)
    np.testing.assert_allclose(F.velocity_from_momentum(r, p, w, mass=m), v, atol=1e-12)
    # p = ∂L/∂ṙ and ṙ = ∂H/∂p: L and H are quadratic in ṙ, p and r, so central
    # differences are exact up to rounding
    def grad(f, x, h=1e-3):
        return np.array([(f(x + e) - f(x - e)) / (2 * h) for e in np.eye(3) * h])

    np.testing.assert_allclose(grad(lambda x: F.lagrangian(r, x, w, a0=a0, mass=m), v), p, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(grad(lambda x: F.hamiltonian(r, x, w, a0=a0, mass=m), p), v, rtol=1e-9, atol=1e-9)
    # ṗ = -∂H/∂r must equal the Lagrange equation's force: m(r̈ + ω×ṙ) for constant ω
    dHr = grad(lambda x: F.hamiltonian(x, p, w, a0=a0, mass=m), r)
    rdd = F.inertial_forces(r, v, w, a0=a0, mass=m).total / m
    np.testing.assert_allclose(-dHr, m * (rdd + np.cross(w, v)), rtol=1e-8, atol=1e-8)


def test_terms_sum_and_names():
    r, v, w, a0 = np.array([1.0, 2, 3]), np.array([0.5, -1, 2]), np.array([0.1, 0.2, 0.3]), np.array([1.0, 0, -2])
    lt = F.lagrangian_terms(r, v, w, a0=a0, potential=2.0, mass=3.0)
    assert lt.translational == pytest.approx(-3.0 * a0 @ r)
    assert sum(lt) == pytest.approx(F.lagrangian(r, v, w, a0=a0, potential=2.0, mass=3.0))
    f = F.inertial_forces(r, v, w, omega_dot=[0, 0, 1.0], a0=a0, mass=3.0)
    np.testing.assert_allclose(f.euler, -3.0 * np.cross([0, 0, 1.0], r))
    np.testing.assert_allclose(f.total, f.translational + f.coriolis + f.centrifugal + f.euler)


def _inertial_reference(t_eval, r0, v0, w0, wdot, a0, gravity, spring):
    """Integrate the frame (R, origin) and the particle in the inertial frame with scipy."""

    def rhs(t, y):
        R = y[:9].reshape(3, 3)
        xo, vo, x, v = y[9:12], y[12:15], y[15:18], y[18:21]
        w = w0 + wdot * t
        rel = R.T @ (x - xo)
        acc = R @ (gravity - spring * rel)
        return np.concatenate([(R @ hat(w)).ravel(), vo, R @ a0, v, acc])

    # inertial velocity of the particle: v = R (ṙ + ω×r) + v_origin (origin at rest initially)
    y0 = np.concatenate([np.eye(3).ravel(), np.zeros(6), r0, v0 + np.cross(w0, r0)])
    sol = solve_ivp(rhs, (t_eval[0], t_eval[-1]), y0, t_eval=t_eval, method="DOP853", rtol=1e-12, atol=1e-13)
    R = sol.y[:9].T.reshape(-1, 3, 3)
    return np.einsum("nji,nj->ni", R, sol.y[15:18].T - sol.y[9:12].T)


def test_simulation_matches_inertial_frame_integration():
    t = np.linspace(0.0, 6.0, 13)
    r0, v0 = np.array([1.0, 0.5, -0.2]), np.array([0.1, -0.4, 0.3])
    w0, wdot, a0 = np.array([0.3, -0.2, 0.9]), np.array([0.05, 0.1, -0.08]), np.array([0.2, -0.1, 0.3])
    gravity, spring = np.array([0.0, 0.0, -1.0]), 2.0
    tr = F.simulate_particle(t, r0, v0, w0, omega_dot=wdot, a0=a0, gravity=gravity, spring=spring)
    ref = _inertial_reference(t, r0, v0, w0, wdot, a0, gravity, spring)
    np.testing.assert_allclose(tr.r, ref, atol=1e-8)


def test_jacobi_integral_conserved_for_constant_rotation():
    t = np.linspace(0.0, 50.0, 201)
    tr = F.simulate_particle(t, [1.0, 0.0, 0.3], [0.0, 0.8, 0.0], [0.2, 0.1, 1.3],
                             a0=[0.3, 0.0, -0.1], gravity=[0, 0, -2.0], spring=3.0)
    H = tr.hamiltonian
    assert np.max(np.abs(H - H[0])) < 1e-9 * np.max(np.abs(tr.r)) ** 2 * 10
    # with a spinning-up frame the Hamiltonian is not conserved
    tr2 = F.simulate_particle(t, [1.0, 0.0, 0.3], [0.0, 0.8, 0.0], [0.2, 0.1, 1.3], omega_dot=[0, 0, 0.05])
    assert np.ptp(tr2.hamiltonian) > 1e-3


def test_callable_force_and_rotation_match_builtin():
    t = np.linspace(0.0, 4.0, 9)
    args = (t, [1.0, 0.2, 0.0], [0.0, -1.0, 0.3])
    built = F.simulate_particle(*args, [0.1, 0.2, 1.0], omega_dot=[0.0, 0.0, 0.1], gravity=[0, 0, -1.0], spring=2.0)

    def spring_force(tt, r, v):
        return -2.0 * 0.5 * r  # k/m = 2 with m = 0.5

    def omega(tt):
        return np.array([0.1, 0.2, 1.0 + 0.1 * tt])

    def omega_dot(tt):
        return np.array([0.0, 0.0, 0.1])

    call = F.simulate_particle(*args, omega, omega_dot=omega_dot, gravity=[0, 0, -1.0], force=spring_force, mass=0.5)
    np.testing.assert_allclose(call.r, built.r, atol=1e-9)
    np.testing.assert_allclose(call.omega, built.omega, atol=1e-15)
    with pytest.raises(ValueError, match="potential"):
        call.hamiltonian


def test_simulate_particle_validates():
    with pytest.raises(ValueError, match="increasing"):
        F.simulate_particle([0.0, 0.0], [1, 0, 0], [0, 0, 0], [0, 0, 1])
    with pytest.raises(ValueError, match="r0"):
        F.simulate_particle([0.0, 1.0], [1, 0], [0, 0, 0], [0, 0, 1])
    with pytest.raises(ValueError, match="omega_dot"):
        F.simulate_particle([0.0, 1.0], [1, 0, 0], [0, 0, 0], lambda t: np.zeros(3))
    with pytest.raises(ValueError, match="mass"):
        F.lagrangian([1, 0, 0], [0, 0, 0], [0, 0, 1], mass=0.0)


def test_callable_force_is_any_python_callable_checked_at_every_call():
    # called from the one cached compiled loop (nothing compiled per call): plain Python is fine
    t = np.linspace(0.0, 2.0, 5)
    calls = []

    def spring(tt, r, v):
        calls.append(tt)
        return -r

    python = F.simulate_particle(t, [1.0, 0.2, 0.0], [0.0, -1.0, 0.3], [0.1, 0.2, 1.0], force=spring)
    built = F.simulate_particle(t, [1.0, 0.2, 0.0], [0.0, -1.0, 0.3], [0.1, 0.2, 1.0], spring=1.0)
    assert len(calls) > 50
    np.testing.assert_allclose(python.r, built.r, atol=1e-9)
    with pytest.raises(ValueError, match=r"force callable must return shape \(3,\), got \(4,\) at t = 0\.5"):
        F.simulate_particle(t, [1.0, 0, 0], [0, 0, 0], [0, 0, 1.0],
                            force=lambda tt, r, v: np.zeros(3) if tt < 0.5 else np.zeros(4))
    with pytest.raises(ValueError, match=r"omega callable returned a non-finite value .* at t = 0\.5"):
        F.simulate_particle(t, [1.0, 0, 0], [0, 0, 0], lambda tt: np.array([0, 0, 1.0 if tt < 0.5 else np.nan]),
                            omega_dot=lambda tt: np.zeros(3), force=lambda tt, r, v: -r)


def test_lagrangian_at_extreme_magnitudes_is_exact_or_refused_as_out_of_range():
    mpmath = pytest.importorskip("mpmath")
    r, v, w = np.array([1e160, 2e160, -1e160]), np.array([3e150, -1e150, 2e150]), np.array([1e-10, 0.0, 2e-10])
    u = [mpmath.mpf(x) for x in v + np.cross(w, r)]  # ω×r is exact here (one nonzero product per entry)
    exact = float(sum(x * x for x in u) / 4)  # mass 0.5
    np.testing.assert_allclose(F.lagrangian(r, v, w, mass=0.5), exact, rtol=1e-14)
    # ṙ = −ω×r: the particle is at rest in the inertial frame, whatever the size of either term
    r, w = np.array([1e200, 0.0, 0.0]), np.array([0.0, 0.0, 1e100])
    assert F.lagrangian(r, -np.cross(w, r), w) == 0.0
    for call in (lambda: F.lagrangian([0, 0, 0], [1e200, 0, 0], [0, 0, 1]),
                 lambda: F.lagrangian_terms(r, [0, 0, 0], w),
                 lambda: F.hamiltonian([0, 0, 0], [1e200, 0, 0], [0, 0, 1])):
        with pytest.raises(ValueError, match="out of range"):
            call()


@pytest.mark.parametrize("omega, omega_dot", [([1e72, 0, 0], [0, 0, 0]), ([0, 0, 1e10], [0, 0, 0]), ([0, 0, 0], [0, 1e200, 0])])
def test_a_frame_turning_beyond_double_precision_is_refused_before_the_run(omega, omega_dot):
    # 1e10 rad/s over 1e6 s is 1e16 rad: the steps would fall below the rounding of t
    with pytest.raises(ValueError, match="omega and t are out of range.*rad"):
        F.simulate_particle([0.0, 1e6], [1.0, 0, 0], [0, 0, 0], omega, omega_dot=omega_dot)


def test_a_frame_turning_just_within_range_is_integrated():
    tr = F.simulate_particle([0.0, 1e-6], [1.0, 0, 0], [0, 0, 0], [0, 0, 1e3])
    assert np.all(np.isfinite(tr.r))


def test_inertial_forces_beyond_the_largest_double_are_refused():
    # the centrifugal force m ω × (ω × r) at |ω| = 1e155 rad/s: a refusal naming the inputs, not numpy's overflow
    with pytest.raises(ValueError, match=r"r, v, omega, omega_dot, a0 and mass are out of range: an inertial force"):
        F.inertial_forces([1.0, 0.5, 0.0], [0.0, 0.0, 0.0], [1e155, 0.0, 2e155])


@pytest.mark.parametrize("scale", [1.0, 1e148, 1e200])
def test_free_particle_far_out_in_a_rotating_frame_is_the_rotated_straight_line(scale):
    # |r0| = 1e148 m: accelerations ~1e148 against a velocity tolerance of 1e-12 once overflowed the squares
    # of the integrator's error norm ('step fell below round-off'); the exact motion is the inertial straight
    # line seen from the turning frame, R(−ω t)(r0 + (v0 + ω × r0) t)
    r0, v0, w = np.array([0.359, 1.511, -1.786]) * scale, np.array([1.687, -0.047, -0.8]), np.array([-0.8, -1.1, -0.2])
    t = np.linspace(0.0, 1.0, 5)
    traj = F.simulate_particle(t, r0, v0, w)
    inertial = r0 + np.outer(t, v0 + np.cross(w, r0))
    exact = np.array([Rotation.from_rotvec(-w * s).apply(x) for s, x in zip(t, inertial)])
    np.testing.assert_allclose(traj.r, exact, rtol=0, atol=2e-11 * np.abs(exact).max())
    assert np.all(traj.potential == 0.0)  # no field, no spring (r² of 1e200 m once made it NaN)
