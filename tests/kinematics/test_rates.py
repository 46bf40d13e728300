"""Angular velocity from R and Ṙ, and quaternion kinematics (Theory §3.1, §3.3)."""

import numpy as np
import pytest

import kreisel as kr

TIMES = [0.0, 0.35, 0.9]


@pytest.mark.parametrize("t", TIMES)
def test_angular_velocity_from_matrix_matches_closed_form(path, t):
    R, Rd = path.R(t), path.Rdot(t)
    np.testing.assert_allclose(kr.angular_velocity(R, Rd), path.omega(t), rtol=0, atol=1e-15)
    np.testing.assert_allclose(kr.angular_velocity(R, Rd, frame="body"), path.omega_body(t), rtol=0, atol=1e-15)


def test_angular_velocity_from_finite_differences_and_batches(path, ref):
    t = np.array([0.1, 0.5, 0.8])
    R = np.stack([path.R(s) for s in t])
    Rd = np.stack([ref.derivative(path.R, s) for s in t])
    expected = np.stack([path.omega(s) for s in t])
    np.testing.assert_allclose(kr.angular_velocity(R, Rd), expected, rtol=0, atol=1e-13)
    # broadcasting: one R against a stack of Rdot
    assert kr.angular_velocity(R[0], Rd[:, None]).shape == (3, 1, 3)


@pytest.mark.parametrize("t", TIMES)
@pytest.mark.parametrize("frame", ["space", "body"])
def test_quaternion_rates_against_finite_differences(path, ref, t, frame):
    q = path.quat(t)
    qdot = ref.derivative(path.quat, t)
    omega = path.omega(t) if frame == "space" else path.omega_body(t)
    np.testing.assert_allclose(kr.quat_rate(q, omega, frame=frame), qdot, rtol=0, atol=1e-13)
    np.testing.assert_allclose(kr.angular_velocity_from_quat_rate(q, qdot, frame=frame), omega, rtol=0, atol=1e-13)


def test_quaternion_rate_chapter_products():
    """q̇ = ½ ω q (space) and ½ q ω′ (body) as Hamilton products (Theory §3.3)."""
    rng = np.random.default_rng(1)
    q = kr.quat_normalize(rng.normal(size=(50, 4)))
    w = rng.normal(size=(50, 3))
    pure = np.concatenate([np.zeros((50, 1)), w], axis=1)
    np.testing.assert_allclose(kr.quat_rate(q, w), 0.5 * kr.quat_multiply(pure, q), atol=1e-15)
    np.testing.assert_allclose(kr.quat_rate(q, w, frame="body"), 0.5 * kr.quat_multiply(q, pure), atol=1e-15)
    # ω = 2 q̇ q*, ω′ = 2 q* q̇ (vector parts) and the rate preserves |q|
    qd = kr.quat_rate(q, w)
    np.testing.assert_allclose(2 * kr.quat_multiply(qd, kr.quat_conjugate(q))[:, 1:], w, atol=1e-14)
    np.testing.assert_allclose(np.einsum("ij,ij->i", q, qd), 0.0, atol=1e-15)
    w_body = kr.quat_apply(q, w, inverse=True)
    np.testing.assert_allclose(kr.quat_rate(q, w_body, frame="body"), qd, atol=1e-14)


def test_non_unit_quaternion_gives_the_rotation_angular_velocity(path, ref):
    """q(t) = s(t) u(t) with a varying scale describes the same rotation, hence the same ω."""
    t = 0.6

    def scaled(s):
        return (2.0 + np.sin(3 * s)) * path.quat(s)

    omega = kr.angular_velocity_from_quat_rate(scaled(t), ref.derivative(scaled, t))
    np.testing.assert_allclose(omega, path.omega(t), atol=1e-13)


def test_bad_input():
    with pytest.raises(ValueError, match="frame"):
        kr.quat_rate([1.0, 0, 0, 0], [0, 0, 1.0], frame="inertial")
    with pytest.raises(ValueError, match="omega"):
        kr.quat_rate([1.0, 0, 0, 0], [0, 1.0])
    with pytest.raises(ValueError, match="q and omega"):
        kr.quat_rate(np.ones((2, 4)), np.ones((3, 3)))
    with pytest.raises(ValueError, match="q must be nonzero"):
        kr.angular_velocity_from_quat_rate([0.0, 0, 0, 0], [0.0, 0, 0, 1])
    with pytest.raises(ValueError, match="Rdot"):
        kr.angular_velocity(np.eye(3), np.zeros((3, 2)))
    with pytest.raises(ValueError, match="R and Rdot"):
        kr.angular_velocity(np.stack([np.eye(3)] * 2), np.zeros((3, 3, 3)))
    with pytest.raises(ValueError, match="finite"):
        kr.quat_rate([1.0, 0, 0, 0], [np.nan, 0, 1.0])


def test_angular_velocity_and_acceleration_refuse_matrices_that_are_not_rotations():
    # 2·1 gave 2ω and a reflection −ω before
    R = kr.quat_to_matrix([0.9, 0.1, -0.3, 0.2])
    Rdot = kr.hat([0.1, 0.2, 0.3]) @ R
    for bad, match in [(2 * R, r"max \|R\^T R - 1\|"), (-R, "det > 0"), (R @ np.diag([1, 1, -1]), "det > 0")]:
        with pytest.raises(ValueError, match=match):
            kr.angular_velocity(bad, Rdot)
        with pytest.raises(ValueError, match=match):
            kr.angular_acceleration(bad, Rdot, Rdot)
    np.testing.assert_allclose(kr.angular_velocity(R, Rdot), [0.1, 0.2, 0.3], atol=1e-15)


@pytest.mark.parametrize("frame", ["space", "body"])
def test_angular_velocity_from_quat_rate_of_any_size(frame):
    """ω = 2 vec(q̇ q⁻¹) scales as |q̇|/|q|: exact powers of ten from 1e-300 to 1e300 in either
    argument, with |q|² never formed (it over- or underflowed beyond 1e±154); an ω beyond the
    float range is refused as out of range."""
    q = np.array([0.5, 0.5, -0.5, 0.5]) * 1.3
    qdot = np.array([0.1, -0.3, 0.2, 0.4])
    base = kr.angular_velocity_from_quat_rate(q, qdot, frame=frame)
    for exponent in (-300, -200, -154, -100, 100, 154, 200, 300):
        s = 10.0**exponent
        np.testing.assert_allclose(kr.angular_velocity_from_quat_rate(s * q, s * qdot, frame=frame), base, rtol=1e-14)
        np.testing.assert_allclose(kr.angular_velocity_from_quat_rate(q, s * qdot, frame=frame), s * base, rtol=1e-14)
        np.testing.assert_allclose(kr.angular_velocity_from_quat_rate(s * q, qdot, frame=frame), base / s, rtol=1e-14)
    with pytest.raises(ValueError, match="q and qdot are out of range"):
        kr.angular_velocity_from_quat_rate(1e-316 * q, qdot, frame=frame)
