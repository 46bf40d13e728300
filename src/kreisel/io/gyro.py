"""Gyroscope recordings from phones and logging apps (phyphox exports, plain tables).

A phone's gyroscope reports the body angular velocity ω′ in the phone's own
axes (sensor axes): that is exactly what Euler's equations describe, so a
recording of a tossed phone is a free-top experiment (Theory §5).
:func:`read_gyro` turns the files such apps write into arrays; every problem
with a file is reported as one :class:`GyroFileError` naming the file and line.
"""

from __future__ import annotations

import csv
import pathlib
import re
import zipfile
from dataclasses import dataclass
from importlib import resources
from typing import Optional

import numpy as np

__all__ = ["GyroFileError", "GyroRecording", "RECORDINGS", "parse_gyro", "read_gyro", "recording_path"]

# bundled synthetic recordings (package data), so the fit runs offline: name -> file
RECORDINGS = {"phone_toss": "phone_toss.csv"}

# phyphox's "Gyroscope" experiment writes this file; its export folder or zip holds it
GYRO_FILE = "gyroscope.csv"
# rate units a column header may give, in rad/s; milli-units first: "mdps" also matches "dps"
_RATE_UNITS = ((re.compile(r"mdps|mdeg\s*/\s*s|m°/s", re.IGNORECASE), np.pi / 180e3),
               (re.compile(r"deg|°|dps", re.IGNORECASE), np.pi / 180.0),
               (re.compile(r"mrad\s*/\s*s", re.IGNORECASE), 1e-3))
# the time column's unit: the first word in brackets, "(ms)", "[ms since boot]", or a "_ms" suffix;
# phones and loggers stamp samples in ms, µs or ns
_TIME_UNIT = re.compile(r"[(\[]\s*([^()\[\]\s]+)[^()\[\]]*[)\]]|_(ns|us|µs|μs|ms|s)$", re.IGNORECASE)
_SECONDS = {"s": 1.0, "sec": 1.0, "secs": 1.0, "second": 1.0, "seconds": 1.0, "ms": 1e-3, "us": 1e-6,
            "µs": 1e-6, "μs": 1e-6, "ns": 1e-9}


class GyroFileError(ValueError):
    """A recording that cannot be read; the message names the file (and line)."""


@dataclass(frozen=True)
class GyroRecording:
    """Angular velocity measured by a gyroscope, in the sensor's axes.

    Attributes
    ----------
    t : (n,) ndarray
        Sample times in seconds, strictly increasing, as in the file (not shifted).
    omega : (n, 3) ndarray
        Body angular velocity ω′ in the sensor's x, y, z axes, rad/s.
    accel : (n, 3) ndarray or None
        Accelerometer channel (m/s²) when the file has one, else None.
    source : str
        Where the data came from (file, or ``archive.zip:member``).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "spin.txt"
    >>> _ = path.write_text("# t wx wy wz\\n0.0 0 0 1\\n0.01 0 0 1\\n")
    >>> rec = read_gyro(path)
    >>> rec.t.tolist(), rec.omega.shape, rec.accel
    ([0.0, 0.01], (2, 3), None)
    """

    t: np.ndarray
    omega: np.ndarray
    accel: Optional[np.ndarray]
    source: str


def _cells(line):
    """Split one line: tab, then semicolon, then comma, else whitespace separated.

    Tab- and semicolon-separated exports may use a decimal comma (phyphox's
    "decimal comma" formats); inside such cells a comma is the decimal point.
    """
    for delimiter in ("\t", ";", ","):
        if delimiter in line:
            cells = [cell.strip() for cell in next(csv.reader([line], delimiter=delimiter))]
            if delimiter != ",":
                cells = [cell.replace(",", ".") if "." not in cell else cell for cell in cells]
            break
    else:
        cells = [cell.strip("\"'") for cell in line.split()]
    while cells and cells[-1] == "":
        cells.pop()  # a trailing separator is not an empty column
    if any(_number(cell) is None for cell in cells):
        # a whitespace-aligned table with a stray tab: the tab was not the separator
        spaced = line.split()
        if all(_number(cell) is not None for cell in spaced):
            return spaced
    return cells


def _number(cell):
    try:
        return float(cell)
    except ValueError:
        return None


