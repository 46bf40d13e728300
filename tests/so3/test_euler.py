"""Euler angles: the chapter's ZXZ and ZYZ matrices, scipy for all 24 conventions, gimbal lock."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as S

import kreisel as kr
from kreisel import Rotation

PROPER = ["xyx", "xzx", "yxy", "yzy", "zxz", "zyz"]
TAIT_BRYAN = ["xyz", "xzy", "yxz", "yzx", "zxy", "zyx"]
ALL_SEQUENCES = [s for base in PROPER + TAIT_BRYAN for s in (base, base.upper())]


def test_there_are_24_conventions():
    assert len(set(ALL_SEQUENCES)) == 24


def test_chapter_zxz_matrix(rng):
    """R(φ, θ, ψ) = Rz(φ) Rx(θ) Rz(ψ) as printed in Theory §2.3 (2)."""
    for phi, theta, psi in rng.uniform(-3, 3, size=(10, 3)):
        c, s = np.cos, np.sin
        expected = np.array(
            [
                [c(psi) * c(phi) - c(theta) * s(psi) * s(phi), -c(theta) * c(psi) * s(phi) - s(psi) * c(phi), s(theta) * s(phi)],
                [c(psi) * s(phi) + c(theta) * s(psi) * c(phi), c(theta) * c(psi) * c(phi) - s(psi) * s(phi), -s(theta) * c(phi)],
                [s(theta) * s(psi), s(theta) * c(psi), c(theta)],
            ]
        )
        np.testing.assert_allclose(kr.euler_to_matrix("ZXZ", [phi, theta, psi]), expected, atol=1e-15)


def test_chapter_zyz_matrix(rng):
    """Quantum-mechanics R(α, β, γ) = Rz(α) Ry(β) Rz(γ), Theory §2.3 (2)."""
    for a, b, g in rng.uniform(-3, 3, size=(10, 3)):
        c, s = np.cos, np.sin
        expected = np.array(
            [
                [c(a) * c(b) * c(g) - s(a) * s(g), -c(a) * c(b) * s(g) - s(a) * c(g), c(a) * s(b)],
                [s(a) * c(b) * c(g) + c(a) * s(g), -s(a) * c(b) * s(g) + c(a) * c(g), s(a) * s(b)],
                [-s(b) * c(g), s(b) * s(g), c(b)],
            ]
        )
        np.testing.assert_allclose(kr.euler_to_matrix("ZYZ", [a, b, g]), expected, atol=1e-15)


def test_intrinsic_zxz_equals_body_axis_rotations():
    """R_z''(ψ) R_x'(θ) R_z(φ) = R_z(φ) R_x(θ) R_z(ψ) (Theory §2.3 (2)); extrinsic reverses the order."""
    phi, theta, psi = 0.4, 1.1, -2.0
    Rz = lambda a: kr.rotvec_to_matrix([0, 0, a])  # noqa: E731
    Rx = lambda a: kr.rotvec_to_matrix([a, 0, 0])  # noqa: E731
    np.testing.assert_allclose(kr.euler_to_matrix("ZXZ", [phi, theta, psi]), Rz(phi) @ Rx(theta) @ Rz(psi), atol=1e-15)
    np.testing.assert_allclose(kr.euler_to_matrix("zxz", [phi, theta, psi]), Rz(psi) @ Rx(theta) @ Rz(phi), atol=1e-15)


@pytest.mark.parametrize("seq", ALL_SEQUENCES)
def test_against_scipy(seq, random_quats):
    q = random_quats(300)
    R = kr.quat_to_matrix(q)
    angles = S.from_matrix(R).as_euler(seq)
    np.testing.assert_allclose(kr.matrix_to_euler(seq, R), angles, atol=5e-15)
    np.testing.assert_allclose(kr.quat_to_euler(seq, q), angles, atol=5e-15)
    np.testing.assert_allclose(kr.euler_to_matrix(seq, angles), S.from_euler(seq, angles).as_matrix(), atol=2e-15)
    qs = kr.euler_to_quat(seq, angles)
    np.testing.assert_allclose(kr.quat_to_matrix(qs), R, atol=2e-15)
    np.testing.assert_allclose(
        kr.euler_to_matrix(seq, np.degrees(angles), degrees=True), S.from_euler(seq, angles).as_matrix(), atol=2e-15
    )
    np.testing.assert_allclose(kr.matrix_to_euler(seq, R, degrees=True), np.degrees(angles), atol=1e-12)


def _singular_middles(seq):
    return [0.0, np.pi] if seq[0].lower() == seq[2].lower() else [-np.pi / 2, np.pi / 2]


