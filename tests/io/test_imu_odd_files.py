"""read_imu on files loggers and spreadsheets write: each read right or refused in one line, never misread."""

import zipfile

import numpy as np
import pytest

import kreisel as kr
from kreisel.io import GyroFileError

ROWS = [(0.0, 0.1, 0.2, 0.3), (0.01, 0.4, 0.5, 0.6), (0.02, 0.7, 0.8, 0.9)]


def table(rows=ROWS, header="time,gx,gy,gz", newline="\n", trailing=""):
    lines = [header + trailing, *(",".join(repr(v) for v in row) + trailing for row in rows)]
    return newline.join(lines) + newline


@pytest.mark.parametrize("text", [
    "\ufeff" + table(),
    table(newline="\r\n"),
    table(trailing=","),
    "\ufeff" + table(newline="\r\n", trailing=","),
], ids=["BOM", "CRLF", "trailing commas", "all three"])
def test_excel_and_windows_files_read_as_the_plain_one(tmp_path, text):
    path = tmp_path / "log.csv"
    path.write_bytes(text.encode("utf-8"))
    rec = kr.io.read_imu(path)
    np.testing.assert_array_equal(rec.t, [row[0] for row in ROWS])
    np.testing.assert_array_equal(rec.omega, [row[1:] for row in ROWS])


@pytest.mark.parametrize("text, message", [
    (table(rows=[ROWS[0], ROWS[1], (0.01, 1.0, 1.0, 1.0), ROWS[2]]),
     r"log.csv:4: time not increasing \(0.01 after 0.01\)"),
    ("time,gx,gy,gz\n", r"log.csv: empty \(no data rows\)"),
    ("time,gx,gy,gz\r\n", r"log.csv: empty \(no data rows\)"),
    ("", r"log.csv: empty \(no data rows\)"),
], ids=["duplicate time stamp", "header only", "header only, CRLF", "empty"])
def test_files_without_a_usable_clock_or_data_are_refused_naming_the_line(tmp_path, text, message):
    path = tmp_path / "log.csv"
    path.write_bytes(text.encode("utf-8"))
    with pytest.raises(GyroFileError, match=message):
        kr.io.read_imu(path)


def test_nanosecond_time_stamps_without_a_unit_are_not_taken_for_seconds(tmp_path):
    """An Android log's ``timestamp`` column (ns since boot) was read as seconds: samples 10⁷ s apart, and
    ``kreisel attitude`` integrated 1 rad/s over them without a word."""
    t = 1_700_000_000_000_000_000 + 10_000_000 * np.arange(50)   # 100 Hz
    omega = np.tile([0.1, 0.2, 1.0], (50, 1))
    path = tmp_path / "android.csv"
    path.write_text("timestamp,gx,gy,gz\n" + "".join(f"{ti},{w[0]},{w[1]},{w[2]}\n" for ti, w in zip(t, omega)))
    with pytest.raises(GyroFileError, match=r"android.csv: the time stamps, taken as seconds \(no unit is given\), "
                                            r"are 1e\+07 s apart, .* the times look like ns: name the unit in the "
                                            r"header \('time \(ns\)'\) or read them with units=\{'time': 'ns'\}"):
        kr.io.read_imu(path)
    rec = kr.io.read_imu(path, units={"time": "ns"})
    np.testing.assert_allclose(np.diff(rec.t), 0.01, rtol=0, atol=2.6e-7)   # a double holds 1.7e18 ns to 256 ns
    path.write_text(path.read_text().replace("timestamp,", "timestamp (ns),", 1))
    np.testing.assert_array_equal(kr.io.read_imu(path).t, rec.t)


@pytest.mark.parametrize("unit, scale", [("ms", 1e3), ("us", 1e6)])
def test_milli_and_microsecond_stamps_of_a_turning_gyro_are_named(tmp_path, unit, scale):
    t = np.arange(40) * 0.005 * scale                            # 200 Hz
    path = tmp_path / "log.csv"
    path.write_text("t,gx,gy,gz\n" + "".join(f"{ti:.17g},0.5,3.0,0.2\n" for ti in t))
    with pytest.raises(GyroFileError, match=f"the times look like {unit}"):
        kr.io.read_imu(path)
    np.testing.assert_allclose(kr.io.read_imu(path, units={"time": unit}).t[1], 0.005, rtol=1e-12)


