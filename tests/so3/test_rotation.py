"""The Rotation object layer: every representation, group operations, scipy interop."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation as S

import kreisel as kr
from kreisel import Rotation


def test_round_trips_through_every_representation():
    r = Rotation.random(50, rng=7)
    R = r.as_matrix()
    pairs = [
        ("quat", ()),
        ("matrix", ()),
        ("rotvec", ()),
        ("euler", ("ZXZ",)),
        ("euler", ("xyz",)),
        ("su2", ()),
        ("cayley_klein", ()),
        ("euler_parameters", ()),
        ("gibbs", ()),
        ("mrp", ()),
    ]
    for name, args in pairs:
        rep = getattr(r, f"as_{name}")(*args)
        back = getattr(Rotation, f"from_{name}")(*args, rep)
        np.testing.assert_allclose(back.as_matrix(), R, atol=3e-15, err_msg=name)
    axis, angle = r.as_axis_angle(degrees=True)
    np.testing.assert_allclose(Rotation.from_axis_angle(axis, angle, degrees=True).as_matrix(), R, atol=3e-15)
    np.testing.assert_allclose(Rotation.from_rotvec(r.as_rotvec(degrees=True), degrees=True).as_matrix(), R, atol=3e-15)


def test_composition_inverse_apply(rng):
    a, b = Rotation.random(20, rng=1), Rotation.random(20, rng=2)
    np.testing.assert_allclose((a * b).as_matrix(), a.as_matrix() @ b.as_matrix(), atol=2e-15)
    np.testing.assert_allclose((a * a.inv()).magnitude(), 0, atol=1e-7)
    v = rng.normal(size=(20, 3))
    np.testing.assert_allclose(a.apply(v), np.einsum("nij,nj->ni", a.as_matrix(), v), atol=1e-14)
    np.testing.assert_allclose(a.apply(a.apply(v), inverse=True), v, atol=1e-14)
    assert a.approx_equal(a).all()


def test_approx_equal_takes_scipys_degrees():
    a, b = Rotation.random(50, rng=4), Rotation.random(50, rng=5)
    angles = np.degrees((a.inv() * b).magnitude())
    for atol in (np.median(angles), 90.0):
        expected = S.from_quat(a.as_quat(), scalar_first=True).approx_equal(
            S.from_quat(b.as_quat(), scalar_first=True), atol=atol, degrees=True)
        np.testing.assert_array_equal(a.approx_equal(b, atol, degrees=True), expected)
        np.testing.assert_array_equal(a.approx_equal(b, atol=np.radians(atol)), expected)
    with pytest.raises(TypeError, match="degrees"):
        a.approx_equal(b, 1.0, degrees="yes")


def test_container_protocol_and_repr():
    r = Rotation.random((4, 3), rng=3)
    assert r.shape == (4, 3) and len(r) == 4
    assert r[1].shape == (3,) and r[1, 2].single
    np.testing.assert_array_equal(r[1, 2].as_quat(), r.as_quat()[1, 2])
    one = Rotation.from_rotvec([0, 0, np.pi / 2])
    assert repr(one) == "Rotation.from_quat([0.707107, 0, 0, 0.707107])"
    assert "shape (4, 3)" in repr(r)
    with pytest.raises(TypeError):
        len(one)
    with pytest.raises(TypeError):
        one[0]
    assert Rotation.identity(3).magnitude().tolist() == [0.0, 0.0, 0.0]


def test_canonical_and_scalar_last():
    r = Rotation.from_quat([-0.5, 0.5, 0.5, 0.5])
    assert r.as_quat(canonical=True)[0] > 0 and r.as_quat()[0] < 0
    np.testing.assert_allclose(r.as_quat(scalar_first=False), [0.5, 0.5, 0.5, -0.5])
    np.testing.assert_allclose(Rotation.from_quat([0.5, 0.5, 0.5, -0.5], scalar_first=False).as_quat(), r.as_quat())


def test_scipy_interop():
    r = Rotation.random(10, rng=4)
    s = r.to_scipy()
    assert isinstance(s, S)
    np.testing.assert_allclose(s.as_matrix(), r.as_matrix(), atol=1e-15)
    np.testing.assert_allclose(Rotation.from_scipy(s).as_matrix(), r.as_matrix(), atol=1e-15)


def test_random_is_uniform_and_seeded():
    r = Rotation.random(20000, rng=5)
    np.testing.assert_array_equal(r.as_quat(), Rotation.random(20000, rng=5).as_quat())
    # Haar measure: the rotation angle has density (1 - cos ψ)/π, so E[ψ] = π/2 + 2/π.
    assert r.magnitude().mean() == pytest.approx(np.pi / 2 + 2 / np.pi, abs=0.02)
    # Each column of R is uniform on the sphere: zero mean.
    np.testing.assert_allclose(r.as_matrix().mean(axis=0), 0.0, atol=0.02)


def test_mean_matches_scipy_and_is_sign_independent():
    r = Rotation.from_rotvec(0.3 * np.random.default_rng(6).normal(size=(30, 3)))
    w = np.linspace(0.5, 2.0, 30)
    expected = S.from_quat(r.as_quat(scalar_first=False)).mean(weights=w)
    flipped = Rotation.from_quat(r.as_quat() * np.where(np.arange(30) % 2, -1, 1)[:, None])
    np.testing.assert_allclose(flipped.mean(w).as_matrix(), expected.as_matrix(), atol=1e-14)
    with pytest.raises(ValueError, match="weights"):
        r.mean(-w)


@pytest.mark.parametrize("axis", [None, 0, ()])
def test_the_mean_of_a_single_rotation_is_itself_as_in_scipy(axis):
    # scipy averages a single rotation as a batch of one: the result's shape follows axis
    v = np.array([0.1, 0.2, -3.0])
    ours, theirs = Rotation.from_rotvec(v).mean(axis=axis), S.from_rotvec(v).mean(axis=axis)
    assert ours.shape == theirs.as_quat().shape[:-1]
    np.testing.assert_allclose(ours.as_matrix(), theirs.as_matrix(), atol=1e-15)
    np.testing.assert_allclose(Rotation.from_rotvec(v).mean(weights=[2.0]).as_matrix(),
                               Rotation.from_rotvec(v).as_matrix(), atol=1e-15)
    with pytest.raises(ValueError, match=r"weights must have the batch shape \(1,\)"):
        Rotation.from_rotvec(v).mean(weights=2.0)


def test_slerp_constant_rate_and_endpoints():
    a, b = Rotation.random(rng=8), Rotation.random(rng=9)
    t = np.linspace(0, 1, 11)
    path = a.slerp(b, t)
    np.testing.assert_allclose(path[0].as_matrix(), a.as_matrix(), atol=1e-15)
    np.testing.assert_allclose(path[-1].as_matrix(), b.as_matrix(), atol=1e-14)
    steps = (path[:-1].inv() * path[1:]).magnitude()
    np.testing.assert_allclose(steps, (a.inv() * b).magnitude() / 10, rtol=1e-12)
    # Shorter arc even when b is given with the opposite sign.
    minus_b = Rotation.from_quat(-b.as_quat())
    np.testing.assert_allclose(a.slerp(minus_b, 0.5).as_matrix(), path[5].as_matrix(), atol=1e-14)


def test_bad_input():
    with pytest.raises(ValueError, match="q must be nonzero"):
        Rotation.from_quat([0.0, 0, 0, 0])
    with pytest.raises(ValueError, match="R must be rotation matrices"):
        Rotation.from_matrix(np.diag([1.0, 1.0, 2.0]))
    with pytest.raises(ValueError, match="det > 0"):
        Rotation.from_matrix(np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(ValueError, match="seq"):
        Rotation.from_euler("xYz", [0, 0, 0])
    assert kr.Rotation is Rotation


# -- regressions (issue: rotations a scipy user can switch to) ----------------


def test_composition_stays_on_the_unit_sphere():
    # rs -> rs r rs squares the norm error every round without renormalisation
    # (|q| - 1 reached 0.36 after 50 rounds, then overflowed).
    r, rs = Rotation.random(rng=0), Rotation.random(rng=1)
    batch_r, batch_rs = Rotation.random(5, rng=2), Rotation.random(5, rng=3)
    for _ in range(80):
        rs = rs * r * rs
        batch_rs = batch_rs * batch_r * batch_rs
    assert abs(np.linalg.norm(rs.as_quat()) - 1.0) < 4e-16
    np.testing.assert_allclose(np.linalg.norm(batch_rs.as_quat(), axis=-1), 1.0, atol=4e-16)
    # Renormalising does not move the rotation: same matrix as the plain product.
    a, b = Rotation.random(100, rng=4), Rotation.random(100, rng=5)
    np.testing.assert_allclose((a * b).as_quat(), kr.quat_multiply(a.as_quat(), b.as_quat()), atol=4e-16)


@pytest.mark.parametrize(
    "q",
    [[0.0, 0.6, -0.8, 0.0], [0.0, 0.0, -1.0, 0.0], [0.0, 0.0, 0.0, -1.0], [0.0, -0.0, 0.6, 0.8], [-0.6, 0.0, 0.8, 0.0]],
)
def test_canonical_quaternion_is_unique_for_half_turns(q):
    q = np.array(q)
    a = Rotation.from_quat(q).as_quat(canonical=True)
    b = Rotation.from_quat(-q).as_quat(canonical=True)
    assert a.tobytes() == b.tobytes()
    first = a[np.flatnonzero(a)[0]]
    assert first > 0
    # scipy's canonical form is the same quaternion (scalar last there).
    np.testing.assert_array_equal(S.from_quat(q, scalar_first=True).as_quat(canonical=True, scalar_first=True), a)


def test_canonical_quaternion_batch():
    q = np.array([[0.0, -0.6, 0.8, 0.0], [-1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, -1.0]])
    np.testing.assert_array_equal(
        Rotation.from_quat(q).as_quat(canonical=True), [[0.0, 0.6, -0.8, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
    )


@pytest.mark.parametrize("width", [3, 5, 7, 8])
@pytest.mark.parametrize("scalar_first", [True, False])
def test_quaternion_width_is_checked_before_reordering(width, scalar_first):
    x = np.ones((2, width))
    with pytest.raises(ValueError, match=r"quat must have shape \(\.\.\., 4\)"):
        Rotation.from_quat(x, scalar_first=scalar_first)
    with pytest.raises(ValueError, match=r"\(\.\.\., 4\)"):
        Rotation(x)


def test_mean_of_no_rotations_is_refused():
    with pytest.raises(ValueError, match="empty"):
        Rotation.identity(0).mean()
    with pytest.raises(ValueError, match="empty"):
        kr.quat_mean(np.zeros((0, 4)))


@pytest.mark.parametrize("shape", [2.5, 2.0, (2, 1.5), "3", (-1,), [True]])
def test_shape_arguments_are_checked(shape):
    for make in (Rotation.identity, Rotation.random, kr.quat_identity, kr.RigidTransform.identity):
        with pytest.raises(ValueError, match="shape"):
            make(shape)


def test_random_matches_scipy_seeds():
    for seed in (0, 1, 123):
        np.testing.assert_allclose(
            Rotation.random((3, 2), rng=seed).as_quat(scalar_first=False),
            S.random(shape=(3, 2), rng=seed).as_quat(),
            rtol=0,
            atol=3e-16,
        )
        np.testing.assert_allclose(
            Rotation.random(rng=seed).as_quat(), S.random(rng=seed).as_quat(scalar_first=True), rtol=0, atol=3e-16
        )


# -- powers and means over axes (scipy parity) ----------------------------------


@pytest.mark.parametrize("p", [0, 1, -1, 0.5, -0.25, 2, 3.7, -2.5, 1e-9])
def test_powers_match_scipy_and_scale_the_rotation_vector(p):
    r = Rotation.random(200, rng=8)
    got = r**p
    np.testing.assert_allclose(got.as_matrix(), (r.to_scipy() ** p).as_matrix(), atol=3e-15)
    # Independent: exp(p ψ) with ψ = log r, |ψ| <= π.
    np.testing.assert_allclose(got.as_matrix(), kr.rotvec_to_matrix(p * r.as_rotvec()), atol=3e-15)
    np.testing.assert_allclose(np.linalg.norm(got.as_quat(), axis=-1), 1.0, atol=3e-16)


def test_power_special_cases_are_exact_and_exponents_broadcast():
    r = Rotation.random(6, rng=9)
    np.testing.assert_array_equal((r**0).as_quat(), Rotation.identity(6).as_quat())
    np.testing.assert_allclose((r**-1).as_quat(), r.inv().as_quat(), rtol=0, atol=2.3e-16)  # renormalised only
    np.testing.assert_allclose((r**1).as_quat(), r.as_quat(), rtol=0, atol=2.3e-16)
    # (r^a)(r^b) = r^(a+b) for exponents that keep the angle within π.
    np.testing.assert_allclose((r**0.3 * r**0.4).as_matrix(), (r**0.7).as_matrix(), atol=3e-15)
    p = np.linspace(-1.0, 1.0, 6)
    np.testing.assert_allclose((r**p).as_matrix(), [(r[i] ** p[i]).as_matrix() for i in range(6)], atol=1e-15)
    half = Rotation.from_rotvec([0.0, 0.0, 1.5 * np.pi])  # 270° is stored as -90°
    np.testing.assert_allclose((half**2).magnitude(), np.pi, atol=1e-15)
    with pytest.raises(ValueError, match="p must be finite"):
        r ** np.nan
    with pytest.raises(TypeError):
        pow(r, 2, 3)
    big = Rotation.random(40000, rng=10)  # the multi-core loop
    np.testing.assert_allclose((big**0.3).as_matrix()[::997], (big[::997] ** 0.3).as_matrix(), atol=0)


@pytest.mark.parametrize("axis", [None, 0, 1, -1, (0, 1), (1,)])
def test_mean_over_axes_matches_scipy(axis, rng):
    r = Rotation.random((4, 5), rng=11)
    w = rng.random((4, 5))
    s = r.to_scipy()
    for weights in (None, w):
        got = r.mean(weights, axis=axis)
        want = Rotation.from_scipy(s.mean(weights, axis=axis))
        assert got.shape == want.shape
        assert got.approx_equal(want, atol=1e-12).all()
    with pytest.raises(ValueError, match="out of bounds"):
        r.mean(axis=2)
    with pytest.raises(ValueError, match="weights must have the batch shape"):
        r.mean(np.ones(5))


_AXES_ZXZ = [[0, 0, 1], [1, 0, 0], [0, 0, 1]]
_FLAG_CALLS = {
    "scalar_first": [lambda f: Rotation.from_quat([1.0, 0, 0, 0], scalar_first=f),
                     lambda f: Rotation.identity().as_quat(scalar_first=f)],
    "canonical": [lambda f: Rotation.identity().as_quat(canonical=f)],
    "degrees": [lambda f: Rotation.from_rotvec([1.0, 0, 0], degrees=f),
                lambda f: Rotation.identity().as_rotvec(degrees=f),
                lambda f: Rotation.identity().as_axis_angle(degrees=f),
                lambda f: Rotation.from_euler("ZXZ", [1.0, 2, 3], degrees=f),
                lambda f: Rotation.from_euler("z", 1.0, degrees=f),
                lambda f: Rotation.identity().as_euler("ZXZ", degrees=f),
                lambda f: Rotation.identity().as_euler("ZX", degrees=f),
                lambda f: kr.matrix_to_euler("ZXZ", np.eye(3), degrees=f),
                lambda f: kr.gimbal_lock("ZXZ", [1.0, 2, 3], degrees=f),
                lambda f: Rotation.from_axis_angle([1.0, 0, 0], 1.0, degrees=f),
                lambda f: kr.davenport_to_quat(_AXES_ZXZ, "i", [1.0, 2, 3], degrees=f),
                lambda f: kr.quat_to_davenport(_AXES_ZXZ, "i", [1.0, 0, 0, 0], degrees=f),
                lambda f: kr.davenport_gimbal_lock(_AXES_ZXZ, "i", [1.0, 2, 3], degrees=f)],
    "inverse": [lambda f: Rotation.identity().apply([1.0, 0, 0], inverse=f),
                lambda f: kr.quat_apply([1.0, 0, 0, 0], [1.0, 0, 0], inverse=f)],
    "suppress_warnings": [lambda f: Rotation.identity().as_euler("ZXZ", suppress_warnings=f)],
}


@pytest.mark.filterwarnings("ignore:gimbal lock")
@pytest.mark.parametrize("name, call", [(n, c) for n, calls in _FLAG_CALLS.items() for c in calls])
def test_convention_flags_take_only_booleans(name, call):
    # "no" and None are truthy and falsy: read as flags they would silently pick the
    # other quaternion order, unit or direction than the caller meant
    for bad in ("no", None, 1, "False"):
        with pytest.raises(TypeError, match=f"{name} must be True or False"):
            call(bad)
    for good in (True, False, np.True_, np.False_):
        call(good)
