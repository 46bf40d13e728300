"""estimate_attitude: exact tracking of noise-free motion, the published filters step by step, a real trial."""

from importlib import resources

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from kreisel.nav import _attitude_kernels, attitude_error, attitude_from_vectors, compare_attitude, estimate_attitude

RATE = 200.0
FIELD = np.array([0.0, 20.0, -45.0])  # ENU, µT: north and down


def motion(n=2000, rate=RATE, w=(0.4, -0.3, 0.8), q0=(0.9, 0.1, -0.3, 0.2)):
    """Turning at a constant body rate from q0: exact gyro, accelerometer and field samples."""
    w = np.asarray(w, float)
    r0 = Rotation.from_quat(np.roll(np.asarray(q0) / np.linalg.norm(q0), -1))
    r = r0 * Rotation.from_rotvec(np.arange(n)[:, None] * w / rate)
    q = np.roll(r.as_quat(), 1, axis=1)
    acc = r.inv().apply([0.0, 0.0, 9.81])
    mag = r.inv().apply(FIELD)
    return np.tile(w, (n, 1)), acc, mag, q


@pytest.mark.parametrize("method", [None, "madgwick", "mahony", "complementary"])
def test_noise_free_motion_is_tracked(method):
    """Gyro, accelerometer and field agree exactly: every filter stays on the motion from its TRIAD start."""
    gyr, acc, mag, q_true = motion()
    est = estimate_attitude(gyr, acc, mag, rate=RATE, method=method)
    np.testing.assert_allclose(np.abs(np.sum(est.q[:1] * q_true[:1], axis=1)), 1.0, atol=1e-15)
    # the published filters integrate q̇ to first order and drift a little until their gain pulls them back
    assert attitude_error(est.q, q_true)[0] < (1e-9 if method in (None, "complementary") else 0.5)
    if method is None:
        assert np.abs(est.bias).max() < 1e-12


def test_gyro_bias_is_learned_at_rest():
    n = 4000
    q0 = np.array([0.95, 0.2, 0.1, -0.2])
    q0 /= np.linalg.norm(q0)
    r = Rotation.from_quat(np.roll(q0, -1))
    bias = np.array([0.01, -0.02, 0.005])
    est = estimate_attitude(np.tile(bias, (n, 1)), np.tile(r.inv().apply([0, 0, 9.81]), (n, 1)),
                            np.tile(r.inv().apply(FIELD), (n, 1)), rate=RATE)
    np.testing.assert_allclose(est.bias[-1], bias, atol=5e-4)
    assert attitude_error(est.q[-100:], np.tile(q0, (100, 1)))[0] < 0.1
    # the covariance bound: positive definite and small at the end
    assert np.all(np.linalg.eigvalsh(est.covariance[-1]) > 0)


def test_madgwick_step_as_published():
    """One step of Madgwick's MARG update, written out from the report (NWU frame, q frame ← sensor)."""
    gyr, acc, mag, _ = motion(3)
    beta = 0.12
    q = np.array(attitude_from_vectors(acc[0], mag[0]))
    nwu = Rotation.from_rotvec([0, 0, -np.pi / 2]) * Rotation.from_quat(np.roll(q, -1))
    q = np.roll(nwu.as_quat(), 1)
    qw, qx, qy, qz = q
    a = acc[1] / np.linalg.norm(acc[1])
    m = mag[1] / np.linalg.norm(mag[1])
    h = Rotation.from_quat(np.roll(q, -1)).apply(m)
    bx, bz = np.hypot(h[0], h[1]), h[2]
    f = np.array([2 * (qx * qz - qw * qy) - a[0], 2 * (qw * qx + qy * qz) - a[1], 2 * (0.5 - qx**2 - qy**2) - a[2],
                  2 * bx * (0.5 - qy**2 - qz**2) + 2 * bz * (qx * qz - qw * qy) - m[0],
                  2 * bx * (qx * qy - qw * qz) + 2 * bz * (qw * qx + qy * qz) - m[1],
                  2 * bx * (qw * qy + qx * qz) + 2 * bz * (0.5 - qx**2 - qy**2) - m[2]])
    J = np.array([[-2 * qy, 2 * qz, -2 * qw, 2 * qx], [2 * qx, 2 * qw, 2 * qz, 2 * qy], [0, -4 * qx, -4 * qy, 0],
                  [-2 * bz * qy, 2 * bz * qz, -4 * bx * qy - 2 * bz * qw, -4 * bx * qz + 2 * bz * qx],
                  [-2 * bx * qz + 2 * bz * qx, 2 * bx * qy + 2 * bz * qw, 2 * bx * qx + 2 * bz * qz,
                   -2 * bx * qw + 2 * bz * qy],
                  [2 * bx * qy, 2 * bx * qz - 4 * bz * qx, 2 * bx * qw - 4 * bz * qy, 2 * bx * qx]])
    grad = J.T @ f
    w = gyr[1]
    qdot = 0.5 * np.array([-qx * w[0] - qy * w[1] - qz * w[2], qw * w[0] + qy * w[2] - qz * w[1],
                           qw * w[1] - qx * w[2] + qz * w[0], qw * w[2] + qx * w[1] - qy * w[0]])
    qn = q + (qdot - beta * grad / np.linalg.norm(grad)) / RATE
    qn /= np.linalg.norm(qn)
    enu = np.roll((Rotation.from_rotvec([0, 0, np.pi / 2]) * Rotation.from_quat(np.roll(qn, -1))).as_quat(), 1)
    est = estimate_attitude(gyr[:2], acc[:2], mag[:2], rate=RATE, method="madgwick")
    np.testing.assert_allclose(np.abs(est.q[1] @ enu), 1.0, atol=1e-14)