def _to_rad(name):
    """rad/s per unit of a rate column headed ``name`` (radians unless the header says otherwise)."""
    return next((scale for unit, scale in _RATE_UNITS if unit.search(name)), 1.0)


def _time_scale(name):
    """Seconds per unit of a time column headed ``name``; None for a unit that is not a time."""
    match = _TIME_UNIT.search(name.strip())
    if match is None:
        return 1.0
    return _SECONDS.get((match.group(1) or match.group(2)).lower())


def _layout(header, ncols):
    """Column indices of ω, acceleration and the unit conversions, from the header.

    The time scale is None when the time column's header gives a unit that is not a time.
    """
    gyro, accel = [1, 2, 3], None
    to_rad = np.ones(3)
    time_scale = 1.0
    if header is None:
        return gyro, accel, to_rad, time_scale
    names = [name.lower() for name in header]
    if len(names) == ncols:
        found = [i for i, name in enumerate(names) if "gyro" in name]
        if len(found) >= 3:
            gyro = found[:3]
        found = [i for i, name in enumerate(names) if "acc" in name]
        if len(found) >= 3:
            accel = found[:3]
        to_rad = np.array([_to_rad(names[i]) for i in gyro])
        time_scale = _time_scale(names[0])
    else:
        # names with spaces in a whitespace-separated header: only the units can be trusted
        to_rad[:] = _to_rad(" ".join(header))
        unit = header[1] if len(header) > 1 and header[1][:1] in "([" else ""
        time_scale = _time_scale(f"{header[0]} {unit}")
    return gyro, accel, to_rad, time_scale


def parse_gyro(text, source="<text>"):
    """Parse the text of a gyroscope recording (any layout :func:`read_gyro` reads from a file).

    Parameters
    ----------
    text : str
        The file's content.
    source : str
        Name used in error messages and kept as ``.source``.

    Examples
    --------
    >>> rec = parse_gyro("t;wx;wy;wz\\n0,0;1,5;0;0\\n0,5;1,5;0;0\\n", "upload.csv")
    >>> rec.t.tolist(), rec.omega[1].tolist()
    ([0.0, 0.5], [1.5, 0.0, 0.0])
    """
    if not isinstance(text, str):
        raise TypeError(f"text must be a str, got {type(text).__name__}")
    header = header_line = None
    rows, numbers = [], []
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        cells = _cells(line)
        values = [_number(cell) for cell in cells]
        bad = next((cell for cell, value in zip(cells, values) if value is None), None)
        if bad is not None:
            if header is None and not rows and not any(value is not None for value in values):
                header, header_line = cells, number
                continue
            raise GyroFileError(f"{source}, line {number}: not a number: {bad!r}")
        if not all(np.isfinite(values)):
            raise GyroFileError(f"{source}, line {number}: not a finite number in {line!r}")
        if len(values) < 4:
            raise GyroFileError(
                f"{source}, line {number}: too few columns ({len(values)}); expected time and the "
                "three angular-velocity components"
            )
        rows.append(values)
        numbers.append(number)
    if not rows:
        raise GyroFileError(f"{source}: empty (no data rows)")
    ncols = min(len(row) for row in rows)
    gyro, accel, to_rad, time_scale = _layout(header, max(len(row) for row in rows))
    if time_scale is None:
        raise GyroFileError(f"{source}, line {header_line}: the time column's unit in {header[0]!r} is not one "
                            f"of {', '.join(_SECONDS)}")
    needed = max(gyro + (accel or [])) + 1
    if ncols < needed:
        k = next(i for i, row in enumerate(rows) if len(row) < needed)
        raise GyroFileError(f"{source}, line {numbers[k]}: too few columns ({len(rows[k])}); expected {needed}")
    table = np.array([row[:needed] for row in rows])
    t = table[:, 0] * time_scale
    step = np.diff(t)
    if np.any(step <= 0.0):
        k = int(np.flatnonzero(step <= 0.0)[0]) + 1
        raise GyroFileError(
            f"{source}, line {numbers[k]}: time not increasing ({float(table[k, 0])!r} after {float(table[k - 1, 0])!r})"
        )
    omega = table[:, gyro] * to_rad
    acc = None if accel is None else table[:, accel]
    return GyroRecording(t, omega, acc, source)


