"""read_gyro: every supported layout, and one clear error per kind of bad file."""

import zipfile

import numpy as np
import pytest

import kreisel as kr
from kreisel.io import GyroFileError

T = np.array([0.005048, 0.007548, 0.010049])
W = np.array([[0.1, -2.5, 0.03], [0.11, -2.4, 0.031], [0.12, -2.3, 0.032]])
PHYPHOX_HEADER = ['"Time (s)"', '"Gyroscope x (rad/s)"', '"Gyroscope y (rad/s)"', '"Gyroscope z (rad/s)"',
                  '"Absolute (rad/s)"']


def phyphox_text(delimiter=",", decimal="."):
    lines = [delimiter.join(PHYPHOX_HEADER)]
    for t, w in zip(T, W):
        cells = [f"{v:.9E}" for v in (t, *w, np.linalg.norm(w))]
        lines.append(delimiter.join(cell.replace(".", decimal) for cell in cells))
    return "\n".join(lines) + "\n"


def check(recording, scale=1.0):
    np.testing.assert_allclose(recording.t, T, rtol=1e-12)
    np.testing.assert_allclose(recording.omega, W * scale, rtol=1e-12)


@pytest.mark.parametrize("delimiter, decimal", [(",", "."), ("\t", "."), (";", ","), ("\t", ","), (";", ".")])
def test_phyphox_csv_every_separator(tmp_path, delimiter, decimal):
    path = tmp_path / "Gyroscope.csv"
    path.write_text(phyphox_text(delimiter, decimal), encoding="utf-8")
    recording = kr.io.read_gyro(path)
    check(recording)
    assert recording.accel is None and recording.source == str(path)


def test_phyphox_folder_and_zip(tmp_path):
    folder = tmp_path / "Gyroscope rotation rate 2024-05-01 12-00-00"
    folder.mkdir()
    (folder / "Gyroscope.csv").write_text(phyphox_text(), encoding="utf-8")
    (folder / "meta").mkdir()
    check(kr.io.read_gyro(folder))
    archive = tmp_path / "export.zip"
    with zipfile.ZipFile(archive, "w") as z:
        z.writestr("meta/device.csv", "property,value\n")
        z.writestr("Gyroscope.csv", phyphox_text(";", ","))
    recording = kr.io.read_gyro(archive)
    check(recording)
    assert recording.source.endswith("export.zip:Gyroscope.csv")


def test_plain_whitespace_table_with_comments_and_extra_columns(tmp_path):
    path = tmp_path / "spin.dat"
    rows = "\n".join(f"{t}   {w[0]} {w[1]}\t{w[2]}  99.0 -1" for t, w in zip(T, W))
    path.write_text(f"# recorded by hand\n# ωₓ ω_y ω_z in rad/s\n\n{rows}\n# end\n", encoding="utf-8")
    check(kr.io.read_gyro(path))


def test_plain_comma_table_with_unicode_header(tmp_path):
    path = tmp_path / "spin.csv"
    rows = "\n".join(f"{t}, {w[0]}, {w[1]}, {w[2]}," for t, w in zip(T, W))
    path.write_text(f"t (s), ωₓ (rad/s), ω_y (rad/s), ω_z (rad/s)\n{rows}\n", encoding="utf-8-sig")
    check(kr.io.read_gyro(path))


@pytest.mark.parametrize("unit", ["deg/s", "°/s", "dps"])
def test_degrees_per_second_converted(tmp_path, unit):
    path = tmp_path / "deg.csv"
    rows = "\n".join(",".join(str(v) for v in (t, *np.degrees(w))) for t, w in zip(T, W))
    path.write_text(f"time (s),wx ({unit}),wy ({unit}),wz ({unit})\n{rows}\n", encoding="utf-8")
    check(kr.io.read_gyro(path))


@pytest.mark.parametrize("unit, per_rad_s", [("mdps", 180e3 / np.pi), ("mdeg/s", 180e3 / np.pi),
                                             ("mrad/s", 1e3)])
def test_milli_units_per_second_converted(tmp_path, unit, per_rad_s):
    """MEMS gyros (e.g. STMicro's) report millidegrees per second: "mdps" is not "dps"."""
    path = tmp_path / "milli.csv"
    rows = "\n".join(",".join(str(v) for v in (t, *(w * per_rad_s))) for t, w in zip(T, W))
    path.write_text(f"t (s),gyro x ({unit}),gyro y ({unit}),gyro z ({unit})\n{rows}\n", encoding="utf-8")
    check(kr.io.read_gyro(path))


@pytest.mark.parametrize("header, per_second", [("Time (ns)", 1e9), ("time (us)", 1e6), ("time (µs)", 1e6),
                                                ("timestamp [ms since boot]", 1e3), ("time_ms", 1e3),
                                                ("t_ns", 1e9), ("time (sec)", 1.0)])
