"""IMU recordings from phones, logging apps and data sets: one reader, one record.

A phone's gyroscope reports the body angular velocity ω′ in the phone's own
axes (sensor axes): that is exactly what Euler's equations describe, so a
recording of a tossed phone is a free-top experiment (Theory §5); with the
accelerometer and magnetometer it is the input of strapdown navigation
(Theory §3.5). :func:`read_imu` (and :func:`read_gyro`, its contract name)
turns the files such apps write into an :class:`ImuRecording`; every problem
with a file is reported as one :class:`GyroFileError` naming the file and line.
"""

from __future__ import annotations

import dataclasses
import io
import os
import pathlib
import re
import zipfile
import zlib
from importlib import resources

import numpy as np

from .imu_columns import UNITS, parse_column, unit_scale
from .imu_record import ImuRecording
from .imu_table import TableError, check_columns, check_units, frame_table, parse_table, quantities, where
from .phyphox import TABLES, align, member_for

__all__ = ["GyroFileError", "GyroRecording", "ImuRecording", "RECORDINGS", "TRIALS", "MAX_RATE", "parse_gyro",
           "read_gyro", "read_imu", "recording_path"]

# bundled synthetic recordings (package data), so the fit runs offline: name -> file
RECORDINGS = {"phone_toss": "phone_toss.csv"}
#: Bundled real IMU recordings with a motion-capture reference attitude (BROAD's layout): name -> file.
TRIALS = {"broad_07": "broad/broad_07_fast_rotation_60s.npz"}
#: rad/s beyond which a gyro reading is taken for a unit mistake: phone and MEMS gyros saturate near 35 rad/s
#: (2000 °/s)
MAX_RATE = 40.0
# a member of a zip archive is read up to this size, so that a small archive cannot expand to gigabytes
MAX_MEMBER_BYTES = 64 * 2**20
GyroRecording = ImuRecording
_KINDS = ("rate", "increment")
# what too fast a gyro is most likely in, most common first
_LIKELY = ("deg/s", "mdeg/s", "mrad/s")
# what time stamps too far apart are most likely in (loggers' raw clocks), and the sample interval, s, that an IMU
# log read in the right unit has at most (10 Hz)
_LIKELY_CLOCKS = ("ms", "us", "ns")
_SLOWEST_STEP = 0.1
_BROAD_FIELDS = "gyr, acc, mag, opt_quat, movement, sampling_rate"
# how a zip archive (phyphox's export, or an .xlsx/.ods workbook) and an OLE file (an .xls workbook) begin
_ZIP = b"PK\x03\x04"
_OLE = b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1"
# how an accelerometer or magnetometer without a unit is judged: the statistic of |values|, the band a phone reads
# in m/s² (held still 9.8; beyond 40 g no phone accelerometer reaches) or µT (the Earth's 25…65 µT, with the
# offsets of a phone's own magnets), the units most likely meant, and how the message names them
_FIELD_CHECKS = {
    "accel": ("90th percentile", (4.0, 400.0), ("g", "mg"), "a", "m/s²", "a phone held still reads 9.8 m/s²"),
    "mag": ("median", (2.0, 2000.0), ("G", "mT", "nT"), "B", "µT", "the Earth's field is 25…65 µT"),
}
_SI = {"accel": "m/s2", "mag": "uT"}
_NAMES = {"accel": "accelerometer", "mag": "magnetometer"}
# what a table without units is read in, as its note says
_ASSUMED = {"time": "time s", "gyro": "gyro rad/s", "accel": "accelerometer m/s²", "mag": "magnetometer µT"}
# characters no text table holds (tab, line breaks and form feeds aside)
_CONTROL = re.compile(r"[\x00-\x08\x0e-\x1f\x7f]")


class GyroFileError(ValueError):
    """A recording that cannot be read; the message names the file (and line): ``file:line: what``."""


