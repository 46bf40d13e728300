"""Point velocity and acceleration, relative derivative, five-term acceleration (Theory §3.7, §3.9, §4.6–7)."""

import numpy as np
import pytest

import kreisel as kr
from kreisel.kinematics import (
    five_term_acceleration,
    point_acceleration,
    point_velocity,
    relative_derivative,
    three_term_velocity,
)


def _reference_point(t):
    return np.array([np.cos(t), 0.5 * t * t, np.sin(2 * t)])


def _body_point(t):
    """r′_CP(t): a point moving on the body (constant for a body-fixed point)."""
    return np.array([0.3 + 0.2 * t, -0.4 * t * t, 0.1 + np.sin(t)])


def test_body_fixed_point(path, ref):
    r_body = np.array([0.3, -0.7, 0.5])

    def position(t):
        return _reference_point(t) + path.R(t) @ r_body

    for t in [0.2, 0.7]:
        r = path.R(t) @ r_body
        v_c = ref.derivative(_reference_point, t)
        a_c = ref.second_derivative(_reference_point, t)
        np.testing.assert_allclose(point_velocity(path.omega(t), r, v_c), ref.derivative(position, t), atol=1e-12)
        np.testing.assert_allclose(
            point_acceleration(path.omega(t), path.epsilon(t), r, a_c), ref.second_derivative(position, t), atol=1e-10
        )
        # the same formulas hold with all vectors in body components
        Rt = path.R(t).T
        np.testing.assert_allclose(
            point_velocity(path.omega_body(t), r_body, Rt @ v_c), Rt @ ref.derivative(position, t), atol=1e-12
        )


def test_relative_derivative(path, ref):
    """B′ = dA′/dt + ω′ × A′ for A = R A′ (Theory §4.6)."""

    def A_space(t):
        return path.R(t) @ _body_point(t)

    t = 0.6
    got = relative_derivative(path.omega_body(t), _body_point(t), ref.derivative(_body_point, t))
    np.testing.assert_allclose(got, path.R(t).T @ ref.derivative(A_space, t), atol=1e-12)


def test_moving_point_velocity_and_five_terms(path, ref):
    """A point moving on a moving body: the named terms against the definitions and differences of r_P(t)."""

    def position(t):
        return _reference_point(t) + path.R(t) @ _body_point(t)

    t = 0.45
    R = path.R(t)
    r = R @ _body_point(t)
    v_rel = R @ ref.derivative(_body_point, t)  # v_CP = R dr′/dt, not dr_CP/dt
    a_rel = R @ ref.second_derivative(_body_point, t)
    omega, eps = path.omega(t), path.epsilon(t)
    v = three_term_velocity(omega, r, v_rel, ref.derivative(_reference_point, t))
    np.testing.assert_allclose(v.total, ref.derivative(position, t), atol=1e-12)
    np.testing.assert_allclose(v.rotational, np.cross(omega, r), atol=1e-15)
    np.testing.assert_allclose(v.relative, v_rel, atol=0)

    a_c = ref.second_derivative(_reference_point, t)
    terms = five_term_acceleration(omega, eps, r, v_rel, a_rel, a_c)
    assert terms._fields == ("translational", "tangential", "centripetal", "relative", "coriolis")
    np.testing.assert_allclose(terms.total, ref.second_derivative(position, t), atol=1e-10)
    np.testing.assert_allclose(terms.coriolis, 2 * np.cross(omega, v_rel), atol=1e-15)
    np.testing.assert_allclose(terms.centripetal, np.cross(omega, np.cross(omega, r)), atol=1e-15)
    np.testing.assert_allclose(terms.tangential, np.cross(eps, r), atol=1e-15)
    # body components: Theory §4.7 derives the same five terms with primes
    Rt = R.T
    body = five_term_acceleration(
        path.omega_body(t), path.epsilon_body(t), _body_point(t), Rt @ v_rel, Rt @ a_rel, Rt @ a_c
    )
    for got, want in zip(body, terms):
        np.testing.assert_allclose(got, Rt @ want, atol=1e-13)


