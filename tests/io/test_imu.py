"""read_imu / read_gyro: axes and units from the header, encodings, zip archives, BROAD's layout, DataFrames,
and the issues' reproducers written as the users met them."""

import re
import zipfile

import numpy as np
import pandas as pd
import pytest

import kreisel as kr
from kreisel.io import GyroFileError

G0 = 9.80665


def write(path, text, encoding="utf-8"):
    path.write_text(text, encoding=encoding)
    return path


def test_named_axes_decide_the_order(tmp_path):
    """Issue 33: a file headed z, y, x read as x, y, z."""
    path = write(tmp_path / "zyx.csv", "time (s),gyro z (rad/s),gyro y (rad/s),gyro x (rad/s)\n0,0.3,0.2,0.1\n")
    np.testing.assert_array_equal(kr.io.read_gyro(path).omega, [[0.1, 0.2, 0.3]])
    # unnamed columns keep the file's order
    path = write(tmp_path / "plain.csv", "time,u,v,w\n0,0.3,0.2,0.1\n")
    np.testing.assert_array_equal(kr.io.read_gyro(path).omega, [[0.3, 0.2, 0.1]])
    # short names with axes, in any order, among accelerometer and magnetometer columns
    path = write(tmp_path / "mixed.csv", "t,mz,gz,ay,gx,ax,my,gy,az,mx\n0,9,3,5,1,4,8,2,6,7\n")
    rec = kr.io.read_imu(path)
    np.testing.assert_array_equal(np.vstack([rec.omega, rec.accel, rec.mag]), [[1, 2, 3], [4, 5, 6], [7, 8, 9]])


@pytest.mark.parametrize("unit, rad_per_s", [
    ("rpm", 2 * np.pi / 60), ("rev/s", 2 * np.pi), ("Hz", 2 * np.pi), ("rad/s", 1.0), ("deg/s", np.pi / 180),
    ("°/s", np.pi / 180), ("dps", np.pi / 180), ("mdps", np.pi / 180e3), ("mdeg/s", np.pi / 180e3),
    ("mrad/s", 1e-3), ("deg/h", np.pi / 180 / 3600), ("rev/min", 2 * np.pi / 60)])
def test_every_rate_unit_is_converted(tmp_path, unit, rad_per_s):
    """Issue 33: (rpm), (rev/s), (Hz) were read as rad/s: 60 rpm -> 60 rad/s."""
    path = write(tmp_path / "rates.csv", f"time (s),gyro x ({unit}),gyro y ({unit}),gyro z ({unit})\n"
                                         "0,6,0,-1\n0.5,1,2,3\n")
    np.testing.assert_allclose(kr.io.read_gyro(path).omega, np.array([[6, 0, -1], [1, 2, 3]]) * rad_per_s,
                               rtol=1e-15)


def test_60_rpm_is_one_turn_per_second(tmp_path):
    path = write(tmp_path / "rpm.csv", "time (s),gyro x (rpm),gyro y (rpm),gyro z (rpm)\n0,0,0,60\n")
    assert kr.io.read_gyro(path).omega[0, 2] == pytest.approx(2 * np.pi, rel=1e-15)


def test_unit_tokens_not_substrings(tmp_path):
    """Issue 33: gyro_x_radps matched "dps" and was read as degrees (1 rad/s -> 0.01745)."""
    path = write(tmp_path / "radps.csv", "time,gyro_x_radps,gyro_y_radps,gyro_z_radps\n0,1,2,3\n")
    np.testing.assert_array_equal(kr.io.read_gyro(path).omega, [[1, 2, 3]])
    path = write(tmp_path / "dps.csv", "time_ms,gyro_x_dps,gyro_y_dps,gyro_z_dps\n0,180,0,0\n1000,90,0,0\n")
    rec = kr.io.read_gyro(path)
    np.testing.assert_allclose(rec.omega[:, 0], [np.pi, np.pi / 2], rtol=1e-15)
    np.testing.assert_array_equal(rec.t, [0.0, 1.0])


