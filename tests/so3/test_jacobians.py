"""The SO(3) Jacobians and their inverses (Theory §3.4–5)."""

import mpmath as mp
import numpy as np
import pytest

import kreisel as kr


def test_jacobians():
    rng = np.random.default_rng(5)
    psi = rng.uniform(-3.4, 3.4, size=(10, 10, 3))  # |ψ| up to 5.9, past π but short of the pole at 2π
    v = rng.normal(size=(10, 10, 3))
    Jl, Jr = kr.so3.left_jacobian(psi), kr.so3.right_jacobian(psi)
    assert Jl.shape == (10, 10, 3, 3)
    np.testing.assert_allclose(Jl @ v[..., None], kr.angular_velocity_from_rotvec_rate(psi, v)[..., None], atol=1e-14)
    np.testing.assert_allclose(Jr, np.swapaxes(Jl, -1, -2), atol=1e-15)
    np.testing.assert_allclose(Jr, kr.so3.left_jacobian(-psi), atol=1e-15)
    R = kr.rotvec_to_matrix(psi)
    np.testing.assert_allclose(Jl, R @ Jr, atol=1e-14)  # ω = R ω′
    eye = np.broadcast_to(np.eye(3), Jl.shape)
    np.testing.assert_allclose(kr.so3.left_jacobian_inverse(psi) @ Jl, eye, atol=1e-12)
    np.testing.assert_allclose(kr.so3.right_jacobian_inverse(psi) @ Jr, eye, atol=1e-12)
    # J_l(ψ) = (e^{ψ·X} − 1)/(ψ·X) = Σ (ψ·X)^k/(k+1)!, summed directly at a moderate angle
    p = np.array([0.4, -0.3, 0.2])
    series = sum(np.linalg.matrix_power(kr.hat(p), k) / float(np.prod(np.arange(1, k + 2))) for k in range(30))
    np.testing.assert_allclose(kr.so3.left_jacobian(p), series, atol=1e-15)


def _mp_jacobians(psi):
    """J_l = 1 + A hat + B hat², J_l⁻¹ = 1 − ½ hat + f hat² from the chapter's closed forms, in 1400-digit arithmetic.

    1400 digits absorb both the cancellation of 1 − cos ψ, ψ − sin ψ at ψ ~ 1e-300
    and the reduction of sin ψ at ψ ~ 1e300 (the float's exact binary value).
    """
    with mp.workdps(1400):
        x = [mp.mpf(float(c)) for c in psi]
        angle = mp.sqrt(sum(c * c for c in x))
        hat = mp.matrix([[0, -x[2], x[1]], [x[2], 0, -x[0]], [-x[1], x[0], 0]])
        a = (1 - mp.cos(angle)) / angle**2
        b = (angle - mp.sin(angle)) / angle**3
        f = (2 * mp.sin(angle) - angle * (1 + mp.cos(angle))) / (2 * angle**2 * mp.sin(angle))
        eye = mp.eye(3)
        left = eye + a * hat + b * hat * hat
        inverse = eye - hat / 2 + f * hat * hat
        return (np.array(m.tolist(), dtype=float) for m in (left, inverse))


@pytest.mark.parametrize("exponent", [-996, -530, 24, 530, 996])
def test_jacobians_at_extreme_magnitudes_against_mpmath(exponent):
    """|ψ| from 1e-300 to 1e300: no overflow or underflow; a few ulp of the matrix norm.

    The directions have norms that are exact in binary, so that the reference
    has the same |ψ| mod 2π. The inverses, which depend on it at full size,
    are refused beyond 1e8 rad (there one rounding of a general |ψ| moves
    ψ/2 mod π by more than the singularity tolerance).
    """
    for direction in ([0.0, 0.0, 1.0], [3.0, 4.0, 0.0], [2.0, -1.0, 2.0]):
        psi = 2.0**exponent * np.array(direction)
        left, inverse = _mp_jacobians(psi)
        np.testing.assert_allclose(kr.so3.left_jacobian(psi), left, rtol=0, atol=4e-16 * np.abs(left).max())
        np.testing.assert_allclose(kr.so3.right_jacobian(psi), left.T, rtol=0, atol=4e-16 * np.abs(left).max())
        if exponent < 27:
            np.testing.assert_allclose(kr.so3.left_jacobian_inverse(psi), inverse, rtol=0,
                                       atol=4e-16 * np.abs(inverse).max())
        else:
            with pytest.raises(ValueError, match=r"psi is out of range: \|psi\| = .* exceeds 1e\+08 rad"):
                kr.so3.left_jacobian_inverse(psi)


def test_inverse_jacobians_of_long_rotation_vectors_are_refused_not_noise():
    """A general ψ of length 1e155: its rounded length puts ψ/2 anywhere mod π, and the old
    finite result was off by O(1) (against mpmath); now a clear refusal, also in a batch with
    valid and singular samples, and for the rotation-vector rates and their singularity mask."""
    psi = np.array([[0.3, -0.5, 0.7], [0.0, 0.0, 2 * np.pi], [0.1, 0.2, 0.3]])
    psi[0] *= 1e155 / np.linalg.norm(psi[0])
    for fn in (kr.so3.left_jacobian_inverse, kr.so3.right_jacobian_inverse,
               lambda p: kr.rotvec_rate(p, [1.0, 2.0, 3.0]), kr.kinematics.rotvec_rate_singular):
        with pytest.raises(ValueError, match="psi is out of range.*reduce the angle modulo 2"):
            fn(psi)
    # just inside the range: right to the conditioning |ψ|·eps of the rounded length
    psi = np.array([0.3, -0.5, 0.7]) * (0.9e8 / np.sqrt(0.83))
    _, inverse = _mp_jacobians(psi)
    np.testing.assert_allclose(kr.so3.left_jacobian_inverse(psi), inverse, rtol=0, atol=3e-8 * np.abs(inverse).max())
