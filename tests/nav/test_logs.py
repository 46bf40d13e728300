"""IMU log reading (with deliberate defects) and attitude writing."""

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

import kreisel as kr

nav = kr.nav
OMEGA = 2 * np.pi


def write_csv(path, text):
    path.write_text(text.strip() + "\n")
    return path


GOOD = """
time,gyro_x,gyro_y,gyro_z
0.00,0.0,0.0,10.0
0.01,0.0,0.0,10.0
0.02,0.0,0.0,10.0
0.03,0.0,0.0,10.0
"""


def read_good(path, **kwargs):
    return nav.read_imu_log(path, time="time", gyro=("gyro_x", "gyro_y", "gyro_z"), **kwargs)


def test_reads_a_rate_log_in_degrees(tmp_path):
    log = read_good(write_csv(tmp_path / "imu.csv", GOOD), units="deg/s")
    np.testing.assert_allclose(log.t, [0, 0.01, 0.02, 0.03])
    np.testing.assert_allclose(log.gyro[:, 2], np.radians(10.0), rtol=1e-15)
    t, q = log.attitude()
    expected = Rotation.from_rotvec(np.radians(10.0) * t[:, None] * [0, 0, 1]).as_quat(scalar_first=True)
    np.testing.assert_allclose(q, expected, atol=1e-15)


def test_increment_log_matches_coning_truth(tmp_path, quat):
    # an increment log of exact coning increments, milliseconds, degrees, N = 2
    m = nav.coning_motion(np.radians(5.0), OMEGA, 0.01, 100)
    df = pd.DataFrame({"t_ms": 1e3 * m.t[1:], "dx": np.degrees(m.dtheta[:, 0]), "dy": np.degrees(m.dtheta[:, 1]),
                       "dz": np.degrees(m.dtheta[:, 2])})
    path = tmp_path / "inc.csv"
    df.to_csv(path, index=False, float_format="%.17g")
    log = nav.read_imu_log(path, time="t_ms", gyro=("dx", "dy", "dz"), kind="increment", units="deg",
                           time_scale=1e-3)
    t, q = log.attitude(q0=m.q[0], samples_per_update=2)
    np.testing.assert_allclose(t, m.t[::2], atol=1e-15)
    np.testing.assert_allclose(q, nav.attitude_from_increments(m.q[0], m.dtheta, 2), atol=1e-14)
    # only the two-sample coning drift separates it from the truth
    bound = 1.1 * nav.coning_drift(np.radians(5.0), OMEGA, 0.01, 2) * m.t[-1]
    assert np.linalg.norm(quat.error(m.q[::2], q), axis=-1).max() < bound
    with pytest.raises(ValueError, match=r"100 increment rows are not divisible by samples_per_update=3; "
                                         r"trim 1 row"):
        log.attitude(samples_per_update=3)
    with pytest.raises(ValueError, match="method applies to rate logs"):
        log.attitude(method="quaternion")


def test_rate_log_refuses_increment_options(tmp_path):
    log = read_good(write_csv(tmp_path / "imu.csv", GOOD))
    with pytest.raises(ValueError, match="samples_per_update applies to increment logs"):
        log.attitude(samples_per_update=2)
    t, q = log.attitude(method="quaternion")
    assert q.shape == (4, 4)


DEFECTS = [
    # (csv text, keyword arguments, expected message)
    (GOOD.replace("gyro_y", "gyr_y"), {}, r"column\(s\) 'gyro_y' \(did you mean 'gyr_y'\?\) not found"),
    (GOOD.replace("time,", "stamp,"), {}, r"column\(s\) 'time' .*not found; the log has columns \['stamp'"),
    (GOOD.replace("0.02,0.0,0.0,10.0", "0.02,0.0,,10.0"), {}, r"column 'gyro_y': missing .* at row 2 \(line 4"),
    (GOOD.replace("0.02,0.0,0.0,10.0", "0.02,nan,0.0,10.0"), {}, r"column 'gyro_x': missing or non-finite value "
                                                                 r"nan at row 2 \(line 4 of the file\)"),
    (GOOD.replace("0.03,0.0,0.0,10.0", "0.03,0.0,0.0,abc"), {}, r"column 'gyro_z': non-numeric value 'abc' at row 3"),
    (GOOD.replace("0.02,", "0.01,"), {}, r"time column 'time' must strictly increase; at row 2 \(line 4 of the file\)"),
    (GOOD.replace("0.03,", "0.015,"), {}, r"at row 3 \(line 5 of the file\) 0.015 follows 0.02"),
    ("time,gyro_x,gyro_y,gyro_z\n0.0,1,2,3\n", {}, "need at least 2 rows"),
    (GOOD, {"kind": "increment", "units": "deg/s"}, r"units for kind='increment' must be one of \('rad', 'deg'\)"),
    (GOOD, {"kind": "rates"}, "kind must be 'rate' or 'increment'"),
    (GOOD, {"frame": "NWU"}, "frame must be 'NED' or 'ENU'"),
]


@pytest.mark.parametrize("text, kwargs, match", DEFECTS)
def test_defective_logs_are_refused(tmp_path, text, kwargs, match):
    path = write_csv(tmp_path / "bad.csv", text)
    with pytest.raises(ValueError, match=match):
        read_good(path, **kwargs)


