"""``kreisel attitude`` run as a user runs it: a subprocess on a synthetic recording and on the bundled trial."""

from importlib import resources

import numpy as np
import pandas as pd
import pytest
from PIL import Image

import kreisel as kr

RATE = 100.0
HEADER = "t (s),gx (rad/s),gy (rad/s),gz (rad/s),ax (m/s2),ay (m/s2),az (m/s2),mx (uT),my (uT),mz (uT)"


def synthetic(n=400):
    """A sensor tilted 20° about east, at rest for 1 s, then turning about up at 0.5 rad/s (t, ω, a, m)."""
    t = np.arange(n) / RATE
    tilt = np.radians(20.0)
    q0 = np.array([np.cos(tilt / 2), np.sin(tilt / 2), 0.0, 0.0])
    yaw = 0.5 * np.clip(t - 1.0, 0.0, None)
    q = kr.quat_multiply(np.column_stack([np.cos(yaw / 2), 0 * t, 0 * t, np.sin(yaw / 2)]), q0)
    omega = np.where((t >= 1.0)[:, None], kr.quat_apply(q0, [0.0, 0.0, 0.5], inverse=True), 0.0)
    accel = kr.quat_apply(q, np.tile([0.0, 0.0, 9.81], (n, 1)), inverse=True)
    mag = kr.quat_apply(q, np.tile([0.0, 20.0, -40.0], (n, 1)), inverse=True)
    return t, omega, accel, mag


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    path = tmp_path_factory.mktemp("imu") / "imu.csv"
    np.savetxt(path, np.column_stack(synthetic()), fmt="%.17g", delimiter=",", header=HEADER, comments="")
    return path


def _mean_rate(t):
    return 1.0 / ((t[-1] - t[0]) / (t.size - 1))


@pytest.mark.parametrize("options, keywords", [
    ((), {}),
    (("--method", "mahony", "--frame", "NED"), {"method": "mahony", "frame": "NED"}),
    (("--offline", "--no-mag"), {"offline": True, "mag": None}),
])
def test_csv_matches_estimate_attitude_bit_for_bit(kreisel, recording, tmp_path, options, keywords):
    out = tmp_path / "attitude.csv"
    process = kreisel("attitude", recording, "-o", out, *options)
    assert process.returncode == 0, process.stderr
    assert "400 samples, 3.99 s at 100 Hz" in process.stdout and f"wrote {out}" in process.stdout
    rec = kr.io.read_imu(recording)
    mag = keywords.pop("mag", rec.mag)
    est = kr.nav.estimate_attitude(rec.omega, rec.accel, mag, rate=_mean_rate(rec.t), **keywords)
    table = pd.read_csv(out)
    bias = ["bias_x", "bias_y", "bias_z"]
    assert list(table.columns) == ["t", "q0", "q1", "q2", "q3", *bias]
    np.testing.assert_array_equal(table["t"].to_numpy(), rec.t)
    np.testing.assert_array_equal(table[["q0", "q1", "q2", "q3"]].to_numpy(), est.q)
    np.testing.assert_array_equal(table[bias].to_numpy(), est.bias)
    if "--no-mag" in options:
        assert "no magnetometer" not in process.stderr  # asked for, not missing


def test_method_without_bias_writes_no_bias_columns(kreisel, recording, tmp_path):
    out = tmp_path / "madgwick.csv"
    process = kreisel("attitude", recording, "-o", out, "--method", "madgwick")
    assert process.returncode == 0, process.stderr
    table = np.genfromtxt(out, delimiter=",", names=True)
    assert table.dtype.names == ("t", "q0", "q1", "q2", "q3")
    assert "method madgwick" in process.stdout