def test_mahony_step_as_published():
    gyr, acc, mag, _ = motion(3)
    kp, ki = 0.74, 0.0012
    q = np.array(attitude_from_vectors(acc[0], mag[0]))
    # disturb the start so that the correction is not zero
    q = np.roll((Rotation.from_rotvec([0.02, -0.01, 0.03]) * Rotation.from_quat(np.roll(q, -1))).as_quat(), 1)
    r = Rotation.from_quat(np.roll(q, -1))
    a = acc[1] / np.linalg.norm(acc[1])
    m = mag[1] / np.linalg.norm(mag[1])
    h = r.apply(m)
    v_a = r.inv().apply([0, 0, 1.0])
    v_m = r.inv().apply([0, np.hypot(h[0], h[1]), h[2]])
    v_m /= np.linalg.norm(v_m)
    e = np.cross(a, v_a) + np.cross(m, v_m)
    b = -ki * e / RATE
    w = gyr[1] - b + kp * e
    qw, qx, qy, qz = q
    qdot = 0.5 * np.array([-qx * w[0] - qy * w[1] - qz * w[2], qw * w[0] + qy * w[2] - qz * w[1],
                           qw * w[1] - qx * w[2] + qz * w[0], qw * w[2] + qx * w[1] - qy * w[0]])
    qn = q + qdot / RATE
    qn /= np.linalg.norm(qn)
    out = np.empty((2, 4))
    bias = np.empty((2, 3))
    _attitude_kernels.mahony_filter(gyr[:2], acc[:2], mag[:2], True, 1 / RATE, kp, ki, q, out, bias)
    np.testing.assert_allclose(out[1], qn, atol=1e-15)
    np.testing.assert_allclose(bias[1], b, atol=1e-18)


def test_ned_is_the_enu_result_turned():
    gyr, acc, mag, _ = motion(300)
    enu = estimate_attitude(gyr, acc, mag, rate=RATE)
    ned = estimate_attitude(gyr, acc, mag, rate=RATE, frame="NED")
    turn = Rotation.from_matrix([[0, 1, 0], [1, 0, 0], [0, 0, -1]])
    expected = np.roll((turn * Rotation.from_quat(np.roll(enu.q, -1, axis=1))).as_quat(), 1, axis=1)
    np.testing.assert_allclose(np.abs(np.sum(ned.q * expected, axis=1)), 1.0, atol=1e-13)


@settings(max_examples=25, deadline=None)
@given(st.sampled_from([(None, False), (None, True), ("madgwick", False), ("mahony", False),
                        ("complementary", False)]),
       st.lists(st.floats(-1.0, 1.0), min_size=4, max_size=4).filter(lambda q: np.linalg.norm(q) > 0.1),
       st.lists(st.floats(-2.0, 2.0), min_size=3, max_size=3), st.booleans())