def _decode(data, source):
    """Text of ``data`` and a note when it was not UTF-8: UTF-16 (by its byte-order mark or its zero bytes)
    or Latin-1 (which decodes every byte; a control character then shows a binary file)."""
    note = None
    if data[:2] in (b"\xff\xfe", b"\xfe\xff") or (len(data) > 1 and data.count(0) * 3 > len(data)):
        encoding = "utf-16" if data[:2] in (b"\xff\xfe", b"\xfe\xff") else \
            ("utf-16-le" if data[1::2].count(0) > data[0::2].count(0) else "utf-16-be")
        try:
            text, note = data.decode(encoding), f"decoded as UTF-16 ({source} is not UTF-8)"
        except UnicodeDecodeError as exc:
            raise GyroFileError(f"{source}: not a text file (byte {exc.start} is not UTF-16)") from None
    else:
        try:
            text = data.decode("utf-8-sig")
        except UnicodeDecodeError as exc:
            text, note = data.decode("latin-1"), f"decoded as Latin-1 ({source}: byte {exc.start} is not UTF-8)"
    control = _CONTROL.search(text)
    if control is not None:
        raise GyroFileError(f"{source}: not a text file (control character {control.group()!r} at character "
                            f"{control.start()})")
    return text.lstrip("\ufeff"), note


def _is_workbook(raw):
    """Whether the zip archive ``raw`` is an Office Open XML or OpenDocument workbook (or no readable zip)."""
    try:
        with zipfile.ZipFile(io.BytesIO(raw)) as archive:
            names = archive.namelist()
    except (zipfile.BadZipFile, zipfile.LargeZipFile, NotImplementedError, EOFError):
        return True
    return any(name.startswith("xl/") or name == "content.xml" for name in names)


def _read_member(archive, member, path):
    """The bytes of ``member``, refused beyond MAX_MEMBER_BYTES: by its declared size before inflating it, and
    while inflating, in case the declared size lies."""
    too_big = GyroFileError(f"{path}:{member}: expands beyond {MAX_MEMBER_BYTES // 2**20} MiB; unzip the export "
                            "and read its folder")
    if archive.getinfo(member).file_size > MAX_MEMBER_BYTES:
        raise too_big
    data = bytearray()
    with archive.open(member) as fh:
        while chunk := fh.read(2**20):
            data += chunk
            if len(data) > MAX_MEMBER_BYTES:
                raise too_big
    return bytes(data)


def _tables_in_zip(path):
    """``{quantity: (bytes, source)}`` of the phyphox tables in the zip archive ``path``."""
    try:
        with zipfile.ZipFile(path) as archive:
            names = archive.namelist()
            members = {q: member_for(names, q) for q in TABLES}
            if members["gyro"] is None:
                raise GyroFileError(f"{path}: the archive has no Gyroscope.csv (nor Raw Data.csv)")
            return {q: (_read_member(archive, m, path), f"{path}:{m}") for q, m in members.items() if m}
    except (zipfile.BadZipFile, zipfile.LargeZipFile, NotImplementedError, EOFError) as exc:
        raise GyroFileError(f"{path}: not a readable zip archive ({exc})") from None


def _tables_in_folder(path):
    names = sorted(p.name for p in path.iterdir() if p.is_file())
    members = {q: member_for(names, q) for q in TABLES}
    if members["gyro"] is None:
        raise GyroFileError(f"{path}: the folder has no Gyroscope.csv (nor Raw Data.csv)")
    return {q: ((path / m).read_bytes(), str(path / m)) for q, m in members.items() if m}


def _plausible(data, stated, source, kind):
    """Refuse gyro rates no phone or MEMS gyro measures, naming the unit they look like."""
    origin, scale = stated["gyro"]
    if kind != "rate" or origin == "units" or not data["gyro"].size:
        return
    peak = float(np.max(np.linalg.norm(data["gyro"], axis=1)))
    if peak <= MAX_RATE:
        return
    read_as = "in the header's unit" if origin == "header" else "its numbers taken as rad/s: no unit is given"
    likely = next((u for u in _LIKELY if UNITS["gyro"][u] < scale and peak / scale * UNITS["gyro"][u] <= MAX_RATE),
                  None)
    advice = (f"the numbers look like {likely}: read them with units={likely!r} "
              f"(on the command line: --units {likely})" if likely
              else "give the unit with units= (on the command line: --units)")
    unit = next(u for u, s in UNITS["gyro"].items() if s == scale)
    raise GyroFileError(f"{source}: the gyro's |ω| reaches {peak:.4g} rad/s ({read_as}), beyond the ~35 rad/s "
                        f"(2000 °/s) at which phone and MEMS gyros saturate; {advice}, or units={unit!r} if the "
                        "rates are real")


