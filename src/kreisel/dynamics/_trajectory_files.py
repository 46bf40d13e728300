"""The trajectory file formats, in one place: NetCDF (``.nc``), CSV (``.csv``) and Parquet (``.parquet``).

:meth:`Trajectory.save` and :meth:`Trajectory.load` are the one writer and
reader; :mod:`kreisel.io` (``save_result``, ``load_trajectory``) calls them.
NetCDF (xarray's scipy engine) holds batches, with CF ``units`` and
``long_name`` on the variables. CSV and Parquet hold one body as the table of
:meth:`Trajectory.to_pandas` (numbers with 17 significant digits in CSV), with
the inertia tensor, ``meta``, the names of the extra arrays and the number of
samples in a JSON header: a leading ``# kreisel-trajectory`` comment line in
CSV, the frame's ``kreisel`` attribute in Parquet (files written before the
header named the extra arrays or counted the samples still load). Files are
written atomically; a CSV file that lost rows or ends within one (an
interrupted copy) is refused, not read with the missing values as NaN.
"""

from __future__ import annotations

import json
import os
import pathlib
from typing import Any, TypeVar

import numpy as np

from .._fileio import atomic_output, cf_labelled
from .._optional import require
from .._validation import check_inertia_tensor, check_principal_moments

SUFFIXES = (".nc", ".csv", ".parquet")

_CSV_MARK = "# kreisel-trajectory "
_TABLES = {".csv": "CSV", ".parquet": "Parquet"}
_AXES = ("x", "y", "z")
# a file kreisel writes holds unit quaternions to 17 digits; a larger departure is an edit, not round-off
UNIT_TOLERANCE = 1e-9

# the Trajectory class itself (this module sits below it: naming it here would be an import cycle)
_T = TypeVar("_T")


def _suffix(path):
    path = pathlib.Path(path)
    if path.suffix not in SUFFIXES:
        raise ValueError(f"path must end in one of {', '.join(SUFFIXES)}, got {str(path)!r}")
    return path, path.suffix


def save(trajectory: Any, path: str | os.PathLike[str]) -> None:
    """Write ``trajectory`` to ``path`` in the format its suffix names."""
    path, suffix = _suffix(path)
    if suffix in _TABLES and trajectory.batch_shape:
        raise ValueError(f"{_TABLES[suffix]} holds one body; save a batched trajectory as .nc")
    header = json.dumps({"inertia": trajectory.inertia.tolist(), "meta": trajectory.meta,
                         "extra": list(trajectory._extra), "samples": len(trajectory)}, default=str)
    with atomic_output(path) as tmp:
        if suffix == ".nc":
            cf_labelled(trajectory.to_xarray()).to_netcdf(tmp, engine="scipy")
        elif suffix == ".csv":
            with open(tmp, "w", encoding="utf-8", newline="") as fh:
                fh.write(_CSV_MARK + header + "\n")
                trajectory.to_pandas().to_csv(fh, float_format="%.17g")
        else:
            frame = trajectory.to_pandas()
            frame.attrs["kreisel"] = header
            frame.to_parquet(tmp)


def _check_complete(path: pathlib.Path, frame: Any, header: dict[str, Any]) -> None:
    """Refuse a CSV file cut short: pandas reads the missing fields of a partial last row as NaN."""
    with open(path, "rb") as fh:
        fh.seek(-1, os.SEEK_END)
        if fh.read(1) != b"\n":
            raise ValueError(f"{path} ends within a row (a truncated file?)")
    samples = header.get("samples", len(frame))
    if len(frame) != samples:
        raise ValueError(f"{path} holds {len(frame)} of the {samples} rows it was written with (a truncated file?)")


