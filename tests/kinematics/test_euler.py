"""Euler kinematic equations, all 24 conventions (Theory §3.6)."""

import itertools
import warnings

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st
from scipy.spatial.transform import Rotation as ScipyRotation

import kreisel as kr
from kreisel import GimbalLockWarning

_UPPER = ["".join(s) for s in itertools.product("XYZ", repeat=3) if s[0] != s[1] and s[1] != s[2]]
SEQUENCES = _UPPER + [s.lower() for s in _UPPER]
FRAMES = ["space", "body"]


def _proper(seq):
    return seq[0].lower() == seq[2].lower()


def _chapter_zxz(phi, theta, psi):
    """The chapter's explicit ZXZ matrices: space, body and the inverse of the body one."""
    s, c = np.sin, np.cos
    space = np.array([[0, c(phi), s(phi) * s(theta)], [0, s(phi), -c(phi) * s(theta)], [1, 0, c(theta)]])
    body = np.array([[s(theta) * s(psi), c(psi), 0], [s(theta) * c(psi), -s(psi), 0], [c(theta), 0, 1]])
    body_inverse = np.array(
        [
            [s(psi) / s(theta), c(psi) / s(theta), 0],
            [c(psi), -s(psi), 0],
            [-c(theta) * s(psi) / s(theta), -c(theta) * c(psi) / s(theta), 1],
        ]
    )
    return space, body, body_inverse


@pytest.mark.parametrize("angles", [(0.3, 0.8, -1.2), (2.5, 2.9, 0.4), (-1.0, 0.05, 3.0)])
def test_zxz_matrices_are_the_chapters(angles):
    space, body, body_inverse = _chapter_zxz(*angles)
    np.testing.assert_allclose(kr.kinematics.euler_rate_matrix("ZXZ", angles), space, atol=1e-15)
    np.testing.assert_allclose(kr.kinematics.euler_rate_matrix("ZXZ", angles, frame="body"), body, atol=1e-15)
    np.testing.assert_allclose(
        kr.kinematics.euler_rate_matrix_inverse("ZXZ", angles, frame="body"), body_inverse, rtol=1e-14, atol=1e-15
    )
    np.testing.assert_allclose(
        kr.kinematics.euler_rate_matrix_inverse("ZXZ", angles), np.linalg.inv(space), rtol=1e-13, atol=1e-14
    )
    rates = np.array([0.7, -1.1, 2.3])
    np.testing.assert_allclose(kr.angular_velocity_from_euler_rates("ZXZ", angles, rates, frame="body"), body @ rates, atol=1e-15)
    np.testing.assert_allclose(kr.euler_rates("ZXZ", angles, body @ rates, frame="body"), rates, atol=1e-13)


def _angle_path(t):
    return np.array([0.4 + 1.3 * t - 0.2 * t * t, 0.6 + 0.5 * t + 0.3 * t**3, -1.0 + 0.8 * t + 0.5 * t * t])


def _angle_rates(t):
    return np.array([1.3 - 0.4 * t, 0.5 + 0.9 * t * t, 0.8 + 1.0 * t])


@pytest.mark.parametrize("seq", SEQUENCES)
def test_all_conventions_against_finite_differences_of_R(ref, seq):
    """ω from central differences of R(t) = scipy's Euler matrix along a smooth angle path."""

    def R(t):
        return ScipyRotation.from_euler(seq, _angle_path(t)).as_matrix()

    ts = np.array([0.0, 0.45, 0.9])
    angles = np.stack([_angle_path(t) for t in ts])
    rates = np.stack([_angle_rates(t) for t in ts])
    Rs = np.stack([R(t) for t in ts])
    Rds = np.stack([ref.derivative(R, t) for t in ts])
    for frame in FRAMES:
        A = np.swapaxes(Rs, -1, -2) @ Rds if frame == "body" else Rds @ np.swapaxes(Rs, -1, -2)
        omega = ref.vee(A)
        np.testing.assert_allclose(kr.angular_velocity_from_euler_rates(seq, angles, rates, frame=frame), omega, atol=1e-13)
        np.testing.assert_allclose(kr.euler_rates(seq, angles, omega, frame=frame), rates, atol=1e-12)
        M = kr.kinematics.euler_rate_matrix(seq, angles, frame=frame)
        np.testing.assert_allclose(M @ rates[..., None], omega[..., None], atol=1e-13)