def test_slow_samples_of_a_slow_turn_and_a_stated_second_are_trusted(tmp_path):
    t = np.arange(20) * 2.0                                      # one sample every 2 s, 0.1 rad/s: 0.2 rad apart
    path = tmp_path / "slow.csv"
    path.write_text("t,gx,gy,gz\n" + "".join(f"{ti},0.1,0,0\n" for ti in t))
    np.testing.assert_array_equal(kr.io.read_imu(path).t, t)
    path.write_text("t,gx,gy,gz\n" + "".join(f"{ti},3.0,0,0\n" for ti in t))   # 6 rad apart: refused ...
    with pytest.raises(GyroFileError, match="more than half a turn"):
        kr.io.read_imu(path)
    np.testing.assert_array_equal(kr.io.read_imu(path, units={"time": "s"}).t, t)   # ... unless the unit is stated


@pytest.mark.parametrize("text, message", [
    ("time,mx,my,mz,other\n0,1,2,3,4\n0.01,1,2,3,4\n",
     r"log.csv:1: the header names no gyro columns \(it names the magnetometer's\), and 1 other column \('other'\) "
     r"is left; expected three gyro columns x, y, z: name them with columns="),
    ("time,mx,my,mz\n0,1,2,3\n0.01,1,2,3\n",
     r"log.csv:1: the header names no gyro columns \(it names the magnetometer's\), and no other column is left"),
    ('"Time (s)","Acceleration x (m/s^2)","Acceleration y (m/s^2)","Acceleration z (m/s^2)",'
     '"Absolute acceleration (m/s^2)"\n0,1,2,3,4\n0.01,1,2,3,4\n',
     r"log.csv:1: the header names no gyro columns \(it names the accelerometer's\), and no other column is left"),
], ids=["magnetometer and one more column", "magnetometer only", "phyphox Accelerometer.csv"])
def test_a_table_of_other_sensors_is_not_read_as_a_gyro(tmp_path, text, message):
    """A magnetometer log with one spare column came back as a gyro of shape (n, 1), one with none as (n, 0)."""
    path = tmp_path / "log.csv"
    path.write_text(text)
    with pytest.raises(GyroFileError, match=message):
        kr.io.read_imu(path)


