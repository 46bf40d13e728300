"""IMU logs in, attitude files out.

:func:`read_imu_log` takes a CSV file or a :class:`pandas.DataFrame` with a
time column and three named gyro columns, from a rate-output gyro (rad/s or
deg/s) or an increment-output gyro (rad or deg), validates every value and
returns an :class:`ImuLog` in SI units. :meth:`ImuLog.attitude` integrates it
(:func:`attitude_from_rates` or :func:`attitude_from_increments`) and
:func:`write_attitude` writes quaternions and roll/pitch/yaw (ZYX) in NED or
ENU, atomically.

NED goes with front-right-down (FRD) body axes, ENU with front-left-up (FLU):
the usual aerospace and robotics (ROS REP 103) pairings. Converting an
attitude between them changes both frames,

    q_ENU←FLU = q_ENU←NED ⊗ q_NED←FRD ⊗ q_FRD←FLU,

with q_ENU←NED a half turn about (1, 1, 0)/√2 (x_E = y_N, y_E = x_N, z_U = −z_D)
and q_FRD←FLU a half turn about x.
"""

from __future__ import annotations

import difflib
import os

import numpy as np

from .._fileio import atomic_output
from .._optional import require
from .._validation import as_float_array
from .coning import coning_coefficients
from .strapdown import attitude_from_increments, attitude_from_rates

__all__ = ["ImuLog", "read_imu_log", "write_attitude", "convert_attitude_frame"]

_UNITS = {"rate": {"rad/s": 1.0, "deg/s": np.pi / 180.0},
          "increment": {"rad": 1.0, "deg": np.pi / 180.0}}
_FRAMES = ("NED", "ENU")
_S = np.sqrt(0.5)
# body→nav quaternions of the two pairings relative to each other (module docstring)
_ENU_FROM_NED = np.array([0.0, _S, _S, 0.0])
_FRD_FROM_FLU = np.array([0.0, 1.0, 0.0, 0.0])


class ImuLog:
    """A validated gyro log in SI units.

    Attributes
    ----------
    t : (n,) ndarray
        Strictly increasing time stamps (s).
    gyro : (n, 3) ndarray
        Body rates (rad/s) for ``kind="rate"``, angle increments (rad) for
        ``kind="increment"``; row k's increment covers (t_{k−1}, t_k].
    kind : {"rate", "increment"}
        Sensor output type.
    frame : {"NED", "ENU"}
        Navigation frame the body axes go with (FRD for NED, FLU for ENU).
    source : str
        Where the data came from (file name or ``"DataFrame"``).

    Examples
    --------
    :func:`read_imu_log` checks a table and converts it to SI units:

    >>> import pandas as pd
    >>> df = pd.DataFrame({"t": [0.0, 0.5, 1.0], "gx": [0, 0, 0], "gy": [0, 0, 0], "gz": [10.0, 10.0, 10.0]})
    >>> log = read_imu_log(df, units="deg/s")
    >>> len(log), log.kind, log.frame, log.t.tolist()
    (3, 'rate', 'NED', [0.0, 0.5, 1.0])
    >>> np.degrees(log.gyro[0]).round(12).tolist()
    [0.0, 0.0, 10.0]
    """

    def __init__(self, t, gyro, kind, frame, source):
        self.t = t
        self.gyro = gyro
        self.kind = kind
        self.frame = frame
        self.source = source

    def __len__(self):
        return self.t.size

    def __repr__(self):
        return (f"ImuLog({self.source!r}, n={self.t.size}, kind={self.kind!r}, frame={self.frame!r}, "
                f"t=[{self.t[0]!r}, {self.t[-1]!r}])")

    def attitude(self, q0=(1.0, 0.0, 0.0, 0.0), samples_per_update=None, method=None):
        """Integrate the log into attitude (body → ``self.frame``).

        Rate logs use :func:`attitude_from_rates` (``method``, default
        ``"bortz"``) and return the attitude at every time stamp. Increment
        logs use :func:`attitude_from_increments` with ``samples_per_update``
        = N (default 1); q0 is the attitude at the start of the first
        increment, taken as t_0 − (t_1 − t_0), and the result holds that
        instant followed by the time stamp closing each update.

        Returns
        -------
        t : (m,) ndarray
            Times of the attitudes.
        q : (m, 4) ndarray
            Attitude quaternions, body → navigation frame.

        Examples
        --------
        An increment-output gyro turning 0.01 rad about its down axis per sample;
        100 increments rotate the body by 1 rad in heading (an attitude at the
        start of the first increment, then one per update):

        >>> import pandas as pd
        >>> df = pd.DataFrame({"t": np.arange(1, 101) * 0.01, "gx": 0.0, "gy": 0.0, "gz": 0.01})
        >>> log = read_imu_log(df, kind="increment")
        >>> t, q = log.attitude(samples_per_update=2)
        >>> t.shape, q.shape, round(float(t[0]), 12)
        ((51,), (51, 4), 0.0)
        >>> round(float(2 * np.arctan2(q[-1, 3], q[-1, 0])), 12)
        1.0
        """
        if self.kind == "rate":
            if samples_per_update is not None:
                raise ValueError("samples_per_update applies to increment logs; this log holds rates "
                                 "(coning algorithms need increment-output gyros)")
            return self.t, attitude_from_rates(q0, self.t, self.gyro, method=method or "bortz")
        if method is not None:
            raise ValueError("method applies to rate logs; increment logs use the coning algorithm "
                             "(choose samples_per_update)")
        samples_per_update = 1 if samples_per_update is None else samples_per_update
        coning_coefficients(samples_per_update)  # validates N before the row count is judged
        n = self.t.size
        if n % samples_per_update:
            raise ValueError(f"{self.source}: {n} increment rows are not divisible by samples_per_update="
                             f"{samples_per_update}; trim {n % samples_per_update} row(s) at the end")
        q = attitude_from_increments(q0, self.gyro, samples_per_update)
        start = self.t[0] - (self.t[1] - self.t[0])
        return np.concatenate([[start], self.t[samples_per_update - 1:: samples_per_update]]), q