def _nonsingular_angles(seq):
    middle = st.floats(0.05, np.pi - 0.05) if _proper(seq) else st.floats(-np.pi / 2 + 0.05, np.pi / 2 - 0.05)
    outer = st.floats(-np.pi, np.pi)
    return st.tuples(outer, middle, outer).map(np.array)


vec3 = st.tuples(*[st.floats(-10, 10)] * 3).map(np.array)


@settings(max_examples=40, deadline=None)
@given(data=st.data(), seq=st.sampled_from(SEQUENCES), frame=st.sampled_from(FRAMES))
def test_round_trips(data, seq, frame):
    angles = data.draw(_nonsingular_angles(seq))
    rates = data.draw(vec3)
    omega = kr.angular_velocity_from_euler_rates(seq, angles, rates, frame=frame)
    # |det| ≥ sin 0.05 bounds the condition number by ~40
    np.testing.assert_allclose(kr.euler_rates(seq, angles, omega, frame=frame), rates, atol=1e-12 * (1 + np.abs(rates).max()))
    w = data.draw(vec3)
    back = kr.angular_velocity_from_euler_rates(seq, angles, kr.euler_rates(seq, angles, w, frame=frame), frame=frame)
    np.testing.assert_allclose(back, w, atol=1e-12 * (1 + np.abs(w).max()))


@settings(max_examples=25, deadline=None)
@given(data=st.data(), seq=st.sampled_from(SEQUENCES))
def test_space_and_body_are_related_by_R(data, seq):
    angles = data.draw(_nonsingular_angles(seq))
    rates = data.draw(vec3)
    R = ScipyRotation.from_euler(seq, angles).as_matrix()
    space = kr.angular_velocity_from_euler_rates(seq, angles, rates)
    body = kr.angular_velocity_from_euler_rates(seq, angles, rates, frame="body")
    np.testing.assert_allclose(R @ body, space, atol=1e-13 * (1 + np.abs(rates).max()))


def _locked_middle(seq):
    return [0.0, np.pi, -np.pi] if _proper(seq) else [np.pi / 2, -np.pi / 2]


@pytest.mark.parametrize("seq", SEQUENCES)
@pytest.mark.parametrize("frame", FRAMES)
def test_gimbal_lock(seq, frame):
    middles = _locked_middle(seq)
    angles = np.array([[0.3, m, -0.7] for m in middles] + [[0.3, 1.0, -0.7]])
    omega = np.array([0.4, -1.2, 0.9])
    assert kr.kinematics.euler_rates_singular(seq, angles).tolist() == [True] * len(middles) + [False]
    with pytest.warns(GimbalLockWarning, match=f"{len(middles)} of {len(middles) + 1}"):
        rates = kr.euler_rates(seq, angles, omega, frame=frame)
    assert np.isnan(rates[:-1, [0, 2]]).all()
    assert np.isfinite(rates[:-1, 1]).all() and np.isfinite(rates[-1]).all()
    # the middle rate is still right: it is the component of ω along the middle axis (column 1)
    M = kr.kinematics.euler_rate_matrix(seq, angles[:-1], frame=frame)
    np.testing.assert_allclose(rates[:-1, 1], M[..., :, 1] @ omega, atol=1e-15)
    # at lock the outer columns are parallel: M is singular
    np.testing.assert_allclose(np.abs(np.linalg.det(M)), 0.0, atol=1e-15)
    with pytest.warns(GimbalLockWarning):
        Minv = kr.kinematics.euler_rate_matrix_inverse(seq, angles, frame=frame)
    assert np.isnan(Minv[:-1, [0, 2]]).all() and np.isfinite(Minv[:-1, 1]).all()


