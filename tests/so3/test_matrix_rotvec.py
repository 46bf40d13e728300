"""Matrices, rotation vectors and the exponential map against the chapter's explicit formulas."""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from scipy.spatial.transform import Rotation as S

import kreisel as kr


def chapter_rodrigues(psi):
    """R(ψn) = 1 cos ψ + n nᵀ (1 - cos ψ) + X_n sin ψ, Theory §2.2 (3)."""
    angle = np.linalg.norm(psi)
    n = psi / angle
    Xn = np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    return np.eye(3) * np.cos(angle) + np.outer(n, n) * (1 - np.cos(angle)) + Xn * np.sin(angle)


def chapter_quat_matrix(q):
    """R(q) as printed in Theory §2.4 (unit q)."""
    q0, q1, q2, q3 = q
    return np.array(
        [
            [q0**2 + q1**2 - q2**2 - q3**2, 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)],
            [2 * (q1 * q2 + q0 * q3), q0**2 - q1**2 + q2**2 - q3**2, 2 * (q2 * q3 - q0 * q1)],
            [2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), q0**2 - q1**2 - q2**2 + q3**2],
        ]
    )


unit_quats = arrays(np.float64, 4, elements=st.floats(-1, 1)).filter(lambda q: np.linalg.norm(q) > 0.1).map(
    lambda q: q / np.linalg.norm(q)
)
# Inside the ball |ψ| < π where log(exp(ψ)) = ψ.
rotvecs = arrays(np.float64, 3, elements=st.floats(-3.0, 3.0)).filter(lambda p: np.linalg.norm(p) < 3.1)


def test_rotvec_to_matrix_is_chapter_rodrigues(rng):
    for psi in rng.normal(size=(20, 3)) * 2:
        np.testing.assert_allclose(kr.rotvec_to_matrix(psi), chapter_rodrigues(psi), atol=2e-15)


def test_quat_to_matrix_is_chapter_formula(random_quats):
    for q in random_quats(20):
        np.testing.assert_allclose(kr.quat_to_matrix(q), chapter_quat_matrix(q), atol=1e-15)


def test_generators_and_hat_vee(rng):
    X = kr.generators()
    eps = np.zeros((3, 3, 3))
    eps[0, 1, 2] = eps[1, 2, 0] = eps[2, 0, 1] = 1
    eps[0, 2, 1] = eps[2, 1, 0] = eps[1, 0, 2] = -1
    np.testing.assert_array_equal(X, -eps)
    for j in range(3):  # [X_j, X_k] = ε_jkl X_l
        for k in range(3):
            np.testing.assert_array_equal(X[j] @ X[k] - X[k] @ X[j], np.einsum("l,lab->ab", eps[j, k], X))
    v, w = rng.normal(size=(2, 5, 3))
    np.testing.assert_allclose(np.einsum("...ij,...j->...i", kr.hat(v), w), np.cross(v, w), atol=1e-15)
    np.testing.assert_array_equal(kr.vee(kr.hat(v)), v)


def test_exp_is_matrix_exponential_of_generators(rng):
    from scipy.linalg import expm

    for psi in rng.normal(size=(5, 3)):
        np.testing.assert_allclose(kr.rotvec_to_matrix(psi), expm(np.einsum("j,jkl->kl", psi, kr.generators())), atol=1e-14)


def test_double_cover_and_full_turn():
    q = kr.rotvec_to_quat([0.0, 2 * np.pi, 0.0])
    np.testing.assert_allclose(q, [-1.0, 0, 0, 0], atol=1e-15)
    np.testing.assert_allclose(kr.rotvec_to_matrix([0, 0, 2 * np.pi]), np.eye(3), atol=1e-15)
    np.testing.assert_allclose(kr.rotvec_to_quat([4 * np.pi, 0, 0]), [1.0, 0, 0, 0], atol=1e-15)


@settings(max_examples=200, deadline=None)
@given(unit_quats, unit_quats)
def test_homomorphism(p, q):
    """R(pq) = R(p) R(q), Theory §2.4."""
    np.testing.assert_allclose(
        kr.quat_to_matrix(kr.quat_multiply(p, q)), kr.quat_to_matrix(p) @ kr.quat_to_matrix(q), atol=2e-15
    )
    np.testing.assert_allclose(kr.quat_to_matrix(-q), kr.quat_to_matrix(q), atol=0)


@settings(max_examples=200, deadline=None)
@given(unit_quats)
def test_matrix_quat_round_trip(q):
    back = kr.matrix_to_quat(kr.quat_to_matrix(q))
    assert back[0] >= 0
    assert min(np.abs(back - q).max(), np.abs(back + q).max()) < 2e-15
    np.testing.assert_allclose(kr.quat_to_matrix(back), kr.quat_to_matrix(q), atol=2e-15)


@settings(max_examples=200, deadline=None)
@given(rotvecs)
def test_exp_log_round_trip(psi):
    np.testing.assert_allclose(kr.matrix_to_rotvec(kr.rotvec_to_matrix(psi)), psi, atol=4e-15)
    np.testing.assert_allclose(kr.quat_to_rotvec(kr.rotvec_to_quat(psi)), psi, atol=4e-15)


