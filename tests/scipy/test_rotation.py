"""kreisel.scipy.Rotation against scipy's Rotation: the same numbers from the same calls."""

import pickle
import warnings

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as ScipyRotation

import kreisel as kr
from kreisel.kinematics import GimbalLockWarning
from kreisel.scipy import Rotation


def test_scipy_script_reads_quaternions_scalar_last():
    # issue 34: kr.Rotation.from_quat([0, 0, .7071, .7071]) is a half turn (scalar first); scipy's is a quarter turn
    q = [0, 0, 0.7071, 0.7071]
    r = Rotation.from_quat(q)
    assert np.degrees(r.magnitude()) == pytest.approx(90.0, abs=1e-12)
    np.testing.assert_allclose(r.as_rotvec(), ScipyRotation.from_quat(q).as_rotvec(), rtol=0, atol=1e-15)
    np.testing.assert_allclose(r.as_quat(), ScipyRotation.from_quat(q).as_quat(), rtol=0, atol=1e-15)
    assert np.degrees(kr.Rotation.from_quat(q).magnitude()) == pytest.approx(180.0, abs=1e-12)


def test_kreisel_round_trip_is_scalar_first():
    r = Rotation.from_quat([0.0, 0.0, 0.6, 0.8])
    assert r.to_kreisel().as_quat().tolist() == [0.8, 0.0, 0.0, 0.6]
    assert Rotation.from_kreisel(r.to_kreisel()).as_quat().tolist() == [0.0, 0.0, 0.6, 0.8]
    assert Rotation.from_quat([0.8, 0, 0, 0.6], scalar_first=True).as_quat(scalar_first=True).tolist() == [0.8, 0, 0, 0.6]
    with pytest.raises(TypeError, match="rotation must be a kreisel.so3.Rotation"):
        Rotation.from_kreisel(ScipyRotation.identity())


