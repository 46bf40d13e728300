"""kreisel.scipy.Slerp against scipy's Slerp."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as ScipyRotation
from scipy.spatial.transform import Slerp as ScipySlerp

from kreisel.scipy import Rotation, Slerp


def test_slerp_matches_scipy():
    times, at = [0.0, 1.0, 3.0], np.linspace(0.0, 3.0, 13)
    ours = Slerp(times, Rotation.random(3, rng=4))
    theirs = ScipySlerp(times, ScipyRotation.random(3, rng=4))
    np.testing.assert_allclose(ours(at).as_matrix(), theirs(at).as_matrix(), rtol=0, atol=1e-14)
    assert isinstance(ours(at), Rotation) and ours(1.5).single
    with pytest.raises(ValueError, match="times must be a scalar or 1-D"):
        ours(at.reshape(1, -1))
    with pytest.raises(TypeError, match="rotations must be a kreisel.scipy Rotation"):
        Slerp(times, ScipyRotation.random(3, rng=4))
