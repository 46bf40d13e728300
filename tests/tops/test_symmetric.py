import numpy as np
import pytest

import kreisel as kr
from kreisel.so3 import quat_apply


@pytest.mark.parametrize("I1, I3", [(1.0, 2.0), (2.0, 1.0), (1.5, 0.3)])
@pytest.mark.parametrize("theta0", [0.3, 1.2, 2.5])
def test_regular_precession_matches_chapter_and_exact_free_top(reference, I1, I3, theta0):
    top = kr.SymmetricTop(I1, I3)
    J, phi0, psi0 = 1.7, 0.4, -0.9
    t = np.linspace(0.0, 15.0, 151)
    angles = top.euler_angles(t, J, theta0, phi0, psi0)
    # Theory §5.7 (3), written out
    np.testing.assert_allclose(angles[:, 0], J * t / I1 + phi0, rtol=1e-15)
    np.testing.assert_allclose(angles[:, 1], theta0)
    np.testing.assert_allclose(angles[:, 2], -(I3 - I1) * J * np.cos(theta0) * t / (I1 * I3) + psi0, rtol=1e-14, atol=1e-15)
    tr = top.solve(t, J, theta0, phi0, psi0)
    # Theory §5.7 (4): ω in the body
    Omega = (I3 - I1) * J * np.cos(theta0) / (I1 * I3)
    body = np.stack(
        [
            J * np.sin(theta0) / I1 * np.cos(Omega * t + np.pi / 2 - psi0),
            J * np.sin(theta0) / I1 * np.sin(Omega * t + np.pi / 2 - psi0),
            np.full_like(t, J * np.cos(theta0) / I3),
        ],
        axis=-1,
    )
    np.testing.assert_allclose(tr.omega, body, atol=1e-14)
    # Theory §5.7 (5): ω in space
    k = (I3 - I1) / (2 * I1 * I3) * J * np.sin(2 * theta0)
    space = np.stack(
        [
            k * np.cos(J * t / I1 + phi0 + np.pi / 2),
            k * np.sin(J * t / I1 + phi0 + np.pi / 2),
            np.full_like(t, ((I1 + I3) + (I1 - I3) * np.cos(2 * theta0)) / (2 * I1 * I3) * J),
        ],
        axis=-1,
    )
    np.testing.assert_allclose(top.angular_velocity(t, J, theta0, phi0, psi0, frame="space"), space, atol=1e-14)
    np.testing.assert_allclose(quat_apply(tr.q, tr.omega), space, atol=1e-13)
    # J stays along space z, and the same motion solves Euler's equations
    np.testing.assert_allclose(quat_apply(tr.q, [I1, I1, I3] * tr.omega), np.broadcast_to([0, 0, J], body.shape), atol=1e-13)
    omega_ref, q_ref = reference((I1, I1, I3), tr.omega[0], tr.q[0], t)
    np.testing.assert_allclose(tr.q, q_ref, atol=1e-11)
    exact = kr.EulerTop(I1, I1, I3).solve(t, tr.omega[0], tr.q[0])
    np.testing.assert_allclose(exact.q, tr.q, atol=1e-12)


@pytest.mark.parametrize("I1, I3", [(1.0, 2.0), (2.0, 1.0)])
@pytest.mark.parametrize("theta0", [0.4, 2.2])
def test_cones_against_the_motion(I1, I3, theta0):
    top = kr.SymmetricTop(I1, I3)
    J = 1.3
    cones = top.cones(J, theta0)
    t = np.linspace(0.0, 10.0, 400)
    tr = top.solve(t, J, theta0)
    omega_space = quat_apply(tr.q, tr.omega)
    e3_space = quat_apply(tr.q, [0.0, 0.0, 1.0])
    axis = np.sign(np.cos(theta0))  # the half of the symmetry axis on J's side
    angle = lambda a, b: np.arccos(np.clip(np.sum(a * b, -1) / np.linalg.norm(a, axis=-1) / np.linalg.norm(b, axis=-1), -1, 1))
    np.testing.assert_allclose(angle(omega_space, np.array([0, 0, 1.0])), cones.space_half_angle, atol=1e-7)
    np.testing.assert_allclose(angle(tr.omega, np.array([0, 0, axis])), cones.body_half_angle, atol=1e-7)
    # which cone is inside: J lies inside the body cone iff the space cone is inside it
    j_to_axis = angle(np.array([0, 0, 1.0]), axis * e3_space)
    inside = j_to_axis[0] < cones.body_half_angle
    assert inside == (cones.relation == "space cone inside body cone")
    # senses: ω about J in space, and ω about the axis in the body
    space_sense = np.sign(np.cross(omega_space[:-1], omega_space[1:])[:, 2])
    body_sense = np.sign(np.cross(tr.omega[:-1], tr.omega[1:])[:, 2] * axis)
    assert np.all(space_sense > 0)
    assert np.all((space_sense == body_sense) == cones.same_sense)
    assert cones.space_rate == pytest.approx(J / I1)
    assert cones.body_rate == pytest.approx(top.body_precession_rate(J, theta0))


def test_bad_input():
    with pytest.raises(ValueError, match="theta0"):
        kr.SymmetricTop(1.0, 2.0).euler_angles([0.0], 1.0, 4.0)
    with pytest.raises(ValueError, match="J must be"):
        kr.SymmetricTop(1.0, 2.0).cones(-1.0, 0.3)
    with pytest.raises(ValueError, match="frame"):
        kr.SymmetricTop(1.0, 2.0).angular_velocity([0.0], 1.0, 0.3, frame="lab")
