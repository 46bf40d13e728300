"""kreisel.scipy.RotationSpline against scipy's RotationSpline: body-frame rates as scipy returns them."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as ScipyRotation
from scipy.spatial.transform import RotationSpline as ScipyRotationSpline

from kreisel.scipy import Rotation, RotationSpline


def test_spline_and_its_rates_match_scipy():
    times, at = [0.0, 0.5, 1.5, 2.0], np.linspace(-0.5, 2.5, 31)
    ours = RotationSpline(times, Rotation.random(4, rng=9))
    theirs = ScipyRotationSpline(times, ScipyRotation.random(4, rng=9))
    np.testing.assert_allclose(ours(at).as_matrix(), theirs(at).as_matrix(), rtol=0, atol=1e-12)
    for order in (1, 2):
        np.testing.assert_allclose(ours(at, order), theirs(at, order), rtol=1e-10, atol=1e-10)
    with pytest.raises(ValueError, match="times must be a scalar or 1-D"):
        ours(np.zeros((2, 2)))
