"""One table of IMU samples: text or a DataFrame to numbers, then to SI arrays per quantity.

:func:`parse_table` splits the text of a CSV/TSV/whitespace table (``#``
comments, an optional header line, decimal commas with ``;`` or tab) into a
numeric array, remembering each row's line in the file; :func:`quantities`
finds time, gyro, accelerometer and magnetometer columns (header names,
:mod:`.imu_columns`, or the caller's ``columns``) and converts them to SI
units. Every error names the file and, where there is one, the line:
``file:line: what is wrong``.
"""

from __future__ import annotations

import csv
import io
import re
from dataclasses import dataclass
from typing import Optional

import numpy as np

from .imu_columns import UNITS, Column, known_units, layout, parse_column, unit_scale

__all__ = ["Table", "TableError", "parse_table", "frame_table", "quantities", "check_units", "check_columns",
           "where"]

_QUANTITIES = ("time", "gyro", "accel", "mag")
_LABELS = {"time": "time", "gyro": "angular-rate", "increment": "angle-increment", "accel": "acceleration",
           "mag": "magnetic-field"}
_DEFAULT_UNITS = {"time": "s", "gyro": "rad/s", "increment": "rad", "accel": "m/s2", "mag": "ut"}


class TableError(ValueError):
    """A table that cannot be read; the message is ``file:line: what``."""


def where(source, line=None):
    """``source:line`` when the line is known, else ``source``."""
    return f"{source}:{line}" if line is not None else f"{source}"


@dataclass(frozen=True, eq=False)
class Table:
    """Numbers of a table: ``values`` (n, m) with NaN where a row is short, ``lines`` the file line of each
    row (None for a DataFrame), the ``header`` cells (or None) and the header's line."""

    values: np.ndarray
    lines: Optional[list]
    header: Optional[list]
    header_line: Optional[int]
    source: str


def _number(cell):
    try:
        return float(cell)
    except ValueError:
        return None


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


def _header_cells(cells, line, width):
    """Header cells matched to ``width`` data columns: a short header leaves the last columns unnamed; names
    with spaces in a whitespace-separated header ("time (s)  rate x (deg/s)") are regrouped by wide gaps, or
    by gluing units and axis letters to the word before them. None when no grouping fits."""
    if len(cells) != width and not any(delimiter in line for delimiter in "\t;,"):
        wide = [cell for cell in re.split(r"\s{2,}", line) if cell]
        glued = []
        for word in line.split():
            if glued and (word[:1] in "([" or word.lower() in ("x", "y", "z")):
                glued[-1] += " " + word
            else:
                glued.append(word)
        cells = next((grouped for grouped in (wide, glued) if len(grouped) == width), glued)
    return cells + [""] * (width - len(cells)) if len(cells) <= width else None


def _fast_values(data, width):
    """All rows of ``data`` [(line number, text)] at C speed, when one delimiter splits every row into the same
    number of finite numbers; None otherwise (the line-by-line reading then finds and names the problem)."""
    delimiter = next((d for d in ("\t", ";", ",") if d in data[0][1]), None)
    body = "\n".join(line for _, line in data)
    if delimiter in ("\t", ";"):
        body = body.replace(",", ".")  # phyphox's decimal-comma formats
    try:
        values = np.loadtxt(io.StringIO(body), delimiter=delimiter, ndmin=2, comments=None, dtype=np.float64)
    except ValueError:
        return None
    if values.shape[0] != len(data) or values.shape[1] < width or not np.isfinite(values).all():
        return None
    return values


def _column(k, header):
    """``column 2, 'Gyroscope x (rad/s)'``: the position of the ``k``-th cell, and its header name if any."""
    name = header[k] if header is not None and k < len(header) and header[k] else None
    return f"column {k + 1}" + (f", {name!r}" if name else "")


