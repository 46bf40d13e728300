"""kreisel.scipy.RigidTransform against scipy's RigidTransform: normalisation and conventions."""

import numpy as np
import pytest
from scipy.spatial.transform import RigidTransform as ScipyRigidTransform
from scipy.spatial.transform import Rotation as ScipyRotation

from kreisel.scipy import RigidTransform, Rotation


def test_from_matrix_normalises_the_rotation_block_as_scipy():
    rng = np.random.default_rng(5)
    m = np.tile(np.eye(4), (4, 1, 1))
    m[:, :3, :3] = ScipyRotation.random(4, rng=rng).as_matrix() + 0.05 * rng.standard_normal((4, 3, 3))
    m[:, :3, 3] = rng.standard_normal((4, 3))
    np.testing.assert_allclose(RigidTransform.from_matrix(m).as_matrix(), ScipyRigidTransform.from_matrix(m).as_matrix(),
                               rtol=0, atol=1e-14)
    m[1, 3, 0] = 1e-3
    with pytest.raises(ValueError, match=r"last row exactly \[0, 0, 0, 1\]; matrix \(1,\)"):
        RigidTransform.from_matrix(m)


def test_from_dual_quat_normalises_as_scipy():
    rng = np.random.default_rng(6)
    dq = rng.standard_normal((5, 8))                  # neither unit nor orthogonal parts
    dq[0, :4] = 0.0                                  # a zero real part is the identity rotation
    for scalar_first in (False, True):
        ours = RigidTransform.from_dual_quat(dq, scalar_first=scalar_first)
        theirs = ScipyRigidTransform.from_dual_quat(dq, scalar_first=scalar_first)
        np.testing.assert_allclose(ours.as_matrix(), theirs.as_matrix(), rtol=0, atol=1e-13)
        np.testing.assert_allclose(ours.as_dual_quat(scalar_first=scalar_first),
                                   theirs.as_dual_quat(scalar_first=scalar_first), rtol=0, atol=1e-13)


def test_components_and_operations_match_scipy():
    rng = np.random.default_rng(8)
    t, v = rng.standard_normal((3, 3)), rng.standard_normal((3, 3))
    ours = RigidTransform.from_components(t, Rotation.random(3, rng=1))
    theirs = ScipyRigidTransform.from_components(t, ScipyRotation.random(3, rng=1))
    translation, rotation = ours.as_components()
    assert isinstance(rotation, Rotation)
    np.testing.assert_allclose(translation, t, rtol=0, atol=0)
    np.testing.assert_allclose((ours * ours.inv()[::-1]).as_matrix(), (theirs * theirs.inv()[::-1]).as_matrix(),
                               rtol=0, atol=1e-14)
    np.testing.assert_allclose((ours ** 0.5).as_exp_coords(), (theirs ** 0.5).as_exp_coords(), rtol=0, atol=1e-13)
    np.testing.assert_allclose(ours.apply(v, inverse=True), theirs.apply(v, inverse=True), rtol=0, atol=1e-14)
    np.testing.assert_allclose(ours.mean().as_matrix(), theirs.mean().as_matrix(), rtol=0, atol=1e-14)
    assert repr(RigidTransform.identity()) == repr(ScipyRigidTransform.identity())
    with pytest.raises(TypeError, match="rotation must be a kreisel.scipy Rotation"):
        RigidTransform.from_rotation(np.eye(3))
