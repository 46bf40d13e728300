"""Screw interpolation (Theory §3.8)."""

import numpy as np
import pytest

from kreisel.se3 import RigidTransform, sclerp


def test_sclerp_end_points_and_halves():
    a, b = RigidTransform.random(10, rng=1), RigidTransform.random(10, rng=2)
    np.testing.assert_allclose(sclerp(a, b, 0.0).as_matrix(), a.as_matrix(), atol=1e-15)
    np.testing.assert_allclose(sclerp(a, b, 1.0).as_matrix(), b.as_matrix(), atol=1e-13)
    half = a.inv() * sclerp(a, b, 0.5)
    np.testing.assert_allclose((a * half * half).as_matrix(), b.as_matrix(), atol=1e-13)


def test_sclerp_follows_the_screw_of_the_relative_displacement():
    axis, point, angle, slide = np.array([0.0, 0.6, 0.8]), np.array([1.0, -2.0, 1.5]), 2.5, -0.4
    start = RigidTransform.random(rng=3)
    end = start * RigidTransform.from_screw(axis, point, angle, slide)
    s = np.linspace(-0.5, 1.5, 9)
    path = sclerp(start, end, s)
    assert path.shape == (9,)
    expected = start * RigidTransform.from_screw(axis, point, s * angle, s * slide)
    np.testing.assert_allclose(path.as_matrix(), expected.as_matrix(), atol=1e-13)


def test_sclerp_refuses_non_transforms():
    with pytest.raises(TypeError, match="end"):
        sclerp(RigidTransform.identity(), np.eye(4), 0.5)
    with pytest.raises(ValueError, match="fraction"):
        sclerp(RigidTransform.identity(), RigidTransform.identity(), np.nan)
