"""Header cells: quantity, axis and unit tokens, and any column order read the same."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import kreisel as kr
from kreisel.io.imu_columns import parse_column, unit_scale

G0 = 9.80665


@pytest.mark.parametrize("name, quantity, axis, unit", [
    ("Gyroscope x (rad/s)", "gyro", 0, "rad/s"), ("gyro_z_radps", "gyro", 2, "radps"),
    ("ωₓ (rad/s)", "gyro", 0, "rad/s"), ("ω_y", "gyro", 1, None), ("gx", "gyro", 0, None), ("wz (dps)", "gyro", 2, "dps"),
    ("rate y [deg/s]", "gyro", 1, "deg/s"),
    ("AccX (g)", "accel", 0, "g"), ("acc_y_g", "accel", 1, "g"), ("Acceleration z (m/s^2)", "accel", 2, "m/s^2"),
    ("Magnetic field x (µT)", "mag", 0, "µT"), ("mag_y_uT", "mag", 1, "ut"), ("MagZ (nT)", "mag", 2, "nT"),
    ("Time (s)", "time", None, "s"), ("timestamp [ms since boot]", "time", None, "ms"), ("t_ns", "time", None, "ns"),
    ("Absolute (rad/s)", None, None, "rad/s"), ("Linear Acceleration x (m/s^2)", None, 0, "m/s^2"),
    ("a", None, None, None), ("x_gyro", "gyro", 0, None)])
def test_header_cells(name, quantity, axis, unit):
    column = parse_column(name)
    assert (column.quantity, column.axis, column.unit) == (quantity, axis, unit)


@pytest.mark.parametrize("quantity, unit, value", [
    ("gyro", "rad/s", 1.0), ("gyro", "radps", 1.0), ("gyro", "dps", np.pi / 180), ("gyro", "mdps", np.pi / 180e3),
    ("gyro", "°/s", np.pi / 180), ("gyro", "rpm", np.pi / 30), ("gyro", "Hz", 2 * np.pi), ("gyro", "rad s^-1", 1.0),
    ("accel", "m/s²", 1.0), ("accel", "g", G0), ("accel", "mg", G0 / 1e3), ("mag", "G", 100.0), ("mag", "mT", 1e3),
    ("mag", "μT", 1.0), ("time", "µs", 1e-6), ("gyro", "dpsx", None), ("gyro", "g", None), ("accel", "rad/s", None)])
def test_unit_tokens(quantity, unit, value):
    assert unit_scale(quantity, unit) == (None if value is None else pytest.approx(value, rel=1e-15))


@settings(max_examples=25, derandomize=True, database=None, deadline=None)
@given(st.permutations(range(10)))
def test_any_column_order_reads_the_same(order):
    """Every order of named columns (time, gyro, accelerometer, magnetometer) gives the same record."""
    names = ["time (ms)", "gyro x (deg/s)", "gyro y (deg/s)", "gyro z (deg/s)", "acc_x_g", "acc_y_g", "acc_z_g",
             "Magnetic field x (nT)", "Magnetic field y (nT)", "Magnetic field z (nT)"]
    values = np.array([[0.0, 1, 2, 3, 4, 5, 6, 7, 8, 9], [10.0, 11, 12, 13, 14, 15, 16, 17, 18, 19]])
    text = ",".join(names[k] for k in order) + "\n" + "\n".join(",".join(str(v) for v in row[list(order)])
                                                                for row in values) + "\n"
    rec = kr.io.parse_gyro(text, "perm.csv")
    np.testing.assert_array_equal(rec.t, values[:, 0] * 1e-3)
    np.testing.assert_allclose(rec.omega, np.radians(values[:, 1:4]), rtol=1e-15)
    np.testing.assert_allclose(rec.accel, values[:, 4:7] * G0, rtol=1e-15)
    np.testing.assert_allclose(rec.mag, values[:, 7:10] * 1e-3, rtol=1e-15)