def _pandas():
    # pandas is slow to import, and only log reading and writing need it
    return require("pandas", extra="io", feature="reading and writing IMU logs")


def _show(value):
    """A log value as the user wrote it: numbers plainly, text quoted."""
    value = value.item() if isinstance(value, np.generic) else value
    return repr(value) if isinstance(value, str) else str(value)


def _where(row, lines):
    """Data row ``row``, with its line in the file when ``lines`` (the file line of each row) is known."""
    return f"row {row}" + (f" (line {lines[row]} of the file)" if lines is not None else "")


def _csv_layout(name):
    """The separator and decimal mark of CSV file ``name``, and the file line of each data row.

    A header with semicolons and no comma is a European export (``;`` between cells, ``,`` as the
    decimal mark); tabs alone make a tab-separated file. pandas skips blank lines, so the data rows'
    lines are counted over the non-blank ones after the header.
    """
    with open(name, encoding="utf-8-sig", errors="replace") as fh:
        filled = [(number, line) for number, line in enumerate(fh, start=1) if line.strip()]
    header = filled[0][1] if filled else ""
    if "," not in header and ";" in header:
        sep, decimal = ";", ","
    elif "," not in header and "\t" in header:
        sep, decimal = "\t", "."
    else:
        sep, decimal = ",", "."
    return sep, decimal, [number for number, _ in filled[1:]]


def _numeric_column(frame, column, lines):
    pd = _pandas()
    raw = frame[column]
    values = pd.to_numeric(raw, errors="coerce").to_numpy(dtype=np.float64)
    bad = ~np.isfinite(values)
    if bad.any():
        i = int(np.argmax(bad))
        if pd.isna(raw.iloc[i]) or isinstance(raw.iloc[i], (float, np.floating)):
            what = f"missing or non-finite value {_show(raw.iloc[i])}"
        else:
            what = f"non-numeric value {_show(raw.iloc[i])}"
        raise ValueError(f"column {column!r}: {what} at {_where(i, lines)}; "
                         f"{int(bad.sum())} bad value(s) in total")
    return values


