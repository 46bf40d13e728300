"""Change of base point (Theory §1.3 corollary) and Chasles/Mozzi screws of finite displacements."""

import numpy as np
import pytest

from kreisel.se3 import RigidTransform, Screw, change_base_point

TIGHT = 1e-13


def assert_same_pose(a, b, atol=TIGHT):
    np.testing.assert_allclose(a.as_matrix(), b.as_matrix(), rtol=0, atol=atol)


def test_change_of_base_point_keeps_rotation_and_moves_every_point_alike():
    rng = np.random.default_rng(1)
    t_c = RigidTransform.random(20, rng=2, translation_scale=2.0)
    r_ca = rng.normal(size=(20, 3))  # body components of the new base point A, relative to C
    r_cp = rng.normal(size=(20, 3))  # a body point P
    t_a = change_base_point(t_c, r_ca)
    # the corollary: R unchanged ...
    np.testing.assert_array_equal(t_a.as_quat(), t_c.as_quat())
    np.testing.assert_array_equal(t_a.rotation.as_matrix(), t_c.rotation.as_matrix())
    # ... the new translation is where A went ...
    np.testing.assert_allclose(t_a.translation, t_c.apply(r_ca), rtol=0, atol=TIGHT)
    # ... and r_P = R r′_AP + r_A = R r′_CP + r_C for every body point
    np.testing.assert_allclose(t_a.apply(r_cp - r_ca), t_c.apply(r_cp), rtol=0, atol=TIGHT)
    assert_same_pose(t_a, t_c * RigidTransform.from_translation(r_ca))
    assert_same_pose(t_c.change_base_point(r_ca), t_a, atol=0)


def test_change_of_base_point_refuses_bad_input():
    with pytest.raises(TypeError, match="transform"):
        change_base_point(np.eye(4), [0, 0, 0])
    with pytest.raises(ValueError, match="offset"):
        change_base_point(RigidTransform.identity(), [0, 0])


def check_screw(t, s):
    """The screw reproduces the pose, and its parameters mean what they say."""
    assert isinstance(s, Screw)
    assert_same_pose(RigidTransform.from_screw(s.axis, s.point, s.angle, s.translation), t)
    np.testing.assert_allclose(np.linalg.norm(s.axis, axis=-1), 1.0, rtol=0, atol=1e-15)
    assert np.all((s.angle >= 0) & (s.angle <= np.pi))
    np.testing.assert_allclose(np.sum(s.point * s.axis, axis=-1), 0.0, atol=1e-12)  # closest to the origin
    # points of the axis only slide along it (Mozzi)
    for lam in (0.0, 2.5):
        on_axis = s.point + lam * s.axis
        np.testing.assert_allclose(t.apply(on_axis), on_axis + s.translation[..., None] * s.axis, atol=1e-12)


def test_screw_round_trip_random_poses():
    t = RigidTransform.random(100, rng=5, translation_scale=3.0)
    s = t.as_screw()
    check_screw(t, s)
    np.testing.assert_allclose(s.pitch, s.translation / s.angle, rtol=1e-15)


def test_screw_is_the_exponential_coordinates():
    t = RigidTransform.random(30, rng=6)
    s = t.as_screw()
    omega = s.angle[:, None] * s.axis
    v = np.cross(s.point, omega) + s.pitch[:, None] * omega  # v = -ω × p + h ω
    np.testing.assert_allclose(t.as_exp_coords(), np.concatenate([omega, v], axis=-1), atol=1e-12)


def test_pure_rotations():
    axis = np.array([1.0, 2.0, -2.0]) / 3.0
    point = np.array([0.5, 1.0, 1.25])  # any point: from_screw accepts points not closest to the origin
    t = RigidTransform.from_screw(axis, point, 1.2, 0.0)
    s = t.as_screw()
    check_screw(t, s)
    np.testing.assert_allclose(s.axis, axis, atol=1e-15)
    np.testing.assert_allclose(s.angle, 1.2, rtol=1e-15)
    assert abs(s.translation) < 1e-15 and abs(s.pitch) < 1e-15
    np.testing.assert_allclose(s.point, point - (point @ axis) * axis, atol=1e-15)