def test_log_matches_scipy(random_quats):
    q = random_quats(500)
    R = kr.quat_to_matrix(q)
    np.testing.assert_allclose(kr.matrix_to_rotvec(R), S.from_matrix(R).as_rotvec(), atol=2e-15)


@pytest.mark.parametrize("angle", [1e-300, 1e-20, 1e-12, 1e-8, 1e-5, 1e-3])
def test_exp_log_relative_accuracy_near_zero(angle):
    n = np.array([2.0, -3.0, 6.0]) / 7.0
    psi = angle * n
    q = kr.rotvec_to_quat(psi)
    np.testing.assert_allclose(q[1:], n * np.sin(angle / 2), rtol=1e-15)
    np.testing.assert_allclose(kr.quat_to_rotvec(q), psi, rtol=1e-15)
    np.testing.assert_allclose(kr.matrix_to_rotvec(kr.rotvec_to_matrix(psi)), psi, rtol=2e-10 if angle < 1e-8 else 1e-9)


@pytest.mark.parametrize("delta", [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3])
def test_log_near_pi_keeps_all_digits(delta):
    """arccos((tr R - 1)/2) loses half the digits near π; Shepperd + atan2 does not."""
    n = np.array([2.0, -3.0, 6.0]) / 7.0
    angle = np.pi - delta
    R = chapter_rodrigues(angle * n)
    psi = kr.matrix_to_rotvec(R)
    err = min(np.linalg.norm(psi - angle * n), np.linalg.norm(psi + angle * n))
    assert err < 2e-15
    assert np.linalg.norm(psi) <= np.pi * (1 + 2e-16)


def test_nearly_orthogonal_is_projected_far_is_refused(random_quats):
    R = kr.quat_to_matrix(random_quats(4))
    noisy = R + 1e-8 * np.array([[1.0, -2, 0.5], [0.3, 0.1, -1], [2, 0, 1]])
    q = kr.matrix_to_quat(noisy)
    np.testing.assert_allclose(kr.quat_to_matrix(q), kr.orthonormalize(noisy), atol=1e-15)
    np.testing.assert_allclose(kr.quat_to_matrix(q), R, atol=1e-7)
    with pytest.raises(ValueError, match="R must be rotation matrices"):
        kr.matrix_to_quat(R + 1e-3)
    with pytest.raises(ValueError, match="det > 0"):
        kr.matrix_to_rotvec(-np.eye(3))
    with pytest.raises(ValueError, match="finite"):
        kr.matrix_to_quat(np.full((3, 3), np.nan))
    with pytest.raises(ValueError, match=r"\(\.\.\., 3, 3\)"):
        kr.matrix_to_quat(np.eye(4))


def test_orthonormalize_is_nearest_rotation(rng):
    M = np.eye(3) + 0.1 * rng.normal(size=(3, 3))
    R = kr.orthonormalize(M)
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-15)
    assert np.linalg.det(R) > 0
    # Nearest: no random rotation does better in the Frobenius norm.
    others = kr.quat_to_matrix(kr.quat_multiply(kr.matrix_to_quat(R), kr.rotvec_to_quat(1e-3 * rng.normal(size=(200, 3)))))
    assert np.all(np.linalg.norm(others - M, axis=(-2, -1)) >= np.linalg.norm(R - M))
    with pytest.raises(ValueError, match="full rank"):
        kr.orthonormalize(np.zeros((3, 3)))


def test_adjoint_identity(rng, random_quats):
    """Q R(ψn) Qᵀ = R(ψ Q n), Theory §2.2 (5)."""
    Q = kr.quat_to_matrix(random_quats(30))
    psi = rng.normal(size=(30, 3))
    lhs = Q @ kr.rotvec_to_matrix(psi) @ np.swapaxes(Q, -1, -2)
    np.testing.assert_allclose(kr.rotvec_to_matrix(kr.adjoint_action(Q, psi)), lhs, atol=3e-15)
    np.testing.assert_allclose(Q @ kr.hat(psi) @ np.swapaxes(Q, -1, -2), kr.hat(kr.adjoint_action(Q, psi)), atol=1e-14)


def test_compose_rotvec_is_exact(rng):
    a, b = rng.normal(size=(2, 50, 3))
    np.testing.assert_allclose(
        kr.rotvec_to_matrix(kr.compose_rotvec(a, b)), kr.rotvec_to_matrix(a) @ kr.rotvec_to_matrix(b), atol=3e-15
    )
    assert np.all(np.linalg.norm(kr.compose_rotvec(a, b), axis=-1) <= np.pi)


@pytest.mark.parametrize("order", [1, 2, 3, 4, 5, 6])
def test_bch_error_scales_with_order(rng, order):
    """The truncated series errs by O(ε^(order+1)): halving ε divides the error by 2^(order+1)."""
    a, b = rng.normal(size=(2, 3))
    errors = []
    for eps in (0.1, 0.05):
        exact = kr.compose_rotvec(eps * a, eps * b)
        errors.append(np.linalg.norm(kr.bch(eps * a, eps * b, order=order) - exact))
    assert errors[1] < 1e-2
    assert errors[0] / errors[1] == pytest.approx(2.0 ** (order + 1), rel=0.2)


