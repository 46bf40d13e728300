"""Rotation-vector kinematics: dexp and the Bortz equation (Theory §3.4–5)."""

import warnings
from decimal import Decimal, localcontext

import numpy as np
import pytest

import kreisel as kr
from kreisel.kinematics import RotationVectorSingularityWarning


def _sin_cos(x, digits=45):
    """sin and cos of a Decimal by their Taylor series, to ``digits`` digits."""
    with localcontext() as ctx:
        ctx.prec = digits + 10
        s, c, term, n = Decimal(0), Decimal(0), Decimal(1), 0
        while True:
            if n % 4 == 0:
                c += term
            elif n % 4 == 1:
                s += term
            elif n % 4 == 2:
                c -= term
            else:
                s -= term
            n += 1
            term = term * x / n
            if abs(term) < Decimal(10) ** (-digits - 5):
                return +s, +c


def _bortz_decimal(psi):
    """(1 - (ψ/2) cot(ψ/2))/ψ² in 45-digit arithmetic."""
    with localcontext() as ctx:
        ctx.prec = 60
        x = Decimal(psi)
        s, c = _sin_cos(x / 2)
        return float((1 - (x / 2) * c / s) / (x * x))


def _dexp_coefficients_decimal(psi):
    with localcontext() as ctx:
        ctx.prec = 60
        x = Decimal(psi)
        s, c = _sin_cos(x)
        return float((1 - c) / (x * x)), float((x - s) / (x * x * x))


def _chapter_space(psi, psidot):
    """ω = ψ̇ + (1 − cos ψ)/ψ² ψ×ψ̇ + (ψ − sin ψ)/ψ³ ψ×(ψ×ψ̇), written as in Theory §3.4."""
    a = np.linalg.norm(psi, axis=-1)[..., None]
    c = np.cross(psi, psidot)
    return psidot + (1 - np.cos(a)) / a**2 * c + (a - np.sin(a)) / a**3 * np.cross(psi, c)


def _chapter_body(psi, psidot):
    a = np.linalg.norm(psi, axis=-1)[..., None]
    c = np.cross(psi, psidot)
    return psidot - (1 - np.cos(a)) / a**2 * c + (a - np.sin(a)) / a**3 * np.cross(psi, c)


def _chapter_bortz(psi, omega_body):
    """The Bortz equation with the chapter's coefficient (2 sin ψ − ψ(1 + cos ψ))/(2ψ² sin ψ)."""
    a = np.linalg.norm(psi, axis=-1)[..., None]
    f = (2 * np.sin(a) - a * (1 + np.cos(a))) / (2 * a**2 * np.sin(a))
    c = np.cross(psi, omega_body)
    return omega_body + 0.5 * c + f * np.cross(psi, c)


def _random_rotvecs(rng, n, low, high):
    axis = rng.normal(size=(n, 3))
    axis /= np.linalg.norm(axis, axis=1, keepdims=True)
    return axis * rng.uniform(low, high, size=(n, 1))


def test_dexp_matches_the_chapter_closed_forms():
    rng = np.random.default_rng(3)
    psi = _random_rotvecs(rng, 200, 0.5, 6.0)
    psidot = rng.normal(size=(200, 3))
    np.testing.assert_allclose(kr.angular_velocity_from_rotvec_rate(psi, psidot), _chapter_space(psi, psidot), atol=1e-14)
    np.testing.assert_allclose(
        kr.angular_velocity_from_rotvec_rate(psi, psidot, frame="body"), _chapter_body(psi, psidot), atol=1e-14
    )


def test_bortz_equation_matches_the_chapter_formula():
    rng = np.random.default_rng(4)
    psi = _random_rotvecs(rng, 200, 0.5, 3.0)  # |sin ψ| ≥ 0.14: the chapter's form is well conditioned here
    w = rng.normal(size=(200, 3))
    np.testing.assert_allclose(kr.rotvec_rate(psi, w, frame="body"), _chapter_bortz(psi, w), atol=1e-13)
    # space frame: ψ → −ψ in the body formula (Theory §3.4 remark)
    np.testing.assert_allclose(kr.rotvec_rate(psi, w), _chapter_bortz(-psi, w), atol=1e-13)


@pytest.mark.parametrize("t", [0.2, 0.7])
@pytest.mark.parametrize("frame", ["space", "body"])
def test_rotvec_maps_along_paths(path, ref, t, frame):
    psi = path.rotvec(t)
    psidot = ref.derivative(path.rotvec, t)
    omega = path.omega(t) if frame == "space" else path.omega_body(t)
    np.testing.assert_allclose(kr.angular_velocity_from_rotvec_rate(psi, psidot, frame=frame), omega, atol=1e-13)
    np.testing.assert_allclose(kr.rotvec_rate(psi, omega, frame=frame), psidot, atol=1e-13)


@pytest.mark.parametrize("frame", ["space", "body"])
def test_large_rotation_vectors_against_finite_differences_of_R(ref, frame):
    """ψ(t) polynomial, running through |ψ| = π up to 5.5; ω from finite differences of exp(ψ(t))."""

    def psi(t):
        return np.array([1.0 + 2.0 * t, -0.5 + t * t, 1.5 * t - 0.3 * t**3])

    def psidot(t):
        return np.array([2.0, 2 * t, 1.5 - 0.9 * t * t])

    def R(t):
        return ref.Rotation.from_rotvec(psi(t)).as_matrix()

    for t in np.linspace(0.0, 1.6, 9):
        Rd = ref.derivative(R, t)
        A = R(t).T @ Rd if frame == "body" else Rd @ R(t).T
        omega = ref.vee(A)
        assert np.linalg.norm(psi(t)) < 5.5
        np.testing.assert_allclose(kr.angular_velocity_from_rotvec_rate(psi(t), psidot(t), frame=frame), omega, atol=1e-12)
        np.testing.assert_allclose(kr.rotvec_rate(psi(t), omega, frame=frame), psidot(t), atol=1e-11)


