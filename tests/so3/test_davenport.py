"""Davenport angles against scipy and against the product of axis-angle rotations."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as S

import kreisel as kr
from kreisel import Rotation


def random_axes(rng, kind):
    n1 = rng.normal(size=3)
    n2 = np.cross(n1, rng.normal(size=3))
    n3 = {"general": np.cross(n2, rng.normal(size=3)), "proper": n1, "opposite": -n1}[kind]
    axes = np.array([n1, n2, n3])
    return axes / np.linalg.norm(axes, axis=1, keepdims=True)


def product(axes, order, angles):
    """Independent reference: compose the elementary axis-angle rotations in the stated order."""
    factors = [Rotation.from_rotvec(axes[i] * angles[:, [i]]) for i in range(len(axes))]
    out = factors[0]
    for f in factors[1:]:
        out = out * f if order.startswith("i") else f * out
    return out


@pytest.mark.parametrize("kind", ["general", "proper", "opposite"])
@pytest.mark.parametrize("order", ["i", "e", "intrinsic", "extrinsic"])
def test_matches_scipy_and_the_axis_angle_product(rng, kind, order):
    for _ in range(4):
        axes = random_axes(rng, kind)
        angles = rng.uniform(-np.pi, np.pi, size=(500, 3))
        r = Rotation.from_davenport(3.0 * axes, order, angles)  # axes need not be unit
        s = S.from_davenport(axes, order, angles)
        np.testing.assert_allclose(r.as_matrix(), s.as_matrix(), atol=3e-15)
        np.testing.assert_allclose(r.as_matrix(), product(axes, order, angles).as_matrix(), atol=3e-15)
        back = r.as_davenport(axes, order)
        np.testing.assert_allclose(Rotation.from_davenport(axes, order, back).as_matrix(), r.as_matrix(), atol=3e-15)
        # Same branch as scipy: the angles agree (scipy's own are good to ~1e-12 here).
        np.testing.assert_allclose(back, s.as_davenport(axes, order), atol=1e-9)


def test_coordinate_axes_are_euler_angles(rng):
    angles = rng.uniform(-np.pi, np.pi, size=(100, 3))
    e = np.eye(3)
    for seq in ["ZXZ", "XYZ", "zyx", "yxy"]:
        axes = e[["xyz".index(c) for c in seq.lower()]]
        order = "i" if seq.isupper() else "e"
        np.testing.assert_allclose(kr.davenport_to_quat(axes, order, angles), kr.euler_to_quat(seq, angles), atol=1e-15)
        q = kr.euler_to_quat(seq, angles)
        np.testing.assert_allclose(kr.quat_to_davenport(axes, order, q), kr.quat_to_euler(seq, q), atol=1e-14)


def test_exact_at_gimbal_lock_and_warns_on_request():
    axes = random_axes(np.random.default_rng(3), "general")
    lam = np.arctan2(axes[2] @ np.cross(axes[0], axes[1]), axes[2] @ axes[0])
    locked = np.array([[0.4, lam, -0.3], [0.4, lam + np.pi, 1.0], [0.1, lam + 1e-12, 0.2], [0.3, 0.5, 0.7]])
    r = Rotation.from_davenport(axes, "i", locked)
    back = r.as_davenport(axes, "i")
    np.testing.assert_allclose(Rotation.from_davenport(axes, "i", back).as_matrix(), r.as_matrix(), atol=3e-15)
    np.testing.assert_array_equal(kr.davenport_gimbal_lock(axes, "i", back), [True, True, True, False])
    with pytest.warns(kr.GimbalLockWarning, match="3 of 4"):
        r.as_davenport(axes, "i", suppress_warnings=False)


def test_one_and_two_axes(rng):
    axes = random_axes(rng, "general")
    for k in (1, 2):
        angles = rng.uniform(-np.pi, np.pi, size=(50, k))
        for order in "ie":
            r = Rotation.from_davenport(axes[:k], order, angles)
            np.testing.assert_allclose(r.as_matrix(), S.from_davenport(axes[:k], order, angles).as_matrix(), atol=3e-15)
            np.testing.assert_allclose(r.as_matrix(), product(axes[:k], order, angles).as_matrix(), atol=3e-15)
            np.testing.assert_allclose(r.as_davenport(axes[:k], order), angles, atol=1e-14)
    assert Rotation.from_davenport(axes[0], "e", 0.5).single
    np.testing.assert_allclose(Rotation.from_davenport(axes[0], "e", 0.5).as_davenport(axes[0], "e"), [0.5], atol=1e-15)
    with pytest.raises(ValueError, match="not of the form"):
        Rotation.from_davenport(axes, "i", [0.1, 0.2, 0.3]).as_davenport(axes[:2], "i")


@pytest.mark.parametrize(
    "axes, order, match",
    [
        ([[1, 0, 0], [1, 1, 0], [0, 0, 1]], "i", "orthogonal"),
        ([[1, 0, 0], [0, 1, 0], [0, 1, 1]], "e", "orthogonal"),
        ([[1, 0, 0], [0, 1, 0], [1, 0, 0]], "x", "order"),
        ([[1, 0, 0], [0, 0, 0], [1, 0, 0]], "i", "nonzero"),
        (np.eye(4, 3), "i", "k = 1, 2 or 3"),
        ([[1, 0], [0, 1]], "i", r"axes must have shape \(\.\.\., 3\)"),
    ],
)
def test_bad_axes_are_refused(axes, order, match):
    with pytest.raises(ValueError, match=match):
        Rotation.from_davenport(axes, order, [0.1, 0.2, 0.3])
    with pytest.raises(ValueError, match=match):
        Rotation.identity().as_davenport(axes, order)


def test_large_batches_and_single_calls_agree(rng):
    axes = random_axes(rng, "general")
    angles = rng.uniform(-np.pi, np.pi, size=(40000, 3))  # the multi-core loops
    for order in "ie":
        r = Rotation.from_davenport(axes, order, angles)
        back = r.as_davenport(axes, order)
        for i in (0, 12345, 39999):
            np.testing.assert_array_equal(Rotation.from_davenport(axes, order, angles[i]).as_quat(), r[i].as_quat())
            np.testing.assert_array_equal(r[i].as_davenport(axes, order), back[i])
        np.testing.assert_allclose(Rotation.from_davenport(axes, order, back).as_matrix(), r.as_matrix(), atol=3e-15)


def test_axes_of_any_size_give_the_same_rotation(rng):
    """The axes are directions: scaled by 1e-300 ... 1e300 they give the same quaternion
    (their lengths' squares over- or underflowed beyond 1e±154, and 1e-300 axes were called zero)."""
    axes = np.array([[0.0, 0.0, 1.0], [0.6, 0.8, 0.0], [0.0, 0.0, 1.0]])
    angles = rng.uniform(-2, 2, size=(5, 3))
    want = S.from_davenport(axes, "extrinsic", angles).as_quat(scalar_first=True)
    want *= np.sign(want[:, :1])
    for exponent in (-300, -160, 160, 300):
        got = kr.davenport_to_quat(10.0**exponent * axes, "extrinsic", angles)
        np.testing.assert_allclose(got * np.sign(got[:, :1]), want, atol=1e-15)
        back = kr.so3.quat_to_davenport(10.0**exponent * axes, "extrinsic", 10.0**exponent * got)
        again = kr.davenport_to_quat(axes, "extrinsic", back)
        np.testing.assert_allclose(np.abs(np.sum(again * got, axis=-1)), 1.0, atol=2e-15)