@pytest.mark.parametrize("sep, decimal", [(";", ","), (";", "."), ("\t", ".")])
def test_semicolon_and_tab_separated_logs_read_as_the_comma_one(tmp_path, sep, decimal):
    """European spreadsheets export ';' between cells and a decimal comma."""
    text = "\n".join(line.replace(",", sep).replace(".", decimal) for line in GOOD.strip().splitlines())
    log = read_good(write_csv(tmp_path / "imu.csv", text))
    reference = read_good(write_csv(tmp_path / "comma.csv", GOOD))
    np.testing.assert_array_equal(log.t, reference.t)
    np.testing.assert_array_equal(log.gyro, reference.gyro)


def test_rows_after_blank_lines_are_named_by_their_file_line(tmp_path):
    text = GOOD.replace("0.01,", "\n  \n0.01,").replace("0.03,0.0,0.0,10.0", "0.03,0.0,0.0,abc")
    path = write_csv(tmp_path / "gaps.csv", text)
    with pytest.raises(ValueError, match=r"'gyro_z': non-numeric value 'abc' at row 3 \(line 7 of the file\)"):
        read_good(path)
    assert path.read_text().splitlines()[6] == "0.03,0.0,0.0,abc"


def test_dataframe_rows_are_named_without_file_lines():
    df = pd.DataFrame({"t": [0.0, 0.1, 0.2], "gx": [0.0, np.nan, 0.0], "gy": [0.0] * 3, "gz": [0.0] * 3})
    with pytest.raises(ValueError, match=r"column 'gx': missing or non-finite value nan at row 1; 1 bad"):
        nav.read_imu_log(df)
    with pytest.raises(ValueError, match="no such file"):
        nav.read_imu_log("/nonexistent/imu.csv")
    with pytest.raises(TypeError, match="source must be a file path or a pandas DataFrame"):
        nav.read_imu_log(np.zeros((3, 4)))


def test_frame_conversion_ned_enu():
    # level, heading east in NED (yaw 90°) is heading east in ENU too (yaw 0°)
    q_ned = Rotation.from_euler("ZYX", [90, 0, 0], degrees=True).as_quat(scalar_first=True)
    q_enu = nav.convert_attitude_frame(q_ned, "NED", "ENU")
    np.testing.assert_allclose(Rotation.from_quat(q_enu, scalar_first=True).as_euler("ZYX", degrees=True),
                               [0, 0, 0], atol=1e-12)
    # nose up 10° (pitch +10° in NED/FRD) is pitch −10° in ENU/FLU (y axis to the left)
    q_ned = Rotation.from_euler("ZYX", [0, 10, 0], degrees=True).as_quat(scalar_first=True)
    ypr = Rotation.from_quat(nav.convert_attitude_frame(q_ned, "NED", "ENU"), scalar_first=True).as_euler(
        "ZYX", degrees=True)
    np.testing.assert_allclose(ypr, [90, -10, 0], atol=1e-12)
    q = Rotation.random(20, random_state=3).as_quat(scalar_first=True)
    back = nav.convert_attitude_frame(nav.convert_attitude_frame(q, "NED", "ENU"), "ENU", "NED")
    np.testing.assert_allclose(back, q, atol=1e-15)
    with pytest.raises(ValueError, match="to_frame must be 'NED' or 'ENU'"):
        nav.convert_attitude_frame(q, "NED", "XYZ")


@pytest.mark.parametrize("frame", ["NED", "ENU"])
def test_write_attitude_round_trip(tmp_path, frame):
    t = np.linspace(0.0, 1.0, 7)
    ypr = np.column_stack([np.linspace(-170, 170, 7), np.linspace(-60, 60, 7), np.linspace(20, -100, 7)])
    q = Rotation.from_euler("ZYX", ypr, degrees=True).as_quat(scalar_first=True)
    path = tmp_path / "att.csv"
    nav.write_attitude(path, t, q, frame=frame)
    back = pd.read_csv(path)
    assert list(back.columns) == ["t", "q0", "q1", "q2", "q3", "roll_deg", "pitch_deg", "yaw_deg"]
    q_out = back[["q0", "q1", "q2", "q3"]].to_numpy()
    np.testing.assert_allclose(q_out, nav.convert_attitude_frame(q, "NED", frame) * np.sign(
        nav.convert_attitude_frame(q, "NED", frame)[:, :1]), atol=1e-16)
    expected = Rotation.from_quat(q_out, scalar_first=True).as_euler("ZYX", degrees=True)
    np.testing.assert_allclose(back[["yaw_deg", "pitch_deg", "roll_deg"]].to_numpy(), expected, atol=1e-10)
    if frame == "NED":
        np.testing.assert_allclose(back[["yaw_deg", "pitch_deg", "roll_deg"]].to_numpy(), ypr, atol=1e-10)
    assert [p.name for p in tmp_path.iterdir()] == ["att.csv"]   # no temporary file left


def test_write_attitude_failure_keeps_the_old_file(tmp_path):
    path = tmp_path / "att.csv"
    path.write_text("previous\n")
    with pytest.raises(ValueError, match=r"q must have shape \(\.\.\., 3, 4\)"):
        nav.write_attitude(path, [0.0, 1.0, 2.0], np.ones((2, 4)))
    assert path.read_text() == "previous\n"
