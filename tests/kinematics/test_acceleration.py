"""Angular acceleration from second derivatives of every parameterisation (Theory §3.9)."""

import itertools

import mpmath as mp
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


def _mp_epsilon(psi, psidot, psiddot, sign):
    """dω/dt of ω = ψ̇ + sign A ψ×ψ̇ + B ψ×(ψ×ψ̇) (Theory §3.4) along ψ + tψ̇ + t²ψ̈/2, by mpmath.diff at 1400 digits."""

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    with mp.workdps(1400):
        p0, p1, p2 = ([mp.mpf(float(c)) for c in x] for x in (psi, psidot, psiddot))

        def omega(t, k):
            x = [a + t * b + t * t * c / 2 for a, b, c in zip(p0, p1, p2)]
            rate = [b + t * c for b, c in zip(p1, p2)]
            angle = mp.sqrt(sum(c * c for c in x))
            once = cross(x, rate)
            twice = cross(x, once)
            return rate[k] + sign * (1 - mp.cos(angle)) / angle**2 * once[k] + (angle - mp.sin(angle)) / angle**3 * twice[k]

        return np.array([float(mp.diff(lambda t: omega(t, k), 0)) for k in range(3)])


@pytest.mark.parametrize("exponent", [-996, -530, 530, 996])
@pytest.mark.parametrize("frame", ["space", "body"])
def test_from_rotvec_at_extreme_magnitudes_against_mpmath(exponent, frame):
    """|ψ| ~ 1e±300 and 1e±160: the norm and ψ×(ψ×ψ̇) neither overflow nor underflow.

    With ψ̈ = 0 the result is the coefficient terms alone (~|ψ| or ~1/|ψ|). The
    direction (2, −1, 2) has a norm exact in binary, so that sin |ψ| is well posed.
    """
    psi = 2.0**exponent * np.array([2.0, -1.0, 2.0])
    psidot = np.array([0.3, 0.7, -0.4])
    for psiddot in (np.zeros(3), np.array([-0.2, 0.5, 0.1])):
        want = _mp_epsilon(psi, psidot, psiddot, 1.0 if frame == "space" else -1.0)
        got = angular_acceleration_from_rotvec(psi, psidot, psiddot, frame=frame)
        assert np.all(np.isfinite(got))
        assert np.linalg.norm(got - want) <= 1e-13 * np.linalg.norm(want)


@pytest.mark.parametrize("frame", ["space", "body"])
def test_from_rotvec_refuses_an_acceleration_beyond_the_float_range(frame):
    """ε is quadratic in ψ̇: at |ψ̇| ~ 1e155 it exceeds 1.8e308 and is refused, naming psidot and psiddot.

    Just below, at 1e150, it is ψ̇'s square times the same coefficients (ψ̈ = 0), so still exact.
    """
    psi = np.array([0.3, -0.4, 0.2])
    psidot = np.array([0.3, 0.7, -0.4])
    base = angular_acceleration_from_rotvec(psi, psidot, np.zeros(3), frame=frame)
    np.testing.assert_allclose(angular_acceleration_from_rotvec(psi, 1e150 * psidot, np.zeros(3), frame=frame),
                               1e300 * base, rtol=1e-13)
    out = np.zeros(3)
    with pytest.raises(ValueError, match="psidot and psiddot are out of range: the angular acceleration exceeds"):
        angular_acceleration_from_rotvec(psi, 1e155 * psidot, np.zeros(3), frame=frame, out=out)


@pytest.mark.parametrize("scale", [1e-200, 1e200])
@pytest.mark.parametrize("frame", ["space", "body"])
def test_from_quaternion_of_any_size(scale, frame):
    """ε of a scaled quaternion path is that of the unit one: |q|² would over- or underflow here."""
    q = np.array([0.5, 0.5, -0.5, 0.5])
    qdot = np.array([0.1, -0.3, 0.2, 0.4])
    qddot = np.array([-0.2, 0.1, 0.3, -0.1])
    want = angular_acceleration_from_quat(q, qdot, qddot, frame=frame)
    got = angular_acceleration_from_quat(scale * q, scale * qdot, scale * qddot, frame=frame)
    np.testing.assert_allclose(got, want, rtol=1e-14, atol=1e-15)


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


@pytest.mark.parametrize("frame", ["space", "body"])
def test_from_quaternion_scaled_alone_against_mpmath(frame):
    """Only q scaled (1e-300 ... 1e300), q̇ and q̈ unit size: ε = 2 vec(q̈ q⁻¹ − (q̇ q⁻¹)²) grows as
    1/|q|² until it leaves the float range, where it is refused as out of range (|q|² alone
    over- or underflowed beyond 1e±154 before)."""
    import mpmath as mp

    def reference(q, qd, qdd):
        with mp.workdps(50):
            def mul(p, r):
                return [p[0] * r[0] - p[1] * r[1] - p[2] * r[2] - p[3] * r[3],
                        p[0] * r[1] + p[1] * r[0] + p[2] * r[3] - p[3] * r[2],
                        p[0] * r[2] - p[1] * r[3] + p[2] * r[0] + p[3] * r[1],
                        p[0] * r[3] + p[1] * r[2] - p[2] * r[1] + p[3] * r[0]]
            q, qd, qdd = ([mp.mpf(float(x)) for x in v] for v in (q, qd, qdd))
            n2 = sum(x * x for x in q)
            inv = [q[0] / n2, -q[1] / n2, -q[2] / n2, -q[3] / n2]
            rate, curv = (mul(inv, qd), mul(inv, qdd)) if frame == "body" else (mul(qd, inv), mul(qdd, inv))
            sq = mul(rate, rate)
            return np.array([float(2 * (curv[k] - sq[k])) for k in (1, 2, 3)])

    q = np.array([0.5, 0.5, -0.5, 0.5])
    qdot = np.array([0.3, -0.3, 0.2, 0.4])  # not orthogonal to q: the 1/|q|² term is present
    qddot = np.array([-0.2, 0.1, 0.3, -0.1])
    for exponent in (-300, -160, -100, 0, 100, 160, 300):
        scaled = 10.0**exponent * q
        if exponent <= -160:
            with pytest.raises(ValueError, match="q, qdot and qddot are out of range"):
                angular_acceleration_from_quat(scaled, qdot, qddot, frame=frame)
            continue
        want = reference(scaled, qdot, qddot)
        # to 1e-14 of the vector's size: a component 1e-16 of the others is rounding either way
        np.testing.assert_allclose(angular_acceleration_from_quat(scaled, qdot, qddot, frame=frame), want, rtol=0,
                                   atol=1e-14 * np.abs(want).max())


def test_angular_acceleration_from_euler_beyond_the_largest_double_is_refused():
    # products of rates of 1e155 rad/s exceed 1.8e308 rad/s²: a refusal naming them, not numpy's overflow
    with pytest.raises(ValueError, match="rates and accelerations are out of range: the angular acceleration"):
        angular_acceleration_from_euler("ZXZ", [0.1, 0.5, 0.2], [1e155, 2e155, 1e155], [0.0, 0.0, 0.0])