def test_gimbal_lock_tolerance_and_degrees():
    omega = [0.4, -1.2, 0.9]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        near = kr.euler_rates("ZXZ", [0.1, 1e-6, 0.2], omega)
        assert np.isfinite(near).all()
        assert not kr.kinematics.euler_rates_singular("ZXZ", [0.1, 1e-6, 0.2])
    assert kr.kinematics.euler_rates_singular("ZXZ", [0.1, 1e-6, 0.2], tol=1e-5)
    with pytest.warns(GimbalLockWarning):
        kr.euler_rates("ZXZ", [0.1, 1e-6, 0.2], omega, tol=1e-5)
    assert kr.kinematics.euler_rates_singular("xyz", [10.0, 90.0, 0.0], degrees=True)
    with pytest.warns(GimbalLockWarning):
        kr.euler_rates("xyz", [10.0, 90.0, 0.0], omega, degrees=True)


def test_degrees():
    angles = np.array([30.0, 45.0, 60.0])
    rates = np.array([10.0, -20.0, 5.0])
    omega = kr.angular_velocity_from_euler_rates("ZYX", angles, rates, degrees=True)
    np.testing.assert_allclose(omega, kr.angular_velocity_from_euler_rates("ZYX", np.radians(angles), np.radians(rates)), atol=1e-15)
    np.testing.assert_allclose(kr.euler_rates("ZYX", angles, omega, degrees=True), rates, atol=1e-12)


def test_batches_broadcast():
    angles = np.random.default_rng(0).uniform(0.2, 1.2, size=(4, 1, 3))
    omega = np.random.default_rng(1).normal(size=(5, 3))
    assert kr.euler_rates("XYZ", angles, omega).shape == (4, 5, 3)
    assert kr.kinematics.euler_rate_matrix("XYZ", angles).shape == (4, 1, 3, 3)


@pytest.mark.parametrize("seq", ["ZZX", "XyZ", "abc", "XY", "XYZW", 5])
def test_invalid_sequences(seq):
    with pytest.raises(ValueError, match="seq"):
        kr.euler_rates(seq, [0.1, 0.2, 0.3], [0, 0, 1.0])
    with pytest.raises(ValueError, match="seq"):
        kr.angular_velocity_from_euler_rates(seq, [0.1, 0.2, 0.3], [0, 0, 1.0])


def test_bad_input():
    with pytest.raises(ValueError, match="frame"):
        kr.euler_rates("ZXZ", [0.1, 0.2, 0.3], [0, 0, 1.0], frame="lab")
    with pytest.raises(ValueError, match="angles and omega"):
        kr.euler_rates("ZXZ", np.ones((2, 3)), np.ones((3, 3)))
    with pytest.raises(ValueError, match="rates"):
        kr.angular_velocity_from_euler_rates("ZXZ", [0.1, 0.2, 0.3], [1.0, 2.0])
    with pytest.raises(ValueError, match="angles"):
        kr.euler_rates("ZXZ", [0.1, np.inf, 0.3], [0, 0, 1.0])


def test_inverse_near_gimbal_lock_is_right_or_a_documented_refusal():
    """Angles scaled towards 0 put "ZXZ" at gimbal lock: within ``tol`` of it the outer rows are
    NaN with a GimbalLockWarning (never a silent non-finite result); with ``tol=0`` the inverse is
    computed down to |θ| = 1e-300 and matches the chapter's body matrix in 60-digit arithmetic."""
    import mpmath as mp

    for scale in (1e-300, 1e-100, 1e-9):
        angles = scale * np.array([0.8, 0.5, 1.1])
        with pytest.warns(GimbalLockWarning, match="1 of 1 samples"):
            locked = kr.kinematics.euler_rate_matrix_inverse("ZXZ", angles, frame="body")
        assert np.isnan(locked[[0, 2]]).all() and np.isfinite(locked[1]).all()
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            got = kr.kinematics.euler_rate_matrix_inverse("ZXZ", angles, frame="body", tol=0.0)
        with mp.workdps(60):
            theta, psi = (mp.mpf(float(x)) for x in angles[1:])
            cot = mp.cos(theta) / mp.sin(theta)
            want = np.array([[mp.sin(psi) / mp.sin(theta), mp.cos(psi) / mp.sin(theta), 0],
                             [mp.cos(psi), -mp.sin(psi), 0],
                             [-cot * mp.sin(psi), -cot * mp.cos(psi), 1]], dtype=float)
        np.testing.assert_allclose(got, want, rtol=4e-16, atol=1e-300)