@pytest.mark.parametrize("seq", ALL_SEQUENCES)
def test_gimbal_lock_reconstruction_is_exact(seq):
    """At and near the singular middle angle the rebuilt rotation matches to ~1e-15.

    (scipy's as_euler sets the third angle to 0 within 1e-7 of the singularity
    and loses up to ~1e-9 there.)
    """
    worst = 0.0
    for middle in _singular_middles(seq):
        for offset in (0.0, 1e-15, 1e-12, 1e-9, 3e-8, 1e-7, -1e-7, 1e-5):
            m = middle + offset if middle <= 0 or middle == np.pi / 2 else middle - abs(offset)
            for first, third in [(0.3, 1.1), (-2.9, 2.5), (1.0, -1.0)]:
                R = kr.euler_to_matrix(seq, [first, m, third])
                angles = kr.matrix_to_euler(seq, R)
                worst = max(worst, np.abs(kr.euler_to_matrix(seq, angles) - R).max())
                q = kr.matrix_to_quat(R)
                worst = max(worst, np.abs(kr.euler_to_matrix(seq, kr.quat_to_euler(seq, q)) - R).max())
    assert worst < 1.5e-15


def test_gimbal_lock_exact_sets_third_intrinsic_angle_to_zero():
    R = kr.euler_to_matrix("ZXZ", [0.3, 0.0, 0.5])
    np.testing.assert_allclose(kr.matrix_to_euler("ZXZ", R), [0.8, 0.0, 0.0], atol=1e-15)
    # Extrinsic: the first angle is the third intrinsic one. Rz(0.5) Ry(π/2) exactly:
    R = np.array([[0.0, 0, 1], [0, 1, 0], [-1, 0, 0]])
    R = np.array([[np.cos(0.5), -np.sin(0.5), 0], [np.sin(0.5), np.cos(0.5), 0], [0, 0, 1]]) @ R
    angles = kr.matrix_to_euler("xyz", R)
    assert angles[0] == 0.0
    np.testing.assert_allclose(kr.euler_to_matrix("xyz", angles), R, atol=1e-15)


def test_gimbal_lock_report():
    angles = [[0.1, 1e-9, 0.2], [0.1, 0.5, 0.2], [0.1, np.pi - 1e-9, 0.2], [0.1, np.pi / 2, 0.2]]
    np.testing.assert_array_equal(kr.gimbal_lock("ZXZ", angles), [True, False, True, False])
    np.testing.assert_array_equal(kr.gimbal_lock("xyz", angles), [False, False, False, True])
    np.testing.assert_array_equal(kr.gimbal_lock("XYZ", np.degrees(angles), degrees=True, tolerance=1e-3), [False, False, False, True])


def test_ranges(random_quats):
    q = random_quats(2000)
    proper = kr.quat_to_euler("ZXZ", q)
    assert np.all((proper[:, 1] >= 0) & (proper[:, 1] <= np.pi))
    tb = kr.quat_to_euler("xyz", q)
    assert np.all(np.abs(tb[:, 1]) <= np.pi / 2)
    assert np.all(np.abs(np.concatenate([proper[:, ::2], tb[:, ::2]])) <= np.pi)


def test_parse_sequence():
    assert kr.parse_sequence("ZXZ") == ((2, 0, 2), True)
    assert kr.parse_sequence("yzx") == ((1, 2, 0), False)
    assert sorted(kr.parse_sequence(s) for s in ALL_SEQUENCES) == sorted(
        (tuple("xyz".index(c) for c in s.lower()), s.isupper()) for s in ALL_SEQUENCES
    )


@pytest.mark.parametrize("bad", ["xYz", "XYZX", "XXY", "xyy", "abc", "", 3, "XYW", "Xy", "XX", "w"])
def test_malformed_sequences_are_refused(bad):
    with pytest.raises(ValueError, match="seq"):
        kr.parse_sequence(bad)
    with pytest.raises(ValueError, match="seq"):
        kr.euler_to_matrix(bad, [0.1, 0.2, 0.3])


def test_parse_sequence_is_for_three_axes_only():
    with pytest.raises(ValueError, match="seq"):
        kr.parse_sequence("XY")


def test_bad_angles_are_refused():
    with pytest.raises(ValueError, match=r"angles must have shape \(\.\.\., 3\)"):
        kr.euler_to_quat("ZXZ", [0.1, 0.2])
    with pytest.raises(ValueError, match="angles must be finite"):
        kr.euler_to_quat("ZXZ", [0.1, np.nan, 0.2])


def test_broadcasting():
    angles = np.zeros((2, 5, 3))
    assert kr.euler_to_matrix("XYZ", angles).shape == (2, 5, 3, 3)
    assert kr.matrix_to_euler("zyx", np.broadcast_to(np.eye(3), (4, 3, 3))).shape == (4, 3)


SHORT_SEQUENCES = ["x", "Y", "z", "XY", "XZ", "YX", "YZ", "ZX", "ZY", "xy", "xz", "yx", "yz", "zx", "zy"]