@pytest.mark.parametrize("header, column, unit", [
    ("t (s),gyro x (furlong/s),gyro y (furlong/s),gyro z (furlong/s)", "gyro x (furlong/s)", "furlong/s"),
    ("t,gyro_x_raw,gyro_y_raw,gyro_z_raw", "gyro_x_raw", "raw"),
    ("t,gx,gy,gz,ax (lbf),ay (lbf),az (lbf)", "ax (lbf)", "lbf")])
def test_unknown_units_are_refused_naming_the_column(tmp_path, header, column, unit):
    row = ",".join(str(k) for k in range(header.count(",") + 1))
    path = write(tmp_path / "odd.csv", f"# logger v2\n{header}\n{row}\n")
    message = rf"odd.csv:2: column {re.escape(repr(column))}: unknown \w+(-\w+)? unit '{unit}'"
    with pytest.raises(GyroFileError, match=message):
        kr.io.read_gyro(path)


def test_a_stated_unit_reads_an_unknown_header_unit_and_a_contradiction_is_refused(tmp_path):
    path = write(tmp_path / "raw.csv", "t,gyro_x_raw,gyro_y_raw,gyro_z_raw\n0,90,0,0\n")
    assert kr.io.read_gyro(path, units="deg/s").omega[0, 0] == pytest.approx(np.pi / 2, rel=1e-15)
    path = write(tmp_path / "rad.csv", "t,gyro x (rad/s),gyro y (rad/s),gyro z (rad/s)\n0,1,0,0\n")
    with pytest.raises(GyroFileError, match=r"rad.csv:1: column 'gyro x \(rad/s\)' is in rad/s, but units gives "
                                            r"'deg/s'"):
        kr.io.read_gyro(path, units="deg/s")
    with pytest.raises(ValueError, match=r"units\['gyro'\] must be one of rad/s, .*; got 'furlong/s'"):
        kr.io.read_gyro(path, units="furlong/s")
    with pytest.raises(ValueError, match=r"units: keys must be among time, gyro, accel, mag, got 'gyr'"):
        kr.io.read_gyro(path, units={"gyr": "rad/s"})


DEG_TOSS = np.degrees(kr.EulerTop(0.5, 0.8, 1.0).omega(np.linspace(0, 0.6, 200), [0.3, 12.0, 0.4]))


def deg_file(tmp_path):
    t = np.linspace(0, 0.6, 200)
    rows = "\n".join(",".join(f"{v:.17g}" for v in (ti, *w)) for ti, w in zip(t, DEG_TOSS))
    return write(tmp_path / "deg.csv", f"time,gx,gy,gz\n{rows}\n")


def test_deg_per_second_without_a_unit_is_refused_naming_the_likely_unit(tmp_path):
    """Issue 34: deg/s read as rad/s (a phone gyro saturates near 35 rad/s)."""
    path = deg_file(tmp_path)
    with pytest.raises(GyroFileError, match=r"deg.csv: the gyro's \|ω\| reaches 6\d\d(\.\d+)? rad/s \(its numbers "
                                            r"taken as rad/s: no unit is given\), beyond the ~35 rad/s .* the "
                                            r"numbers look like deg/s: read them with units='deg/s' "
                                            r"\(on the command line: --units deg/s\)"):
        kr.io.read_gyro(path)
    rec = kr.io.read_gyro(path, units="deg/s")
    np.testing.assert_allclose(rec.omega, np.radians(DEG_TOSS), rtol=1e-15)
    # a header that says deg/s for millidegrees is refused too; a stated unit is trusted
    path = write(tmp_path / "mdeg.csv", "t,gx (deg/s),gy (deg/s),gz (deg/s)\n0,5000,0,0\n")
    with pytest.raises(GyroFileError, match="in the header's unit.*look like mdeg/s.*or units='deg/s' if the rates"):
        kr.io.read_gyro(path)
    assert kr.io.read_gyro(path, units="deg/s").omega[0, 0] == pytest.approx(np.radians(5000.0), rel=1e-15)
    rotor = write(tmp_path / "rotor.csv", "t,gx,gy,gz\n0,0,0,300\n")
    assert kr.io.read_gyro(rotor, units="rad/s").omega[0, 2] == 300.0


