"""Wahba's problem: kreisel's q-method against an SVD (Kabsch) solution, TRIAD and scipy."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as S

import kreisel as kr
from kreisel import Rotation


def kabsch(a, b, w):
    """Independent reference: R = U diag(1, 1, det(U Vᵀ)) Vᵀ from the SVD of B = Σ w a bᵀ."""
    B = np.einsum("n,ni,nj->ij", w, a, b)
    U, _, Vt = np.linalg.svd(B)
    D = np.diag([1.0, 1.0, np.linalg.det(U @ Vt)])
    return U @ D @ Vt


def triad(a, b):
    """TRIAD (Black 1964): the orthonormal triads of (a1, a2) and (b1, b2) mapped onto each other."""

    def frame(v1, v2):
        t1 = v1 / np.linalg.norm(v1)
        t2 = np.cross(v1, v2)
        t2 /= np.linalg.norm(t2)
        return np.column_stack([t1, t2, np.cross(t1, t2)])

    return frame(a[0], a[1]) @ frame(b[0], b[1]).T


def problems(rng, m, n, noise=0.1):
    truth = Rotation.random(m, rng=rng)
    b = rng.normal(size=(m, n, 3))
    a = truth[:, None].apply(b) + noise * rng.normal(size=(m, n, 3))
    return a, b, rng.random((m, n)) + 0.1


@pytest.mark.parametrize("n", [2, 3, 7, 40])
def test_matches_svd_reference_and_scipy(rng, n):
    a, b, w = problems(rng, 30, n)
    r, rssd, sens = Rotation.align_vectors(a, b, w, return_sensitivity=True)
    assert r.shape == (30,) and rssd.shape == (30,) and sens.shape == (30, 3, 3)
    for i in range(30):
        R = kabsch(a[i], b[i], w[i])
        np.testing.assert_allclose(r[i].as_matrix(), R, atol=1e-12)
        direct = np.sqrt(np.sum(w[i] * np.sum((a[i] - b[i] @ R.T) ** 2, axis=-1)))
        np.testing.assert_allclose(rssd[i], direct, rtol=1e-12)
        s, srssd, ssens = S.align_vectors(a[i], b[i], w[i], return_sensitivity=True)
        np.testing.assert_allclose(r[i].as_matrix(), s.as_matrix(), atol=1e-12)
        np.testing.assert_allclose(rssd[i], srssd, rtol=1e-9)
        np.testing.assert_allclose(sens[i], ssens, rtol=1e-9, atol=1e-12)
        # The single-problem call gives the same result as the batch.
        one, one_rssd, one_sens = Rotation.align_vectors(a[i], b[i], w[i], return_sensitivity=True)
        assert one.single and isinstance(one_rssd, float)
        np.testing.assert_allclose(one.as_quat(), r[i].as_quat(), atol=1e-15)
        np.testing.assert_allclose(one_sens, sens[i], rtol=1e-14)


def test_solution_minimises_the_loss(rng):
    a, b, w = problems(rng, 1, 6, noise=0.5)
    r, rssd = Rotation.align_vectors(a[0], b[0], w[0])
    loss = lambda rot: np.sum(w[0] * np.sum((a[0] - rot.apply(b[0])) ** 2, axis=-1))  # noqa: E731
    assert np.isclose(loss(r), rssd**2, rtol=1e-13)
    nudged = Rotation.from_rotvec(1e-4 * rng.normal(size=(200, 3))) * r
    assert all(loss(x) > loss(r) for x in nudged)


def test_degenerate_and_reflected_profiles_match_kabsch(rng):
    # Coplanar vectors (rank-2 B) and a noisy set whose SVD has det(U Vᵀ) = -1.
    b = rng.normal(size=(5, 3))
    b[:, 2] = 0.0
    truth = Rotation.from_rotvec([0.3, -1.0, 2.0])
    cases = [(truth.apply(b), b), (rng.normal(size=(4, 3)), rng.normal(size=(4, 3)))]
    for a, bb in cases:
        w = np.ones(len(a))
        r, _ = Rotation.align_vectors(a, bb)
        np.testing.assert_allclose(r.as_matrix(), kabsch(a, bb, w), atol=1e-12)


def test_exact_data_gives_rounding_level_rssd():
    truth = Rotation.from_euler("ZYX", [1.0, 0.4, -2.0])
    b = np.array([[1.0, 2.0, 3.0], [-1.0, 0.5, 0.0], [0.0, 0.0, 4.0]])
    r, rssd = Rotation.align_vectors(truth.apply(b), b)
    assert r.approx_equal(truth, atol=1e-15) and rssd < 1e-14


def test_infinite_weight_aligns_primary_exactly_and_matches_scipy(rng):
    for primary in range(4):
        a, b, w = problems(rng, 1, 4, noise=0.3)
        a, b, w = a[0], b[0], w[0]
        w[primary] = np.inf
        r, rssd = Rotation.align_vectors(a, b, w)
        s, srssd = S.align_vectors(a, b, w)
        np.testing.assert_allclose(r.as_matrix(), s.as_matrix(), atol=1e-12)
        np.testing.assert_allclose(rssd, srssd, rtol=1e-10)
        c = r.apply(b[primary])
        np.testing.assert_allclose(c / np.linalg.norm(c), a[primary] / np.linalg.norm(a[primary]), atol=1e-15)


def test_two_vectors_with_infinite_weight_are_triad(rng):
    a, b = rng.normal(size=(2, 3)), rng.normal(size=(2, 3))
    r, _ = Rotation.align_vectors(a, b, [np.inf, 1.0])
    np.testing.assert_allclose(r.as_matrix(), triad(a, b), atol=1e-14)


@pytest.mark.parametrize(
    "a",
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.3, -0.2, 0.9], [1.0, 1.0, 1.0], [1.0, 1.0, 0.0]],
)
@pytest.mark.parametrize("turn", [0.0, 1e-9, 0.7, np.pi - 1e-6, np.pi])
def test_single_pair_is_the_shortest_arc(a, turn):
    a = np.array(a)
    perp = np.cross(a, [0.2, 0.5, -0.7])
    b = 2.0 * Rotation.from_rotvec(turn * perp / np.linalg.norm(perp)).apply(a)
    r, rssd = Rotation.align_vectors(a, b)
    np.testing.assert_allclose(r.magnitude(), turn, atol=3e-10)
    np.testing.assert_allclose(r.apply(b / 2.0), a, atol=1e-15)
    np.testing.assert_allclose(rssd, np.linalg.norm(a), rtol=1e-12)  # |a - R b| = |a| as |b| = 2|a|
    if turn < np.pi:
        # At a rounded half turn b × a is noise, and scipy's axis is not normal to a:
        # its rotation then misses a by O(1); kreisel projects the axis first.
        s, srssd = S.align_vectors(a, b)
        np.testing.assert_allclose(r.as_matrix(), s.as_matrix(), atol=3e-10)
        np.testing.assert_allclose(rssd, srssd, rtol=1e-9)


def test_exactly_antiparallel_pairs_agree_with_scipy():
    for a in np.eye(3).tolist() + [[0.3, -0.2, 0.9], [-1.0, 2.0, 0.5]]:
        a = np.array(a)
        r, _ = Rotation.align_vectors(a, -a)
        s, _ = S.align_vectors(a, -a)
        np.testing.assert_allclose(r.as_matrix(), s.as_matrix(), atol=1e-15)


def test_batches_broadcast_weights_and_equal_the_loop(rng):
    a, b, _ = problems(rng, 24, 5)
    a, b = a.reshape(4, 6, 5, 3), b.reshape(4, 6, 5, 3)
    w = np.array([1.0, 2.0, 0.5, 1.0, np.inf])
    q, rssd = kr.align_vectors(a, b, w)
    assert q.shape == (4, 6, 4) and rssd.shape == (4, 6)
    for i, j in np.ndindex(4, 6):
        s, srssd = S.align_vectors(a[i, j], b[i, j], w)
        np.testing.assert_allclose(kr.quat_to_matrix(q[i, j]), s.as_matrix(), atol=1e-12)
        np.testing.assert_allclose(rssd[i, j], srssd, rtol=1e-10)


def test_large_batches_use_both_cores_and_agree(rng):
    a, b, w = problems(rng, 5000, 4)
    q, rssd, sens = kr.align_vectors(a, b, w, return_sensitivity=True)
    for i in rng.integers(0, 5000, 5):
        qi, ri, si = kr.align_vectors(a[i], b[i], w[i], return_sensitivity=True)
        np.testing.assert_array_equal(q[i], qi)
        np.testing.assert_array_equal(rssd[i], ri)
        np.testing.assert_array_equal(sens[i], si)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: Rotation.align_vectors(np.ones((3, 3)), np.ones((4, 3))), "same shape"),
        (lambda: Rotation.align_vectors(np.ones((3, 2)), np.ones((3, 2))), r"a must have shape \(\.\.\., 3\)"),
        (lambda: Rotation.align_vectors(np.ones((0, 3)), np.ones((0, 3))), "at least one"),
        (lambda: Rotation.align_vectors(np.eye(3), np.eye(3), [1.0, -1.0, 1.0]), "non-negative"),
        (lambda: Rotation.align_vectors(np.eye(3), np.eye(3), [1.0, np.nan, 1.0]), "non-negative"),
        (lambda: Rotation.align_vectors(np.eye(3), np.eye(3), [1.0, 1.0]), r"weights must have shape"),
        (lambda: Rotation.align_vectors(np.eye(3), np.eye(3), [np.inf, np.inf, 1.0]), "at most one inf"),
        (lambda: Rotation.align_vectors(np.eye(3), np.eye(3), [np.inf, 1, 1], return_sensitivity=True), "sensitivity"),
        (lambda: Rotation.align_vectors([1.0, 0, 0], [0.0, 1, 0], return_sensitivity=True), "sensitivity"),
        (lambda: Rotation.align_vectors([0.0, 0, 0], [0.0, 1, 0]), "zero-length primary"),
        (lambda: Rotation.align_vectors(np.eye(3), np.eye(3) * np.nan), "b must be finite"),
    ],
)
def test_bad_input_is_refused_by_name(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_vectors_and_weights_of_any_size(rng):
    """a, b and the weights scaled by 1e-300 ... 1e300: the same rotation (scipy), the rssd scaled
    with the vectors and the sensitivity inversely to them (the profile matrix, its eigen-solve and
    ζ over- or underflowed; 1e-109 vectors raised a bare ZeroDivisionError)."""
    a, b = rng.normal(size=(5, 3)), rng.normal(size=(5, 3))
    w = rng.uniform(0.5, 2.0, size=5)
    r, rssd, sensitivity = S.align_vectors(a, b, w, return_sensitivity=True)
    want = r.as_quat(scalar_first=True) * np.sign(r.as_quat(scalar_first=True)[0])
    for exponent in (-300, -160, -109, 154, 300):
        s = 10.0**exponent
        # the sensitivity of vectors scaled by s is 1/s² times: beyond the float range below 1e-154,
        # a subnormal or zero above 1e154
        inverse_square = None if exponent < -150 else 10.0 ** (-2 * exponent)
        for aa, bb, ww, rssd_scale, sensitivity_scale in ((s * a, s * b, w, s, inverse_square),
                                                          (a, b, s * w, np.sqrt(s), 1.0)):
            if sensitivity_scale is None:
                with pytest.raises(ValueError, match="a and b are out of range"):
                    kr.so3.align_vectors(aa, bb, ww, return_sensitivity=True)
                q, got_rssd = kr.so3.align_vectors(aa, bb, ww)
            else:
                q, got_rssd, got_sensitivity = kr.so3.align_vectors(aa, bb, ww, return_sensitivity=True)
                np.testing.assert_allclose(got_sensitivity, sensitivity * sensitivity_scale, rtol=1e-12, atol=1e-300)
            np.testing.assert_allclose(q, want, atol=1e-15)
            np.testing.assert_allclose(got_rssd, rssd * rssd_scale, rtol=1e-13)
        q, _ = kr.so3.align_vectors(s * a[:2], b[:2], [np.inf, 1.0])  # primary vector and best turn
        np.testing.assert_allclose(q, kr.so3.align_vectors(a[:2], b[:2], [np.inf, 1.0])[0], atol=1e-15)


def test_parallel_vectors_have_no_sensitivity_matrix():
    a = np.array([[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    q, rssd = kr.so3.align_vectors(a, a)
    np.testing.assert_allclose(q, [1.0, 0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="do not determine the rotation"):
        kr.so3.align_vectors(a, a, return_sensitivity=True)
