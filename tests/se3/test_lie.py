"""SE(3) exp/log and Jacobians against the matrix exponential, series and finite differences."""

import numpy as np
import pytest
from scipy.linalg import expm

from kreisel.se3 import (
    RigidTransform,
    se3_hat,
    se3_left_jacobian,
    se3_left_jacobian_inverse,
    se3_right_jacobian,
    se3_right_jacobian_inverse,
    se3_vee,
)
from kreisel._compiled.dexp import se3_coupling_coefficients


def twists():
    """Twists (ω, v) at generic, tiny, moderate and near-π angles."""
    rng = np.random.default_rng(11)
    axes = rng.normal(size=(8, 3))
    axes /= np.linalg.norm(axes, axis=-1, keepdims=True)
    angles = np.array([1e-12, 1e-7, 1e-3, 0.5, 1.999, 2.001, np.pi - 1e-6, np.pi - 1e-9])
    return np.concatenate([angles[:, None] * axes, rng.normal(size=(8, 3))], axis=-1)


def ad(xi):
    """Twist adjoint ad_ξ = [[hat ω, 0], [hat v, hat ω]] for the (ω, v) order."""
    h = se3_hat(xi)
    a = np.zeros((6, 6))
    a[:3, :3] = a[3:, 3:] = h[:3, :3]
    a[3:, :3] = se3_hat(np.r_[xi[3:], 0, 0, 0])[:3, :3]
    return a


def jacobian_series(xi, terms=60):
    """J_l(ξ) = Σ ad_ξⁿ/(n+1)!, summed directly (independent of the closed form)."""
    a = ad(xi)
    total, term = np.zeros((6, 6)), np.eye(6)
    for n in range(terms):
        total += term
        term = term @ a / (n + 2)
    return total


def test_hat_vee_round_trip():
    xi = np.random.default_rng(0).normal(size=(4, 6))
    np.testing.assert_array_equal(se3_vee(se3_hat(xi)), xi)


@pytest.mark.parametrize("i", range(8))
def test_exp_is_matrix_exponential(i):
    xi = twists()[i]
    np.testing.assert_allclose(RigidTransform.from_exp_coords(xi).as_matrix(), expm(se3_hat(xi)), rtol=0, atol=2e-15 * 8)


@pytest.mark.parametrize("i", range(8))
def test_log_exp_round_trip(i):
    xi = twists()[i]
    back = RigidTransform.from_exp_coords(xi).as_exp_coords()
    np.testing.assert_allclose(back, xi, rtol=0, atol=1e-15)


def test_exp_log_round_trip_on_random_poses():
    t = RigidTransform.random(200, rng=3, translation_scale=5.0)
    np.testing.assert_allclose(RigidTransform.from_exp_coords(t.as_exp_coords()).as_matrix(), t.as_matrix(), atol=1e-13)
    assert np.all(np.linalg.norm(t.as_exp_coords()[:, :3], axis=-1) <= np.pi)


def test_log_of_half_turn_is_a_valid_log():
    t = RigidTransform.from_rotation_translation([0.0, 0.0, 0.0, 1.0], [1.0, 2.0, 3.0])
    xi = t.as_exp_coords()
    assert np.isclose(np.linalg.norm(xi[:3]), np.pi, rtol=0, atol=1e-15)
    np.testing.assert_allclose(expm(se3_hat(xi)), t.as_matrix(), atol=1e-14)


def test_small_angle_log_keeps_relative_accuracy():
    xi = np.array([3e-10, -1e-10, 2e-10, 1.0, -2.0, 0.5])
    back = RigidTransform.from_exp_coords(xi).as_exp_coords()
    np.testing.assert_allclose(back[:3], xi[:3], rtol=1e-15)
    np.testing.assert_allclose(back[3:], xi[3:], rtol=1e-15)


@pytest.mark.parametrize("i", range(8))
def test_left_jacobian_matches_series(i):
    xi = twists()[i]
    np.testing.assert_allclose(se3_left_jacobian(xi), jacobian_series(xi), rtol=0, atol=1e-15)


@pytest.mark.parametrize("switch", [1.0, 2.0])
def test_coupling_coefficients_are_continuous_at_the_series_switch(switch):
    below, above = se3_coupling_coefficients(switch - 1e-13), se3_coupling_coefficients(switch + 1e-13)
    for b, a in zip(below, above):
        np.testing.assert_allclose(b, a, rtol=1e-12)  # their slopes (< 1 relative) move them by < 2e-13


def finite_difference_jacobian(xi, side, h=1e-6):
    base = RigidTransform.from_exp_coords(xi)
    cols = []
    for k in range(6):
        d = np.zeros(6)
        d[k] = h
        plus, minus = RigidTransform.from_exp_coords(xi + d), RigidTransform.from_exp_coords(xi - d)
        if side == "left":
            diff = (plus * base.inv()).as_exp_coords() - (minus * base.inv()).as_exp_coords()
        else:
            diff = (base.inv() * plus).as_exp_coords() - (base.inv() * minus).as_exp_coords()
        cols.append(diff / (2 * h))
    return np.stack(cols, axis=-1)