def _plausible_clock(data, stated, source, kind):
    """Refuse time stamps taken as seconds between which the gyro turns more than half a turn (most likely ms, µs, ns).

    No sampled rotation can be followed across half a turn between two samples, so such a file is a unit mistake
    (an Android log's nanosecond stamps read as seconds made the samples 10⁷ s apart), not data to integrate.
    """
    t, gyro = data["time"], data["gyro"]
    if kind != "rate" or stated.get("time", ("units",))[0] != "assumed" or t.size < 2:
        return
    step = np.diff(t)
    turn = float(np.median(np.linalg.norm(gyro[1:], axis=1) * step))
    if turn <= np.pi:
        return
    median = float(np.median(step))
    likely = next((u for u in _LIKELY_CLOCKS if median * UNITS["time"][u] <= _SLOWEST_STEP), None)
    advice = (f"the times look like {likely}: name the unit in the header ('time ({likely})') or read them with "
              f"units={{'time': {likely!r}}}" if likely else "give the time column's unit in the header or units=")
    raise GyroFileError(f"{source}: the time stamps, taken as seconds (no unit is given), are {median:.4g} s apart, "
                        f"and the gyro turns {turn:.3g} rad between two samples (median), more than half a turn; "
                        f"{advice}, or units={{'time': 's'}} if the samples are that far apart")


def _plausible_field(data, stated, source, quantity):
    """Refuse accelerometer or magnetometer numbers without a unit that no phone reads in m/s² or µT but that
    fit another unit (g, mg; G, mT, nT), naming that unit."""
    origin, _ = stated.get(quantity, ("units", None))
    values = data.get(quantity)
    if origin != "assumed" or values is None or not values.size:
        return
    statistic, band, likely_units, symbol, unit, reading = _FIELD_CHECKS[quantity]
    norm = np.linalg.norm(values, axis=1)
    size = float(np.percentile(norm, 90) if statistic == "90th percentile" else np.median(norm))
    low, high = band
    likely = next((shown for shown in likely_units if low <= size * unit_scale(quantity, shown) <= high), None)
    if low <= size <= high or likely is None:
        return
    axis = {"accel": "ax", "mag": "mx"}[quantity]
    raise GyroFileError(f"{source}: the {_NAMES[quantity]}'s |{symbol}| is {size:.3g} ({statistic}), taken as {unit} "
                        f"(no unit is given): {reading}; the numbers look like {likely}: name the unit in the header "
                        f"('{axis} ({likely})') or read them with units={{{quantity!r}: {likely!r}}}, or "
                        f"units={{{quantity!r}: {_SI[quantity]!r}}} if the values are real")


def _assumed_units(data, stated, kind):
    """The note naming the units the reader assumed for a table that names none, or None."""
    assumed = [q for q in _ASSUMED if stated.get(q, ("",))[0] == "assumed" and (q == "time" or q in data)]
    if not assumed:
        return None
    shown = ", ".join("gyro rad" if q == "gyro" and kind == "increment" else _ASSUMED[q] for q in assumed)
    note = f"units assumed where the file names none: {shown}; name them in the header ('gx (deg/s)') or give units="
    t = data["time"]
    median = float(np.median(np.diff(t))) if t.size > 1 else 0.0
    if "time" in assumed and median > _SLOWEST_STEP:
        # a still sensor does not turn, so the gyro cannot show a clock in ms (_plausible_clock); say it here
        likely = next((u for u in _LIKELY_CLOCKS if median * UNITS["time"][u] <= _SLOWEST_STEP), "ms")
        note += (f"; the samples, {median:.3g} s apart (median), are slower than any IMU log (10 Hz and faster): "
                 f"if the times are {likely}, name the unit ('time ({likely})') or give units={{'time': {likely!r}}}")
    return note


