"""phyphox exports: one CSV table per sensor, each at its own rate, brought onto the gyro's clock.

phyphox writes ``Gyroscope.csv``, ``Accelerometer.csv`` and
``Magnetometer.csv`` (headers such as ``"Time (s)","Gyroscope x (rad/s)"``)
into an export folder or zip. Android and iOS sample each sensor on its own
clock, so the accelerometer and magnetometer are interpolated linearly onto
the gyro's time stamps; gyro samples outside their time span are dropped
rather than extrapolated. The record's ``notes`` say what was done.
"""

from __future__ import annotations

import numpy as np

__all__ = ["TABLES", "RAW", "member_for", "align"]

#: file names (lower case) of the sensor tables in a phyphox export, by quantity
TABLES = {"gyro": "gyroscope.csv", "accel": "accelerometer.csv", "mag": "magnetometer.csv"}
#: file name (lower case) of the one table of a phyphox experiment's export ("Gyroscope" exports ``Raw Data.csv``)
RAW = "raw data.csv"
_NAMES = {"gyro": "gyroscope", "accel": "accelerometer", "mag": "magnetometer"}


def member_for(names, quantity):
    """The shortest of ``names`` (paths in a folder or archive) whose file name is ``quantity``'s table; for
    the gyro, phyphox's ``Raw Data.csv`` when there is no ``Gyroscope.csv``."""
    for table in (TABLES[quantity], *(RAW,) * (quantity == "gyro")):
        found = [name for name in names if name.replace("\\", "/").rsplit("/", 1)[-1].lower() == table]
        if found:
            return min(found, key=len)
    return None


def _rate(t):
    return (t.size - 1) / (t[-1] - t[0]) if t.size > 1 and t[-1] > t[0] else float("nan")


def align(t, sensors, source):
    """Interpolate each sensor onto the gyro times ``t``; keep the gyro samples that all of them span.

    Parameters
    ----------
    t : (n,) ndarray
        Gyro time stamps, s.
    sensors : dict
        ``{"accel" | "mag": (t_k (m,), values (m, 3))}`` on their own clocks.
    source : str
        Name of the export, for errors.

    Returns
    -------
    keep : (n,) bool ndarray
        Gyro samples inside every sensor's time span.
    values : dict
        ``{quantity: (keep.sum(), 3)}`` on the kept gyro times.
    notes : list of str

    Examples
    --------
    An accelerometer at 4 Hz spans three of five gyro samples at 8 Hz:

    >>> t = np.arange(5) / 8
    >>> accel = (np.array([0.125, 0.375]), np.array([[0.0, 0, 9], [2, 0, 9]]))
    >>> keep, values, notes = align(t, {"accel": accel}, "x")
    >>> keep.tolist(), values["accel"][:, 0].tolist()
    ([False, True, True, True, False], [0.0, 1.0, 2.0])
    """
    keep = np.ones(t.size, bool)
    for quantity, (tk, _) in sensors.items():
        keep &= (t >= tk[0]) & (t <= tk[-1])
    if not keep.any():
        spans = ", ".join(f"{_NAMES[q]} {tk[0]:g}…{tk[-1]:g} s" for q, (tk, _) in sensors.items())
        raise ValueError(f"{source}: the gyroscope ({t[0]:g}…{t[-1]:g} s) and the other sensors ({spans}) "
                         "do not overlap in time")
    kept = t[keep]
    values, notes = {}, []
    for quantity, (tk, v) in sensors.items():
        if tk.size == t.size and np.array_equal(tk, t):
            values[quantity] = v[keep]
            notes.append(f"{_NAMES[quantity]} on the gyroscope's clock (same time stamps)")
            continue
        values[quantity] = np.column_stack([np.interp(kept, tk, v[:, k]) for k in range(3)])
        notes.append(f"{_NAMES[quantity]} ({tk.size} samples, {_rate(tk):.4g} Hz) interpolated linearly onto the "
                     f"gyroscope's clock ({t.size} samples, {_rate(t):.4g} Hz)")
    dropped = int(t.size - keep.sum())
    if dropped:
        notes.append(f"{dropped} gyroscope sample(s) outside the other sensors' time span dropped "
                     f"(kept t = {kept[0]:g} … {kept[-1]:g} s)")
    return keep, values, notes