def load(cls: type[_T], path: str | os.PathLike[str]) -> _T:
    """The trajectory (an instance of ``cls``) in the file ``path``."""
    path, suffix = _suffix(path)
    if suffix == ".nc":
        xr = require("xarray", extra="io", feature="Trajectory.load")
        with xr.open_dataset(path, engine="scipy") as ds:
            return cls.from_xarray(ds.load())
    pd = require("pandas", extra="io", feature="Trajectory.load")
    if suffix == ".parquet":
        frame = pd.read_parquet(path)
        header = _header(path, frame.attrs.get("kreisel", ""))
        first_line = None
    else:
        with open(path, encoding="utf-8") as fh:
            first = fh.readline()
            if not first.startswith(_CSV_MARK):
                raise ValueError(f"{path} is not a kreisel trajectory CSV")
            header = _header(path, first[len(_CSV_MARK):])
            frame = pd.read_csv(fh, index_col=0)
        _check_complete(path, frame, header)
        first_line = 3  # after the JSON header and the column names
    table = _Table(path, frame, first_line)
    q, omega = table.numbers([f"q{k}" for k in range(4)]), table.numbers([f"omega_{k + 1}" for k in range(3)])
    table.check_unit(q, "q0..q3")
    extra = {}
    for name in header.get("extra", ()):
        columns = [f"{name}_{c}" for c in _AXES]
        extra[name] = table.numbers(columns) if columns[0] in frame else table.numbers([name])[:, 0]
    return cls(table.times(), q, omega, _inertia(path, header), meta=header["meta"], **extra)


def _header(path, text):
    """The JSON header of a table file, or ValueError naming the file."""
    try:
        header = json.loads(text)
    except ValueError as exc:
        raise ValueError(f"{path}: the kreisel header is not valid JSON ({exc}); was the file edited?") from None
    if not isinstance(header, dict) or not {"inertia", "meta"} <= header.keys():
        raise ValueError(f"{path}: the kreisel header lacks 'inertia' or 'meta'; was the file edited?")
    return header


def _inertia(path, header):
    """The header's inertia tensor: symmetric and positive definite (textbook bodies outside the triangle
    inequalities, simulated with ``allow_unphysical``, load too)."""
    try:
        tensor = check_inertia_tensor(header["inertia"], "inertia")
        check_principal_moments(np.linalg.eigvalsh(tensor), "inertia", allow_unphysical=True)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{path}: header: {exc}") from None
    return tensor


class _Table:
    """The columns of a trajectory table, refused by file, column and line (or row) when not numbers.

    An empty cell is read as NaN (what the Trajectory constructor takes); text in a number column and a
    quaternion that is not of unit length (a hand-edited file) are refused.
    """

    def __init__(self, path, frame, first_line):
        self.path, self.frame, self.first_line = path, frame, first_line

    def where(self, row):
        return f"line {row + self.first_line}" if self.first_line is not None else f"row {row}"

    def _column(self, name, values):
        pd = require("pandas", extra="io", feature="Trajectory.load")
        numbers = pd.to_numeric(values, errors="coerce")
        bad = np.flatnonzero(pd.isna(numbers) & ~pd.isna(values))
        if bad.size:
            raise ValueError(f"{self.path}: column {name!r}, {self.where(int(bad[0]))}: not a number: "
                             f"{values.iloc[int(bad[0])]!r}")
        return np.asarray(numbers, dtype=float)

    def numbers(self, names):
        missing = [name for name in names if name not in self.frame.columns]
        if missing:
            raise ValueError(f"{self.path}: column(s) {', '.join(missing)} not found; the file has columns "
                             f"{[str(c) for c in self.frame.columns][:16]} (saved again with another separator?)")
        return np.column_stack([self._column(name, self.frame[name]) for name in names])

    def times(self):
        import pandas as pd

        # in the order written: an exact solution may be sampled at times in any order
        return self._column("t", pd.Series(self.frame.index))

    def check_unit(self, q, name):
        norm = np.linalg.norm(q, axis=-1)
        bad = np.flatnonzero(np.abs(norm - 1.0) > UNIT_TOLERANCE)
        if bad.size:
            k = int(bad[0])
            raise ValueError(f"{self.path}: columns {name}, {self.where(k)}: quaternion of length {float(norm[k])!r}, not a "
                             f"unit quaternion (to within {UNIT_TOLERANCE:g})")