def _record(data, stated, source, kind, notes, assumed=True, **extra):
    _plausible(data, stated, source, kind)
    _plausible_field(data, stated, source, "accel")
    _plausible_field(data, stated, source, "mag")
    note = _assumed_units(data, stated, kind) if assumed else None
    notes = [note, *notes] if note else notes
    _plausible_clock(data, stated, source, kind)
    t, gyro = data["time"], data["gyro"]
    dtheta = None
    if kind == "increment":
        if t.size < 2:
            raise GyroFileError(f"{source}: an increment gyro needs at least 2 samples (for the first interval)")
        dt = np.diff(t, prepend=2 * t[0] - t[1])
        dtheta, gyro = gyro, gyro / dt[:, None]
    return ImuRecording(t, gyro, data.get("accel"), data.get("mag"), source, tuple(notes), dtheta, **extra)


def _on_gyro_clock(data, sensors, source):
    """``data`` with ``sensors`` ``{quantity: (t, values)}`` interpolated onto its times, and notes saying how."""
    try:
        keep, values, notes = align(data["time"], sensors, source)
    except ValueError as exc:
        raise GyroFileError(str(exc)) from None
    return {key: value[keep] for key, value in data.items()} | values, notes


def _on_one_clock(table, units, columns, kind, default="gyro"):
    """Data of ``table`` with every sensor on the main clock (the gyro's), and notes saying what was aligned."""
    try:
        data, stated = quantities(table, default=default, units=units, columns=columns, kind=kind)
    except TableError as exc:
        raise GyroFileError(str(exc)) from None
    clocks = data.pop("clocks", {})
    if not clocks:
        return data, stated, []
    data, notes = _on_gyro_clock(data, {q: (clocks[q], data.pop(q)) for q in clocks}, table.source)
    return data, stated, notes


def _table_data(text, source, units, columns, kind, default="gyro", rate=None):
    try:
        table = parse_table(text, source, timed=rate is None)
    except TableError as exc:
        raise GyroFileError(str(exc)) from None
    if rate is not None:
        table = _evenly_timed(table, rate)
    data, stated, notes = _on_one_clock(table, units, columns, kind, default)
    if rate is not None:
        stated["time"] = ("units", 1.0)   # the caller's rate gave the clock
    return data, stated, notes


def _evenly_timed(table, rate):
    """``table`` with a first column of times 0, 1/rate, 2/rate, … (s): its rows are samples at ``rate`` Hz."""
    if table.header is not None and any(parse_column(name).quantity == "time" for name in table.header):
        raise GyroFileError(f"{where(table.source, table.header_line)}: the table has a time column; rate= is "
                            "for a table without one")
    times = np.arange(table.values.shape[0]) / rate
    header = None if table.header is None else ["time (s)", *table.header]
    return dataclasses.replace(table, values=np.column_stack([times, table.values]), header=header)


def _rate(rate):
    if rate is None:
        return None
    try:
        value = float(rate)
    except (TypeError, ValueError):
        raise TypeError(f"rate must be a number (Hz) or None, got {rate!r}") from None
    if not (np.isfinite(value) and value > 0):
        raise ValueError(f"rate must be a finite positive sampling rate in Hz, got {rate!r}")
    return value


def _from_tables(tables, units, columns, kind, folder):
    """One record from the phyphox tables ``{quantity: (bytes, source)}``; other sensors put on the gyro's clock."""
    notes = []
    texts = {}
    for quantity, (raw, source) in tables.items():
        text, note = _decode(raw, source)
        texts[quantity] = (text, source)
        notes += [note] if note else []
    data, stated, aligned = _table_data(*texts["gyro"], units, columns, kind)
    notes += aligned
    sensors = {}
    for quantity in ("accel", "mag"):
        if quantity in texts and quantity not in data:
            other, other_stated, _ = _table_data(*texts[quantity], units, None, "rate", default=quantity)
            stated[quantity] = other_stated[quantity]
            sensors[quantity] = (other["time"], other[quantity])
    if sensors:
        data, aligned = _on_gyro_clock(data, sensors, folder)
        notes += aligned
    return _record(data, stated, texts["gyro"][1] if not sensors else str(folder), kind, notes)