def test_ned_is_the_enu_result_turned_for_every_method(variant, q0, w, with_mag):
    # the same samples give, in NED, the ENU attitude turned by the fixed half turn NED ← ENU, the same bias
    # and the covariance in NED components (y, x, −z)
    method, offline = variant
    gyr, acc, mag, _ = motion(150, w=w, q0=q0)
    mag = mag if with_mag else None
    enu = estimate_attitude(gyr, acc, mag, rate=RATE, method=method, offline=offline)
    ned = estimate_attitude(gyr, acc, mag, rate=RATE, method=method, offline=offline, frame="NED")
    turn = Rotation.from_matrix([[0, 1, 0], [1, 0, 0], [0, 0, -1]])
    expected = (turn * Rotation.from_quat(enu.q, scalar_first=True)).as_quat(scalar_first=True)
    np.testing.assert_allclose(np.abs(np.sum(ned.q * expected, axis=1)), 1.0, atol=1e-13)
    assert (enu.bias is None and ned.bias is None) or np.array_equal(enu.bias, ned.bias)
    if enu.covariance is not None:
        m = turn.as_matrix()
        np.testing.assert_allclose(ned.covariance, m @ enu.covariance @ m.T, atol=1e-18)


def test_without_magnetometer_the_heading_is_the_sensors():
    gyr, acc, _, _ = motion(500, w=(0.0, 0.0, 0.0), q0=(1.0, 0.0, 0.0, 0.0))
    est = estimate_attitude(gyr, acc, rate=RATE)
    np.testing.assert_allclose(est.q, np.tile([1.0, 0, 0, 0], (500, 1)), atol=1e-12)


@pytest.fixture(scope="module")
def trial():
    path = resources.files("kreisel.io.examples").joinpath("broad/broad_07_fast_rotation_60s.npz")
    with resources.as_file(path) as p, np.load(p) as d:
        return {key: d[key] for key in d.files}


def test_bundled_trial_against_motion_capture(trial):
    # 20 s: 15 s at rest, then 5 s of fast rotation
    cut = slice(int(11.5 * 285.714), int(31.5 * 285.714))
    gyr, acc, mag = (trial[k][cut].astype(float) for k in ("gyr", "acc", "mag"))
    rate = float(trial["sampling_rate"])
    ref = trial["opt_quat"][cut]
    est = estimate_attitude(gyr, acc, mag, rate=rate)
    total, heading, incl = attitude_error(est.q, ref)
    assert total < 3.0 and incl < 1.5
    six = estimate_attitude(gyr, acc, rate=rate)
    assert attitude_error(six.q, ref)[2] < 1.5
    offline = estimate_attitude(gyr, acc, mag, rate=rate, offline=True)
    assert attitude_error(offline.q, ref)[0] < 3.0