def workbook(path, excel97=False):
    """An .xlsx as Excel writes it (a zip of XML parts), or the OLE header of an .xls."""
    if excel97:
        path.write_bytes(b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1" + bytes(504))
        return
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("[Content_Types].xml", "<Types/>")
        archive.writestr("xl/workbook.xml", "<workbook/>")
        archive.writestr("xl/worksheets/sheet1.xml", "<worksheet/>")


@pytest.mark.parametrize("name, excel97", [("Gyroscope.xlsx", False), ("Gyroscope.xls", True), ("gyro.csv", False)],
                         ids=["xlsx", "xls", "xlsx named csv"])
def test_spreadsheet_exports_are_refused_as_such(tmp_path, name, excel97):
    """phyphox's "Excel" export was refused as "not a text file (control character '\\x03' ...)"."""
    path = tmp_path / name
    workbook(path, excel97)
    with pytest.raises(GyroFileError, match=rf"{name}: a spreadsheet workbook, not a text table; export it as CSV "
                                            r"\(phyphox: 'CSV \(Comma, decimal point\)'\)"):
        kr.io.read_imu(path)


def test_a_phyphox_zip_without_its_suffix_is_read_as_the_zip(tmp_path):
    path = tmp_path / "export"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("Gyroscope.csv", "time,gx,gy,gz\n0,1,2,3\n0.01,1,2,3\n")
    np.testing.assert_array_equal(kr.io.read_imu(path).omega, [[1, 2, 3], [1, 2, 3]])
    with pytest.raises(GyroFileError, match=r"export: rate= is for a table file without a time column; this zip"):
        kr.io.read_imu(path, rate=100)


ACCEL_MAG = "t,gx,gy,gz,ax,ay,az,mx,my,mz\n" + "".join(f"{0.01 * k},0.1,0,0,{{a}},{{m}}\n" for k in range(20))


@pytest.mark.parametrize("accel, mag, message", [
    ("0.02,-0.01,0.99", "20,0,-40",
     r"log.csv: the accelerometer's \|a\| is 0.99 \(90th percentile\), taken as m/s² \(no unit is given\): a phone "
     r"held still reads 9.8 m/s²; the numbers look like g: name the unit in the header \('ax \(g\)'\) or read them "
     r"with units=\{'accel': 'g'\}, or units=\{'accel': 'm/s2'\} if the values are real"),
    ("20,-10,990", "20,0,-40", r"the accelerometer's \|a\| is 990 .* the numbers look like mg"),
    ("0,0,9.81", "0.2,0,-0.4",
     r"log.csv: the magnetometer's \|B\| is 0.447 \(median\), taken as µT \(no unit is given\): the Earth's field is "
     r"25…65 µT; the numbers look like G: name the unit in the header \('mx \(G\)'\) or read them with "
     r"units=\{'mag': 'G'\}, or units=\{'mag': 'uT'\} if the values are real"),
    ("0,0,9.81", "20000,0,-40000", r"the magnetometer's \|B\| is 4.47e\+04 .* the numbers look like nT"),
], ids=["accel in g", "accel in mg", "mag in gauss", "mag in nT"])
def test_accelerometer_and_magnetometer_without_units_in_other_units_are_named(tmp_path, accel, mag, message):
    """A log with the accelerometer in g and the magnetometer in gauss, no units in the header, was read as m/s²
    and µT: gravity 10 times too weak and a field 100 times too weak, without a word."""
    path = tmp_path / "log.csv"
    path.write_text(ACCEL_MAG.format(a=accel, m=mag))
    with pytest.raises(GyroFileError, match=message):
        kr.io.read_imu(path)


def test_accelerometer_and_magnetometer_in_stated_units_are_trusted(tmp_path):
    path = tmp_path / "log.csv"
    path.write_text(ACCEL_MAG.format(a="0,0,1", m="0.2,0,-0.4"))
    rec = kr.io.read_imu(path, units={"accel": "g", "mag": "G"})
    np.testing.assert_allclose(rec.accel[0], [0, 0, 9.80665], rtol=1e-15)
    np.testing.assert_allclose(rec.mag[0], [20.0, 0.0, -40.0], rtol=1e-15)
    rec = kr.io.read_imu(path, units={"accel": "m/s2", "mag": "uT"})
    np.testing.assert_array_equal(rec.accel[0], [0, 0, 1])
    np.testing.assert_array_equal(rec.mag[0], [0.2, 0, -0.4])
    path.write_text(ACCEL_MAG.format(a="0,0,9.81", m="20,0,-40"))
    rec = kr.io.read_imu(path)
    np.testing.assert_array_equal([rec.accel[0, 2], rec.mag[0, 2]], [9.81, -40])


@pytest.mark.parametrize("header, kw, note", [
    ("t,gx,gy,gz,ax,ay,az", {}, "units assumed where the file names none: time s, gyro rad/s, accelerometer m/s²; "
                                "name them in the header ('gx (deg/s)') or give units="),
    ("t,gx (deg/s),gy (deg/s),gz (deg/s),ax,ay,az", {},
     "units assumed where the file names none: time s, accelerometer m/s²; name them in the header"),
    ("t,gx,gy,gz,ax,ay,az", {"units": {"time": "s", "gyro": "rad/s"}}, "units assumed where the file names none: "
                                                                        "accelerometer m/s²;"),
    ("time (s),gx (rad/s),gy (rad/s),gz (rad/s),ax (g),ay (g),az (g)", {}, None),
], ids=["nothing named", "gyro named", "units= given", "all named"])
def test_the_units_the_reader_assumed_are_in_the_notes(tmp_path, header, kw, note):
    """A log without units was read as s, rad/s and m/s² without a word: nothing told a user reading a deg/s
    file at slow rates that it had been taken for rad/s."""
    path = tmp_path / "log.csv"
    path.write_text(header + "\n" + "".join(f"{0.01 * k},0.1,0,0,0,0,{1 if '(g)' in header else 9.81}\n"
                                            for k in range(5)))
    notes = kr.io.read_imu(path, **kw).notes
    assert [n for n in notes if n.startswith("units assumed")] == ([] if note is None else [notes[0]])
    assert note is None or notes[0].startswith(note), notes


def test_rate_and_the_bundled_recordings_assume_nothing(tmp_path):
    path = tmp_path / "bare.txt"
    np.savetxt(path, np.full((4, 3), 0.1))
    assert kr.io.read_imu(path, rate=50, units="rad/s").notes == ()
    assert kr.io.read_imu(kr.io.recording_path("phone_toss")).notes == ()
    assert kr.io.read_imu(kr.io.recording_path("broad_07")).notes == ()


def test_time_stamps_too_slow_for_an_imu_taken_as_seconds_say_so(tmp_path):
    """Millisecond stamps of a phone lying still were read as seconds: 10 s between samples, a 1000 times too long
    recording, and no note."""
    path = tmp_path / "still.csv"
    path.write_text("timestamp,gx (rad/s),gy (rad/s),gz (rad/s)\n" + "".join(f"{10 * k},0.001,0,0\n" for k in range(5)))
    notes = kr.io.read_imu(path).notes
    assert notes == ("units assumed where the file names none: time s; name them in the header ('gx (deg/s)') or give "
                     "units=; the samples, 10 s apart (median), are slower than any IMU log (10 Hz and faster): "
                     "if the times are ms, name the unit ('time (ms)') or give units={'time': 'ms'}",)


PHYPHOX = '"Time (s)","Gyroscope x (rad/s)","Gyroscope y (rad/s)","Gyroscope z (rad/s)","Absolute (rad/s)"\n'


@pytest.mark.parametrize("row, message", [
    ("0.01,NaN,0.2,0.3,0.37", r"Gyroscope.csv:3: not a finite number: 'NaN' \(column 2, 'Gyroscope x \(rad/s\)'\); "
                              r"expected a finite number"),
    ("0.01,,0.2,0.3,0.37", r"Gyroscope.csv:3: not a number: '' \(column 2, 'Gyroscope x \(rad/s\)'\), an empty "
                           r"cell; expected a number"),
    ("0.01,0.1,x,0.3,0.37", r"Gyroscope.csv:3: not a number: 'x' \(column 3, 'Gyroscope y \(rad/s\)'\); expected"),
    ("0.01,0.1,0.2,inf,0.37", r"Gyroscope.csv:3: not a finite number: 'inf' \(column 4, 'Gyroscope z \(rad/s\)'\)"),
], ids=["NaN", "empty", "letter", "inf"])
@pytest.mark.parametrize("semicolons", [False, True], ids=["comma", "semicolon, decimal comma"])
def test_a_bad_cell_mid_file_is_named_by_line_and_column(tmp_path, row, message, semicolons):
    """A NaN or an empty cell mid-file named the line but not the column, and showed the whole line instead."""
    text = PHYPHOX + "0.0,0.1,0.2,0.3,0.37\n" + row + "\n0.02,0.1,0.2,0.3,0.37\n"
    if semicolons:
        text = text.replace(",", ";").replace(".", ",")
    path = tmp_path / "Gyroscope.csv"
    path.write_text(text)
    with pytest.raises(GyroFileError, match=message):
        kr.io.read_imu(path)


RAW_GYRO = PHYPHOX + "".join(f"{0.0025 * k:.9E},1.0E-1,-2.5E0,3.0E-2,2.5E0\n" for k in range(8))
RAW_ACCEL = ('"Time (s)","Linear Acceleration x (m/s^2)","Linear Acceleration y (m/s^2)",'
             '"Linear Acceleration z (m/s^2)","Absolute acceleration (m/s^2)"\n0,1,2,3,3.7\n0.01,1,2,3,3.7\n')


@pytest.mark.parametrize("folder", [False, True], ids=["zip", "folder"])
def test_a_phyphox_experiment_export_with_its_raw_data_table_is_read(tmp_path, folder):
    """phyphox's "Gyroscope" experiment exports "Raw Data.csv" (and meta/), not Gyroscope.csv: such a zip was
    refused for having no Gyroscope.csv."""
    files = {"Raw Data.csv": RAW_GYRO, "meta/device.csv": '"property","value"\n"model","Pixel"\n'}
    path = tmp_path / ("export" if folder else "export.zip")
    if folder:
        (path / "meta").mkdir(parents=True)
        for name, text in files.items():
            (path / name).write_text(text)
    else:
        with zipfile.ZipFile(path, "w") as archive:
            for name, text in files.items():
                archive.writestr(name, text)
    rec = kr.io.read_imu(path)
    np.testing.assert_allclose(rec.t, np.arange(8) * 0.0025, rtol=1e-15, atol=0)
    np.testing.assert_array_equal(rec.omega, np.tile([0.1, -2.5, 0.03], (8, 1)))


def test_a_phyphox_export_of_another_experiment_is_refused_naming_what_it_holds(tmp_path):
    path = tmp_path / "export.zip"
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("Raw Data.csv", RAW_ACCEL)
    with pytest.raises(GyroFileError, match=r"export.zip:Raw Data.csv:1: the header names no gyro columns, and no "
                                            r"other column is left; expected three gyro columns x, y, z"):
        kr.io.read_imu(path)
