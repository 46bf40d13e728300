"""Screw axis of a twist, planar instantaneous centre and centrodes (Theory §3.8)."""

import numpy as np
import pytest

from kreisel.kinematics import centrodes, instantaneous_centre, point_velocity, screw_axis


def test_screw_axis_properties():
    rng = np.random.default_rng(7)
    omega = rng.normal(size=(200, 3))
    v = rng.normal(size=(200, 3))
    c = rng.normal(size=(200, 3))
    s = screw_axis(omega, v, c)
    assert (s.kind == "screw").all()
    # points on the axis move along it with the axial velocity h ω
    for lam in [0.0, 2.5]:
        on_axis = s.point + lam * s.direction
        vel = point_velocity(omega, on_axis - c, v)
        np.testing.assert_allclose(vel, s.axial_velocity, atol=1e-12)
        np.testing.assert_allclose(np.cross(vel, omega), 0.0, atol=1e-12)
    np.testing.assert_allclose(s.axial_velocity, s.pitch[:, None] * omega, atol=1e-15)
    np.testing.assert_allclose(np.einsum("ij,ij->i", s.point - c, omega), 0.0, atol=1e-12)  # nearest point
    np.testing.assert_allclose(np.linalg.norm(s.direction, axis=1), 1.0, atol=1e-15)
    # the axis does not depend on the reference point (Theory §3.7 corollary: same ω for every base point)
    c2 = c + rng.normal(size=(200, 3))
    s2 = screw_axis(omega, point_velocity(omega, c2 - c, v), c2)
    np.testing.assert_allclose(s2.pitch, s.pitch, rtol=1e-11, atol=1e-12)
    np.testing.assert_allclose(np.cross(s2.point - s.point, omega), 0.0, atol=1e-11)