def test_as_euler_warns_at_gimbal_lock_as_scipy():
    r = Rotation.from_euler("zxz", [[10, 0, 30], [10, 20, 30]], degrees=True)
    with pytest.warns(UserWarning) as caught:
        angles = r.as_euler("zxz", degrees=True)
    assert [w.category for w in caught] == [GimbalLockWarning]
    assert "1 of 2" in str(caught[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        np.testing.assert_allclose(angles, ScipyRotation.from_euler("zxz", [[10, 0, 30], [10, 20, 30]], degrees=True)
                                   .as_euler("zxz", degrees=True, suppress_warnings=True), rtol=0, atol=1e-12)
        r.as_euler("zxz", suppress_warnings=True)


def test_from_matrix_projects_onto_the_nearest_rotation_as_scipy():
    rng = np.random.default_rng(3)
    m = ScipyRotation.random(5, rng=rng).as_matrix() + 0.1 * rng.standard_normal((5, 3, 3))
    r = Rotation.from_matrix(m)
    np.testing.assert_allclose(r.as_matrix(), ScipyRotation.from_matrix(m).as_matrix(), rtol=0, atol=1e-14)
    u, _, vt = np.linalg.svd(m)
    np.testing.assert_allclose(r.as_matrix(), u @ vt, rtol=0, atol=1e-14)
    # the same sign of the quaternion as scipy, for orthogonal and projected matrices alike
    for matrix in (m, ScipyRotation.random(50, rng=rng).as_matrix()):
        np.testing.assert_allclose(Rotation.from_matrix(matrix).as_quat(), ScipyRotation.from_matrix(matrix).as_quat(),
                                   rtol=0, atol=1e-14)
    with pytest.raises(ValueError, match="matrix must have a positive determinant"):
        Rotation.from_matrix(np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(ValueError, match="shape"):
        Rotation.from_matrix(np.eye(4))


def test_davenport_with_batched_axes_matches_scipy():
    rng = np.random.default_rng(0)
    axes = ScipyRotation.random(shape=(4, 1), rng=rng).as_matrix()          # orthonormal rows: valid axes sets
    angles = rng.uniform(-1.0, 1.0, (1, 5, 3))
    for order in ("e", "i"):
        ours = Rotation.from_davenport(axes, order, angles)
        theirs = ScipyRotation.from_davenport(axes, order, angles)
        assert ours.shape == theirs.shape == (4, 5)
        np.testing.assert_allclose(ours.as_matrix(), theirs.as_matrix(), rtol=0, atol=1e-14)
        np.testing.assert_allclose(ours.as_davenport(axes, order), theirs.as_davenport(axes, order), rtol=0, atol=1e-12)


def test_mean_of_a_single_rotation_over_an_axis_is_itself():
    r = Rotation.from_rotvec([0.1, 0.2, 0.3])
    for axis in (None, 0, (0,)):
        np.testing.assert_allclose(r.mean(axis=axis).as_quat(), r.as_quat(), rtol=0, atol=1e-15)
        assert r.mean(axis=axis).single
    np.testing.assert_allclose(r.mean(axis=0).as_quat(), ScipyRotation.from_rotvec([0.1, 0.2, 0.3]).mean(axis=0).as_quat(),
                               rtol=0, atol=1e-15)


def test_operations_match_scipy():
    rng = np.random.default_rng(7)
    a, b = Rotation.random(6, rng=1), Rotation.random(6, rng=2)
    sa, sb = ScipyRotation.random(6, rng=1), ScipyRotation.random(6, rng=2)
    v = rng.standard_normal((6, 3))
    np.testing.assert_allclose((a * b).as_matrix(), (sa * sb).as_matrix(), rtol=0, atol=1e-14)
    np.testing.assert_allclose(a.apply(v, inverse=True), sa.apply(v, inverse=True), rtol=0, atol=1e-14)
    np.testing.assert_allclose((a ** 0.3).as_matrix(), (sa ** 0.3).as_matrix(), rtol=0, atol=1e-14)
    np.testing.assert_allclose(a.as_euler("XYZ"), sa.as_euler("XYZ"), rtol=0, atol=1e-12)
    np.testing.assert_allclose(a.as_mrp(), sa.as_mrp(), rtol=0, atol=1e-14)
    np.testing.assert_allclose(a.mean(weights=np.arange(1, 7)).as_matrix(),
                               sa.mean(weights=np.arange(1, 7)).as_matrix(), rtol=0, atol=1e-14)
    r, rssd = Rotation.align_vectors(v, a.apply(v))
    s, srssd = ScipyRotation.align_vectors(v, sa.apply(v))
    np.testing.assert_allclose(r.as_quat(), s.as_quat(), rtol=0, atol=1e-12)
    assert isinstance(rssd, float)
    assert a.approx_equal(a * Rotation.from_rotvec([0, 0, 1e-9])).all()
    assert repr(Rotation.identity()) == repr(ScipyRotation.identity())
    assert pickle.loads(pickle.dumps(a)).as_quat().tolist() == a.as_quat().tolist()


def test_bad_input_is_refused_before_any_work():
    r = Rotation.random(3, rng=0)
    with pytest.raises(ValueError, match="exponent must be a scalar"):
        r ** np.array([1.0, 2.0])
    with pytest.raises(NotImplementedError, match="modulus"):
        pow(r, 2, 3)
    with pytest.raises(ValueError, match="a must have shape"):
        Rotation.align_vectors(np.ones((2, 2, 3)), np.ones((2, 2, 3)))
    with pytest.raises(ValueError, match="either rng or random_state"):
        Rotation.random(2, rng=0, random_state=0)
    with pytest.raises(TypeError, match="value must be a kreisel.scipy Rotation"):
        r[0] = ScipyRotation.identity()


def test_kreisel_accepts_its_scipy_rotations_wherever_it_takes_a_rotation():
    r = Rotation.from_rotvec([0.1, 0.2, 0.3])
    pose = kr.RigidTransform(r, [1.0, 2.0, 3.0])
    np.testing.assert_allclose(pose.as_quat(), r.to_kreisel().as_quat(), rtol=0, atol=1e-16)