def test_imu_csv_with_deg_per_second_and_g_named_in_the_header(tmp_path):
    """Issue 35: CSV with deg/s and g units named in the header; magnetometer in nT and mT."""
    header = "\t".join(["Time (ms)", "AccX (g)", "AccY (g)", "AccZ (g)", "GyrX (deg/s)", "GyrY (deg/s)", "GyrZ (deg/s)",
                        "MagX (nT)", "MagY (nT)", "MagZ (nT)"])
    rows = ["0\t0,01\t-0,02\t1\t90\t-45\t180\t20000\t0\t-43000", "10\t0\t0\t0,98\t91\t-44\t179\t20100\t1\t-43010"]
    rec = kr.io.read_imu(write(tmp_path / "imu.tsv", "\n".join([header, *rows]) + "\n"))
    np.testing.assert_array_equal(rec.t, [0.0, 0.01])
    np.testing.assert_allclose(rec.omega[0], np.radians([90, -45, 180]), rtol=1e-15)
    np.testing.assert_allclose(rec.accel[:, 2], [G0, 0.98 * G0], rtol=1e-15)
    np.testing.assert_allclose(rec.mag[0], [20.0, 0.0, -43.0], rtol=1e-15)
    path = write(tmp_path / "mt.csv", "t,gx,gy,gz,mx (mT),my (mT),mz (mT),ax (mg),ay (mg),az (mg)\n"
                                      "0,0,0,0,0.05,0,0,0,0,1000\n")
    rec = kr.io.read_imu(path)
    np.testing.assert_allclose([rec.mag[0, 0], rec.accel[0, 2]], [50.0, G0], rtol=1e-15)
    rec = kr.io.read_imu(path, units={"accel": "mg", "mag": "mT"})
    assert rec.accel[0, 2] == pytest.approx(G0, rel=1e-15)


def test_units_by_keyword_for_a_file_that_names_none(tmp_path):
    path = write(tmp_path / "bare.csv", "t,gx,gy,gz,ax,ay,az,mx,my,mz\n0,1,0,0,0,0,1,0.3,0,-0.4\n")
    rec = kr.io.read_imu(path, units={"gyro": "deg/s", "accel": "g", "mag": "G", "time": "ms"})
    np.testing.assert_allclose(rec.omega[0], [np.pi / 180, 0, 0], rtol=1e-15)
    np.testing.assert_allclose(rec.accel[0], [0, 0, G0], rtol=1e-15)
    np.testing.assert_allclose(rec.mag[0], [30.0, 0.0, -40.0], rtol=1e-15)


def test_latin1_and_utf16_files_are_decoded_and_say_so(tmp_path):
    """Issue 33: a Latin-1 file with °/s in its header was "not a text file"."""
    text = "time (s),gyro x (°/s),gyro y (°/s),gyro z (°/s)\n0,90,0,0\n0.1,90,0,0\n"
    for encoding, name in (("latin-1", "Latin-1"), ("utf-16", "UTF-16"), ("utf-16-le", "UTF-16")):
        path = write(tmp_path / f"{encoding}.csv", text, encoding)
        rec = kr.io.read_gyro(path)
        np.testing.assert_allclose(rec.omega[:, 0], np.pi / 2, rtol=1e-15)
        assert len(rec.notes) == 1 and rec.notes[0].startswith(f"decoded as {name}"), rec.notes
    assert kr.io.read_gyro(write(tmp_path / "utf8.csv", text)).notes == ()


def test_a_zip_that_expands_to_gigabytes_is_refused_before_it_is_read(tmp_path):
    """Issue 33: a 611 kB zip of zeros used 1.3 GB."""
    archive = tmp_path / "bomb.zip"
    with zipfile.ZipFile(archive, "w", zipfile.ZIP_DEFLATED) as z:
        with z.open("Gyroscope.csv", "w", force_zip64=True) as member:
            block = bytes(2**20)
            for _ in range(80):
                member.write(block)
    assert archive.stat().st_size < 200_000
    with pytest.raises(GyroFileError, match=r"bomb.zip:Gyroscope.csv: expands beyond 64 MiB; unzip the export"):
        kr.io.read_gyro(archive)