def noisy_recording(seed, n=4000, rate=RATE, rest=5.0):
    """Smooth random turning between rests at both ends, with gyro bias and noise on every sensor."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / rate
    freq, amp, phase = rng.uniform(0.05, 0.5, (3, 3)), rng.uniform(0.2, 1.5, (3, 3)), rng.uniform(0, 2 * np.pi, (3, 3))
    w = np.einsum("kj,kjn->nk", amp, np.sin(2 * np.pi * freq[..., None] * t + phase[..., None]))
    # the motion starts and stops within 0.1 s (a slower start reads as rest to the filter's rest detector,
    # whose threshold is 0.37 rad/s, and the rate it measures then goes into the bias)
    w *= np.clip(10.0 * np.minimum(t - rest, t[-1] - rest - t), 0.0, 1.0)[:, None]
    steps = Rotation.from_rotvec(np.concatenate([rng.normal(size=(1, 3)) * 0.5, w[1:] / rate]))
    r = [steps[0]]
    for step in steps[1:]:
        r.append(r[-1] * step)
    r = Rotation.concatenate(r)
    gyr = w + rng.normal(scale=0.01, size=3) + rng.normal(scale=0.005, size=(n, 3))
    acc = r.inv().apply([0.0, 0.0, 9.81]) + rng.normal(scale=0.05, size=(n, 3))
    mag = r.inv().apply(FIELD) + rng.normal(scale=0.5, size=(n, 3))
    return gyr, acc, mag, np.roll(r.as_quat(), 1, axis=1)


def reversed_in_time(gyr, acc, mag):
    """The recording played backward: the rate that turned sample i − 1 into i, negated, turns i into i − 1."""
    return -np.concatenate([gyr[:1], gyr[:0:-1]]), acc[::-1], None if mag is None else mag[::-1]


@settings(max_examples=5, deadline=None)
@given(st.integers(0, 2**32 - 1), st.booleans())
def test_offline_is_consistent_under_time_reversal(seed, with_mag):
    """The recording played backward gives, reversed again, the same smoothed attitude (up to noise)."""
    gyr, acc, mag, q_true = noisy_recording(seed)
    mag = mag if with_mag else None
    est = estimate_attitude(gyr, acc, mag, rate=RATE, offline=True)
    back = estimate_attitude(*reversed_in_time(gyr, acc, mag), rate=RATE, offline=True)
    total, _, incl = attitude_error(back.q[::-1], est.q)
    causal = estimate_attitude(gyr, acc, mag, rate=RATE)
    # measured on seeds 0-15: up to 0.9° apart (inclination 0.24° without field), 0.52° from the truth
    # (inclination 0.20°), the causal estimates 1.4-10° (inclination 0.12-0.49°)
    if with_mag:
        assert total < 1.5
        assert attitude_error(est.q, q_true)[0] < min(1.0, attitude_error(causal.q, q_true)[0])
    else:
        # each estimate's heading starts at the sensor's own: only the inclinations compare
        assert incl < 0.5
        assert attitude_error(est.q, q_true)[2] < attitude_error(causal.q, q_true)[2]


@pytest.mark.parametrize("k", [2, 3])
def test_smoother_fusion_against_the_information_form(k, quat):
    """exp(P_f S⁻¹ δ) ⊗ q_f and (P_f⁻¹ + P_b⁻¹)⁻¹, S = P_f + P_b, on the first k components, by numpy's inverses."""
    rng = np.random.default_rng(7)
    n = 50
    qf = np.roll(Rotation.random(n, random_state=rng).as_quat(), 1, axis=1)
    # the backward estimate a few degrees away, tilted and turned about the vertical
    tilt = np.concatenate([rng.normal(scale=0.02, size=(n, 2)), np.zeros((n, 1))], axis=1)
    turn = rng.normal(scale=0.05, size=n)
    qb = quat.mul(quat.mul(np.roll(Rotation.from_rotvec(tilt).as_quat(), 1, axis=1),
                           np.stack([np.cos(turn / 2), 0 * turn, 0 * turn, np.sin(turn / 2)], axis=1)), qf)
    a, b = rng.normal(size=(2, n, 3, 3)) * 1e-3
    pf, pb = a @ np.swapaxes(a, 1, 2) + 1e-7 * np.eye(3), b @ np.swapaxes(b, 1, 2) + 1e-7 * np.eye(3)
    q, cov = np.empty((n, 4)), np.empty((n, 3, 3))
    _attitude_kernels.smoother_fusion(qf, pf, qb, pb, k, q, cov)
    delta = np.concatenate([quat.log(np.roll(Rotation.from_rotvec(tilt).as_quat(), 1, axis=1))[:, :2], turn[:, None]],
                           axis=1)[:, :k]
    step = np.zeros((n, 3))
    step[:, :k] = np.einsum("nij,njl,nl->ni", pf[:, :k, :k], np.linalg.inv(pf[:, :k, :k] + pb[:, :k, :k]), delta)
    expected = quat.mul(np.roll(Rotation.from_rotvec(step).as_quat(), 1, axis=1), qf)
    np.testing.assert_allclose(np.abs(np.sum(q * expected, axis=1)), 1.0, atol=1e-14)
    fused = np.linalg.inv(np.linalg.inv(pf[:, :k, :k]) + np.linalg.inv(pb[:, :k, :k]))
    np.testing.assert_allclose(cov[:, :k, :k], fused, rtol=1e-9, atol=1e-9 * np.abs(fused).max())
    np.testing.assert_array_equal(cov[:, k:, :], pf[:, k:, :])
    np.testing.assert_array_equal(cov[:, :, k:], pf[:, :, k:])