def test_classification():
    # rolling wheel: pure rotation about the contact line
    s = screw_axis([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    assert s.kind == "rotation" and s.pitch == 0.0
    np.testing.assert_allclose(s.point, [0, 0, 0], atol=1e-15)
    np.testing.assert_allclose(s.axial_velocity, 0.0)
    # translation: ω = 0
    t = screw_axis([0.0, 0.0, 0.0], [0.0, 3.0, 4.0])
    assert t.kind == "translation" and np.isinf(t.pitch) and np.isnan(t.point).all()
    np.testing.assert_allclose(t.direction, [0, 0.6, 0.8])
    np.testing.assert_allclose(t.axial_velocity, [0, 3.0, 4.0])
    # a screw: rotation about z through (1, 0, 0) with axial speed 2 → pitch 2/ω
    w = 4.0
    v_origin = np.cross([0, 0, w], [0.0 - 1.0, 0.0, 0.0]) + [0, 0, 2.0]
    sc = screw_axis([0, 0, w], v_origin)
    assert sc.kind == "screw" and sc.pitch == pytest.approx(2.0 / w, rel=1e-15)
    np.testing.assert_allclose(sc.point, [1.0, 0, 0], atol=1e-15)
    kinds = screw_axis([[0, 0, 1.0], [0, 0, 0], [0, 0, 1.0]], [[1.0, 0, 0], [1.0, 0, 0], [1.0, 0, 1.0]]).kind
    assert kinds.tolist() == ["rotation", "translation", "screw"]
    # tolerances
    assert screw_axis([0, 0, 1.0], [1.0, 0, 1e-14]).kind == "rotation"
    assert screw_axis([0, 0, 1e-20], [1.0, 0, 0], omega_atol=1e-15).kind == "translation"


def test_instantaneous_centre_has_zero_velocity():
    rng = np.random.default_rng(2)
    omega = rng.normal(size=50)
    v = rng.normal(size=(50, 2))
    c = rng.normal(size=(50, 2))
    centre = instantaneous_centre(omega, v, c)
    w3 = np.stack([np.zeros(50), np.zeros(50), omega], -1)
    vel = point_velocity(w3, np.pad(centre - c, ((0, 0), (0, 1))), np.pad(v, ((0, 0), (0, 1))))
    np.testing.assert_allclose(vel, 0.0, atol=1e-12)
    assert np.isnan(instantaneous_centre(0.0, [1.0, 0.0])).all()


def _wheel(radius, speed):
    """Wheel rolling to the right on y = 0: centre (speed t, radius), angle −speed t / radius."""
    return (lambda t: -speed * t / radius), (lambda t: np.stack([speed * t, radius + 0 * t], -1))


@pytest.mark.parametrize("sampled", [False, True])
def test_rolling_wheel_centrodes(sampled):
    """Space centrode: the ground; body centrode: the rim (Theory §3.8, 例 rolling on a rail)."""
    radius, speed = 0.4, 1.5
    angle, centre = _wheel(radius, speed)
    t = np.linspace(0.0, 2.0, 41)
    if sampled:
        c = centrodes(t, angle(t), centre(t))
    else:
        c = centrodes(t, angle, centre)
    np.testing.assert_allclose(c.space[:, 1], 0.0, atol=1e-9)
    np.testing.assert_allclose(c.space[:, 0], speed * t, atol=1e-9)
    np.testing.assert_allclose(np.linalg.norm(c.body, axis=-1), radius, atol=1e-9)
    # the body centrode is traversed once per turn: contact point angle in body axes advances by the wheel angle
    body_angle = np.unwrap(np.arctan2(c.body[:, 1], c.body[:, 0]))
    np.testing.assert_allclose(body_angle - body_angle[0], speed * t / radius, atol=1e-8)


def test_ladder_centrodes():
    """Ladder sliding down a wall: space centrode circle of radius L, body centrode circle of radius L/2."""
    L = 3.0
    t = np.linspace(0.1, 1.4, 30)  # θ(t) = t: angle of the ladder with the floor

    def midpoint(s):
        return np.stack([L * np.cos(s) / 2, L * np.sin(s) / 2], -1)

    c = centrodes(t, lambda s: -s, midpoint, angle_rate=lambda s: -np.ones_like(s))
    np.testing.assert_allclose(c.space, np.stack([L * np.cos(t), L * np.sin(t)], -1), atol=1e-10)
    np.testing.assert_allclose(np.linalg.norm(c.body, axis=-1), L / 2, atol=1e-10)
    # in the body frame the centre runs around the circle whose diameter is the ladder (Thales)
    end_a = np.array([-L / 2, 0.0])  # the ladder lies along the body x axis, ends at ±L/2
    end_b = np.array([L / 2, 0.0])
    np.testing.assert_allclose(np.einsum("ij,ij->i", c.body - end_a, c.body - end_b), 0.0, atol=1e-9)
    # sampled values with their rates given as functions of t: the same centrodes
    sampled = centrodes(t, -t, midpoint(t), angle_rate=lambda s: -np.ones_like(s),
                        velocity=lambda s: np.stack([-L * np.sin(s) / 2, L * np.cos(s) / 2], -1))
    np.testing.assert_allclose(sampled.space, c.space, atol=1e-10)
    np.testing.assert_allclose(sampled.body, c.body, atol=1e-10)


def test_centrode_batches_and_bad_input():
    t = np.linspace(0, 1, 5)
    angle = np.stack([t, 2 * t])  # two bodies
    pos = np.stack([np.stack([t, 0 * t], -1)] * 2)
    c = centrodes(t, angle, pos)
    assert c.space.shape == (2, 5, 2) and c.body.shape == (2, 5, 2)
    with pytest.raises(ValueError, match="t must be"):
        centrodes(t[::-1], t, pos[0])
    with pytest.raises(ValueError, match="angle"):
        centrodes(t, t[:4], pos[0])
    with pytest.raises(ValueError, match="position"):
        centrodes(t, t, np.ones((5, 3)))


@pytest.mark.parametrize("scale", [2.0**514, 2.0**-514, 1e300, 1e-300])
def test_centrodes_of_sampled_motion_are_independent_of_the_time_unit(scale):
    # np.gradient multiplies three spacings: a span of 1e155 s overflowed and one of 1e-155 s lost digits;
    # the centrodes do not depend on the unit of time
    t = np.linspace(0.0, 1.0, 7)
    angle, position = 0.3 + t + 0.2 * t**2, np.stack([np.cos(t), 2.0 * t], axis=-1)
    base = centrodes(t, angle, position)
    scaled = centrodes(t * scale, angle, position)
    # (1e±300 times are rounded: differences of 1e-15 in the O(1) centrodes)
    np.testing.assert_allclose(scaled.space, base.space, rtol=1e-13, atol=1e-14)
    np.testing.assert_allclose(scaled.body, base.body, rtol=1e-13, atol=1e-14)