def broad_npz(path, n=50, **changes):
    rng = np.random.default_rng(5)
    fields = {"gyr": rng.normal(0, 0.5, (n, 3)).astype(np.float32),
              "acc": (rng.normal(0, 0.1, (n, 3)) + [0, 0, 9.81]).astype(np.float32),
              "mag": rng.normal([20, 0, -40], 1, (n, 3)).astype(np.float32),
              "opt_quat": np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)), "movement": np.arange(n) > 10,
              "sampling_rate": np.array(285.714)}
    fields["opt_quat"][3] = np.nan
    fields.update(changes)
    np.savez_compressed(path, **{k: v for k, v in fields.items() if v is not None})
    return fields


def test_broad_layout(tmp_path):
    fields = broad_npz(tmp_path / "trial.npz")
    rec = kr.io.read_imu(tmp_path / "trial.npz")
    np.testing.assert_allclose(rec.t, np.arange(50) / 285.714, rtol=1e-15)
    np.testing.assert_array_equal(rec.omega, fields["gyr"].astype(np.float64))
    np.testing.assert_array_equal(rec.accel, fields["acc"].astype(np.float64))
    np.testing.assert_array_equal(rec.mag, fields["mag"].astype(np.float64))
    assert np.isnan(rec.reference[3]).all() and rec.reference.shape == (50, 4)
    np.testing.assert_array_equal(rec.movement, fields["movement"])
    assert rec.omega.dtype == np.float64 and repr(rec).endswith("gyro, accel, mag, reference)")
    broad_npz(tmp_path / "gyro_only.npz", acc=None, mag=None, opt_quat=None, movement=None)
    rec = kr.io.read_gyro(tmp_path / "gyro_only.npz")
    assert rec.accel is None and rec.mag is None and rec.reference is None


@pytest.mark.parametrize("changes, match", [
    ({"gyr": None}, r"fields \[.*\]; expected BROAD's layout \(gyr, acc, mag, opt_quat, movement, sampling_rate\)"),
    ({"acc": np.zeros((49, 3))}, r"field 'acc' has shape \(49, 3\) and dtype float64; expected numbers of shape "
                                 r"\(50, 3\)"),
    ({"gyr": np.full((50, 3), np.nan)}, r"field 'gyr', row 0: not a finite number"),
    ({"gyr": np.zeros((0, 3))}, r"bad.npz: empty \(no samples\)"),
    ({"t": np.array([0.0, 1.0, 1.0] + list(range(2, 49)))}, r"field 't', row 2: time not increasing"),
    ({"sampling_rate": np.array(-1.0)}, r"field 'sampling_rate' must be one positive number \(Hz\)"),
    ({"gyr": np.full((50, 3), 700.0)}, r"the gyro's \|ω\| reaches 1212 rad/s .* look like deg/s")])
def test_bad_broad_files(tmp_path, changes, match):
    broad_npz(tmp_path / "bad.npz", **changes)
    with pytest.raises(GyroFileError, match=match) as info:
        kr.io.read_imu(tmp_path / "bad.npz")
    assert str(info.value).count(str(tmp_path)) == 1
    (tmp_path / "cut.npz").write_bytes((tmp_path / "bad.npz").read_bytes()[:100])
    with pytest.raises(GyroFileError, match="cut.npz: not a readable .npz archive"):
        kr.io.read_imu(tmp_path / "cut.npz")


