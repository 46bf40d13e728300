"""Finite input of any magnitude: norms scaled before squaring, non-real dtypes refused, clear messages."""

import warnings

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as ScipyRotation

import kreisel as kr
from kreisel import inertia
from kreisel.so3._coercion import as_quaternion, as_rotation_matrix

Q = np.array([0.3, -0.5, 0.7, 0.4]) / np.linalg.norm([0.3, -0.5, 0.7, 0.4])
SCALES = [1e-300, 1e-200, 1e-155, 1e-150, 1e150, 1e155, 1e200, 1e300]


@pytest.fixture(autouse=True)
def no_runtime_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        yield


@pytest.mark.parametrize("scale", SCALES)
def test_quaternion_functions_see_only_the_direction_of_q(scale):
    q = scale * Q
    assert kr.quat_norm(q) == pytest.approx(scale, rel=1e-15)
    np.testing.assert_allclose(kr.quat_normalize(q), Q, atol=4e-16)
    np.testing.assert_allclose(kr.quat_to_matrix(q), ScipyRotation.from_quat(Q, scalar_first=True).as_matrix(),
                               atol=1e-15)
    np.testing.assert_allclose(kr.quat_to_rotvec(q), kr.quat_to_rotvec(Q), atol=1e-15)
    # quat_apply(2e-150 q, 1e-20 x) was off by 1.1e-5 (subnormal intermediate products)
    for v in ([1e-20, 0, 0], [0, 3e-200, 1e-200], [1e250, -1e250, 0]):
        v = np.asarray(v)
        np.testing.assert_allclose(kr.quat_apply(q, v), kr.quat_to_matrix(Q) @ v, rtol=1e-14,
                                   atol=1e-15 * np.abs(v).max())
    np.testing.assert_allclose(inertia.rotate(np.diag([1.0, 2.0, 3.0]), q),
                               inertia.rotate(np.diag([1.0, 2.0, 3.0]), Q), atol=1e-14)
    for f in (kr.quat_to_gibbs, kr.quat_to_mrp):
        np.testing.assert_allclose(f(q), f(Q), atol=1e-15)


@pytest.mark.parametrize("scale", [1e-300, 1e-200, 1e200, 1e300])
def test_quaternion_inverse_any_size_in_range(scale):
    np.testing.assert_allclose(kr.quat_multiply(scale * Q, kr.quat_inverse(scale * Q)), [1, 0, 0, 0], atol=1e-15)
    with pytest.raises(ValueError, match="out of range"):
        kr.quat_inverse([1e-320, 0, 0, 0])


def test_inverse_of_the_largest_quaternions_is_representable():
    # [0, -0, -0, -0] once: the scaled branch formed |q/m|² m = 2e308
    np.testing.assert_array_equal(kr.quat_inverse([1e308, 1e308, 0, 0]), [0.5 / 1e308, -0.5 / 1e308, 0, 0])


def test_rotating_the_largest_vectors():
    """A rotated vector is as long as the vector: finite whenever that fits in a double (scipy on a scaled copy)."""
    q = np.array([0.7e300, 0.2e300, -0.3e300, 0.5e300])
    v = np.full(3, 1e308)  # [-inf, 3.3e307, inf] once, with only numba's RuntimeWarning
    unit = ScipyRotation.from_quat(q / np.linalg.norm(q / 1e300) / 1e300, scalar_first=True)
    for inverse in (False, True):
        expected = 2.0**10 * (unit.inv() if inverse else unit).apply(v / 2.0**10)
        np.testing.assert_allclose(kr.quat_apply(q, v, inverse=inverse), expected, rtol=0, atol=1e-15 * 1e308)
    # a quaternion of size 1e100 once made |q|² v overflow for |v| beyond 1e108
    np.testing.assert_allclose(kr.quat_apply(1e100 * Q, [1e250, 0, 0]), 1e250 * kr.quat_to_matrix(Q)[:, 0],
                               rtol=1e-15)
    turn = [np.cos(np.pi / 8), 0, 0, np.sin(np.pi / 8)]  # 45° about z: x + y of 1.7e308 each has 2.4e308
    with pytest.raises(ValueError, match="q and v are out of range for quat_apply: the result overflows"):
        kr.quat_apply(turn, [1.7e308, 1.7e308, 0])