def test_bch_low_orders_are_chapter_formula(rng):
    a, b = rng.normal(size=(2, 3))
    c = np.cross(a, b)
    np.testing.assert_allclose(kr.bch(a, b, order=3), a + b + c / 2 + np.cross(a - b, c) / 12, atol=1e-15)
    with pytest.raises(ValueError, match="order"):
        kr.bch(a, b, order=0)


@pytest.mark.parametrize("name", ["a", "b"])
def test_bch_refuses_rotation_vectors_beyond_rotvec_range(name):
    """Like every rotation-vector entry point, bch refuses |ψ| > 1e8 rad, naming the argument, before work.

    At 1e155 the series' cubic terms would overflow; just past 1e8 the terms are finite but noise.
    """
    ok = np.array([0.1, -0.2, 0.3])
    for length in (1.01e8, 1e155):
        long = length * np.array([0.6, 0.0, 0.8])
        args = {"a": ok, "b": ok, name: long}
        with pytest.raises(ValueError, match=rf"^{name} is out of range: \|psi\| = .* exceeds 1e\+08 rad"):
            kr.bch(args["a"], args["b"])
    np.testing.assert_allclose(kr.bch(1e8 * np.array([0.6, 0.0, 0.8]), np.zeros(3)), [6e7, 0.0, 8e7])



def test_bch_fourth_order_and_high_orders_converge(rng):
    """Degree 4 is the known -[b, [a, [a, b]]]/24; at order 30 the series is the exact composition."""
    a, b = 0.3 * rng.normal(size=(2, 3))
    ab = np.cross(a, b)
    fourth = a + b + ab / 2 + (np.cross(a, ab) + np.cross(b, -ab)) / 12 - np.cross(b, np.cross(a, ab)) / 24
    np.testing.assert_allclose(kr.bch(a, b, order=4), fourth, atol=1e-16)
    u, v = rng.normal(size=(2, 20, 3))
    u *= 0.4 / np.linalg.norm(u, axis=-1, keepdims=True)
    v *= 0.4 / np.linalg.norm(v, axis=-1, keepdims=True)
    np.testing.assert_allclose(kr.bch(u, v, order=30), kr.compose_rotvec(u, v), atol=1e-15)


def test_bch_high_orders_finite_or_refused_before_work(rng):
    """From 1e-300 to 5e7 rad, every order gives finite numbers without warnings or is refused, naming order.

    Order 40 at 1e8 rad once overflowed (terms of (2e8)^40) and order 30 took minutes (2^29 splittings).
    """
    u, v = rng.normal(size=(2, 4, 3))
    u /= np.linalg.norm(u, axis=-1, keepdims=True)
    v /= np.linalg.norm(v, axis=-1, keepdims=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for length in (1e-300, 1e-100, 1e-8, 1.0, 1e4, 5e7):
            for order in (1, 2, 7, 20) + ((36,) if length in (1e-300, 5e7) else ()):
                assert np.all(np.isfinite(kr.bch(length * u, length * v, order=order)))
        with pytest.raises(ValueError, match=r"^a, b and order are out of range: with \|a\| \+ \|b\| = 1e\+08 rad .* "
                                             r"lower the order to 36 or less"):
            kr.bch(5e7 * u, 5e7 * v, order=37)
    for order in (0, 41, True, 3.0):
        with pytest.raises(ValueError, match=r"order must be an integer in \[1, 40\]"):
            kr.bch(u, v, order=order)


def test_axis_angle(rng):
    psi = rng.normal(size=(10, 3))
    axis, angle = kr.rotvec_to_axis_angle(psi)
    np.testing.assert_allclose(np.linalg.norm(axis, axis=-1), 1.0)
    np.testing.assert_allclose(kr.axis_angle_to_rotvec(3 * axis, angle), psi, atol=1e-15)
    axis0, angle0 = kr.rotvec_to_axis_angle([0.0, 0, 0])
    assert angle0 == 0 and np.array_equal(axis0, [0, 0, 1])
    with pytest.raises(ValueError, match="axis must be nonzero"):
        kr.axis_angle_to_rotvec([0.0, 0, 0], 1.0)


def test_adjoint_action_does_not_depend_on_the_memory_layout(random_quats, rng):
    """A strided Q gave other last bits in two of three cases (einsum's summation order)."""
    Q = kr.quat_to_matrix(random_quats(200))
    psi = rng.normal(size=(200, 3))
    strided = np.repeat(Q, 2, axis=-1)[..., ::2]
    np.testing.assert_array_equal(kr.so3.adjoint_action(strided, psi), kr.so3.adjoint_action(Q, psi))
    np.testing.assert_array_equal(kr.so3.adjoint_action(Q, np.repeat(psi, 2, axis=-1)[..., ::2]), kr.so3.adjoint_action(Q, psi))