def test_dataframe_columns_by_name_and_rows_named():
    df = pd.DataFrame({"stamp": [0.0, 0.1, 0.2], "p": [0.0, 1.0, 0.0], "q": [0.0] * 3, "r": [10.0] * 3,
                       "ax": [0.0] * 3, "ay": [0.0] * 3, "az": [1.0] * 3})
    rec = kr.io.read_imu(df, columns={"time": "stamp", "gyro": ("p", "q", "r")}, units={"gyro": "deg/s",
                                                                                          "accel": "g"})
    np.testing.assert_allclose(rec.omega[1], np.radians([1.0, 0.0, 10.0]), rtol=1e-15)
    np.testing.assert_allclose(rec.accel[:, 2], G0, rtol=1e-15)
    with pytest.raises(GyroFileError, match=r"DataFrame: column 'q', row 1: not a finite number"):
        kr.io.read_imu(df.assign(q=[0.0, np.nan, 0.0]), columns={"time": "stamp", "gyro": ("p", "q", "r")})
    with pytest.raises(GyroFileError, match=r"column\(s\) 'w' not found; the table has \['stamp'"):
        kr.io.read_imu(df, columns={"gyro": ("p", "q", "w")})
    with pytest.raises(TypeError, match="source must be a file path or a pandas DataFrame"):
        kr.io.read_imu(np.zeros((3, 4)))
    with pytest.raises(ValueError, match="kind must be 'rate' or 'increment'"):
        kr.io.read_imu(df, kind="rates")


def test_bad_columns_and_short_headers(tmp_path):
    path = write(tmp_path / "imu.csv", "t,gx,gy,gz\n0,1,2,3,4,5\n")
    np.testing.assert_array_equal(kr.io.read_imu(path).omega, [[1, 2, 3]])   # unnamed extra columns
    with pytest.raises(ValueError, match=r"columns\['gyro'\] must be three header names \(x, y, z\), got 'gx'"):
        kr.io.read_imu(path, columns={"gyro": "gx"})
    with pytest.raises(ValueError, match=r"columns: keys must be among time, gyro, accel, mag, got 'acc'"):
        kr.io.read_imu(path, columns={"acc": ("gx", "gy", "gz")})
    path = write(tmp_path / "twice.csv", "t,gyro x,gyro x,gyro z\n0,1,2,3\n")
    with pytest.raises(GyroFileError, match=r"twice.csv:1: the gyro x axis is named by more than one column"):
        kr.io.read_imu(path)
    path = write(tmp_path / "two.csv", "t,ax,ay,gx,gy,gz\n0,1,2,3,4,5\n")
    with pytest.raises(GyroFileError, match=r"two.csv:1: 2 accelerometer column\(s\) \('ax', 'ay'\); expected x, y "
                                            r"and z"):
        kr.io.read_imu(path)


def test_rate_times_a_table_without_a_time_column(tmp_path):
    rows = np.arange(12.0).reshape(4, 3) / 10.0
    bare = tmp_path / "bare.txt"
    np.savetxt(bare, rows)
    named = tmp_path / "named.csv"
    np.savetxt(named, np.column_stack([rows, rows + 9.0]), delimiter=",", header="gx,gy,gz,ax,ay,az", comments="")
    for path in (bare, named):
        rec = kr.io.read_imu(path, rate=50)
        np.testing.assert_array_equal(rec.t, np.arange(4) / 50.0)
        np.testing.assert_array_equal(rec.omega, rows)
    np.testing.assert_array_equal(kr.io.read_imu(named, rate=50).accel, rows + 9.0)


def test_rate_is_refused_where_the_recording_has_its_own_clock(tmp_path):
    timed = tmp_path / "timed.csv"
    timed.write_text("t,gx,gy,gz\n0,0,0,1\n0.01,0,0,1\n")
    with pytest.raises(GyroFileError, match=r"timed.csv:1: the table has a time column"):
        kr.io.read_imu(timed, rate=100)
    np.savez(tmp_path / "broad.npz", gyr=np.zeros((3, 3)), sampling_rate=100.0)
    with pytest.raises(GyroFileError, match="has its own clock"):
        kr.io.read_imu(tmp_path / "broad.npz", rate=100)
    for rate, error in ((0, ValueError), (float("nan"), ValueError), ("fast", TypeError)):
        with pytest.raises(error, match="rate must be"):
            kr.io.read_imu(timed, rate=rate)
