"""RigidTransform: group operations against 4×4 matrix products and scipy, conversions, refusals."""

import numpy as np
import pytest
from scipy.spatial.transform import RigidTransform as ScipyRigidTransform
from scipy.spatial.transform import Rotation as ScipyRotation

import kreisel as kr
from kreisel.se3 import RigidTransform

TIGHT = 1e-13


def homogeneous(points):
    return np.concatenate([points, np.ones(points.shape[:-1] + (1,))], axis=-1)


@pytest.fixture
def poses():
    return RigidTransform.random(50, rng=1, translation_scale=3.0), RigidTransform.random(50, rng=2)


def test_exported_at_top_level():
    assert kr.RigidTransform is RigidTransform


def test_composition_is_matrix_product(poses):
    a, b = poses
    np.testing.assert_allclose((a * b).as_matrix(), a.as_matrix() @ b.as_matrix(), rtol=0, atol=TIGHT)


def test_composition_broadcasts_single_against_batch(poses):
    a, b = poses
    c = a[3] * b
    assert c.shape == (50,)
    np.testing.assert_allclose(c.as_matrix(), a.as_matrix()[3] @ b.as_matrix(), rtol=0, atol=TIGHT)
    grid = a[:4, None] * b[None, :5]
    assert grid.shape == (4, 5)
    np.testing.assert_allclose(grid.as_matrix()[2, 1], a.as_matrix()[2] @ b.as_matrix()[1], rtol=0, atol=TIGHT)


def test_composition_is_associative(poses):
    a, b = poses
    c = RigidTransform.random(50, rng=3)
    np.testing.assert_allclose(((a * b) * c).as_matrix(), (a * (b * c)).as_matrix(), rtol=0, atol=TIGHT)


def test_inverse_is_matrix_inverse(poses):
    a, _ = poses
    np.testing.assert_allclose(a.inv().as_matrix(), np.linalg.inv(a.as_matrix()), rtol=0, atol=TIGHT)
    np.testing.assert_allclose((a * a.inv()).as_matrix(), np.broadcast_to(np.eye(4), (50, 4, 4)), rtol=0, atol=TIGHT)


def test_apply_points_and_vectors(poses):
    a, _ = poses
    p = np.random.default_rng(4).normal(size=(50, 3))
    m = a.as_matrix()
    expected = np.einsum("...ij,...j->...i", m, homogeneous(p))[..., :3]
    np.testing.assert_allclose(a.apply(p), expected, rtol=0, atol=TIGHT)
    np.testing.assert_allclose(a.apply(a.apply(p), inverse=True), p, rtol=0, atol=TIGHT)
    np.testing.assert_allclose(a.apply_vector(p), np.einsum("...ij,...j->...i", m[..., :3, :3], p), rtol=0, atol=TIGHT)
    np.testing.assert_allclose(a.apply_vector(a.apply_vector(p), inverse=True), p, rtol=0, atol=TIGHT)


def test_single_transform_moves_many_points():
    t = RigidTransform.random(rng=5)
    p = np.random.default_rng(6).normal(size=(7, 2, 3))
    out = t.apply(p)
    assert out.shape == (7, 2, 3)
    np.testing.assert_allclose(out[4, 1], t.apply(p[4, 1]), rtol=0, atol=0)


def test_agrees_with_scipy(poses):
    a, b = poses
    sa, sb = a.to_scipy(), b.to_scipy()
    assert isinstance(sa, ScipyRigidTransform)
    p = np.random.default_rng(7).normal(size=(50, 3))
    np.testing.assert_allclose(a.as_matrix(), sa.as_matrix(), rtol=0, atol=TIGHT)
    np.testing.assert_allclose((a * b).as_matrix(), (sa * sb).as_matrix(), rtol=0, atol=TIGHT)
    np.testing.assert_allclose(a.inv().as_matrix(), sa.inv().as_matrix(), rtol=0, atol=TIGHT)
    np.testing.assert_allclose(a.apply(p), sa.apply(p), rtol=0, atol=TIGHT)
    np.testing.assert_allclose(a.as_exp_coords(), sa.as_exp_coords(), rtol=0, atol=1e-12)
    # scipy does not fix the sign of the real part; compare the double cover once signs are aligned
    ours, theirs = a.as_dual_quat(), sa.as_dual_quat(scalar_first=True)
    sign = np.sign(np.sum(ours[:, :4] * theirs[:, :4], axis=-1))[:, None]
    np.testing.assert_allclose(ours, sign * theirs, rtol=0, atol=TIGHT)
    back = RigidTransform.from_scipy(sa)
    np.testing.assert_allclose(back.as_matrix(), a.as_matrix(), rtol=0, atol=TIGHT)
    xi = np.random.default_rng(8).normal(size=(20, 6))
    np.testing.assert_allclose(
        RigidTransform.from_exp_coords(xi).as_matrix(), ScipyRigidTransform.from_exp_coords(xi).as_matrix(), atol=1e-13
    )