def _field(archive, name, path, width, n=None, finite=True):
    value = archive[name]
    shape = (n if n is not None else value.shape[0], width) if width else (n,)
    if value.shape != shape or value.dtype.kind not in ("f", "i", "u", "b"):
        raise GyroFileError(f"{path}: field {name!r} has shape {value.shape} and dtype {value.dtype}; expected "
                            f"numbers of shape {shape}")
    value = value.astype(bool if name == "movement" else np.float64)
    if finite and not np.isfinite(value).all():
        row = int(np.argwhere(~np.isfinite(value))[0][0])
        raise GyroFileError(f"{path}: field {name!r}, row {row}: not a finite number")
    return value


def _npz_fields(archive, path):
    """Time, sensors and the reference of an open BROAD-layout archive."""
    fields = set(archive.files)
    if "gyr" not in fields or not fields & {"sampling_rate", "t"}:
        raise GyroFileError(f"{path}: fields {sorted(fields)}; expected BROAD's layout ({_BROAD_FIELDS}) with at "
                            "least gyr and sampling_rate")
    gyr = _field(archive, "gyr", path, 3)
    n = gyr.shape[0]
    if not n:
        raise GyroFileError(f"{path}: empty (no samples)")
    if "t" in fields:
        t = _field(archive, "t", path, None, n)
    else:
        rate = archive["sampling_rate"]
        if rate.shape != () or rate.dtype.kind not in "fiu" or not 0 < float(rate) < np.inf:
            raise GyroFileError(f"{path}: field 'sampling_rate' must be one positive number (Hz), got {rate!r}")
        t = np.arange(n) / float(rate)
    data = {"time": t, "gyro": gyr}
    for quantity, name in (("accel", "acc"), ("mag", "mag")):
        if name in fields:
            data[quantity] = _field(archive, name, path, 3, n)
    extra = {key: _field(archive, name, path, width, n, finite=False)
             for key, name, width in (("reference", "opt_quat", 4), ("movement", "movement", None)) if name in fields}
    return data, extra


def _from_npz(path, units, kind):
    """BROAD's layout: ``gyr`` (n, 3), optional ``acc``, ``mag``, ``opt_quat``, ``movement``, and
    ``sampling_rate`` (or a time field ``t``)."""
    with open(path, "rb") as fh:
        try:
            with np.load(fh, allow_pickle=False) as archive:
                data, extra = _npz_fields(archive, path)
        except GyroFileError:
            raise
        except (ValueError, OSError, EOFError, zipfile.BadZipFile, zlib.error) as exc:
            raise GyroFileError(f"{path}: not a readable .npz archive ({exc})") from None
    t = data["time"]
    if np.any(np.diff(t) <= 0):
        raise GyroFileError(f"{path}: field 't', row {int(np.argmax(np.diff(t) <= 0)) + 1}: time not increasing")
    stated = {}
    for quantity in ("time", "gyro", "accel", "mag"):
        if quantity in data:
            unit = units.get(quantity)
            table = "increment" if quantity == "gyro" and kind == "increment" else quantity
            scale = 1.0 if unit is None else unit_scale(table, unit)
            if scale is None:
                raise GyroFileError(f"{path}: units gives {unit!r}, not a unit of {quantity}")
            data[quantity] = data[quantity] * scale
            stated[quantity] = ("units" if unit else "assumed", scale)
    # BROAD's layout fixes the units (rad/s, m/s², µT): nothing is assumed that the format does not say
    return _record(data, stated, str(path), kind, [], assumed=False, **extra)


def parse_gyro(text, source="<text>", *, units=None, columns=None, kind="rate"):
    """Parse the text of one IMU table (any table layout :func:`read_imu` reads from a file).

    Parameters
    ----------
    text : str
        The file's content.
    source : str
        Name used in error messages and kept as ``.source``.
    units, columns, kind
        As for :func:`read_imu`.

    Examples
    --------
    >>> rec = parse_gyro("t;wx;wy;wz\\n0,0;1,5;0;0\\n0,5;1,5;0;0\\n", "upload.csv")
    >>> rec.t.tolist(), rec.omega[1].tolist()
    ([0.0, 0.5], [1.5, 0.0, 0.0])
    """
    if not isinstance(text, str):
        raise TypeError(f"text must be a str, got {type(text).__name__}")
    units, columns, kind = _options(units, columns, kind)
    data, stated, notes = _table_data(text, source, units, columns, kind)
    return _record(data, stated, source, kind, notes)


