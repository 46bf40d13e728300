"""SU(2), Cayley–Klein, Euler parameters (Theory §A), Gibbs vectors and MRPs."""

import numpy as np
import pytest
from scipy.linalg import expm
from scipy.spatial.transform import Rotation as S

import kreisel as kr

SIGMA = np.array([[[0, 1], [1, 0]], [[0, -1j], [1j, 0]], [[1, 0], [0, -1]]])


def chapter_R_of_u(a, b):
    """R(u) of Theory §A (1), u = [[a, b], [-b*, a*]]."""
    ac, bc = np.conj(a), np.conj(b)
    return np.real(
        np.array(
            [
                [(a**2 + ac**2 - b**2 - bc**2) / 2, -1j / 2 * (a**2 - ac**2 + b**2 - bc**2), -(a * b + ac * bc)],
                [1j / 2 * (a**2 - ac**2 - b**2 + bc**2), (a**2 + ac**2 + b**2 + bc**2) / 2, 1j * (ac * bc - a * b)],
                [ac * b + a * bc, 1j * (ac * b - a * bc), a * ac - b * bc],
            ]
        )
    )


def chapter_R_of_cayley_klein(al, be, ga, de):
    """R(α, β, γ, δ) of Theory §A (3)."""
    return np.real(
        np.array(
            [
                [(al**2 + de**2 - be**2 - ga**2) / 2, -1j / 2 * (al**2 - de**2 + be**2 - ga**2), -al * be + ga * de],
                [1j / 2 * (al**2 - de**2 - be**2 + ga**2), (al**2 + de**2 + be**2 + ga**2) / 2, -1j * (ga * de + al * be)],
                [be * de - al * ga, 1j * (be * de + al * ga), al * de + be * ga],
            ]
        )
    )


def test_su2_is_exponential_of_pauli(rng):
    for psi in rng.normal(size=(10, 3)):
        u = kr.quat_to_su2(kr.rotvec_to_quat(psi))
        np.testing.assert_allclose(u, expm(-0.5j * np.einsum("j,jab->ab", psi, SIGMA)), atol=1e-15)


def test_su2_acts_by_conjugation_and_matches_chapter_matrix(random_quats, rng):
    for q in random_quats(20):
        u = kr.quat_to_su2(q)
        R = kr.quat_to_matrix(q)
        np.testing.assert_allclose(u @ u.conj().T, np.eye(2), atol=1e-15)
        assert np.linalg.det(u) == pytest.approx(1.0, abs=1e-15)
        np.testing.assert_allclose(chapter_R_of_u(u[0, 0], u[0, 1]), R, atol=2e-15)
        r = rng.normal(size=3)
        lhs = u @ np.einsum("j,jab->ab", r, SIGMA) @ u.conj().T
        np.testing.assert_allclose(lhs, np.einsum("j,jab->ab", R @ r, SIGMA), atol=1e-14)


def test_su2_homomorphism_and_double_cover(random_quats):
    p, q = random_quats(2)
    np.testing.assert_allclose(kr.quat_to_su2(kr.quat_multiply(p, q)), kr.quat_to_su2(p) @ kr.quat_to_su2(q), atol=1e-15)
    np.testing.assert_allclose(kr.quat_to_su2(-q), -kr.quat_to_su2(q))
    np.testing.assert_allclose(kr.su2_to_quat(kr.quat_to_su2(q)), q, atol=1e-15)
    np.testing.assert_allclose(kr.su2_to_quat(kr.quat_to_su2(-q)), -q, atol=1e-15)
    np.testing.assert_allclose(kr.quat_to_su2(kr.rotvec_to_quat([0, 0, 2 * np.pi])), -np.eye(2), atol=1e-15)


def test_cayley_klein(random_quats):
    q = random_quats(20)
    ck = kr.quat_to_cayley_klein(q)
    al, be, ga, de = np.moveaxis(ck, -1, 0)
    np.testing.assert_allclose(de, al.conj(), atol=0)
    np.testing.assert_allclose(ga, -be.conj(), atol=0)
    np.testing.assert_allclose(al * de - be * ga, 1.0, atol=1e-15)
    for i in range(20):
        np.testing.assert_allclose(chapter_R_of_cayley_klein(*ck[i]), kr.quat_to_matrix(q[i]), atol=2e-15)
    np.testing.assert_allclose(kr.cayley_klein_to_quat(ck), q, atol=1e-15)


def test_euler_parameters_active_and_passive(random_quats):
    """Theory §A (2): e_j = -n_j sin(ψ/2); the printed matrix is R of e and Goldstein's passive A of q."""
    q = random_quats(20)
    e = kr.quat_to_euler_parameters(q)
    np.testing.assert_allclose(e, q * [1, -1, -1, -1])
    np.testing.assert_allclose(kr.euler_parameters_to_matrix(e), kr.quat_to_matrix(q), atol=1e-15)
    np.testing.assert_allclose(kr.euler_parameters_to_matrix(q), np.swapaxes(kr.quat_to_matrix(q), -1, -2), atol=1e-15)
    np.testing.assert_allclose(kr.euler_parameters_to_quat(e), q, atol=1e-16)
    # Seed: u = [[e0 + i e3, e2 + i e1], [-e2 + i e1, e0 - i e3]].
    u = kr.quat_to_su2(q[0])
    e0, e1, e2, e3 = e[0]
    np.testing.assert_allclose(u, [[e0 + 1j * e3, e2 + 1j * e1], [-e2 + 1j * e1, e0 - 1j * e3]], atol=1e-16)


def test_su2_refusals():
    with pytest.raises(ValueError, match="u must"):
        kr.su2_to_quat(2 * np.eye(2))
    with pytest.raises(ValueError, match="u must have the SU"):
        kr.su2_to_quat(np.array([[1, 0], [0, -1]]))
    with pytest.raises(ValueError, match=r"u must have shape"):
        kr.su2_to_quat(np.eye(3))
    with pytest.raises(ValueError, match="u must be finite"):
        kr.su2_to_quat(np.array([[np.nan, 0], [0, 1]]))


def test_gibbs_and_mrp(random_quats):
    q = random_quats(100)
    q = np.where(q[:, :1] < 0, -q, q)
    r = S.from_quat(q[:, [1, 2, 3, 0]])
    np.testing.assert_allclose(kr.quat_to_mrp(q), r.as_mrp(), atol=1e-15)
    psi = r.as_rotvec()
    angle = np.linalg.norm(psi, axis=-1, keepdims=True)
    np.testing.assert_allclose(kr.quat_to_gibbs(q), psi / angle * np.tan(angle / 2), rtol=1e-12)
    np.testing.assert_allclose(kr.gibbs_to_quat(kr.quat_to_gibbs(q)), q, atol=1e-15)
    np.testing.assert_allclose(kr.mrp_to_quat(kr.quat_to_mrp(q)), q, atol=1e-15)
    assert np.all(np.linalg.norm(kr.quat_to_mrp(-q), axis=-1) <= 1 + 1e-15)
    p = kr.quat_to_mrp(q[0])
    shadow = -p / np.dot(p, p)
    np.testing.assert_allclose(kr.quat_to_matrix(kr.mrp_to_quat(shadow)), kr.quat_to_matrix(q[0]), atol=1e-15)
    with pytest.raises(ValueError, match="half-turn"):
        kr.quat_to_gibbs([0.0, 1.0, 0.0, 0.0])