@pytest.mark.parametrize("seq", SHORT_SEQUENCES)
def test_short_sequences_match_scipy_and_invert_exactly(rng, seq):
    angles = rng.uniform(-np.pi, np.pi, size=(200, len(seq)))
    angles[:3, -1] = [0.0, np.pi, -np.pi / 2]  # edges: axes aligned, half turns
    if len(seq) == 2:
        angles[3:6, 0] = [0.0, np.pi, -np.pi / 2]
    q = kr.euler_to_quat(seq, angles)
    np.testing.assert_allclose(kr.quat_to_matrix(q), S.from_euler(seq, angles).as_matrix(), atol=1e-15)
    np.testing.assert_allclose(kr.euler_to_matrix(seq, angles), S.from_euler(seq, angles).as_matrix(), atol=1e-15)
    # Composition of elementary rotations, as the sequence says (an independent reference).
    axes = ["xyz".index(c) for c in seq.lower()]
    factors = [Rotation.from_rotvec(np.eye(3)[a] * angles[:, [i]]) for i, a in enumerate(axes)]
    product = factors[0]
    for f in factors[1:]:
        product = product * f if seq.isupper() else f * product
    np.testing.assert_allclose(product.as_matrix(), kr.quat_to_matrix(q), atol=1e-15)
    back = kr.quat_to_euler(seq, q)
    np.testing.assert_allclose(kr.euler_to_matrix(seq, back), kr.quat_to_matrix(q), atol=1e-15)
    wrapped = np.angle(np.exp(1j * (back - angles)))
    np.testing.assert_allclose(wrapped, 0.0, atol=1e-14)
    np.testing.assert_allclose(kr.matrix_to_euler(seq, kr.quat_to_matrix(q)), back, atol=1e-14)
    r = Rotation.from_euler(seq, np.rad2deg(angles), degrees=True)
    np.testing.assert_allclose(r.as_euler(seq, degrees=True), np.rad2deg(back), atol=1e-12)


def test_short_sequences_refuse_rotations_they_cannot_represent():
    q = kr.euler_to_quat("ZXY", [0.1, 0.2, 1e-6])
    with pytest.raises(ValueError, match="seq 'ZX'"):
        kr.quat_to_euler("ZX", q)
    with pytest.raises(ValueError, match="seq 'z'"):
        Rotation.from_quat(q).as_euler("z")
    with pytest.raises(ValueError, match=r"angles must have shape \(\.\.\., 2\)"):
        kr.euler_to_quat("ZX", [0.1, 0.2, 0.3])
    # One axis: a scalar is one rotation, (..., 1) a batch, as in scipy.
    assert kr.euler_to_quat("z", 0.3).shape == (4,)
    assert Rotation.from_euler("z", [[0.1], [0.2]]).shape == (2,)


def test_as_euler_warns_at_gimbal_lock_only_on_request():
    import warnings

    locked = Rotation.from_euler("ZYX", [[0.3, np.pi / 2, 0.1], [0.3, 0.2, 0.1]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        angles = locked.as_euler("ZYX")
    np.testing.assert_allclose(Rotation.from_euler("ZYX", angles).as_matrix(), locked.as_matrix(), atol=1e-15)
    with pytest.warns(kr.GimbalLockWarning, match="1 of 2"):
        locked.as_euler("ZYX", suppress_warnings=False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        locked[1].as_euler("ZYX", suppress_warnings=False)


@pytest.mark.parametrize("seq", ["ZXZ", "xyz", "ZX"])
def test_quaternions_of_any_size_give_the_same_angles(seq, random_quats):
    """quat_to_euler is scale invariant from 1e-300 to 1e300 (the half-angle pairs' squares
    overflowed beyond 1e154)."""
    q = random_quats(20) if len(seq) == 3 else kr.euler_to_quat(seq, np.random.default_rng(3).uniform(-2, 2, (20, 2)))
    want = kr.quat_to_euler(seq, q)
    for exponent in (-300, -160, 160, 300):
        np.testing.assert_allclose(kr.quat_to_euler(seq, 10.0**exponent * q), want, rtol=0, atol=4e-15)


def test_a_scaled_matrix_is_refused_as_not_a_rotation(random_quats):
    """R·1e103 has finite entries whose squares overflow: it is not a rotation (never 'must be finite')."""
    R = kr.quat_to_matrix(random_quats(1))[0]
    for fn in (lambda m: kr.matrix_to_euler("ZXZ", m), kr.matrix_to_rotvec, kr.matrix_to_quat):
        with pytest.raises(ValueError, match=r"R must be rotation matrices \(entries in \[-1, 1\]\), got entries as large as"):
            fn(1e103 * R)
        with pytest.raises(ValueError, match=r"R must be rotation matrices: max \|R\^T R - 1\| = 1 exceeds"):
            fn(1e-200 * R)
        with pytest.raises(ValueError, match="must be finite"):
            fn(np.full((3, 3), np.inf))