def _slow_values(data, source, empty_cells, width, header=None):
    """Rows of ``data`` read line by line: the first bad cell is named by line and column (``header``
    names the columns). ``empty_cells``: an empty cell is NaN (a sensor's buffer that ended before the
    others' in a table with several time columns)."""
    rows = []
    for number, line in data:
        cells = _cells(line)
        values = [float("nan") if empty_cells and cell == "" else _number(cell) for cell in cells]
        bad = next((k for k, value in enumerate(values) if value is None), None)
        if bad is not None:
            empty = ", an empty cell" if cells[bad] == "" else ""
            raise TableError(f"{source}:{number}: not a number: {cells[bad]!r} ({_column(bad, header)}){empty}; "
                             "expected a number")
        infinite = next((k for k, value in enumerate(values) if not np.isfinite(value) and cells[k] != ""), None)
        if infinite is not None:
            raise TableError(f"{source}:{number}: not a finite number: {cells[infinite]!r} "
                             f"({_column(infinite, header)}); expected a finite number")
        if len(values) < width:
            raise TableError(f"{source}:{number}: too few columns ({len(values)}); expected "
                             f"{'time and ' * (width > 3)}the three components of a sensor")
        rows.append(values)
    table = np.full((len(rows), max(len(row) for row in rows)), np.nan)
    for k, row in enumerate(rows):
        table[k, :len(row)] = row
    return table


def parse_table(text, source, timed=True):
    """Numbers, file lines and header of the table in ``text`` (see the module docstring).

    ``timed``: every row holds a time besides a sensor's three components
    (False for a table whose times are given by its rate).

    Examples
    --------
    >>> table = parse_table("t;wx;wy;wz\\n0,0;1,5;0;0\\n0,5;1,5;0;0\\n", "upload.csv")
    >>> table.header, table.values[1].tolist(), table.lines
    (['t', 'wx', 'wy', 'wz'], [0.5, 1.5, 0.0, 0.0], [2, 3])
    """
    data = [(number, line) for number, line in enumerate(map(str.strip, text.splitlines()), start=1)
            if line and not line.startswith("#")]
    header = header_line = header_text = None
    if data:
        cells = _cells(data[0][1])
        if all(_number(cell) is None for cell in cells):
            (header_line, header_text), header, data = data[0], cells, data[1:]
    if not data:
        raise TableError(f"{source}: empty (no data rows)")
    width = 4 if timed else 3
    table = _fast_values(data, width)
    if table is None:
        clocks = sum(parse_column(cell).quantity == "time" for cell in header or ())
        table = _slow_values(data, source, clocks > 1, width, header)
    width = table.shape[1]
    if header is not None:
        header = _header_cells(header, header_text, width)
        if header is None:
            raise TableError(f"{source}:{header_line}: the header's names do not match the {width} columns; "
                             "separate them by commas or tabs")
    return Table(table, [number for number, _ in data], header, header_line, source)


def frame_table(frame, source="DataFrame"):
    """The :class:`Table` of a pandas DataFrame (column names as the header; rows named by index)."""
    header = [str(name) for name in frame.columns]
    if not len(frame):
        raise TableError(f"{source}: empty (no data rows)")
    values = np.empty((len(frame), len(header)))
    for k, name in enumerate(frame.columns):
        column = frame[name]
        try:
            values[:, k] = column.to_numpy(dtype=np.float64)
        except (TypeError, ValueError):
            bad = next(i for i, v in enumerate(column) if _number(str(v)) is None)
            raise TableError(f"{source}: column {name!r}, row {bad}: not a number: {column.iloc[bad]!r}") from None
    if not np.isfinite(values).all():
        row, k = np.argwhere(~np.isfinite(values))[0]
        raise TableError(f"{source}: column {header[k]!r}, row {row}: not a finite number ({values[row, k]!r})")
    return Table(values, None, header, None, source)


def check_units(units):
    """``units`` (a gyro unit, or a dict by quantity) as a dict ``{quantity: unit}``, checked.

    Examples
    --------
    >>> check_units("deg/s"), check_units({"accel": "g", "mag": "nT"})
    ({'gyro': 'deg/s'}, {'accel': 'g', 'mag': 'nT'})
    """
    if units is None:
        return {}
    if isinstance(units, str):
        units = {"gyro": units}
    if not isinstance(units, dict):
        raise TypeError(f"units must be a str (the gyro's unit) or a dict by quantity, got {type(units).__name__}")
    for quantity, unit in units.items():
        if quantity not in _QUANTITIES:
            raise ValueError(f"units: keys must be among {', '.join(_QUANTITIES)}, got {quantity!r}")
        tables = ("gyro", "increment") if quantity == "gyro" else (quantity,)
        if not isinstance(unit, str) or all(unit_scale(q, unit) is None for q in tables):
            known = ", ".join(known_units(q) for q in tables)
            raise ValueError(f"units[{quantity!r}] must be one of {known}; got {unit!r}")
    return dict(units)