def test_time_units_converted(tmp_path, header, per_second):
    """Loggers stamp samples in ms, µs or ns; the header's unit scales them to seconds."""
    path = tmp_path / "stamped.csv"
    rows = "\n".join(",".join(repr(float(v)) for v in (t * per_second, *w)) for t, w in zip(T, W))
    path.write_text(f"{header},gx,gy,gz\n{rows}\n", encoding="utf-8")
    check(kr.io.read_gyro(path))


def test_time_unit_that_is_not_a_time_is_refused(tmp_path):
    path = tmp_path / "minutes.csv"
    path.write_text("# a log\ntime (min),gx,gy,gz\n0,0,0,1\n1,0,0,1\n", encoding="utf-8")
    with pytest.raises(GyroFileError, match=r"minutes.csv:2: column 'time \(min\)': unknown time unit 'min' "
                                            r"\(known: s, ms, µs, ns\)"):
        kr.io.read_gyro(path)


def test_degrees_in_whitespace_header_with_spaces(tmp_path):
    path = tmp_path / "deg.txt"
    rows = "\n".join(" ".join(str(v) for v in (t, *np.degrees(w))) for t, w in zip(T, W))
    path.write_text(f"time (s)  rate x (deg/s)  rate y (deg/s)  rate z (deg/s)\n{rows}\n", encoding="utf-8")
    check(kr.io.read_gyro(path))


def test_milliseconds_and_named_columns_anywhere_with_accelerometer(tmp_path):
    path = tmp_path / "raw.csv"
    header = "Time (ms),Acceleration x (m/s^2),Acceleration y (m/s^2),Acceleration z (m/s^2)," \
             "Gyroscope x (rad/s),Gyroscope y (rad/s),Gyroscope z (rad/s)"
    rows = "\n".join(",".join(str(v) for v in (1e3 * t, 0.1, 0.2, 9.8, *w)) for t, w in zip(T, W))
    path.write_text(f"{header}\n{rows}\n", encoding="utf-8")
    recording = kr.io.read_gyro(path)
    check(recording)
    np.testing.assert_allclose(recording.accel, np.tile([0.1, 0.2, 9.8], (3, 1)))


@pytest.mark.parametrize(
    "text, match",
    [
        ("", r"empty \(no data rows\)"),
        ("# only a comment\n\n", "empty"),
        ('"Time (s)","Gyroscope x (rad/s)"\n', "empty"),
        ("0 1 2 3\n0.1 1 x 3\n", r":2: not a number: 'x'"),
        ("t wx wy wz\n0 1 2 3\nt wx wy wz\n", r":3: not a number: 't'"),
        ("0 1 2 3\n0.1 1 2\n", r":2: too few columns \(3\)"),
        ("0 1 2\n", r":1: too few columns"),
        ("# c\n0 1 2 3\n0.2 1 2 3\n0.1 1 2 3\n", r":4: time not increasing \(0.1 after 0.2\)"),
        ("0 1 2 3\n0 1 2 3\n", r":2: time not increasing"),
        ("0 1 2 3\n0.1 1 nan 3\n", r":2: not a finite number"),
        ("0,1,,3\n", r":1: not a number: ''"),
    ],
)
def test_bad_files_name_file_and_line(tmp_path, text, match):
    path = tmp_path / "bad.csv"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(GyroFileError, match=match) as info:
        kr.io.read_gyro(path)
    assert str(path) in str(info.value) and "\n" not in str(info.value)
    assert isinstance(info.value, ValueError)


def test_bad_containers(tmp_path):
    (tmp_path / "empty_dir").mkdir()
    with pytest.raises(GyroFileError, match="folder has no Gyroscope.csv"):
        kr.io.read_gyro(tmp_path / "empty_dir")
    archive = tmp_path / "other.zip"
    with zipfile.ZipFile(archive, "w") as z:
        z.writestr("Accelerometer.csv", "t,x,y,z\n")
    with pytest.raises(GyroFileError, match="archive has no Gyroscope.csv"):
        kr.io.read_gyro(archive)
    broken = tmp_path / "broken.zip"
    broken.write_bytes(b"PK\x03\x04 not really")
    with pytest.raises(GyroFileError, match="not a readable zip"):
        kr.io.read_gyro(broken)
    binary = tmp_path / "image.png"
    binary.write_bytes(b"\x89PNG\r\n\x1a\n\xff\xfe")
    with pytest.raises(GyroFileError, match="not a text file"):
        kr.io.read_gyro(binary)
    with pytest.raises(OSError):
        kr.io.read_gyro(tmp_path / "missing.csv")