def test_pure_translations_and_identity():
    t = RigidTransform.from_translation([[0.0, 3.0, 4.0], [0.0, 0.0, 0.0]])
    with np.errstate(all="raise"):  # no division by zero anywhere
        s = t.as_screw()
    check_screw(t, s)
    np.testing.assert_array_equal(s.axis, [[0.0, 0.6, 0.8], [0.0, 0.0, 1.0]])
    np.testing.assert_array_equal(s.angle, [0.0, 0.0])
    np.testing.assert_array_equal(s.translation, [5.0, 0.0])
    np.testing.assert_array_equal(s.point, np.zeros((2, 3)))
    np.testing.assert_array_equal(s.pitch, [np.inf, 0.0])
    assert_same_pose(RigidTransform.from_screw([0, 0, 2], [7, 7, 7], 0.0, 5.0), RigidTransform.from_translation([0, 0, 5]))


@pytest.mark.parametrize("angle", [np.pi, np.pi - 1e-12, np.pi - 1e-7, 1e-9, 1e-15])
def test_screw_accuracy_near_half_turn_and_tiny_angles(angle):
    axis = np.array([2.0, -1.0, 2.0]) / 3.0
    point = np.array([1.0, 2.0, 0.0])  # perpendicular to the axis
    t = RigidTransform.from_screw(axis, point, angle, 0.7)
    s = t.as_screw()
    np.testing.assert_allclose(s.angle, angle, rtol=1e-15)
    np.testing.assert_allclose(s.axis, axis, rtol=0, atol=2e-16)
    np.testing.assert_allclose(s.translation, 0.7, rtol=1e-15)
    # The axis point of a tiny rotation is ill-conditioned by nature: it comes from the
    # part of r_C across the axis, ~angle |p|, so rounding of r_C (~1e-16) is amplified by 1/angle.
    np.testing.assert_allclose(s.point, point, rtol=0, atol=1e-15 + 4e-16 / angle)


def test_from_screw_refuses_zero_axis_and_bad_shapes():
    with pytest.raises(ValueError, match="axis"):
        RigidTransform.from_screw([0, 0, 0], [0, 0, 0], 1.0)
    with pytest.raises(ValueError, match="point"):
        RigidTransform.from_screw([0, 0, 1], [0, 0], 1.0)
    with pytest.raises(ValueError, match="angle"):
        RigidTransform.from_screw([0, 0, 1], [0, 0, 0], np.nan)


def test_finite_screw_is_the_instantaneous_screw_of_the_uniform_motion():
    # T(s) = exp(s ξ) has the constant space twist ξ = (ω, v): v is the velocity of the
    # space point at the origin (Theory §3.8). Its instantaneous axis, found independently
    # by kreisel.kinematics.screw_axis, is the screw of the finite displacement T(1).
    from kreisel.kinematics import screw_axis

    rng = np.random.default_rng(9)
    omega = rng.normal(size=(10, 3))
    omega *= (np.linspace(0.1, 3.1, 10) / np.linalg.norm(omega, axis=-1))[:, None]
    v = rng.normal(size=(10, 3))
    finite = RigidTransform.from_exp_coords(np.concatenate([omega, v], axis=-1)).as_screw()
    instantaneous = screw_axis(omega, v)
    np.testing.assert_allclose(finite.axis, instantaneous.direction, atol=1e-15)
    np.testing.assert_allclose(finite.point, instantaneous.point, atol=1e-14)
    np.testing.assert_allclose(finite.pitch, instantaneous.pitch, rtol=1e-13)
    np.testing.assert_allclose(finite.angle, np.linalg.norm(omega, axis=-1), rtol=1e-15)