def check_columns(columns):
    """``columns`` checked: None, or a dict with ``"time"`` (a header name) and ``"gyro"``, ``"accel"``,
    ``"mag"`` (three header names each, x, y, z).

    Examples
    --------
    >>> check_columns({"time": "stamp", "gyro": ["p", "q", "r"]})
    {'time': 'stamp', 'gyro': ('p', 'q', 'r')}
    """
    if columns is None:
        return None
    if not isinstance(columns, dict):
        raise TypeError(f"columns must be a dict of header names by quantity, got {type(columns).__name__}")
    checked = {}
    for quantity, names in columns.items():
        if quantity not in _QUANTITIES:
            raise ValueError(f"columns: keys must be among {', '.join(_QUANTITIES)}, got {quantity!r}")
        if quantity == "time":
            if not isinstance(names, str):
                raise ValueError(f"columns['time'] must be one header name, got {names!r}")
            checked[quantity] = names
            continue
        if isinstance(names, str) or len(names := tuple(names)) != 3 or not all(isinstance(n, str) for n in names):
            raise ValueError(f"columns[{quantity!r}] must be three header names (x, y, z), got {names!r}")
        checked[quantity] = names
    return checked


def _selected(table, columns, default):
    """Column indices by quantity: the caller's names, else the header's, else positions."""
    width = table.values.shape[1]
    if columns:
        if table.header is None:
            raise TableError(f"{table.source}: columns= names header cells, but the table has no header")
        found = {}
        for quantity, names in columns.items():
            names = [names] if quantity == "time" else names
            missing = [n for n in names if n not in table.header]
            if missing:
                raise TableError(f"{where(table.source, table.header_line)}: column(s) "
                                 f"{', '.join(map(repr, missing))} not found; the table has {table.header}")
            found[quantity] = [table.header.index(n) for n in names]
        parsed = [parse_column(name) for name in table.header]
        try:
            picked = layout(parsed, table.source, default)
        except ValueError:  # the header's own reading does not matter where the caller names the columns
            picked = {"time": 0, default: [1, 2, 3]}
        found["time"] = found["time"][0] if "time" in found else picked["time"]
        return {**picked, **found}, parsed
    if table.header is None:
        return {"time": 0, default: [1, 2, 3]}, [Column("", None, None, None)] * width
    parsed = [parse_column(name) for name in table.header]
    try:
        return layout(parsed, table.source, default), parsed
    except ValueError as exc:
        raise TableError(f"{where(table.source, table.header_line)}{str(exc)[len(table.source):]}") from None


def _scale(table, parsed, members, quantity, units):
    """SI value of one unit of ``quantity``'s columns, and whether the caller or the header stated the unit."""
    stated = units.get("gyro" if quantity == "increment" else quantity)
    scale = unit_scale(quantity, stated) if stated is not None else None
    header_scale = None
    for k in members:
        unit = parsed[k].unit
        if unit is None:
            continue
        value = unit_scale(quantity, unit)
        if value is None and stated is None:
            raise TableError(f"{where(table.source, table.header_line)}: column {parsed[k].name!r}: unknown "
                             f"{_LABELS[quantity]} unit {unit!r} (known: {known_units(quantity)}); give the unit "
                             "with units=")
        if value is not None and scale is not None and not np.isclose(value, scale, rtol=1e-12, atol=0.0):
            raise TableError(f"{where(table.source, table.header_line)}: column {parsed[k].name!r} is in {unit}, "
                             f"but units gives {stated!r}")
        if value is not None and header_scale is not None and value != header_scale:
            raise TableError(f"{where(table.source, table.header_line)}: the {_LABELS[quantity]} columns are in "
                             "different units")
        header_scale = value if value is not None else header_scale
    if scale is None and stated is not None:
        raise TableError(f"{table.source}: units gives {stated!r}, which is not among the {_LABELS[quantity]} "
                         f"units ({known_units(quantity)})")
    if scale is not None:
        return scale, "units"
    if header_scale is not None:
        return header_scale, "header"
    return UNITS[quantity][_DEFAULT_UNITS[quantity]], "assumed"