def test_coriolis_bead_on_a_turntable():
    """A bead sliding radially at speed u on a disc turning at Ω: Coriolis 2Ωu sideways, centripetal Ω² r inwards."""
    omega, u, r = 3.0, 0.5, 0.2
    terms = five_term_acceleration([0, 0, omega], [0, 0, 0], [r, 0, 0], [u, 0, 0], [0, 0, 0])
    np.testing.assert_allclose(terms.coriolis, [0, 2 * omega * u, 0])
    np.testing.assert_allclose(terms.centripetal, [-(omega**2) * r, 0, 0])
    np.testing.assert_allclose(terms.total, [-(omega**2) * r, 2 * omega * u, 0])


def test_batches_and_bad_input():
    omega = np.random.default_rng(0).normal(size=(4, 1, 3))
    r = np.random.default_rng(1).normal(size=(5, 3))
    assert point_velocity(omega, r).shape == (4, 5, 3)
    terms = five_term_acceleration(omega, 0 * omega, r, 0.0, 0.0)
    assert all(x.shape == (4, 5, 3) for x in terms)
    terms.coriolis[0, 0, 0] = 1.0  # results are writable arrays, not broadcast views
    with pytest.raises(ValueError, match="omega and r"):
        point_velocity(np.ones((2, 3)), np.ones((3, 3)))
    with pytest.raises(ValueError, match="relative_rate"):
        relative_derivative([0, 0, 1.0], [1.0, 0, 0], [1.0, 0])


def test_five_terms_against_a_differentiated_platform_motion():
    # a point moving on a rotating, accelerating platform; absolute position
    # x(t) = x_C(t) + R(t) r'(t) differentiated by complex-free finite parts analytically
    t = 0.7
    phi, dphi, ddphi = 0.3 * t**2, 0.6 * t, 0.6  # rotation about z
    c, s = np.cos(phi), np.sin(phi)
    R = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    rp, vp, ap = np.array([1 + t**2, t, 0.5]), np.array([2 * t, 1, 0.0]), np.array([2.0, 0, 0])
    aC = np.array([0.0, -1.0, 0.4])
    w, eps = np.array([0, 0, dphi]), np.array([0, 0, ddphi])
    terms = five_term_acceleration(w, eps, R @ rp, R @ vp, R @ ap, aC)
    # reference: second derivative of R(t) r'(t) by the product rule
    W = kr.hat(w)
    Rd, Rdd = W @ R, (kr.hat(eps) + W @ W) @ R
    ref = aC + Rdd @ rp + 2 * Rd @ vp + R @ ap
    np.testing.assert_allclose(terms.total, ref, rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(three_term_velocity(w, R @ rp, R @ vp).total, Rd @ rp + R @ vp, atol=1e-14)


def test_accelerations_beyond_the_largest_double_are_refused_naming_the_arguments():
    # ω × (ω × r) at |ω| = 1e155 is ~1e310: once numpy's overflow warning and inf, now a clear refusal
    omega, r = np.array([1e155, 2e155, -1e155]), np.array([0.3, -1.0, 2.0])
    for call in (lambda: point_acceleration(omega, np.zeros(3), r),
                 lambda: five_term_acceleration(omega, np.zeros(3), r, np.zeros(3), np.zeros(3))):
        with pytest.raises(ValueError, match=r"omega, epsilon, r, .* are out of range: the acceleration exceeds"):
            call()
    with pytest.raises(ValueError, match="omega, r, relative_velocity and reference_velocity are out of range"):
        point_velocity(omega * 1e150, r * 1e10)
    # one below, where the answer is representable, the result is exact to rounding
    scaled = point_acceleration(omega * 1e-3, np.zeros(3), r)
    np.testing.assert_allclose(scaled, point_acceleration(omega / 1e155, np.zeros(3), r) * 1e304, rtol=1e-15)