def _options(units, columns, kind):
    if kind not in _KINDS:
        raise ValueError(f"kind must be 'rate' or 'increment', got {kind!r}")
    return check_units(units), check_columns(columns), kind


def read_imu(source, *, units=None, columns=None, kind="rate", rate=None):
    """Read an IMU recording: gyro, and accelerometer and magnetometer when the file has them.

    Formats:

    - phyphox exports: a ``Gyroscope.csv`` (comma, tab or semicolon separated,
      decimal comma accepted with tab and semicolon, headers such as
      ``"Time (s)","Gyroscope x (rad/s)"``), or an export folder or ``.zip``
      holding ``Gyroscope.csv`` and possibly ``Accelerometer.csv`` and
      ``Magnetometer.csv`` (or the one ``Raw Data.csv`` that phyphox's
      "Gyroscope" experiment exports), each at its own rate: those are
      interpolated linearly onto the gyro's time stamps, gyro samples outside
      their span are dropped, and ``.notes`` says so (a zip archive is recognised by its
      content, whatever its name); spreadsheet workbooks (phyphox's "Excel"
      export, ``.xlsx``, ``.xls``, ``.ods``) are refused: export CSV instead;
    - plain CSV/TSV or whitespace tables, ``#`` comment lines, an optional
      header line; without a header: time, ωx, ωy, ωz, further columns ignored;
    - BROAD's ``.npz`` layout: ``gyr`` (rad/s), ``acc`` (m/s²), ``mag`` (µT),
      ``opt_quat`` (kept as ``.reference``), ``movement``, ``sampling_rate``;
    - a pandas DataFrame (column names as the header).

    Header cells name the quantity (``gyro``, ``ω``, ``gx``, ``acc``, ``ax``,
    ``mag``, ``Magnetic field``…), the axis (``x``/``y``/``z``, which decides
    the order; columns without axes keep the file's order) and the unit, in
    brackets or after the axis (``gyro_x_radps``, ``acc_x_g``). Units are
    matched as whole tokens and converted: rates rad/s, mrad/s, deg/s, °/s,
    dps, mdeg/s, mdps, deg/h, rpm, rev/s, Hz; accelerations m/s², g
    (9.80665 m/s²), mg, cm/s², ft/s²; magnetic fields µT, nT, mT, T, G (gauss),
    mG; time s, ms, µs, ns. A unit not in these lists is refused, naming the
    column.

    Parameters
    ----------
    source : str, os.PathLike or pandas.DataFrame
        A file, a phyphox export folder, a zip archive, an ``.npz`` file or a DataFrame.
    units : str or dict, optional
        The gyro's unit (``"deg/s"``), or units by quantity
        (``{"gyro": "deg/s", "accel": "g", "mag": "nT", "time": "ms"}``); they
        override what the header says only where it says nothing (a header
        that states another unit is an error). Without a unit stated anywhere
        the gyro is read in rad/s, and rates beyond ``MAX_RATE`` (40 rad/s,
        where phone gyros have long saturated) are refused, naming the unit they
        look like; a stated unit is trusted.
    columns : dict, optional
        Header names to use, by quantity: ``{"time": "t", "gyro": ("gx", "gy",
        "gz"), "accel": (...), "mag": (...)}``.
    kind : {"rate", "increment"}
        The gyro gives rates, or angle increments since the previous sample
        (units rad, mrad, deg, mdeg; kept as ``.dtheta``).
    rate : float, optional
        Sampling rate in Hz of a table file without a time column: its rows
        are taken as evenly spaced samples from t = 0 (a header, if any,
        must then name no time column; without a header the first three
        columns are the gyro's).

    Returns
    -------
    ImuRecording
        ``.t`` (n,) s, ``.omega`` (n, 3) rad/s, ``.accel`` m/s² or None,
        ``.mag`` µT or None, in the sensor axes; ``.notes``.

    Raises
    ------
    GyroFileError
        The file is empty, not text, has a cell that is not a number, too few
        columns, an unknown unit, implausible rates or a time that does not
        increase; the message is ``file:line: what``.
    OSError
        The file cannot be opened.

    Examples
    --------
    A table with the axes in another order, the gyro in deg/s and the
    accelerometer in g:

    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "imu.csv"
    >>> _ = path.write_text("time (s),gyro z (deg/s),gyro y (deg/s),gyro x (deg/s),acc x (g),acc y (g),acc z (g)\\n"
    ...                     "0,180,0,90,0,0,1\\n0.01,180,0,90,0,0,1\\n")
    >>> rec = read_imu(path)
    >>> (rec.omega[0] / np.pi).tolist(), rec.accel[0].tolist()
    ([0.5, 0.0, 1.0], [0.0, 0.0, 9.80665])
    """
    units, columns, kind = _options(units, columns, kind)
    rate = _rate(rate)
    if hasattr(source, "columns") and hasattr(source, "to_numpy"):
        if rate is not None:
            raise ValueError("rate= is for a table file without a time column, not a DataFrame (add a time column)")
        try:
            table = frame_table(source)
        except TableError as exc:
            raise GyroFileError(str(exc)) from None
        data, stated, notes = _on_one_clock(table, units, columns, kind)
        return _record(data, stated, "DataFrame", kind, notes)
    if not isinstance(source, (str, os.PathLike)):
        raise TypeError(f"source must be a file path or a pandas DataFrame, got {type(source).__name__}")
    path = pathlib.Path(source)
    if rate is not None and (path.is_dir() or path.suffix.lower() in (".npz", ".zip")):
        raise GyroFileError(f"{path}: rate= is for a table file without a time column; this recording has its own "
                            "clock")
    if path.is_dir():
        return _from_tables(_tables_in_folder(path), units, columns, kind, path)
    suffix = path.suffix.lower()
    if suffix == ".npz":
        return _from_npz(path, units, kind)
    if suffix == ".zip":
        return _from_tables(_tables_in_zip(path), units, columns, kind, path)
    raw = path.read_bytes()
    if raw.startswith(_ZIP) and not _is_workbook(raw):
        if rate is not None:
            raise GyroFileError(f"{path}: rate= is for a table file without a time column; this zip archive holds "
                                "phyphox tables with their own clocks")
        return _from_tables(_tables_in_zip(path), units, columns, kind, path)
    if raw.startswith((_ZIP, _OLE)):
        raise GyroFileError(f"{path}: a spreadsheet workbook, not a text table; export it as CSV "
                            "(phyphox: 'CSV (Comma, decimal point)')")
    text, note = _decode(raw, str(path))
    data, stated, notes = _table_data(text, str(path), units, columns, kind, rate=rate)
    return _record(data, stated, str(path), kind, [note] * bool(note) + notes)