def test_vectors_far_from_unit_size():
    # each of these returned 0, the zero quaternion or inf before
    np.testing.assert_allclose(kr.gibbs_to_quat([1e200, 0, 0]), [1e-200, 1, 0, 0], rtol=1e-15)
    np.testing.assert_allclose(kr.axis_angle_to_rotvec([1e200, 0, 0], 1), [1, 0, 0])
    np.testing.assert_allclose(kr.axis_angle_to_rotvec([1e-160, 1e-160, 0], 2), [np.sqrt(2), np.sqrt(2), 0],
                               rtol=1e-15)
    assert inertia.moment_about_axis(np.diag([1.0, 2.0, 3.0]), [1e200, 0, 0]) == pytest.approx(1.0)
    assert inertia.moment_about_axis(np.diag([1.0, 2.0, 3.0]), [0, 1e-200, 0]) == pytest.approx(2.0)
    np.testing.assert_allclose(kr.mrp_to_quat([1e200, 0, 0]), [-1, 2e-200, 0, 0], rtol=1e-15)
    p = np.array([3.0, -1.0, 2.0])  # |p| > 1: the shadow path agrees with the formula
    np.testing.assert_allclose(kr.mrp_to_quat(p), np.r_[1 - p @ p, 2 * p] / (1 + p @ p), atol=1e-15)
    axis, angle = kr.rotvec_to_axis_angle([1e-170, 0, 1e-170])
    np.testing.assert_allclose(axis, [np.sqrt(0.5), 0, np.sqrt(0.5)], rtol=1e-15)
    assert angle == pytest.approx(np.sqrt(2) * 1e-170, rel=1e-15)
    # NaN before; a rotation vector this long has no determined rotation (its length mod 2 pi is
    # lost to rounding unless exact, as here by chance): refused, as every one beyond 1e8 rad
    for psi in ([1e160, 0, 0], [1e160, 3e159, 0]):
        with pytest.raises(ValueError, match=r"psi is out of range: \|psi\| = 1(\.04)?e\+160 rad exceeds 1e\+08"):
            kr.rotvec_to_quat(psi)


def test_screw_axis_of_large_velocity_is_a_screw():
    s = kr.screw_axis([1.0, 0, 0], [1e200, 0, 0])
    assert s.kind == "screw" and s.pitch == pytest.approx(1e200)
    s = kr.screw_axis([1e-200, 0, 0], [0, 1e-200, 0])
    assert s.kind == "rotation"
    np.testing.assert_allclose(s.point, [0, 0, 1])
    with pytest.raises(ValueError, match="out of range"):
        kr.screw_axis([1e-300, 0, 0], [1e300, 1e300, 0])


def test_results_that_overflow_are_refused_as_out_of_range():
    with pytest.raises(ValueError, match="r_c is out of range"):
        inertia.parallel_axis(np.eye(3), 1.0, [1e155, 0, 0])
    np.testing.assert_allclose(inertia.parallel_axis(np.eye(3), 1.0, [1e100, 0, 0]), np.diag([1, 1e200, 1e200]))


@pytest.mark.parametrize("bad", [np.array([1, 0, 0, 0j]), np.zeros(4, "datetime64[D]"), np.zeros(4, "timedelta64[s]"),
                                 np.array(["1", "0", "0", "0"]), "1.0"])
def test_non_real_dtypes_are_refused_not_converted(bad):
    with pytest.raises((TypeError, ValueError), match="must be real numbers|must have shape"):
        kr.quat_to_matrix(bad)
    with pytest.raises((TypeError, ValueError), match="must be real numbers|must have shape"):
        kr.hat(bad[:3] if np.ndim(bad) else bad)


def test_nonzero_quaternions_of_any_size_are_not_called_zero():
    for f in (kr.quat_normalize, kr.quat_to_matrix, kr.quat_to_rotvec):
        f([1e-320, 0, 0, 0])
        with pytest.raises(ValueError, match="nonzero"):
            f([0.0, 0, 0, 0])
        with pytest.raises(ValueError, match="finite"):
            f([np.nan, 0, 0, 0])
        f([1e300, 1e300, 1e300, 1e300])


def test_one_rotation_coercion():
    R = kr.quat_to_matrix(Q)
    for given in (Q, 7.0 * Q, R, kr.Rotation.from_quat(Q), ScipyRotation.from_quat(Q, scalar_first=True)):
        np.testing.assert_allclose(np.abs(as_quaternion(given) @ Q), 1.0, rtol=1e-15)
        np.testing.assert_allclose(as_rotation_matrix(given), R, atol=1e-15)
    for bad, match in [(2 * R, "max \\|R\\^T R - 1\\|"), (-R, "det > 0"), (np.zeros(4), "nonzero"),
                       (np.zeros(3), "must be a Rotation")]:
        with pytest.raises(ValueError, match=match):
            as_rotation_matrix(bad)
    # the inertia layer, the rigid transforms and the integrators take the same inputs
    np.testing.assert_allclose(inertia.rotate(np.diag([1.0, 2, 3]), kr.Rotation.from_quat(Q)),
                               R @ np.diag([1.0, 2, 3]) @ R.T, atol=1e-14)
    np.testing.assert_allclose(kr.RigidTransform.from_rotation_translation(7.0 * Q, [0, 0, 0]).as_matrix()[:3, :3], R,
                               atol=1e-15)
    np.testing.assert_allclose(kr.simulate([1, 2, 3], [0, 1], [0, 0, 0], q0=R).q[-1], Q, atol=1e-15)
    with pytest.raises(ValueError, match="det > 0"):
        inertia.rotate(np.eye(3), -R)


def test_quat_mean_refuses_the_component_axis():
    q = np.stack([Q, -Q, 2 * Q])
    np.testing.assert_allclose(np.abs(kr.quat_mean(q) @ Q), 1.0)
    for axis in (-1, 1):
        with pytest.raises(ValueError, match="not the last one"):
            kr.quat_mean(q, axis=axis)
    with pytest.raises(ValueError, match="out of range"):
        kr.quat_mean(q, axis=5)
    with pytest.raises(TypeError, match="axis must be an integer"):
        kr.quat_mean(q, axis=0.0)
