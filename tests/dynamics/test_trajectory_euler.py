"""Trajectory.euler at and within rounding of gimbal lock: the Rotation layer's angles, third angle 0."""

import numpy as np
import pytest

import kreisel as kr

PROPER = ["xyx", "xzx", "yxy", "yzy", "zxz", "zyz"]
TAIT_BRYAN = ["xyz", "xzy", "yxz", "yzx", "zxy", "zyx"]
CONVENTIONS = [s for base in PROPER + TAIT_BRYAN for s in (base, base.upper())]


def _trajectory(q):
    q = np.asarray(q, dtype=float)
    return kr.Trajectory(np.arange(len(q), dtype=float), q, np.zeros((len(q), 3)), [1.0, 2.0, 3.0])


def _near_lock(seq):
    """Quaternions of ``seq`` with the middle angle at lock and within 2⁻⁵² rad of it.

    The doubles nearest π and ±π/2 lie 1.2e-16 and 6.1e-17 inside the true angles; the next double
    outwards from ±π/2 lies 1.6e-16 outside, the next inwards from either 2.8e-16 or more: too far.
    """
    if seq[0].lower() == seq[2].lower():
        middles = [0.0, 2.0**-52, -(2.0**-52), np.pi]
    else:
        middles = [m for lock in (-np.pi / 2, np.pi / 2) for m in (lock, np.nextafter(lock, 4.0 * lock))]
    outer = [(0.3, 1.1), (-2.9, 2.5), (1.0, -1.0), (0.0, 3.0)]
    return kr.euler_to_quat(seq, [[first, middle, third] for middle in middles for first, third in outer])


@pytest.mark.parametrize("seq", CONVENTIONS)
def test_within_an_ulp_of_gimbal_lock_the_third_angle_is_zero(seq):
    q = _near_lock(seq)
    angles = _trajectory(q).euler(seq)
    # one implementation (Rotation normalises its quaternions: the last bit may differ)
    reference = kr.Rotation.from_quat(q).as_euler(seq)
    np.testing.assert_allclose(angles, reference, rtol=0, atol=1e-15)
    third = 2 if seq.isupper() else 0  # the third intrinsic angle is the first extrinsic one
    np.testing.assert_array_equal(angles[:, third], 0.0)
    np.testing.assert_array_equal(reference[:, third], 0.0)
    # the rotation is kept to rounding: only a phase of the order of 2⁻⁵² was dropped
    assert np.abs(kr.euler_to_matrix(seq, angles) - kr.quat_to_matrix(q)).max() < 1.5e-15


@pytest.mark.parametrize("seq", PROPER)
def test_the_identity_gives_zero_angles_also_with_rounding_noise(seq):
    """The issue: an integrated attitude back at the identity gave (176.4°, 1.9e-14°, −176.4°) for ZXZ."""
    noisy = [[1.0, 0.0, 0.0, 0.0], [1.0, 1e-16, 1.2e-16, 0.0], [1.0, 0.0, -1.3e-16, 0.9e-16], [-1.0, 1e-16, 0.0, 1e-16]]
    for s in (seq, seq.upper()):
        angles = _trajectory(noisy).euler(s, degrees=True)
        np.testing.assert_allclose(angles, kr.Rotation.from_quat(noisy).as_euler(s, degrees=True), rtol=0, atol=1e-13)
        assert np.abs(angles).max() < 2e-14, angles
    np.testing.assert_array_equal(_trajectory(noisy[:1]).euler(seq), [[0.0, 0.0, 0.0]])


def test_just_outside_the_lock_band_the_angles_are_kept():
    """A genuine tiny middle angle (10 ulp) keeps its outer angles: only rounding noise is snapped."""
    angles = [0.3, 10 * 2.0**-52, 1.1]
    np.testing.assert_allclose(_trajectory([kr.euler_to_quat("ZXZ", angles)]).euler("ZXZ")[0], angles, rtol=1e-9)