def test_offline_bridges_a_magnet_on_the_sensor():
    """A magnet fixed to the sensor for 4 s of motion: the smoother leaves that field out and bridges it."""
    gyr, acc, mag, q_true = noisy_recording(0)
    mag[1200:2000] += [30.0, -20.0, 10.0]
    # measured: 0.09° (as without the magnet); the causal filter follows the magnet to 31°
    assert attitude_error(estimate_attitude(gyr, acc, mag, rate=RATE, offline=True).q, q_true)[0] < 0.3
    assert attitude_error(estimate_attitude(gyr, acc, mag, rate=RATE).q, q_true)[0] > 10.0


def test_offline_on_the_bundled_trial(trial):
    """The whole bundled minute over its movement samples: offline beats the causal estimate."""
    gyr, acc, mag = (trial[k].astype(float) for k in ("gyr", "acc", "mag"))
    rate = float(trial["sampling_rate"])
    ref, moving = trial["opt_quat"], trial["movement"]
    offline = attitude_error(estimate_attitude(gyr, acc, mag, rate=rate, offline=True).q, ref, moving)
    causal = attitude_error(estimate_attitude(gyr, acc, mag, rate=rate).q, ref, moving)
    # measured: total 1.78° (heading 0.81°, inclination 1.59°), causal 2.10°; offline VQF 2.07°
    assert offline[0] < 1.9 and offline[1] < 1.0
    assert offline[0] < causal[0]


def test_bad_input():
    gyr, acc, mag, _ = motion(50)
    with pytest.raises(ValueError, match="gyro must be finite: sample 3"):
        estimate_attitude(np.where(np.arange(50)[:, None] == 3, np.nan, gyr), acc, mag, rate=RATE)
    with pytest.raises(ValueError, match="accel must have as many samples as gyro"):
        estimate_attitude(gyr, acc[:-1], mag, rate=RATE)
    with pytest.raises(ValueError, match="accel's first sample has length 0 m/s², below 1e-06"):
        estimate_attitude(gyr, np.zeros_like(acc), mag, rate=RATE)
    with pytest.raises(ValueError, match="mag has no horizontal part"):
        estimate_attitude(gyr, acc, acc * 3.0, rate=RATE)
    with pytest.raises(ValueError, match="mag has no horizontal part"):
        estimate_attitude(gyr, acc, np.zeros_like(mag), rate=RATE)
    with pytest.raises(ValueError, match="rate must be > 0"):
        estimate_attitude(gyr, acc, mag, rate=0.0)
    with pytest.raises(ValueError, match="method must be None or one of"):
        estimate_attitude(gyr, acc, mag, rate=RATE, method="ekf")
    with pytest.raises(ValueError, match="offline=True is available for kreisel's estimator only"):
        estimate_attitude(gyr, acc, mag, rate=RATE, method="madgwick", offline=True)
    with pytest.raises(ValueError, match="unknown parameter"):
        estimate_attitude(gyr, acc, mag, rate=RATE, params={"bta": 0.1})


@pytest.mark.parametrize("method", [None, "madgwick", "mahony", "complementary"])
def test_later_zero_samples_are_skipped(method):
    gyr, acc, mag, q_true = motion(400)
    acc[200:210] = 0.0
    mag[250:260] = 0.0
    est = estimate_attitude(gyr, acc, mag, rate=RATE, method=method)
    assert np.isfinite(est.q).all()
    assert attitude_error(est.q, q_true)[0] < (1e-6 if method is None else 0.5)


def test_vector_attitude_triad_and_quest_agree_with_the_truth():
    rng = np.random.default_rng(3)
    r = Rotation.random(20, random_state=rng)
    q_true = np.roll(r.as_quat(), 1, axis=1)
    acc = r.inv().apply([0.0, 0.0, 9.81])
    mag = r.inv().apply(FIELD)
    dip = np.arctan2(45.0, 20.0)
    for q in (attitude_from_vectors(acc, mag), attitude_from_vectors(acc, mag, method="quest"),
              attitude_from_vectors(acc, mag, method="quest", dip=dip)):
        np.testing.assert_allclose(np.abs(np.sum(q * q_true, axis=1)), 1.0, atol=1e-13)
    with pytest.raises(ValueError, match="mag must have a horizontal part"):
        attitude_from_vectors(acc, acc)
    with pytest.raises(ValueError, match="accel must not have zero-length samples"):
        attitude_from_vectors(np.zeros(3), FIELD)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.0, 0.5))
