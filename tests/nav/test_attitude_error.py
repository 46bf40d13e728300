"""attitude_error against an independent split of the error rotation with scipy."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from kreisel.nav import attitude_error, attitude_error_angles


def scipy_split(q, q_ref):
    """Total, heading, inclination from rotation matrices: E = R R_refᵀ = T H, T ez = E ez."""
    r = Rotation.from_quat(q[:, [1, 2, 3, 0]])
    r_ref = Rotation.from_quat(q_ref[:, [1, 2, 3, 0]])
    e = r * r_ref.inv()
    up = e.apply([0.0, 0.0, 1.0])
    inclination = np.arccos(np.clip(up[:, 2], -1.0, 1.0))
    axis = np.cross([0.0, 0.0, 1.0], up)
    norm = np.linalg.norm(axis, axis=1, keepdims=True)
    tilt = Rotation.from_rotvec(np.where(norm > 0, axis / np.where(norm > 0, norm, 1.0), 0.0) * inclination[:, None])
    heading = (tilt.inv() * e).magnitude()
    return e.magnitude(), heading, inclination


def test_random_rotations_match_scipy():
    rng = np.random.default_rng(1)
    q_ref = rng.normal(size=(500, 4))
    q_ref /= np.linalg.norm(q_ref, axis=1, keepdims=True)
    small = Rotation.from_rotvec(rng.normal(scale=0.3, size=(500, 3)))
    q = (small * Rotation.from_quat(q_ref[:, [1, 2, 3, 0]])).as_quat()[:, [3, 0, 1, 2]]
    ours = attitude_error_angles(q, q_ref)
    for a, b in zip(ours, scipy_split(q, q_ref)):
        np.testing.assert_allclose(a, b, atol=1e-7)
    total, heading, incl = attitude_error(q, q_ref)
    assert total == pytest.approx(np.degrees(np.sqrt(np.mean(ours[0] ** 2))), rel=1e-14)


def test_pure_yaw_is_heading_and_pure_tilt_is_inclination():
    ref = np.array([[np.cos(0.4), 0.3, -0.5, np.sin(0.2)]])
    ref /= np.linalg.norm(ref)
    yaw = Rotation.from_rotvec([0.0, 0.0, np.radians(5.0)])
    tilt = Rotation.from_rotvec(np.radians(4.0) * np.array([np.cos(1.0), np.sin(1.0), 0.0]))
    r_ref = Rotation.from_quat(ref[:, [1, 2, 3, 0]])
    for turn, expected in ((yaw, (5.0, 5.0, 0.0)), (tilt, (4.0, 0.0, 4.0))):
        q = (turn * r_ref).as_quat()[:, [3, 0, 1, 2]]
        np.testing.assert_allclose(attitude_error(q, ref), expected, atol=1e-12)


def test_sign_and_scale_of_quaternions_do_not_matter():
    ref = np.array([[1.0, 0.0, 0.0, 0.0]])
    q = np.array([[np.cos(0.05), 0.0, np.sin(0.05), 0.0]])
    np.testing.assert_allclose(attitude_error(-3.0 * q, 2.0 * ref), attitude_error(q, ref), rtol=1e-14)


def test_nan_reference_rows_and_mask_are_left_out():
    ref = np.tile([1.0, 0.0, 0.0, 0.0], (4, 1))
    q = ref.copy()
    q[1] = [np.cos(0.5), np.sin(0.5), 0.0, 0.0]  # a 57° error in a row the reference lost
    ref[1] = np.nan
    q[2] = [np.cos(0.01), 0.0, 0.0, np.sin(0.01)]
    assert attitude_error(q, ref)[0] == pytest.approx(np.degrees(0.02) / np.sqrt(3), rel=1e-12)
    assert attitude_error(q, ref, mask=np.array([True, True, False, True])) == (0.0, 0.0, 0.0)


def test_bad_input():
    ref = np.tile([1.0, 0.0, 0.0, 0.0], (3, 1))
    with pytest.raises(ValueError, match="q and q_ref must have the same shape"):
        attitude_error(ref[:2], ref)
    with pytest.raises(ValueError, match=r"q must have shape \(n, 4\)"):
        attitude_error(ref[:, :3], ref)
    with pytest.raises(ValueError, match="mask must be a boolean array"):
        attitude_error(ref, ref, mask=[1, 0, 1])
    with pytest.raises(ValueError, match="no sample to evaluate"):
        attitude_error(ref, ref, mask=np.zeros(3, bool))
    with pytest.raises(ValueError, match="q_ref is NaN in every row"):
        attitude_error(ref, np.full((3, 4), np.nan))
    bad = ref.copy()
    bad[0, 0] = np.nan
    with pytest.raises(ValueError, match="q must be finite"):
        attitude_error(bad, ref)