@pytest.mark.parametrize("kind", ["kreisel", "scipy", "matrix", "quat"])
def test_rotation_inputs(kind):
    psi = np.array([0.3, -1.2, 2.0])
    q = kr.rotvec_to_quat(psi)
    rotation = {
        "kreisel": kr.Rotation.from_quat(q),
        "scipy": ScipyRotation.from_rotvec(psi),
        "matrix": kr.rotvec_to_matrix(psi),
        "quat": 2.5 * q,  # any nonzero norm is accepted and normalised
    }[kind]
    t = RigidTransform.from_rotation_translation(rotation, [1.0, 2.0, 3.0])
    np.testing.assert_allclose(t.as_matrix()[:3, :3], kr.rotvec_to_matrix(psi), rtol=0, atol=TIGHT)
    np.testing.assert_allclose(t.translation, [1.0, 2.0, 3.0])
    np.testing.assert_allclose(t.rotation.as_matrix(), kr.rotvec_to_matrix(psi), rtol=0, atol=TIGHT)


def test_matrix_and_dual_quat_round_trips(poses):
    a, _ = poses
    np.testing.assert_allclose(RigidTransform.from_matrix(a.as_matrix()).as_matrix(), a.as_matrix(), rtol=0, atol=TIGHT)
    dq = a.as_dual_quat()
    np.testing.assert_allclose(np.sum(dq[:, :4] ** 2, axis=-1), 1.0, rtol=0, atol=TIGHT)
    np.testing.assert_allclose(np.sum(dq[:, :4] * dq[:, 4:], axis=-1), 0.0, rtol=0, atol=TIGHT)
    np.testing.assert_allclose(RigidTransform.from_dual_quat(dq).as_matrix(), a.as_matrix(), rtol=0, atol=TIGHT)
    np.testing.assert_allclose(RigidTransform.from_dual_quat(-dq).as_matrix(), a.as_matrix(), rtol=0, atol=TIGHT)


def test_dual_quat_layout_is_scalar_first():
    # pure translation by (2, 0, 0): q_r = 1, q_d = ½ (0, 2, 0, 0)
    dq = RigidTransform.from_translation([2.0, 0.0, 0.0]).as_dual_quat()
    np.testing.assert_array_equal(dq, [1, 0, 0, 0, 0, 1, 0, 0])


def test_from_rotation_and_from_translation():
    r = RigidTransform.from_rotation([0.0, 0.0, 0.0, 1.0])
    t = RigidTransform.from_translation([1.0, 2.0, 3.0])
    np.testing.assert_allclose((t * r).apply([1.0, 0.0, 0.0]), [0.0, 2.0, 3.0], atol=TIGHT)
    np.testing.assert_allclose((r * t).apply([1.0, 0.0, 0.0]), [-2.0, -2.0, 3.0], atol=TIGHT)


def test_identity_random_indexing_len_iter():
    ident = RigidTransform.identity((2, 3))
    assert ident.shape == (2, 3) and len(ident) == 2
    np.testing.assert_array_equal(ident.as_matrix(), np.broadcast_to(np.eye(4), (2, 3, 4, 4)))
    assert RigidTransform.identity().single
    a = RigidTransform.random((4, 5), rng=9)
    b = RigidTransform.random((4, 5), rng=9)
    np.testing.assert_array_equal(a.as_matrix(), b.as_matrix())
    assert a[1:3].shape == (2, 5)
    assert a[..., 2].shape == (4,)
    assert a[np.array([True, False, True, False])].shape == (2, 5)
    np.testing.assert_array_equal(a[2, 3].as_matrix(), a.as_matrix()[2, 3])
    assert [x.shape for x in a] == [(5,)] * 4


def test_repr_is_readable():
    t = RigidTransform.from_rotation_translation([1.0, 0.0, 0.0, 0.0], [1.0, 2.0, 3.0])
    assert repr(t) == "RigidTransform(quat=[1.0, 0.0, 0.0, 0.0], translation=[1.0, 2.0, 3.0])"
    assert repr(RigidTransform.identity(2)).startswith("RigidTransform(shape=(2,), quat=")


# -- refusals ------------------------------------------------------------------------------


def test_refuses_non_rigid_matrices():
    m = np.eye(4)
    m[3, 0] = 0.5
    with pytest.raises(ValueError, match="matrix"):
        RigidTransform.from_matrix(m)
    m = np.eye(4)
    m[0, 0] = 1.1
    with pytest.raises(ValueError, match="matrix"):
        RigidTransform.from_matrix(m)
    with pytest.raises(ValueError, match="matrix"):
        RigidTransform.from_matrix(np.diag([1.0, 1.0, -1.0, 1.0]))  # a reflection
    with pytest.raises(ValueError, match="matrix"):
        RigidTransform.from_matrix(np.eye(3))


