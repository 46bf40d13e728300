"""Tensor operations: points, parallel axis, rotation, principal axes, axis moments, ellipsoid."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation as ScipyRotation

import kreisel as kr

I = kr.inertia
seeds = st.integers(0, 2**32 - 1)


def random_rotations(rng, shape=()):
    return ScipyRotation.random(int(np.prod(shape)), random_state=rng).as_matrix().reshape(shape + (3, 3))


def point_cloud(rng, n=9):
    return rng.uniform(0.1, 2.0, size=n), rng.normal(size=(n, 3))


def direct_inertia(m, r):
    """Σ m (r² 1 − r rᵀ) written out term by term (Theory §4.1)."""
    out = np.zeros((3, 3))
    for mass, p in zip(m, r):
        out += mass * (p @ p * np.eye(3) - np.outer(p, p))
    return out


def test_points_matches_definition_and_batches():
    rng = np.random.default_rng(0)
    m, r = point_cloud(rng)
    np.testing.assert_allclose(I.points(m, r), direct_inertia(m, r), rtol=1e-14, atol=1e-14)
    batch_m = rng.uniform(size=(4, 5, 9))
    batch_r = rng.normal(size=(4, 5, 9, 3))
    out = I.points(batch_m, batch_r)
    assert out.shape == (4, 5, 3, 3)
    np.testing.assert_allclose(out[2, 3], direct_inertia(batch_m[2, 3], batch_r[2, 3]), rtol=1e-14, atol=1e-14)


def test_kinetic_energy_identity():
    # Theory §4.1: Σ ½ m (ω × r)² = ½ ωᵀ I ω
    rng = np.random.default_rng(1)
    m, r = point_cloud(rng)
    omega = rng.normal(size=3)
    direct = 0.5 * np.sum(m * np.sum(np.cross(omega, r) ** 2, axis=1))
    assert 0.5 * omega @ I.points(m, r) @ omega == pytest.approx(direct, rel=1e-14)


@settings(max_examples=50, deadline=None)
@given(seeds)
def test_parallel_axis_theorem(seed):
    rng = np.random.default_rng(seed)
    m, r = point_cloud(rng)
    com = m @ r / m.sum()
    I_cm = I.points(m, r - com)
    point = rng.normal(size=3) * 3
    about_point = I.parallel_axis(I_cm, m.sum(), com - point)
    np.testing.assert_allclose(about_point, I.points(m, r - point), atol=1e-13 * np.abs(about_point).max())
    back = I.parallel_axis_to_center_of_mass(about_point, m.sum(), com - point)
    np.testing.assert_allclose(back, I_cm, atol=1e-13 * np.abs(about_point).max())


def test_parallel_axis_broadcasts():
    I_cm = I.solid_sphere(np.array([1.0, 2.0]), 1.0)
    shifted = I.parallel_axis(I_cm[:, None], np.array([1.0, 2.0])[:, None], np.eye(3))
    assert shifted.shape == (2, 3, 3, 3)
    np.testing.assert_allclose(shifted[1, 2], np.diag([0.8 + 2, 0.8 + 2, 0.8]))


@settings(max_examples=50, deadline=None)
@given(seeds)
def test_rotate_matches_rotated_point_cloud(seed):
    rng = np.random.default_rng(seed)
    m, r = point_cloud(rng)
    rotation = ScipyRotation.random(random_state=rng)
    R = rotation.as_matrix()
    expected = I.points(m, r @ R.T)
    scale = np.abs(expected).max()
    tensor = I.points(m, r)
    np.testing.assert_allclose(I.rotate(tensor, R), expected, atol=1e-14 * scale)
    q = np.roll(rotation.as_quat(), 1)  # scalar first
    np.testing.assert_allclose(I.rotate(tensor, q), expected, atol=1e-14 * scale)
    np.testing.assert_allclose(I.rotate(tensor, -3.0 * q), expected, atol=1e-14 * scale)  # scale and sign
    np.testing.assert_allclose(I.rotate(tensor, rotation), expected, atol=1e-14 * scale)


def test_rotate_batches_rotations():
    rng = np.random.default_rng(5)
    R = random_rotations(rng, (4, 2))
    tensor = np.diag([1.0, 2.0, 3.0])
    out = I.rotate(tensor, R)
    assert out.shape == (4, 2, 3, 3)
    np.testing.assert_allclose(out[3, 1], R[3, 1] @ tensor @ R[3, 1].T, atol=1e-15)


def tensors(draw_moments):
    """Strategy: (tensor, moments, Q) with tensor = Q diag(moments) Qᵀ."""
    return st.tuples(draw_moments, seeds).map(
        lambda mv: (mv[0], random_rotations(np.random.default_rng(mv[1])))
    )


positive = st.floats(1e-3, 1e3)
moment_sets = st.one_of(
    st.tuples(positive, positive, positive),
    st.tuples(positive, positive).map(lambda ab: (ab[0], ab[0], ab[1])),  # symmetric top
    st.tuples(positive, positive).map(lambda ab: (ab[0], ab[1], ab[1])),
    positive.map(lambda a: (a, a, a)),  # spherical top
    st.tuples(positive, positive).map(lambda ab: (0.0, ab[0], ab[0])),  # rod-like, semi-definite
)


def check_principal_frame(tensor, moments, R, scale):
    assert np.all(np.diff(moments) >= 0)
    np.testing.assert_allclose(R.T @ R, np.eye(3), atol=4e-15)
    assert np.linalg.det(R) == pytest.approx(1.0, abs=4e-15)
    np.testing.assert_allclose(R @ np.diag(moments) @ R.T, tensor, atol=4e-15 * scale)
    np.testing.assert_allclose(tensor @ R, R * moments, atol=4e-15 * scale)


@settings(max_examples=200, deadline=None)
@given(tensors(moment_sets))
def test_principal_axes_of_constructed_tensors(case):
    given_moments, Q = case
    tensor = Q @ np.diag(given_moments) @ Q.T
    scale = max(given_moments)
    moments, R = I.principal_axes(tensor)
    np.testing.assert_allclose(moments, np.sort(given_moments), atol=4e-15 * scale)
    check_principal_frame(tensor, moments, R, scale)
    # an isolated moment has a well-defined axis: it is the matching column of Q (up to sign)
    order = np.argsort(given_moments, kind="stable")
    sorted_moments = np.sort(given_moments)
    for k in range(3):
        gap = min(abs(sorted_moments[k] - sorted_moments[j]) for j in range(3) if j != k)
        if gap > 1e-2 * scale:
            alignment = abs(R[:, k] @ Q[:, order[k]])
            assert alignment == pytest.approx(1.0, abs=1e-12 * scale / gap)


@settings(max_examples=100, deadline=None)
@given(seeds)
def test_principal_axes_of_random_symmetric_matrices(seed):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(3, 3))
    tensor = A + A.T  # need not be physical: principal_axes is plain linear algebra
    moments, R = I.principal_axes(tensor)
    check_principal_frame(tensor, moments, R, np.abs(tensor).max())


def test_principal_axes_diagonal_and_degenerate_cases():
    moments, R = I.principal_axes(np.diag([1.0, 2.0, 3.0]))
    np.testing.assert_array_equal(R, np.eye(3))
    for tensor in (2.0 * np.eye(3), np.diag([1.0, 1.0, 2.0]), np.diag([2.0, 1.0, 1.0])):
        moments, R = I.principal_axes(tensor)
        check_principal_frame(tensor, moments, R, 2.0)
        assert set(np.abs(R).ravel()) <= {0.0, 1.0}  # coordinate axes, not an arbitrary mix
    # a sphere with rounding noise still gives a proper rotation
    rng = np.random.default_rng(2)
    noise = rng.normal(size=(3, 3)) * 1e-16
    tensor = np.eye(3) + noise + noise.T
    moments, R = I.principal_axes(tensor)
    check_principal_frame(tensor, moments, R, 1.0)


def test_principal_axes_sign_convention_and_batch():
    rng = np.random.default_rng(4)
    Q = random_rotations(rng, (6,))
    tensors_ = Q @ (np.array([1.0, 2.0, 3.0])[:, None] * np.eye(3)) @ np.swapaxes(Q, -1, -2)
    moments, R = I.principal_axes(tensors_)
    assert moments.shape == (6, 3) and R.shape == (6, 3, 3)
    for k in range(6):
        single_moments, single_R = I.principal_axes(tensors_[k])
        np.testing.assert_array_equal(R[k], single_R)
        for column in range(2):
            big = np.argmax(np.abs(R[k, :, column]))
            assert R[k, big, column] > 0
        np.testing.assert_allclose(R[k][:, 2], np.cross(R[k][:, 0], R[k][:, 1]), atol=1e-15)
    # flipping Q's columns does not change the answer: it is a function of the tensor only
    flipped = Q * np.array([-1.0, 1.0, -1.0])
    _, R2 = I.principal_axes(flipped @ np.diag([1.0, 2.0, 3.0]) @ np.swapaxes(flipped, -1, -2))
    np.testing.assert_allclose(R2, R, atol=1e-14)


def test_moment_about_axis_and_radius_of_gyration():
    rng = np.random.default_rng(6)
    m, r = point_cloud(rng)
    n = rng.normal(size=3)
    unit = n / np.linalg.norm(n)
    # Σ m d², d the distance to the axis
    direct = np.sum(m * (np.sum(r**2, axis=1) - (r @ unit) ** 2))
    tensor = I.points(m, r)
    assert I.moment_about_axis(tensor, n) == pytest.approx(direct, rel=1e-14)
    k = I.radius_of_gyration(tensor, m.sum(), n)
    assert m.sum() * k**2 == pytest.approx(direct, rel=1e-14)
    # principal axes are where I_n takes the principal moments
    moments, R = I.principal_axes(tensor)
    np.testing.assert_allclose(I.moment_about_axis(tensor, R.T), moments, rtol=1e-14)
    assert I.moment_about_axis(np.eye(3)[None] * [[[1.0]], [[2.0]]], [0, 1.0, 0]).shape == (2,)


def test_radius_of_gyration_of_rod_axis_is_zero():
    assert I.radius_of_gyration(I.thin_rod(1.0, 2.0), 1.0, [0, 0, 1]) == 0.0


def test_inertia_ellipsoid_surface_satisfies_equation():
    rng = np.random.default_rng(7)
    Q = random_rotations(rng)
    tensor = Q @ np.diag([0.5, 2.0, 2.2]) @ Q.T
    e = I.inertia_ellipsoid(tensor, n_polar=9, n_azimuth=13)
    np.testing.assert_allclose(e.semi_axes, 1.0 / np.sqrt([0.5, 2.0, 2.2]), rtol=1e-14)
    x = np.stack([e.x, e.y, e.z], axis=-1)
    assert x.shape == (9, 13, 3)
    np.testing.assert_allclose(np.einsum("pqi,ij,pqj->pq", x, tensor, x), 1.0, rtol=1e-13)
    # the distance to the surface along n is 1/sqrt(I_n) (Theory §4.3)
    rho = np.linalg.norm(x, axis=-1)
    np.testing.assert_allclose(rho, 1.0 / np.sqrt(I.moment_about_axis(tensor, x)), rtol=1e-13)
    # semi-axes point along the principal axes
    for k in range(3):
        axis_point = e.axes[:, k] * e.semi_axes[k]
        assert axis_point @ tensor @ axis_point == pytest.approx(1.0, rel=1e-13)


def test_inertia_ellipsoid_batches():
    tensors_ = I.box(1.0, [[1.0, 2.0, 3.0], [2.0, 2.0, 2.0]])
    e = I.inertia_ellipsoid(tensors_, 5, 7)
    assert e.semi_axes.shape == (2, 3) and e.x.shape == (2, 5, 7)


@pytest.mark.parametrize(
    "call, error, message",
    [
        (lambda: I.principal_axes([[1.0, 2.0, 0], [0, 1, 0], [0, 0, 1]]), ValueError, "symmetric"),
        (lambda: I.principal_axes(np.eye(2)), ValueError, r"\(\.\.\., 3, 3\)"),
        (lambda: I.principal_axes([[np.nan, 0, 0], [0, 1, 0], [0, 0, 1]]), ValueError, "finite"),
        (lambda: I.points([1.0, -1.0], np.zeros((2, 3))), ValueError, "masses must be >= 0"),
        (lambda: I.points([1.0, 1.0], np.zeros((3, 3))), ValueError, "do not broadcast"),
        (lambda: I.points([1.0], np.zeros(3)), ValueError, r"\(\.\.\., N, 3\)"),
        (lambda: I.parallel_axis(np.eye(3), 0.0, np.zeros(3)), ValueError, "mass must be > 0"),
        (lambda: I.parallel_axis(np.eye(3), 1.0, np.zeros(2)), ValueError, "r_c"),
        (lambda: I.rotate(np.eye(3), np.diag([1.0, 1.0, -1.0])), ValueError, "det > 0"),
        (lambda: I.rotate(np.eye(3), 2 * np.eye(3)), ValueError, r"rotation matrices: max \|R\^T R - 1\|"),
        (lambda: I.rotate(np.eye(3), np.zeros(4)), ValueError, "nonzero"),
        (lambda: I.rotate(np.eye(3), np.zeros(5)), ValueError, "rotation must be"),
        (lambda: I.moment_about_axis(np.eye(3), np.zeros(3)), ValueError, "axis must be nonzero"),
        (lambda: I.radius_of_gyration(np.eye(3), -1.0, [1, 0, 0]), ValueError, "mass"),
        (lambda: I.inertia_ellipsoid(I.thin_rod(1.0, 1.0)), ValueError, "positive definite"),
        (lambda: I.inertia_ellipsoid(np.eye(3), n_polar=1), ValueError, "n_polar"),
    ],
)
def test_refusals(call, error, message):
    with pytest.raises(error, match=message):
        call()