def test_rate_for_a_table_without_time(kreisel, tmp_path):
    _, omega, accel, _ = synthetic(200)
    path = tmp_path / "no_time.csv"
    np.savetxt(path, np.column_stack([np.degrees(omega), accel]), fmt="%.17g", delimiter=",",
               header="gx,gy,gz,ax,ay,az", comments="")
    out = tmp_path / "attitude.csv"
    process = kreisel("attitude", path, "-o", out, "--rate", RATE, "--units", "deg/s")
    assert process.returncode == 0, process.stderr
    assert "no magnetometer: the heading comes from the gyro alone" in process.stderr
    est = kr.nav.estimate_attitude(np.radians(np.degrees(omega)), accel, rate=RATE)
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    np.testing.assert_array_equal(table[:, 0], np.arange(200) / RATE)
    np.testing.assert_array_equal(table[:, 1:5], est.q)


def test_bundled_trial_errors_and_plot(kreisel, tmp_path):
    out, figure = tmp_path / "broad.csv", tmp_path / "broad.png"
    process = kreisel("attitude", "broad_07", "-o", out, "--plot", figure)
    assert process.returncode == 0, process.stderr
    path = resources.files("kreisel.io.examples").joinpath("broad/broad_07_fast_rotation_60s.npz")
    rec = kr.io.read_imu(path)
    est = kr.nav.estimate_attitude(rec.omega, rec.accel, rec.mag, rate=_mean_rate(rec.t))
    np.testing.assert_array_equal(pd.read_csv(out)[["q0", "q1", "q2", "q3"]].to_numpy(), est.q)
    total, heading, inclination = kr.nav.attitude_error(est.q, rec.reference, rec.movement)
    assert (f"RMSE over the movement samples): total {total:.3f}°, heading {heading:.3f}°, "
            f"inclination {inclination:.3f}°") in process.stdout
    assert total < 5.0  # the estimator's own accuracy is tested in tests/nav
    assert Image.open(figure).size[0] > 500


def test_ned_errors_equal_enu_errors(kreisel, tmp_path):
    runs = {frame: kreisel("attitude", "broad_07", "-o", tmp_path / f"{frame}.csv", "--frame", frame,
                           "--method", "mahony") for frame in ("ENU", "NED")}
    lines = {frame: [line for line in p.stdout.splitlines() if "RMSE" in line] for frame, p in runs.items()}
    assert lines["ENU"] and lines["ENU"] == lines["NED"]


def test_refusals(kreisel, usage_error, recording, tmp_path):
    out = tmp_path / "attitude.csv"
    out.write_text("keep me")
    usage_error(kreisel("attitude", recording, "-o", out), "already exists", "--force")
    assert out.read_text() == "keep me"
    fresh = tmp_path / "fresh.csv"
    usage_error(kreisel("attitude", recording, "-o", fresh, "--offline", "--method", "madgwick"), "--offline")
    usage_error(kreisel("attitude", recording, "-o", fresh, "--frame", "NWU"), "--frame", "NWU")
    usage_error(kreisel("attitude", recording, "-o", fresh, "--method", "vqf"), "--method", "vqf")
    usage_error(kreisel("attitude", recording, "-o", fresh, "--rate", "50"), "has a time column")
    usage_error(kreisel("attitude", tmp_path / "[bold]gone.csv", "-o", fresh), "[bold]gone.csv", "no such file")
    assert not fresh.exists()


def test_files_it_cannot_use(kreisel, usage_error, tmp_path):
    t, omega, accel, mag = synthetic(100)
    fresh = tmp_path / "out.csv"
    gyro_only = tmp_path / "gyro.csv"
    np.savetxt(gyro_only, np.column_stack([t, omega]), delimiter=",", header="t,gx,gy,gz", comments="")
    usage_error(kreisel("attitude", gyro_only, "-o", fresh), "no accelerometer")
    gap = tmp_path / "gap.csv"
    keep = np.r_[0:50, 60:100]
    np.savetxt(gap, np.column_stack([t, omega, accel, mag])[keep], delimiter=",", header=HEADER, comments="")
    usage_error(kreisel("attitude", gap, "-o", fresh), "not evenly spaced", "t = 0.49")
    assert not fresh.exists()
