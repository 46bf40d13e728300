"""ImuRecording: its summary and the attitude its gyro integrates to."""

import numpy as np
import pandas as pd
import pytest

import kreisel as kr


def test_repr_is_a_summary():
    """Issue 34: GyroRecording's repr dumped whole arrays."""
    rec = kr.io.ImuRecording(np.linspace(0.0, 100.0, 100_001), np.zeros((100_001, 3)), source="long.csv")
    assert repr(rec) == "ImuRecording('long.csv', n=100001, t=[0, 100] s, gyro)"
    assert kr.io.GyroRecording is kr.io.ImuRecording and len(rec) == 100_001


def test_increment_gyro_matches_coning_truth(tmp_path):
    """An increment-output gyro in degrees and milliseconds integrates with the coning algorithm."""
    m = kr.nav.coning_motion(np.radians(5.0), 2 * np.pi, 0.01, 100)
    path = tmp_path / "inc.csv"
    pd.DataFrame({"t_ms": 1e3 * m.t[1:], "dx": np.degrees(m.dtheta[:, 0]), "dy": np.degrees(m.dtheta[:, 1]),
                  "dz": np.degrees(m.dtheta[:, 2])}).to_csv(path, index=False, float_format="%.17g")
    rec = kr.io.read_imu(path, kind="increment", units="deg", columns={"gyro": ("dx", "dy", "dz")})
    np.testing.assert_allclose(rec.dtheta, m.dtheta, rtol=1e-13, atol=1e-18)
    np.testing.assert_allclose(rec.omega, m.dtheta / 0.01, rtol=1e-9)
    t, q = rec.attitude(q0=m.q[0], samples_per_update=2)
    np.testing.assert_allclose(t, m.t[::2], atol=1e-15)
    np.testing.assert_allclose(q, kr.nav.attitude_from_increments(m.q[0], m.dtheta, 2), atol=1e-13)
    with pytest.raises(ValueError, match=r"100 increment rows are not divisible by samples_per_update=3; trim 1"):
        rec.attitude(samples_per_update=3)
    with pytest.raises(ValueError, match="method applies to rate gyros"):
        rec.attitude(method="quaternion")


def test_rate_recording_attitude(tmp_path):
    path = tmp_path / "spin.csv"
    path.write_text("t,gx (deg/s),gy (deg/s),gz (deg/s)\n0,0,0,10\n0.5,0,0,10\n1,0,0,10\n")
    t, q = kr.io.read_imu(path).attitude()
    angle = 2 * np.arctan2(q[:, 3], q[:, 0])
    np.testing.assert_allclose(angle, np.radians(10.0) * t, atol=1e-15)
    with pytest.raises(ValueError, match="samples_per_update applies to increment gyros"):
        kr.io.read_imu(path).attitude(samples_per_update=2)


def test_uneven_spacing_names_where_the_rate_changes():
    # 100 Hz for 2 s, then 50 Hz: the error named "interval 0.01 s after t = 1.12 s" (the interval farthest from
    # the mean, among equals), not where the spacing changes
    t = np.concatenate([np.arange(200) / 100.0, 1.99 + np.arange(1, 201) / 50.0])
    rec = kr.io.ImuRecording(t, np.zeros((t.size, 3)), source="change.csv")
    with pytest.raises(ValueError, match=r"the interval changes from 0.01 s to 0.02 s after t = 1.99 s"):
        rec.sampling_rate()
    # a gap is named where it is
    t = np.arange(300) / 100.0
    t[150:] += 0.5
    with pytest.raises(ValueError, match=r"interval 0.51 s after t = 1.49 s.*changes from 0.01 s to 0.51 s after "
                                         r"t = 1.49 s"):
        kr.io.ImuRecording(t, np.zeros((300, 3))).sampling_rate()