def _decode(data, source):
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise GyroFileError(f"{source}: not a text file (byte {exc.start} is not UTF-8)") from None


def _from_zip(path):
    try:
        with zipfile.ZipFile(path) as archive:
            members = [name for name in archive.namelist() if name.lower().rsplit("/", 1)[-1] == GYRO_FILE]
            if not members:
                raise GyroFileError(f"{path}: the archive has no Gyroscope.csv")
            member = min(members, key=len)
            data = archive.read(member)
    except zipfile.BadZipFile as exc:
        raise GyroFileError(f"{path}: not a readable zip archive ({exc})") from None
    source = f"{path}:{member}"
    return _decode(data, source), source


def read_gyro(path):
    """Read a gyroscope recording: phyphox export (CSV, folder or zip) or a plain table.

    Formats:

    - phyphox CSV exports, comma, tab or semicolon separated (decimal comma
      accepted with tab and semicolon), with quoted headers such as
      ``"Time (s)","Gyroscope x (rad/s)"`` and numbers like ``5.048000000E-3``;
      a phyphox export folder or ``.zip`` (its ``Gyroscope.csv`` is read);
    - plain numeric tables, whitespace or comma separated, ``#`` comment lines,
      an optional header line: time, ωx, ωy, ωz, further columns ignored.

    Columns headed with ``gyro`` (three of them) are taken as ω wherever they
    stand, columns headed ``acc`` as the accelerometer; columns whose header
    gives degrees (``deg/s``, ``°/s``, ``dps``), millidegrees (``mdps``) or
    milliradians (``mrad/s``) are converted to rad/s, a time header in ``(ms)``,
    ``(us)``, ``(µs)`` or ``(ns)`` (or ending ``_ms``, ``_us``, ``_ns``) to
    seconds; a time header with another unit in brackets is refused.

    Parameters
    ----------
    path : str or os.PathLike
        A file, a phyphox export folder or a zip archive.

    Returns
    -------
    GyroRecording
        ``.t`` (n,) s, ``.omega`` (n, 3) rad/s in the sensor axes, ``.accel`` or None.

    Raises
    ------
    GyroFileError
        The file is empty, has a cell that is not a number, too few columns or
        a time that does not increase; the message names the file and line.
    OSError
        The file cannot be opened.

    Examples
    --------
    A phyphox export (quoted header, exponent notation):

    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "Gyroscope.csv"
    >>> _ = path.write_text('"Time (s)","Gyroscope x (rad/s)","Gyroscope y (rad/s)","Gyroscope z (rad/s)"\\n'
    ...                     '5.048000000E-3,1.0E-1,-2.5E0,3.0E-2\\n7.548000000E-3,1.1E-1,-2.4E0,3.1E-2\\n')
    >>> rec = read_gyro(path)
    >>> rec.t.tolist(), rec.omega[0].tolist()
    ([0.005048, 0.007548], [0.1, -2.5, 0.03])
    """
    path = pathlib.Path(path)
    if path.is_dir():
        matches = sorted(p for p in path.iterdir() if p.name.lower() == GYRO_FILE)
        if not matches:
            raise GyroFileError(f"{path}: the folder has no Gyroscope.csv")
        path = matches[0]
    if path.suffix.lower() == ".zip":
        text, source = _from_zip(path)
    else:
        text, source = _decode(path.read_bytes(), str(path)), str(path)
    return parse_gyro(text, source)


def recording_path(name):
    """Path of a bundled gyroscope recording inside the installed package.

    ``phone_toss`` is a phone (146 × 71 × 8 mm slab) tossed about its middle
    axis, made with kreisel's exact free-top solution in phyphox's CSV format:
    about 400 Hz with jittered sample times, 0.05 rad/s noise and a constant
    bias on each axis, one flip in its 0.65 s of flight.

    Examples
    --------
    >>> rec = read_gyro(recording_path("phone_toss"))
    >>> rec.omega.shape[1], round(float(rec.t[-1] - rec.t[0]), 2)
    (3, 0.65)
    """
    if name not in RECORDINGS:
        raise ValueError(f"name must be one of {', '.join(RECORDINGS)}, got {name!r}")
    return pathlib.Path(str(resources.files("kreisel.io.examples").joinpath(RECORDINGS[name])))