def read_imu_log(source, time="t", gyro=("gx", "gy", "gz"), kind="rate", units=None, frame="NED",
                 time_scale=1.0):
    """Read a gyro log from a CSV file or a DataFrame and check it.

    Parameters
    ----------
    source : str, os.PathLike or pandas.DataFrame
        CSV file with a header row, or a DataFrame. Cells are separated by commas, by
        semicolons (then with a decimal comma, ``0,5``) or by tabs, as the header shows.
    time : str
        Name of the time column.
    gyro : sequence of 3 str
        Names of the x, y, z gyro columns (body axes).
    kind : {"rate", "increment"}
        Rate-output gyro (angular velocity samples) or increment-output gyro
        (angle accumulated since the previous row).
    units : str, optional
        ``"rad/s"`` or ``"deg/s"`` for rates, ``"rad"`` or ``"deg"`` for
        increments; default radians.
    frame : {"NED", "ENU"}
        Navigation frame of the data: NED with FRD body axes, ENU with FLU.
    time_scale : float
        Seconds per time unit of the log (1e-3 for milliseconds).

    Returns
    -------
    ImuLog

    Raises
    ------
    ValueError
        Missing columns (with the closest existing names), empty, NaN or
        non-numeric values (naming the column and row), time stamps that do
        not strictly increase (naming the row), unknown kind/units/frame.

    Examples
    --------
    >>> import pandas as pd
    >>> df = pd.DataFrame({"t": [0.0, 0.1, 0.2], "gx": [0, 0, 0], "gy": [0, 0, 0], "gz": [90, 90, 90]})
    >>> log = read_imu_log(df, units="deg/s")
    >>> t, q = log.attitude()
    >>> np.round(q[-1], 12)                         # 18 degrees about z
    array([0.98768834, 0.        , 0.        , 0.15643447])
    """
    pd = _pandas()
    if kind not in _UNITS:
        raise ValueError(f"kind must be 'rate' or 'increment', got {kind!r}")
    units = next(iter(_UNITS[kind])) if units is None else units
    if units not in _UNITS[kind]:
        raise ValueError(f"units for kind={kind!r} must be one of {tuple(_UNITS[kind])}, got {units!r}")
    if frame not in _FRAMES:
        raise ValueError(f"frame must be 'NED' or 'ENU', got {frame!r}")
    gyro = tuple(gyro)
    if len(gyro) != 3 or not all(isinstance(g, str) for g in gyro):
        raise ValueError(f"gyro must name three columns (x, y, z), got {gyro!r}")
    scale = as_float_array(time_scale, "time_scale")
    if scale.ndim or scale <= 0:
        raise ValueError(f"time_scale must be a positive scalar, got {time_scale!r}")

    if isinstance(source, pd.DataFrame):
        frame_data, name, lines = source, "DataFrame", None
    elif isinstance(source, (str, os.PathLike)):
        name = os.fspath(source)
        if not os.path.isfile(name):
            raise ValueError(f"source: no such file {name!r}")
        sep, decimal, lines = _csv_layout(name)
        try:
            frame_data = pd.read_csv(name, sep=sep, decimal=decimal, skipinitialspace=True)
        except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
            raise ValueError(f"source: {name!r} is not a readable CSV file ({str(exc).strip()})") from exc
    else:
        raise TypeError(f"source must be a file path or a pandas DataFrame, got {type(source).__name__}")

    columns = [str(c) for c in frame_data.columns]
    missing = [c for c in (time, *gyro) if c not in columns]
    if missing:
        hints = []
        for c in missing:
            close = difflib.get_close_matches(c, columns, n=1, cutoff=0.4)
            hints.append(f"{c!r}" + (f" (did you mean {close[0]!r}?)" if close else ""))
        raise ValueError(f"{name}: column(s) {', '.join(hints)} not found; the log has columns {columns}")
    if len(frame_data) < 2:
        raise ValueError(f"{name}: need at least 2 rows of data, got {len(frame_data)}")

    t = _numeric_column(frame_data, time, lines) * float(scale)
    data = np.column_stack([_numeric_column(frame_data, c, lines) for c in gyro])
    step = np.diff(t)
    if np.any(step <= 0):
        i = int(np.argmax(step <= 0)) + 1
        raise ValueError(f"{name}: time column {time!r} must strictly increase; at {_where(i, lines)} "
                         f"{_show(frame_data[time].iloc[i])} follows {_show(frame_data[time].iloc[i - 1])}")
    return ImuLog(t, data * _UNITS[kind][units], kind, frame, name)