@pytest.mark.parametrize("i", [1, 2, 3, 4, 5, 6])
@pytest.mark.parametrize("side", ["left", "right"])
def test_jacobians_match_finite_differences(i, side):
    xi = twists()[i]
    analytic = se3_left_jacobian(xi) if side == "left" else se3_right_jacobian(xi)
    np.testing.assert_allclose(analytic, finite_difference_jacobian(xi, side), rtol=0, atol=2e-9)


def test_inverse_jacobians_and_adjoint_relation():
    xi = twists()
    eye = np.broadcast_to(np.eye(6), (8, 6, 6))
    np.testing.assert_allclose(se3_left_jacobian_inverse(xi) @ se3_left_jacobian(xi), eye, atol=1e-13)
    np.testing.assert_allclose(se3_right_jacobian_inverse(xi) @ se3_right_jacobian(xi), eye, atol=1e-13)
    # J_l = Ad(exp ξ) J_r
    adj = RigidTransform.from_exp_coords(xi).adjoint()
    np.testing.assert_allclose(se3_left_jacobian(xi), adj @ se3_right_jacobian(xi), atol=1e-13)


def test_adjoint_conjugates_twists():
    t = RigidTransform.random(rng=4)
    xi = np.array([0.3, -0.2, 0.4, 1.0, 0.5, -2.0])
    left = t * RigidTransform.from_exp_coords(xi) * t.inv()
    np.testing.assert_allclose(left.as_matrix(), RigidTransform.from_exp_coords(t.adjoint() @ xi).as_matrix(), atol=1e-13)


@pytest.mark.parametrize(
    "call", [se3_hat, se3_left_jacobian, se3_right_jacobian, se3_left_jacobian_inverse, se3_right_jacobian_inverse]
)
def test_refuses_wrong_twist_shapes(call):
    with pytest.raises(ValueError, match="xi"):
        call(np.zeros(3))


def test_vee_refuses_wrong_shape():
    with pytest.raises(ValueError, match="matrix"):
        se3_vee(np.zeros((3, 3)))


def _mp_jacobian_series(xi, terms):
    """Σ ad_ξⁿ/(n+1)! in 60-digit arithmetic: a reference for |ω| up to ~20 where floats cancel."""
    import mpmath as mp

    with mp.workdps(60):
        a = mp.matrix(ad(xi).tolist())
        total, term = mp.zeros(6, 6), mp.eye(6)
        for n in range(terms):
            total += term
            term = term * a / (n + 2)
        return np.array(total.tolist(), dtype=float)


@pytest.mark.parametrize("angle", [1e-300, 1e-160, 0.7, 5.0, 20.0])
def test_jacobians_of_any_rotation_size_against_mpmath(angle):
    """Q is built on the unit axis with its coefficients times powers of |ω|: no overflow
    (|ω|⁵ overflowed at 1e62) and no underflow; a few ulp of the matrix against the series."""
    rng = np.random.default_rng(7)
    axis = rng.normal(size=3)
    xi = np.concatenate([angle * axis / np.linalg.norm(axis), rng.normal(size=3)])
    want = _mp_jacobian_series(xi, 160)
    np.testing.assert_allclose(se3_left_jacobian(xi), want, rtol=0, atol=1e-15 * np.abs(want).max())
    np.testing.assert_allclose(se3_left_jacobian_inverse(xi) @ want, np.eye(6), rtol=0, atol=4e-14 * angle + 1e-15)


def test_long_rotation_parts_and_out_of_range_couplings_are_refused():
    """Beyond |ω| = 1e8 rad the coupling block depends on |ω| mod 2π (refused, as for SO(3)'s
    inverses); a J⁻¹ Q J⁻¹ beyond the float range is refused as out of range, not inf."""
    for fn in (se3_left_jacobian, se3_right_jacobian, se3_left_jacobian_inverse, se3_right_jacobian_inverse):
        with pytest.raises(ValueError, match=r"xi is out of range: the rotation part \|omega\| = 1\.3e\+62"):
            fn(np.array([0.5, -1.2, 0.0, 1.0, 2.0, 3.0]) * 1e62)
    near_pole = np.array([0.0, 0.0, 6.2, 1e308, 1e308, 3.0])  # J⁻¹ ~ 75: J⁻¹ Q J⁻¹ ~ 75² |v|
    with pytest.raises(ValueError, match="xi is out of range: the coupling block"):
        se3_left_jacobian_inverse(near_pole)
    assert np.isfinite(se3_left_jacobian(near_pole)).all()
