"""Attitude files and the NED/ENU conversion (IMU files are read by kreisel.io, tests/io/test_imu.py)."""

import numpy as np
import pandas as pd
import pytest
from scipy.spatial.transform import Rotation

import kreisel as kr

nav = kr.nav


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