def quantities(table, *, default="gyro", units=None, columns=None, kind="rate"):
    """Time (s) and the x, y, z samples of each quantity the table holds, in SI units (µT for the field).

    Parameters
    ----------
    table : Table
    default : {"gyro", "accel", "mag"}
        The quantity of a table whose header names none (a phyphox ``Accelerometer.csv`` read alone).
    units : dict
        From :func:`check_units`: units that override the header's (and the defaults rad/s, m/s², µT, s).
    columns : dict, optional
        Header names by quantity: ``{"time": "t", "gyro": ("gx", "gy", "gz"), ...}``.
    kind : {"rate", "increment"}
        Gyro columns hold rates or angle increments (rad, deg).

    Returns
    -------
    data : dict
        ``"time"`` (n,) and ``"gyro"``/``"accel"``/``"mag"`` (n, 3) as present; a sensor with its own time
        column has its times in ``data["clocks"][quantity]`` and as many samples.
    stated : dict
        ``{quantity: (origin, scale)}``: where the unit came from (``"units"``, ``"header"`` or
        ``"assumed"``) and the SI value of one unit.
    """
    units = units or {}
    found, parsed = _selected(table, columns, default)
    sensors = [q for q in ("gyro", "accel", "mag") if q in found]
    clock = _clocks(found, parsed, columns, sensors)
    time_scale, time_origin = _scale(table, parsed, [found["time"]], "time", units)
    data, stated, main = {}, {"time": (time_origin, time_scale)}, clock[default]
    for time in dict.fromkeys(clock[q] for q in (default, *sensors)):
        on_it = [q for q in sensors if clock[q] == time]
        rows = _complete_rows(table, [time, *(k for q in on_it for k in found[q])], len(set(clock.values())) > 1)
        t = table.values[rows, time] * time_scale
        _increasing(table, t, rows, time)
        for quantity in on_it:
            unit_table = "increment" if quantity == "gyro" and kind == "increment" else quantity
            scale, origin = _scale(table, parsed, found[quantity], unit_table, units)
            stated[quantity] = (origin, scale)
            data[quantity] = table.values[np.ix_(rows, found[quantity])] * scale
            if time != main:
                data.setdefault("clocks", {})[quantity] = t
        if time == main:
            data["time"] = t
    return data, stated


def _clocks(found, parsed, columns, sensors):
    """The time column of each sensor: in a table with several time columns (phyphox exports each sensor's
    buffers side by side), the last one before the sensor's columns."""
    times = [k for k, c in enumerate(parsed) if c.quantity == "time"]
    if len(times) < 2 or (columns and "time" in columns):
        return {q: found["time"] for q in sensors}
    return {q: max([k for k in times if k < min(found[q])], default=found["time"]) for q in sensors}


def _complete_rows(table, members, several_clocks):
    """Indices of the rows holding every column of ``members``; with several clocks in the table a sensor's
    buffer may end before the others (its cells left empty), but no row may hold only part of a sample."""
    present = ~np.isnan(table.values[:, members])
    complete = present.all(axis=1)
    partial = ~complete & (present.any(axis=1) if several_clocks else True)
    if partial.any():
        k = int(np.argmax(partial))
        width = int(np.sum(~np.isnan(table.values[k])))
        raise TableError(f"{where(table.source, table.lines[k] if table.lines else None)}: too few columns "
                         f"({width}); expected {max(members) + 1}")
    rows = np.flatnonzero(complete)
    if not rows.size:
        names = [table.header[k] for k in members] if table.header else members
        raise TableError(f"{table.source}: no row holds all of the columns {names}")
    return rows


def _increasing(table, t, rows, time):
    step = np.diff(t)
    if np.any(step <= 0.0):
        k = rows[int(np.flatnonzero(step <= 0.0)[0]) + 1]
        previous = rows[int(np.flatnonzero(step <= 0.0)[0])]
        raise TableError(f"{where(table.source, table.lines[k] if table.lines else None)}: time not increasing "
                         f"({float(table.values[k, time])!r} after {float(table.values[previous, time])!r})")
