"""RigidBody: accepted forms, derived attributes and refusals."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation as ScipyRotation

import kreisel as kr
from kreisel.inertia import solids


def test_principal_moments_keep_given_order_as_body_axes():
    body = kr.RigidBody([3.0, 1.0, 2.0], mass=2.0)
    np.testing.assert_array_equal(body.inertia, np.diag([3.0, 1.0, 2.0]))
    np.testing.assert_array_equal(body.principal_moments, [1.0, 2.0, 3.0])
    R = body.principal_axes
    np.testing.assert_allclose(R @ np.diag(body.principal_moments) @ R.T, body.inertia, atol=1e-15)
    assert np.linalg.det(R) == pytest.approx(1.0, abs=1e-15)
    assert body.is_principal
    assert body.mass == 2.0


def test_full_tensor_body():
    rng = np.random.default_rng(3)
    Q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    Q *= np.sign(np.linalg.det(Q))
    tensor = Q @ np.diag([1.0, 2.0, 2.5]) @ Q.T
    body = kr.RigidBody(tensor, mass=0.5)
    assert not body.is_principal
    np.testing.assert_allclose(body.principal_moments, [1.0, 2.0, 2.5], rtol=1e-14)
    R = body.principal_axes
    np.testing.assert_allclose(R @ np.diag(body.principal_moments) @ R.T, tensor, atol=1e-14)


def test_attributes_are_read_only():
    body = kr.RigidBody([1.0, 2.0, 2.0])
    with pytest.raises(ValueError):
        body.inertia[0, 0] = 5.0


def test_thin_plate_equality_accepted_within_rounding():
    # a thin rectangular plate: I_z = I_x + I_y exactly, up to rounding
    body = kr.RigidBody(kr.inertia.box(1.0, (0.3, 0.7, 0.0)))
    assert body.principal_moments[2] == pytest.approx(sum(body.principal_moments[:2]), rel=1e-15)
    kr.RigidBody(kr.inertia.rotate(kr.inertia.thin_disk(1.0, 0.1), [0.6, 0.8, 0.0, 0.0]))


@pytest.mark.parametrize(
    "inertia, message",
    [
        ([[1.0, 0.2, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], "symmetric"),
        ([1.0, 1.0, 2.1], "triangle inequality"),
        ([-1.0, 2.0, 2.0], "positive definite"),
        ([0.0, 1.0, 1.0], "positive definite"),
        ([1.0, np.nan, 1.0], "finite"),
        ([1.0, np.inf, 1.0], "finite"),
        ([1.0, 2.0], r"got shape \(2,\)"),
        (np.eye(4), r"shape"),
    ],
)
def test_refuses_unphysical_inertia(inertia, message):
    with pytest.raises(ValueError, match=message):
        kr.RigidBody(inertia)


def test_refuses_zero_moment_rod():
    with pytest.raises(ValueError, match="thin rod"):
        kr.RigidBody(kr.inertia.thin_rod(1.0, 1.0))


@pytest.mark.parametrize("mass", [0.0, -1.0, np.nan, [1.0, 2.0]])
def test_refuses_bad_mass(mass):
    with pytest.raises(ValueError, match="mass"):
        kr.RigidBody([1.0, 1.0, 1.0], mass=mass)


@pytest.mark.parametrize(
    "name, args",
    [
        ("box", ((1.0, 2.0, 3.0),)),
        ("solid_sphere", (0.5,)),
        ("hollow_sphere", (0.5, 0.25)),
        ("solid_cylinder", (0.5, 2.0)),
        ("hollow_cylinder", (0.5, 2.0, 0.3)),
        ("solid_cone", (0.5, 2.0)),
        ("solid_ellipsoid", ((1.0, 2.0, 3.0),)),
        ("thin_disk", (0.5,)),
        ("thin_ring", (0.5,)),
        ("torus", (1.0, 0.25)),
    ],
)
def test_solid_constructors_match_inertia_functions(name, args):
    body = getattr(kr.RigidBody, name)(3.0, *args)
    np.testing.assert_array_equal(body.inertia, getattr(solids, name)(3.0, *args))
    assert body.mass == 3.0


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.booleans())
def test_every_physical_body_is_accepted(seed, planar):
    # point clouds, including planar ones (thin plates, triangle equality) in random
    # orientations where the equality only holds up to rounding
    rng = np.random.default_rng(seed)
    masses = rng.uniform(0.1, 1.0, 7)
    positions = rng.normal(size=(7, 3)) * rng.uniform(1e-3, 1e3)
    if planar:
        positions[:, 2] = 0.0
        positions = positions @ ScipyRotation.random(random_state=rng).as_matrix().T
    body = kr.RigidBody.from_points(masses, positions)
    m1, m2, m3 = body.principal_moments
    assert m3 <= m1 + m2 + 1e-12 * m3
    if planar:
        assert m3 == pytest.approx(m1 + m2, rel=1e-12)