def test_refuses_non_unit_dual_quaternions():
    with pytest.raises(ValueError, match="dual_quat"):
        RigidTransform.from_dual_quat([2, 0, 0, 0, 0, 0, 0, 0])
    with pytest.raises(ValueError, match="dual_quat"):
        RigidTransform.from_dual_quat([1, 0, 0, 0, 0.5, 0, 0, 0])  # q_r·q_d != 0
    with pytest.raises(ValueError, match="dual_quat"):
        RigidTransform.from_dual_quat([1, 0, 0, 0, 0, 0, 0])


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: RigidTransform.from_rotation_translation(np.eye(3), [1.0, 2.0]), "translation"),
        (lambda: RigidTransform.from_rotation_translation(np.ones((3, 3)), [1.0, 2.0, 3.0]), "rotation"),
        (lambda: RigidTransform.from_rotation_translation([1.0, 0.0, 0.0], [1.0, 2.0, 3.0]), "rotation"),
        (lambda: RigidTransform.from_rotation_translation([0.0, 0.0, 0.0, 0.0], [1.0, 2.0, 3.0]), "rotation"),
        (lambda: RigidTransform.from_translation([np.nan, 0.0, 0.0]), "translation"),
        (lambda: RigidTransform.from_exp_coords(np.zeros(5)), "exp_coords"),
        (lambda: RigidTransform.identity().apply(np.zeros(2)), "points"),
        (lambda: RigidTransform.identity().apply([[0.0, 0.0, 0.0], [np.nan, 0.0, 0.0]]), "points"),
        (lambda: RigidTransform.identity().apply([np.inf, -np.inf, 0.0]), "points"),
        (lambda: RigidTransform.from_matrix(np.full((4, 4), np.nan)), "matrix"),
        (lambda: RigidTransform.identity().apply_vector(np.zeros((3, 2))), "vectors"),
    ],
)
def test_refuses_wrong_shapes_and_values(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_accepts_huge_finite_points_whose_sum_overflows():
    p = np.array([1e308, 1e308, 0.0])
    np.testing.assert_array_equal(RigidTransform.identity().apply(p), p)


def test_refuses_container_use_of_single_and_foreign_products():
    t = RigidTransform.identity()
    with pytest.raises(TypeError):
        len(t)
    with pytest.raises(TypeError):
        t[0]
    with pytest.raises(TypeError):
        t * np.eye(4)
    with pytest.raises(TypeError):
        RigidTransform.from_scipy(np.eye(4))


# -- powers and means (scipy parity) --------------------------------------------


@pytest.mark.parametrize("p", [0, 1, -1, 0.5, -2.3, 3, 1e-9])
def test_powers_match_scipy_and_exp_of_scaled_log(p):
    T = RigidTransform.random((4, 5), rng=12)
    got = T**p
    np.testing.assert_allclose(got.as_matrix(), (T.to_scipy() ** p).as_matrix(), atol=5e-15)
    np.testing.assert_allclose(got.as_matrix(), RigidTransform.from_exp_coords(p * T.as_exp_coords()).as_matrix(), atol=5e-15)


def test_power_halves_compose_to_the_whole_and_exponents_broadcast():
    T = RigidTransform.random(6, rng=13)
    np.testing.assert_allclose(((T**0.5) * (T**0.5)).as_matrix(), T.as_matrix(), atol=5e-15)
    np.testing.assert_allclose((T**-1).as_matrix(), T.inv().as_matrix(), atol=0)
    np.testing.assert_array_equal((T**0).as_matrix(), RigidTransform.identity(6).as_matrix())
    p = np.linspace(-2.0, 2.0, 6)
    np.testing.assert_allclose((T**p).as_matrix(), [(T[i] ** p[i]).as_matrix() for i in range(6)], atol=1e-14)


@pytest.mark.parametrize("axis", [None, 0, 1, (0, 1)])
def test_mean_matches_scipy(axis):
    T = RigidTransform.random((4, 5), rng=14)
    w = np.random.default_rng(15).random((4, 5))
    for weights in (None, w):
        np.testing.assert_allclose(
            T.mean(weights, axis=axis).as_matrix(), T.to_scipy().mean(weights, axis=axis).as_matrix(), atol=5e-15
        )
    with pytest.raises(ValueError, match="empty"):
        RigidTransform.identity(0).mean()
    with pytest.raises(ValueError, match="weights"):
        T.mean(-w)


@pytest.mark.parametrize("axis", [None, 0, ()])
def test_the_mean_of_a_single_pose_is_itself_as_in_scipy(axis):
    T = RigidTransform.random(rng=16)
    ours, theirs = T.mean(axis=axis), T.to_scipy().mean(axis=axis)
    assert ours.shape == theirs.as_matrix().shape[:-2]
    np.testing.assert_allclose(ours.as_matrix(), theirs.as_matrix(), atol=5e-15)
    np.testing.assert_allclose(T.mean([3.0]).as_matrix(), T.as_matrix(), atol=5e-15)