def test_bortz_coefficient_against_high_precision():
    angles = np.concatenate([[0.0], np.logspace(-9, 0.78, 60), [0.999999, 1.0, 1.000001, np.pi, 4.0, 5.0, 6.0]])
    got = kr.kinematics.bortz_coefficient(angles)
    want = np.array([1 / 12] + [_bortz_decimal(a) for a in angles[1:]])
    np.testing.assert_allclose(got, want, rtol=3e-16 * 8, atol=0)
    assert kr.kinematics.bortz_coefficient(np.pi) == pytest.approx(1 / np.pi**2, rel=1e-15)


def test_bortz_series_is_the_chapters():
    """1/12 + ψ²/720 + ψ⁴/30240 + O(ψ⁶) (Theory §3.5)."""
    for psi in [1e-3, 1e-2, 5e-2]:
        f = kr.kinematics.bortz_coefficient(psi)
        assert abs(f - (1 / 12 + psi**2 / 720 + psi**4 / 30240)) <= psi**6 / 1209600 * 1.01 + 1e-17


def test_dexp_coefficients_accurate_across_series_switch():
    """The small-angle series and the closed forms agree with 45-digit references."""
    for angle in [1e-6, 0.3, 0.999999, 1.0, 1.000001, 2.5]:
        a, b = _dexp_coefficients_decimal(angle)
        psi = np.array([0.0, 0.0, angle])
        v = np.array([1.0, 0.0, 0.0])
        # ψ×v = (0, angle, 0), ψ×(ψ×v) = (−angle², 0, 0)
        want = np.array([1 - b * angle**2, a * angle, 0.0])
        np.testing.assert_allclose(kr.angular_velocity_from_rotvec_rate(psi, v), want, rtol=4e-16, atol=1e-300)


def test_the_jacobians_are_reexported_from_so3():
    assert kr.kinematics.left_jacobian is kr.so3.left_jacobian
    assert kr.kinematics.right_jacobian_inverse is kr.so3.right_jacobian_inverse


@pytest.mark.parametrize("scale", [1e-300, 1e-160, 1e7])
@pytest.mark.parametrize("frame", ["space", "body"])
def test_rate_maps_at_extreme_magnitudes_are_the_jacobian_matrices(scale, frame):
    """No overflow or underflow of |ψ| or ψ×(ψ×v); the matrices are checked against mpmath in tests/so3
    (longer rotation vectors than 1e8 rad are refused by the rates, tested there)."""
    psi = scale * np.array([[0.0, 0.0, 1.0], [0.36, -0.48, 0.8], [1.0, 2.0, -2.0]])
    v = np.array([[1.0, 2.0, 0.0], [0.3, -1.2, 0.5], [-0.7, 0.1, 0.4]])
    J = kr.so3.left_jacobian(psi) if frame == "space" else kr.so3.right_jacobian(psi)
    inverse = kr.so3.left_jacobian_inverse(psi) if frame == "space" else kr.so3.right_jacobian_inverse(psi)
    omega = kr.angular_velocity_from_rotvec_rate(psi, v, frame=frame)
    rate = kr.rotvec_rate(psi, v, frame=frame)
    # normwise: a few ulp of |J| |v| (J's entries are O(1), J⁻¹'s O(|ψ|))
    np.testing.assert_allclose(omega, np.einsum("nij,nj->ni", J, v), rtol=1e-13, atol=1e-15 * np.abs(J).max())
    np.testing.assert_allclose(rate, np.einsum("nij,nj->ni", inverse, v), rtol=1e-13, atol=1e-15 * np.abs(inverse).max())
    assert not kr.kinematics.rotvec_rate_singular(psi).any()


@pytest.mark.parametrize("k", [1, 2])
def test_singularity_at_multiples_of_two_pi(k):
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    psi = np.stack([axis * 2 * np.pi * k, axis * 1.0, axis * np.pi])
    w = np.array([0.3, -0.2, 0.9])
    with pytest.warns(RotationVectorSingularityWarning, match="1 of 3"):
        out = kr.rotvec_rate(psi, w, frame="body")
    assert np.isnan(out[0]).all() and np.isfinite(out[1:]).all()
    assert kr.kinematics.rotvec_rate_singular(psi).tolist() == [True, False, False]
    with pytest.warns(RotationVectorSingularityWarning):
        Jinv = kr.kinematics.right_jacobian_inverse(psi)
    assert np.isnan(Jinv[0]).all() and np.isfinite(Jinv[1:]).all()
    # no warning away from the poles
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        kr.rotvec_rate(psi[1:], w)
        near = axis * (2 * np.pi * k - 1e-6)
        assert np.isfinite(kr.rotvec_rate(near, w)).all()


def test_bad_input():
    with pytest.raises(ValueError, match="frame"):
        kr.rotvec_rate([0.1, 0, 0], [0, 0, 1.0], frame="world")
    with pytest.raises(ValueError, match="psi and omega"):
        kr.rotvec_rate(np.ones((2, 3)), np.ones((4, 3)))
    with pytest.raises(ValueError, match="psidot"):
        kr.angular_velocity_from_rotvec_rate([0.1, 0, 0], [0, 1.0])
    with pytest.raises(ValueError, match="tol"):
        kr.rotvec_rate([0.1, 0, 0], [0, 0, 1.0], tol=-1.0)