def read_gyro(path, *, units=None, columns=None, kind="rate"):
    """Read a gyroscope (IMU) recording: :func:`read_imu` under its contract name.

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
    return read_imu(path, units=units, columns=columns, kind=kind)


def recording_path(name):
    """Path of a bundled IMU recording inside the installed package.

    ``phone_toss`` is a phone (146 × 71 × 8 mm slab) tossed about its middle
    axis, made with kreisel's exact free-top solution in phyphox's CSV format:
    about 400 Hz with jittered sample times, 0.05 rad/s noise and a constant
    bias on each axis, one flip in its 0.65 s of flight. ``broad_07`` is the
    first 60 s of BROAD's trial 07 (:data:`TRIALS`): gyro, accelerometer and
    magnetometer at 285.7 Hz with the motion-capture attitude, 26.5 s at rest
    and then fast rotation.

    Examples
    --------
    >>> rec = read_gyro(recording_path("phone_toss"))
    >>> rec.omega.shape[1], round(float(rec.t[-1] - rec.t[0]), 2)
    (3, 0.65)
    >>> read_imu(recording_path("broad_07")).reference.shape
    (17142, 4)
    """
    files = {**RECORDINGS, **TRIALS}
    if name not in files:
        raise ValueError(f"name must be one of {', '.join(files)}, got {name!r}")
    return pathlib.Path(str(resources.files("kreisel.io.examples").joinpath(files[name])))