def test_vector_attitude_against_scipy_align_vectors(seed, noise):
    # inconsistent vectors (noise on both): TRIAD is scipy's fit with an infinite weight on up, the q-method
    # scipy's least-squares fit of the unit directions with the given dip
    rng = np.random.default_rng(seed)
    r = Rotation.random(random_state=rng)
    acc = r.inv().apply([0.0, 0.0, 9.81]) + noise * 9.81 * rng.normal(size=3)
    mag = r.inv().apply(FIELD) + noise * 49.0 * rng.normal(size=3)
    if np.linalg.norm(np.cross(acc, mag)) < 1e-3 * np.linalg.norm(acc) * np.linalg.norm(mag):
        return  # field along up: refused (tested above)
    field_ref = FIELD / np.linalg.norm(FIELD)
    dip = np.arcsin(-field_ref[2])
    expected, _ = Rotation.align_vectors([[0.0, 0.0, 1.0], field_ref], [acc, mag], weights=[np.inf, 1.0])
    q = attitude_from_vectors(acc, mag)
    e = expected.as_quat(scalar_first=True)
    assert min(np.abs(q - e).max(), np.abs(q + e).max()) < 1e-12
    expected, _ = Rotation.align_vectors([[0.0, 0.0, 1.0], field_ref],
                                         [acc / np.linalg.norm(acc), mag / np.linalg.norm(mag)], weights=[2.0, 1.0])
    q = attitude_from_vectors(acc, mag, method="quest", dip=dip, weights=(2.0, 1.0))
    e = expected.as_quat(scalar_first=True)
    assert min(np.abs(q - e).max(), np.abs(q + e).max()) < 1e-12


def test_compare_attitude_runs_each_method_once(trial):
    cut = slice(int(11.5 * 285.714), int(21.5 * 285.714))
    gyr, acc, mag = (trial[k][cut].astype(float) for k in ("gyr", "acc", "mag"))
    rate = float(trial["sampling_rate"])
    errors = compare_attitude(gyr, acc, mag, rate=rate, reference=trial["opt_quat"][cut])
    assert list(errors) == ["kreisel", "kreisel offline", "madgwick", "mahony", "complementary"]
    direct = attitude_error(estimate_attitude(gyr, acc, mag, rate=rate, method="mahony").q, trial["opt_quat"][cut])
    assert errors["mahony"] == direct
    with pytest.raises(ValueError, match="methods must be among"):
        compare_attitude(gyr, acc, mag, rate=rate, reference=trial["opt_quat"][cut], methods=("vqf",))


@pytest.mark.parametrize("unit, scale", [("g", 1 / 9.80665), ("mg", 1000 / 9.80665)])
def test_accelerometer_in_another_unit_is_refused(unit, scale):
    # kreisel's estimator weighs the accelerometer by |a| against gravity in m/s²: in g it silently lost the
    # tilt (noisy gyro, 30 s: total error 5.2° in m/s², 25.9° in g, 129° in mg)
    gyr, acc, mag, _ = motion(600)
    with pytest.raises(ValueError, match=rf"accel's samples are .* long .* in m/s²"):
        estimate_attitude(gyr, acc * scale, mag, rate=RATE)
    # the published filters normalise the samples: any unit gives the same attitude
    np.testing.assert_allclose(estimate_attitude(gyr, acc * scale, mag, rate=RATE, method="mahony").q,
                               estimate_attitude(gyr, acc, mag, rate=RATE, method="mahony").q, atol=1e-12)


@pytest.mark.parametrize("name, offline", [("gravity", False), ("rest_tau", False), ("mag_ref_tau", False),
                                           ("acc_noise", True), ("mag_noise", True)])
def test_parameters_that_divide_must_be_positive(name, offline):
    # zero here divided by zero inside the compiled filter (or, offline, in fusing two passes that are both
    # certain): a bare ZeroDivisionError after the work had started
    gyr, acc, mag, _ = motion(100)
    with pytest.raises(ValueError, match=rf"parameter {name} must be a finite number > 0, got 0.0"):
        estimate_attitude(gyr, acc, mag, rate=RATE, offline=offline, params={name: 0.0})


