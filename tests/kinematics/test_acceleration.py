"""Angular acceleration from second derivatives of every parameterisation (Theory §3.9)."""

import itertools

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as ScipyRotation

import kreisel as kr
from kreisel.kinematics import (
    angular_acceleration,
    angular_acceleration_from_euler,
    angular_acceleration_from_quat,
    angular_acceleration_from_rotvec,
)

_UPPER = ["".join(s) for s in itertools.product("XYZ", repeat=3) if s[0] != s[1] and s[1] != s[2]]
SEQUENCES = _UPPER + [s.lower() for s in _UPPER]


def _expected(path, t, frame):
    return path.epsilon(t) if frame == "space" else path.epsilon_body(t)


@pytest.mark.parametrize("frame", ["space", "body"])
@pytest.mark.parametrize("t", [0.0, 0.4, 0.9])
def test_from_matrix_closed_form(path, t, frame):
    eps = angular_acceleration(path.R(t), path.Rdot(t), path.Rddot(t), frame=frame)
    np.testing.assert_allclose(eps, _expected(path, t, frame), atol=1e-14)


@pytest.mark.parametrize("frame", ["space", "body"])
def test_body_acceleration_is_the_derivative_of_body_omega(path, ref, frame):
    t = 0.55
    eps_body = angular_acceleration(path.R(t), path.Rdot(t), path.Rddot(t), frame="body")
    np.testing.assert_allclose(eps_body, ref.derivative(path.omega_body, t), atol=1e-12)


@pytest.mark.parametrize("frame", ["space", "body"])
@pytest.mark.parametrize("t", [0.3, 0.8])
def test_from_quaternion(path, ref, t, frame):
    def scaled(s):  # a non-unit quaternion path describes the same rotation
        return (1.5 + 0.5 * np.cos(2 * s)) * path.quat(s)

    for q in (path.quat, scaled):
        eps = angular_acceleration_from_quat(q(t), ref.derivative(q, t), ref.second_derivative(q, t), frame=frame)
        np.testing.assert_allclose(eps, _expected(path, t, frame), atol=1e-10)


@pytest.mark.parametrize("frame", ["space", "body"])
@pytest.mark.parametrize("t", [0.3, 0.8])
def test_from_rotvec_along_paths(path, ref, t, frame):
    psi = path.rotvec
    eps = angular_acceleration_from_rotvec(psi(t), ref.derivative(psi, t), ref.second_derivative(psi, t), frame=frame)
    np.testing.assert_allclose(eps, _expected(path, t, frame), atol=1e-10)


@pytest.mark.parametrize("frame", ["space", "body"])
def test_from_rotvec_large_angles_and_exact_rates(ref, frame):
    """ψ(t) polynomial through |ψ| = π (exact ψ̇, ψ̈) against second differences of R(t)."""

    def psi(t):
        return np.array([1.0 + 2.0 * t, -0.5 + t * t, 1.5 * t - 0.3 * t**3])

    def R(t):
        return ScipyRotation.from_rotvec(psi(t)).as_matrix()

    for t in [0.0, 0.5, 1.0, 1.5]:
        psidot = np.array([2.0, 2 * t, 1.5 - 0.9 * t * t])
        psiddot = np.array([0.0, 2.0, -1.8 * t])
        want = angular_acceleration(R(t), ref.derivative(R, t), ref.second_derivative(R, t), frame=frame)
        got = angular_acceleration_from_rotvec(psi(t), psidot, psiddot, frame=frame)
        np.testing.assert_allclose(got, want, atol=1e-9)


def test_from_rotvec_small_angles_accurate():
    """Near ψ = 0 the coefficient slopes come from their series: compare with a path through 0."""
    a = np.array([0.3, -0.2, 0.5])
    b = np.array([0.1, 0.4, -0.3])
    for t in [1e-9, 1e-5, 1e-3, 0.3]:
        # ψ(t) = t a + t² b, exact derivatives; ω is smooth so ε is close to its t → 0 limit 2b + …
        psi, psidot, psiddot = t * a + t * t * b, a + 2 * t * b, 2 * b
        got = angular_acceleration_from_rotvec(psi, psidot, psiddot)
        # reference: central difference of the dexp map evaluated with exact rates
        h = 1e-4
        w = lambda s: kr.angular_velocity_from_rotvec_rate(s * a + s * s * b, a + 2 * s * b)  # noqa: E731
        fd = (8 * (w(t + h) - w(t - h)) - (w(t + 2 * h) - w(t - 2 * h))) / (12 * h)
        np.testing.assert_allclose(got, fd, atol=1e-10)


@pytest.mark.parametrize("seq", SEQUENCES)
def test_from_euler_all_conventions(ref, seq):
    def angles(t):
        return np.array([0.4 + 1.3 * t - 0.2 * t * t, 0.6 + 0.5 * t + 0.3 * t**3, -1.0 + 0.8 * t + 0.5 * t * t])

    def R(t):
        return ScipyRotation.from_euler(seq, angles(t)).as_matrix()

    t = 0.35
    rates = np.array([1.3 - 0.4 * t, 0.5 + 0.9 * t * t, 0.8 + 1.0 * t])
    accelerations = np.array([-0.4, 1.8 * t, 1.0])
    for frame in ["space", "body"]:
        want = angular_acceleration(R(t), ref.derivative(R, t), ref.second_derivative(R, t), frame=frame)
        got = angular_acceleration_from_euler(seq, angles(t), rates, accelerations, frame=frame)
        np.testing.assert_allclose(got, want, atol=1e-9)


def test_from_euler_degrees_and_batches():
    angles = np.array([[30.0, 50.0, 10.0], [5.0, 80.0, -40.0]])
    rates = np.array([10.0, 20.0, -30.0])
    acc = np.array([1.0, -2.0, 3.0])
    got = angular_acceleration_from_euler("ZXZ", angles, rates, acc, degrees=True)
    want = angular_acceleration_from_euler("ZXZ", np.radians(angles), np.radians(rates), np.radians(acc))
    assert got.shape == (2, 3)
    np.testing.assert_allclose(got, want, atol=1e-15)


def test_bad_input():
    with pytest.raises(ValueError, match="frame"):
        angular_acceleration_from_rotvec([0.1, 0, 0], [0, 0, 1.0], [0, 0, 0.0], frame="x")
    with pytest.raises(ValueError, match="psiddot"):
        angular_acceleration_from_rotvec([0.1, 0, 0], [0, 0, 1.0], [0, 0.0])
    with pytest.raises(ValueError, match="qddot"):
        angular_acceleration_from_quat([1.0, 0, 0, 0], [0, 0, 0, 0.0], [0, 0.0])
    with pytest.raises(ValueError, match="seq"):
        angular_acceleration_from_euler("XXY", [0.1, 0.2, 0.3], [0, 0, 1.0], [0, 0, 0.0])
    with pytest.raises(ValueError, match="Rddot"):
        angular_acceleration(np.eye(3), np.zeros((3, 3)), np.zeros(3))
