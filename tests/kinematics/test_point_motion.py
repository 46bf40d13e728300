"""Body-point trajectories from sampled attitudes (Theory §3.7, §3.9)."""

import numpy as np
import pytest

from kreisel.dynamics.trajectory import Trajectory
from kreisel.kinematics import PointMotion, point_trajectory
from kreisel.so3 import quat_to_matrix, rotvec_to_quat


def spin(t, phase):
    """Rotation by phase(t) about a fixed tilted axis."""
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    return axis, rotvec_to_quat(phase[:, None] * axis)


def test_point_trajectory_from_trajectory_is_exact_for_polynomial_rates():
    # φ = t³: ω = 3t² n and r_C are polynomials of degree <= 4 in t, which the
    # five-point differences reproduce exactly; ω itself comes from the Trajectory.
    t = np.linspace(0.0, 2.0, 41)
    axis, q = spin(t, t**3)
    omega_body = np.outer(3 * t**2, axis)  # the spin axis has the same components in both frames
    tr = Trajectory(t, q, omega_body, [1.0, 2.0, 3.0])
    r_body = np.array([0.3, -1.0, 0.5])
    r_c = np.stack([t, t**2, np.zeros_like(t)], axis=-1)
    m = point_trajectory(r_body, trajectory=tr, translation=r_c)
    assert isinstance(m, PointMotion)
    arm = np.einsum("nij,j->ni", quat_to_matrix(q), r_body)
    w, eps = np.outer(3 * t**2, axis), np.outer(6 * t, axis)
    v_c = np.stack([np.ones_like(t), 2 * t, 0 * t], axis=-1)
    a_c = np.broadcast_to([0.0, 2.0, 0.0], (41, 3))
    np.testing.assert_allclose(m.position, arm + r_c, atol=1e-14)
    np.testing.assert_allclose(m.velocity, np.cross(w, arm) + v_c, atol=1e-12)
    np.testing.assert_allclose(
        m.acceleration, np.cross(eps, arm) + np.cross(w, np.cross(w, arm)) + a_c, atol=1e-11
    )


def exact_motion(t, r_body):
    """Uniform spin ω = 1.5 rad/s about a tilted axis and a circular drift of the base point."""
    axis, q = spin(t, 1.5 * t)
    arm = np.einsum("nij,j->ni", quat_to_matrix(q), r_body)
    w = 1.5 * axis
    r_c = np.stack([np.cos(t), np.sin(t), 0 * t], axis=-1)
    v_c = np.stack([-np.sin(t), np.cos(t), 0 * t], axis=-1)
    velocity = np.cross(w, arm) + v_c
    acceleration = np.cross(w, np.cross(w, arm)) - r_c
    return q, r_c, arm + r_c, velocity, acceleration


@pytest.mark.parametrize("representation", ["quat", "matrix"])
def test_point_trajectory_from_arrays_converges_at_the_stencil_order(representation):
    r_body = np.array([1.0, -0.5, 0.25])
    errors = []
    for n in (101, 201):
        t = np.linspace(0.0, 2.0, n)
        q, r_c, position, velocity, acceleration = exact_motion(t, r_body)
        rotation = q if representation == "quat" else quat_to_matrix(q)
        m = point_trajectory(r_body, t, rotation, r_c)
        np.testing.assert_allclose(m.position, position, atol=1e-14)
        errors.append([np.abs(m.velocity - velocity).max(), np.abs(m.acceleration - acceleration).max()])
    errors = np.array(errors)
    assert np.all(errors[0] < [1e-7, 2e-5])
    # five-point stencils: velocity errors O(Δt⁴), acceleration errors O(Δt³)
    np.testing.assert_allclose(errors[0] / errors[1], [16.0, 8.0], rtol=0.15)


def test_point_trajectory_handles_sign_flips_and_batches_of_points():
    t = np.linspace(0.0, 1.0, 51)
    q, r_c, *_ = exact_motion(t, np.zeros(3))
    flipped = q * np.where(np.arange(51) % 2, -1.0, 1.0)[:, None]  # same attitudes, alternating signs
    points = np.array([[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]])
    m = point_trajectory(points, t, flipped, r_c)
    assert m.velocity.shape == (2, 51, 3)
    np.testing.assert_allclose(m.velocity[1], point_trajectory(points[1], t, q, r_c).velocity, atol=1e-12)


def test_point_trajectory_refusals():
    t = np.linspace(0.0, 1.0, 5)
    q = np.tile([1.0, 0.0, 0.0, 0.0], (5, 1))
    tr = Trajectory(t, q, np.zeros((5, 3)), [1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="either"):
        point_trajectory([0, 0, 1], t, q, trajectory=tr)
    with pytest.raises(ValueError, match="rotation"):
        point_trajectory([0, 0, 1], t)
    with pytest.raises(TypeError, match="trajectory"):
        point_trajectory([0, 0, 1], trajectory=q)
    with pytest.raises(ValueError, match="rotation"):
        point_trajectory([0, 0, 1], t, q[:4])
    with pytest.raises(ValueError, match="translation"):
        point_trajectory([0, 0, 1], t, q, np.zeros((4, 3)))
    with pytest.raises(ValueError, match="body_point"):
        point_trajectory([0, 1], t, q)
    with pytest.raises(ValueError, match="t must"):
        point_trajectory([0, 0, 1], t[:2], q[:2])
    with pytest.raises(ValueError, match="t must"):
        point_trajectory([0, 0, 1], t[::-1], q)