def test_offline_takes_a_field_time_longer_than_the_recording():
    # a mag_new_time of 1e20 s overflowed the window's sample count (OverflowError) in the offline judgement
    gyr, acc, mag, q_true = motion(300)
    est = estimate_attitude(gyr, acc, mag, rate=RATE, offline=True, params={"mag_new_time": 1e20})
    assert attitude_error(est.q, q_true)[0] < 1e-6


def test_vector_attitude_refuses_what_it_would_ignore():
    acc, mag = [0.3, -0.2, 9.7], [5.0, 18.0, -44.0]
    # a zero weight leaves a direction unmeasured: (1, 0) returned an arbitrary heading, (0, 0) the identity
    for weights in [(1.0, 0.0), (0.0, 1.0), (0.0, 0.0)]:
        with pytest.raises(ValueError, match=r"weights must be two numbers > 0 \(up, field\)"):
            attitude_from_vectors(acc, mag, method="quest", weights=weights)
    with pytest.raises(ValueError, match=r"weights must be two numbers > 0 \(up, field\), got shape \(3,\)"):
        attitude_from_vectors(acc, mag, method="quest", weights=(1.0, 1.0, 1.0))
    # TRIAD takes up exactly and never the dip: a dip or weights given with it were silently dropped
    with pytest.raises(ValueError, match="dip applies to method='quest' only"):
        attitude_from_vectors(acc, mag, dip=0.5)
    with pytest.raises(ValueError, match="weights apply to method='quest' only"):
        attitude_from_vectors(acc, mag, weights=(10.0, 1.0))
    # an infinite weight on up is TRIAD
    np.testing.assert_allclose(attitude_from_vectors(acc, mag, method="quest", weights=(np.inf, 1.0)),
                               attitude_from_vectors(acc, mag), atol=1e-12)


def test_compare_attitude_checks_its_arguments_before_estimating(monkeypatch):
    gyr, acc, mag, q_true = motion(100)
    calls = []
    monkeypatch.setattr("kreisel.nav.attitude.estimate_attitude", lambda *a, **k: calls.append(1))
    # a reference or mask of the wrong length was found only by the first method's error computation, after
    # its estimate; a str of one name was read letter by letter, and no method at all returned {}
    with pytest.raises(ValueError, match=r"reference must have as many rows as gyro \(100\), got 99"):
        compare_attitude(gyr, acc, mag, rate=RATE, reference=q_true[:-1])
    with pytest.raises(ValueError, match=r"mask must be a boolean array of shape \(100,\)"):
        compare_attitude(gyr, acc, mag, rate=RATE, reference=q_true, mask=np.ones(99, bool))
    with pytest.raises(TypeError, match=r"methods must be a sequence of method names, not one str \('mahony'\)"):
        compare_attitude(gyr, acc, mag, rate=RATE, reference=q_true, methods="mahony")
    with pytest.raises(ValueError, match="methods must name at least one method"):
        compare_attitude(gyr, acc, mag, rate=RATE, reference=q_true, methods=())
    assert not calls


def test_offline_must_be_a_bool():
    # offline="no" is truthy: it ran the smoother
    gyr, acc, mag, _ = motion(50)
    with pytest.raises(TypeError, match="offline must be True or False, got 'no'"):
        estimate_attitude(gyr, acc, mag, rate=RATE, offline="no")
    assert estimate_attitude(gyr, acc, mag, rate=RATE, offline=np.bool_(True)).covariance is not None


@pytest.mark.parametrize("first", [0.08, 30.0])
def test_a_first_accelerometer_sample_far_from_gravity_is_refused(first):
    # the start tilt is read from the first sample: from one in free fall (|a| = 0.08 m/s², noise) kreisel's
    # estimator was still 26° off after 5 s at rest and 2° after 15 s, with no error
    gyr, acc, mag, _ = motion(300, w=(0.0, 0.0, 0.0))
    acc[0] = first * np.array([0.6, 0.0, 0.8])
    for method in (None, "mahony"):
        with pytest.raises(ValueError, match=rf"accel's first sample has length {first:.3g}, outside 0.5 … 2 times "
                                             r"the recording's median length 9.81"):
            estimate_attitude(gyr, acc, mag, rate=RATE, method=method)
    # a start within that band is taken (a moving start: |a| 1.3 g)
    acc[0] = 1.3 * 9.81 * np.array([0.0, 0.0, 1.0])
    assert np.isfinite(estimate_attitude(gyr, acc, mag, rate=RATE).q).all()
