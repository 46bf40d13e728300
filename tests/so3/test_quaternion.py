"""Quaternion algebra against the chapter's product rule, scipy and algebraic identities."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as S

import kreisel as kr


def chapter_product(a, b):
    """(a0 b0 - a.b, a0 b + b0 a + a x b), Theory §2.4."""
    a0, av, b0, bv = a[..., :1], a[..., 1:], b[..., :1], b[..., 1:]
    return np.concatenate(
        [a0 * b0 - np.sum(av * bv, axis=-1, keepdims=True), a0 * bv + b0 * av + np.cross(av, bv)], axis=-1
    )


def test_units_multiply_as_hamilton():
    e = np.eye(4)
    i1, i2, i3 = e[1], e[2], e[3]
    assert np.array_equal(kr.quat_multiply(i1, i2), i3)
    assert np.array_equal(kr.quat_multiply(i2, i3), i1)
    assert np.array_equal(kr.quat_multiply(i1, i3), -i2)
    for u in (i1, i2, i3):
        assert np.array_equal(kr.quat_multiply(u, u), -e[0])


def test_multiply_matches_chapter_formula_and_broadcasts(rng):
    p = rng.normal(size=(5, 1, 4))
    q = rng.normal(size=(3, 4))
    out = kr.quat_multiply(p, q)
    assert out.shape == (5, 3, 4)
    np.testing.assert_allclose(out, chapter_product(p, q), rtol=0, atol=1e-14)


def test_multiply_is_associative_and_norm_multiplicative(rng):
    a, b, c = rng.normal(size=(3, 20, 4))
    np.testing.assert_allclose(
        kr.quat_multiply(kr.quat_multiply(a, b), c), kr.quat_multiply(a, kr.quat_multiply(b, c)), atol=1e-13
    )
    np.testing.assert_allclose(kr.quat_norm(kr.quat_multiply(a, b)), kr.quat_norm(a) * kr.quat_norm(b), rtol=1e-14)


def test_a_quaternion_times_its_conjugate_has_an_exactly_zero_vector_part(rng):
    # what a constant attitude needs: R^T R is exactly the identity rotation, batch or single
    q = rng.normal(size=(257, 4))
    for product in (kr.quat_multiply(kr.quat_conjugate(q), q), kr.quat_multiply(q, kr.quat_conjugate(q)),
                    np.array([kr.quat_multiply(kr.quat_conjugate(x), x) for x in q])):
        assert not product[:, 1:].any()


def test_conjugate_inverse_normalize(rng):
    q = rng.normal(size=(10, 4))
    np.testing.assert_allclose(
        kr.quat_multiply(q, kr.quat_inverse(q)), np.broadcast_to([1.0, 0, 0, 0], q.shape), atol=1e-15
    )
    np.testing.assert_allclose(
        kr.quat_conjugate(kr.quat_multiply(q[:5], q[5:])),
        kr.quat_multiply(kr.quat_conjugate(q[5:]), kr.quat_conjugate(q[:5])),
        atol=1e-14,
    )
    n = kr.quat_normalize(q)
    np.testing.assert_allclose(np.linalg.norm(n, axis=-1), 1.0, rtol=0, atol=2e-16)
    np.testing.assert_allclose(n * np.linalg.norm(q, axis=-1, keepdims=True), q, rtol=1e-15)


def test_apply_matches_scipy_and_inverse(rng, random_quats):
    q = random_quats(50)
    v = rng.normal(size=(50, 3))
    expected = S.from_quat(q[:, [1, 2, 3, 0]]).apply(v)
    np.testing.assert_allclose(kr.quat_apply(q, v), expected, atol=1e-14)
    np.testing.assert_allclose(kr.quat_apply(3.0 * q, v), expected, atol=1e-14)
    np.testing.assert_allclose(kr.quat_apply(q, expected, inverse=True), v, atol=1e-14)
    np.testing.assert_allclose(kr.quat_apply(q[:, None], v[None, :3]).shape, (50, 3, 3))


def test_apply_agrees_with_conjugation(rng):
    """q (r·i) q⁻¹ = (R r)·i, Theory §2.4."""
    q = rng.normal(size=(10, 4))
    r = rng.normal(size=(10, 3))
    rq = np.concatenate([np.zeros((10, 1)), r], axis=-1)
    conj = kr.quat_multiply(kr.quat_multiply(q, rq), kr.quat_inverse(q))
    np.testing.assert_allclose(conj[:, 0], 0.0, atol=1e-14)
    np.testing.assert_allclose(conj[:, 1:], kr.quat_apply(q, r), atol=1e-14)


@pytest.mark.parametrize("bad", [[0.0, 0, 0, 0], [np.nan, 1, 0, 0], [np.inf, 0, 0, 0]])
def test_bad_quaternions_are_refused(bad):
    with pytest.raises(ValueError, match="q must be"):
        kr.quat_normalize(bad)
    with pytest.raises(ValueError, match="q must be"):
        kr.quat_apply(bad, [1.0, 0, 0])


def test_wrong_shapes_are_refused():
    with pytest.raises(ValueError, match=r"p must have shape \(\.\.\., 4\)"):
        kr.quat_multiply([1.0, 0, 0], [1.0, 0, 0, 0])
    with pytest.raises(ValueError, match=r"v must have shape \(\.\.\., 3\)"):
        kr.quat_apply([1.0, 0, 0, 0], [1.0, 0])
    with pytest.raises(ValueError, match="q must be finite"):
        kr.quat_multiply([1.0, 0, 0, 0], [np.nan, 0, 0, 0])