def convert_attitude_frame(q, from_frame, to_frame):
    """Re-express body → navigation attitudes between NED/FRD and ENU/FLU.

    Parameters
    ----------
    q : (..., 4) array_like
        Unit quaternions, body → ``from_frame``.
    from_frame, to_frame : {"NED", "ENU"}

    Returns
    -------
    (..., 4) ndarray

    Examples
    --------
    >>> q = convert_attitude_frame([1, 0, 0, 0], "NED", "ENU")   # level, facing north
    >>> np.round(q, 12) + 0.0          # ±(cos 45°, 0, 0, sin 45°): yaw 90° from east
    array([-0.70710678,  0.        ,  0.        , -0.70710678])
    """
    for label, f in (("from_frame", from_frame), ("to_frame", to_frame)):
        if f not in _FRAMES:
            raise ValueError(f"{label} must be 'NED' or 'ENU', got {f!r}")
    from ..so3 import quat_multiply  # lower layer, imported when used to keep import light

    q = as_float_array(q, "q", tail=(4,))
    if from_frame == to_frame:
        return q.copy()
    # both factors are half turns, so the same products convert back (−A ⊗ q ⊗ −B = A ⊗ q ⊗ B)
    return quat_multiply(quat_multiply(_ENU_FROM_NED, q), _FRD_FROM_FLU)


def write_attitude(path, t, q, frame="NED", input_frame="NED", degrees=True):
    """Write attitude as quaternions and roll/pitch/yaw (ZYX) to a CSV file, atomically.

    Columns: ``t, q0, q1, q2, q3, roll, pitch, yaw`` (scalar-first quaternion
    body → ``frame``; yaw, pitch, roll are the intrinsic ZYX Euler angles of
    :func:`kreisel.quat_to_euler`, in degrees unless ``degrees=False``). The
    file appears complete or not at all (temporary file + ``os.replace``).

    Parameters
    ----------
    path : str or os.PathLike
        Output CSV file; its directory must exist. An existing file is
        replaced (as by pandas' ``to_csv``).
    t : (n,) array_like
        Times (s).
    q : (n, 4) array_like
        Attitude quaternions, body → ``input_frame``.
    frame : {"NED", "ENU"}
        Navigation frame of the output (body axes FRD for NED, FLU for ENU).
    input_frame : {"NED", "ENU"}
        Navigation frame of ``q``.
    degrees : bool
        Angles in degrees (default) or radians.

    Returns
    -------
    pandas.DataFrame
        The table written.

    Examples
    --------
    A heading of 90° (body x pointing east) written in NED; the yaw column holds
    90° and the file reads back with pandas:

    >>> import os, tempfile
    >>> import pandas as pd
    >>> path = os.path.join(tempfile.mkdtemp(), "attitude.csv")
    >>> q = [[1.0, 0.0, 0.0, 0.0], [np.sqrt(0.5), 0.0, 0.0, np.sqrt(0.5)]]
    >>> table = write_attitude(path, [0.0, 1.0], q)
    >>> list(table.columns)
    ['t', 'q0', 'q1', 'q2', 'q3', 'roll_deg', 'pitch_deg', 'yaw_deg']
    >>> pd.read_csv(path)["yaw_deg"].astype(float).round(9).tolist()
    [0.0, 90.0]
    """
    from ..so3 import quat_to_euler  # same layer below; imported when used to keep import light

    t = as_float_array(t, "t")
    if t.ndim != 1:
        raise ValueError(f"t must be one-dimensional, got shape {t.shape}")
    q = as_float_array(q, "q", tail=(t.size, 4))
    if q.ndim != 2:
        raise ValueError(f"q must have shape ({t.size}, 4), got {q.shape}")
    q = convert_attitude_frame(q, input_frame, frame)
    q = q * np.where(q[:, :1] < 0, -1.0, 1.0)
    yaw_pitch_roll = quat_to_euler("ZYX", q, degrees=degrees)
    unit = "deg" if degrees else "rad"
    table = _pandas().DataFrame({"t": t, "q0": q[:, 0], "q1": q[:, 1], "q2": q[:, 2], "q3": q[:, 3],
                          f"roll_{unit}": yaw_pitch_roll[:, 2], f"pitch_{unit}": yaw_pitch_roll[:, 1],
                          f"yaw_{unit}": yaw_pitch_roll[:, 0]})
    with atomic_output(path) as tmp:
        table.to_csv(tmp, index=False, float_format="%.17g")
    return table
