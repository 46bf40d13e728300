"""phyphox exports with one table per sensor, each on its own clock, read onto the gyroscope's."""

import zipfile

import numpy as np
import pytest

import kreisel as kr
from kreisel.io import GyroFileError


def write(path, text, encoding="utf-8"):
    path.write_text(text, encoding=encoding)
    return path


ABSOLUTE = {"Gyroscope": "Absolute", "Acceleration": "Absolute acceleration", "Magnetic field": "Absolute field"}


def phyphox_table(t, values, name, unit):
    """A table as phyphox exports it: quoted header with units, the magnitude last, numbers like 4.273100000E+00."""
    header = ",".join(['"Time (s)"', *(f'"{name} {axis} ({unit})"' for axis in "xyz"), f'"{ABSOLUTE[name]} ({unit})"'])
    rows = [",".join(f"{v:.9E}" for v in (ti, *row, np.linalg.norm(row))) for ti, row in zip(t, values)]
    return header + "\n" + "\n".join(rows) + "\n"


def phyphox_export(rng=np.random.default_rng(3)):
    """Gyroscope at ~400 Hz, accelerometer at ~200 Hz, magnetometer at ~50 Hz, each on its own jittered clock."""
    tables, truth = {}, {}
    for name, file, unit, rate, start, stop in (("Gyroscope", "Gyroscope.csv", "rad/s", 400, 0.003, 2.0),
                                                ("Acceleration", "Accelerometer.csv", "m/s^2", 200, 0.010, 1.98),
                                                ("Magnetic field", "Magnetometer.csv", "µT", 50, 0.02, 2.01)):
        t = np.sort(rng.uniform(start, stop, int(rate * (stop - start))))
        t[0], t[-1] = start, stop
        # linear in time, so that linear interpolation is exact
        values = np.column_stack([1.0 + 2.0 * t, -3.0 * t, 0.5 + 0.0 * t])
        tables[file] = phyphox_table(t, values, name, unit)
        truth[file] = t
    return tables, truth


@pytest.mark.parametrize("container", ["zip", "folder"])
def test_phyphox_multi_sensor_export_on_the_gyro_clock(tmp_path, container):
    tables, truth = phyphox_export()
    if container == "zip":
        source = tmp_path / "Sensors 2026-12-05 06-00-00.zip"
        with zipfile.ZipFile(source, "w") as z:
            for name, text in tables.items():
                z.writestr(name, text)
            z.writestr("meta/device.csv", '"property","value"\n"deviceModel","Pixel"\n')
            z.writestr("meta/time.csv", '"event","experiment time","system time","system time text"\n')
    else:
        source = tmp_path / "Sensors 2026-12-05 06-00-00"
        (source / "meta").mkdir(parents=True)
        for name, text in tables.items():
            write(source / name, text)
    rec = kr.io.read_imu(source)
    t_gyro = truth["Gyroscope.csv"]
    inside = (t_gyro >= 0.02) & (t_gyro <= 1.98)
    np.testing.assert_allclose(rec.t, t_gyro[inside], rtol=1e-9)
    expected = np.column_stack([1.0 + 2.0 * rec.t, -3.0 * rec.t, 0.5 + 0.0 * rec.t])
    for values in (rec.omega, rec.accel, rec.mag):
        np.testing.assert_allclose(values, expected, rtol=1e-8, atol=1e-8)
    notes = " | ".join(rec.notes)
    n = {name: t.size for name, t in truth.items()}
    assert (f"accelerometer ({n['Accelerometer.csv']} samples, 199.5 Hz) interpolated linearly onto the gyroscope's "
            f"clock ({n['Gyroscope.csv']} samples, 399.1 Hz)") in notes
    assert f"magnetometer ({n['Magnetometer.csv']} samples, 49.25 Hz) interpolated linearly" in notes
    assert f"{np.sum(~inside)} gyroscope sample(s) outside the other sensors' time span dropped" in notes
    assert rec.source == str(source) and "gyro, accel, mag" in repr(rec)


def test_phyphox_sensors_that_never_overlap_are_refused(tmp_path):
    folder = tmp_path / "export"
    folder.mkdir()
    write(folder / "Gyroscope.csv", phyphox_table([0.0, 0.1], np.zeros((2, 3)), "Gyroscope", "rad/s"))
    write(folder / "Accelerometer.csv", phyphox_table([5.0, 5.1], np.zeros((2, 3)), "Acceleration", "m/s^2"))
    with pytest.raises(GyroFileError, match=r"export: the gyroscope \(0…0.1 s\) and the other sensors "
                                            r"\(accelerometer 5…5.1 s\) do not overlap"):
        kr.io.read_imu(folder)
    write(folder / "Accelerometer.csv", '"Time (s)","Acceleration x (m/s^2)"\n0,1\n')  # cut short
    with pytest.raises(GyroFileError, match=r"Accelerometer.csv:2: too few columns \(2\)"):
        kr.io.read_imu(folder)


def test_sensors_on_the_gyro_clock_are_taken_as_they_are(tmp_path):
    t = np.array([0.0, 0.01, 0.02])
    folder = tmp_path / "export"
    folder.mkdir()
    write(folder / "Gyroscope.csv", phyphox_table(t, np.ones((3, 3)), "Gyroscope", "rad/s"))
    write(folder / "Magnetometer.csv", phyphox_table(t, np.full((3, 3), 40.0), "Magnetic field", "µT"))
    rec = kr.io.read_imu(folder)
    np.testing.assert_array_equal(rec.mag, np.full((3, 3), 40.0))
    assert rec.accel is None and rec.notes == ("magnetometer on the gyroscope's clock (same time stamps)",)


def test_sensors_side_by_side_in_one_table_each_on_its_own_time_column(tmp_path):
    """A phyphox experiment exporting several sensors in one CSV: each buffer with its own "Time (s)", the
    shorter ones ending in empty cells."""
    header = ('"Time (s)","Gyroscope x (rad/s)","Gyroscope y (rad/s)","Gyroscope z (rad/s)",'
              '"Time (s)","Acceleration x (m/s^2)","Acceleration y (m/s^2)","Acceleration z (m/s^2)"')
    t_gyro, t_acc = np.arange(7) * 0.005, 0.002 + np.arange(4) * 0.01
    rows = []
    for k, t in enumerate(t_gyro):
        acc = [f"{t_acc[k]:.9E}", f"{2 * t_acc[k]:.9E}", "0", "9.81"] if k < t_acc.size else [""] * 4
        rows.append(",".join([f"{t:.9E}", "0.1", "0.2", "0.3", *acc]))
    rec = kr.io.read_imu(write(tmp_path / "Sensors.csv", header + "\n" + "\n".join(rows) + "\n"))
    inside = (t_gyro >= t_acc[0]) & (t_gyro <= t_acc[-1])
    np.testing.assert_allclose(rec.t, t_gyro[inside], rtol=1e-15)
    np.testing.assert_allclose(rec.accel[:, 0], 2 * rec.t, rtol=1e-12)
    np.testing.assert_allclose(rec.omega, np.tile([0.1, 0.2, 0.3], (inside.sum(), 1)))
    assert rec.notes[0].startswith("accelerometer (4 samples, 100 Hz) interpolated linearly onto the gyroscope's")
    broken = rows[:2] + [rows[2].rsplit(",", 2)[0] + ",,"] + rows[3:]
    with pytest.raises(GyroFileError, match=r"Broken.csv:4: too few columns \(6\); expected 8"):
        kr.io.read_imu(write(tmp_path / "Broken.csv", header + "\n" + "\n".join(broken) + "\n"))
