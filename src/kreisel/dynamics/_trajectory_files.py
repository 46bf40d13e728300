"""The trajectory file formats, in one place: NetCDF (``.nc``), CSV (``.csv``) and Parquet (``.parquet``).

:meth:`Trajectory.save` and :meth:`Trajectory.load` are the one writer and
reader; :mod:`kreisel.io` (``save_result``, ``load_trajectory``) calls them.
NetCDF (xarray's scipy engine) holds batches, with CF ``units`` and
``long_name`` on the variables. CSV and Parquet hold one body as the table of
:meth:`Trajectory.to_pandas` (numbers with 17 significant digits in CSV), with
the inertia tensor, ``meta``, the names of the extra arrays and the number of
samples in a JSON header: the sidecar file ``NAME.csv.json`` beside a CSV
(which stays plain CSV, for ``pandas.read_csv`` and ``numpy.genfromtxt``), the
frame's ``kreisel`` attribute in Parquet. CSV files of the earlier layout, the
header in a leading ``# kreisel-trajectory`` comment line, still load, as do
files written before the header named the extra arrays or counted the samples.

Every file carries the SHA-256 of its data (times, attitudes, rates, inertia,
extra arrays and ``meta``, as the loaded trajectory holds them), checked on
load: a damaged byte that still parses is refused, not read as other numbers
(files without a checksum, written before it, load unchecked). Files are
written atomically (a CSV first, then its sidecar; a pair interrupted between
the two fails the checksum); a CSV file that lost rows or ends within one (an
interrupted copy) is refused, not read with the missing values as NaN. Every
file that cannot be read raises one :class:`TrajectoryFileError` naming the
file and what is wrong with it.
"""

from __future__ import annotations

import hashlib
import json
import os
import pathlib
import warnings
from typing import Any, TypeVar

import numpy as np

from .._fileio import atomic_output, cf_labelled
from .._optional import MissingExtraError, require
from .._validation import check_inertia_tensor, check_principal_moments

SUFFIXES = (".nc", ".csv", ".parquet")

_CSV_MARK = "# kreisel-trajectory "
_TABLES = {".csv": "CSV", ".parquet": "Parquet"}
_AXES = ("x", "y", "z")
# a file kreisel writes holds unit quaternions to 17 digits; a larger departure is an edit, not round-off
UNIT_TOLERANCE = 1e-9

# the Trajectory class itself (this module sits below it: naming it here would be an import cycle)
_T = TypeVar("_T")


class TrajectoryFileError(ValueError):
    """A trajectory file that cannot be read: the message names the file and what is wrong with it."""


def sidecar(path: str | os.PathLike[str]) -> pathlib.Path:
    """The JSON file beside a trajectory CSV that holds its inertia, metadata and checksum.

    Examples
    --------
    >>> sidecar("runs/top.csv").as_posix()
    'runs/top.csv.json'
    """
    path = pathlib.Path(path)
    return path.with_name(path.name + ".json")


def checksum(trajectory: Any) -> str:
    """SHA-256 (hex) of what a trajectory file restores: times, q, ω′, inertia, extra arrays and ``meta``.

    Numbers are hashed as float64 with one NaN and one zero (a text format keeps neither NaN payloads nor,
    for integer columns, the sign of zero); ``meta`` as the JSON that files store it in.
    """
    digest = hashlib.sha256()
    arrays = [("t", trajectory.t), ("q", trajectory.q), ("omega", trajectory.omega), ("inertia", trajectory.inertia)]
    for name, value in arrays + [(name, getattr(trajectory, name)) for name in trajectory._extra]:
        value = np.asarray(value)
        digest.update(f"{name}{value.shape}".encode())
        if value.dtype.kind in "biuf":
            numbers = np.ascontiguousarray(value, dtype="<f8")
            digest.update((np.where(np.isnan(numbers), np.nan, numbers) + 0.0).tobytes())
        else:
            digest.update(repr(value.tolist()).encode())
    meta = json.loads(json.dumps(trajectory.meta, default=str))
    digest.update(json.dumps(meta, sort_keys=True, default=str).encode())
    return digest.hexdigest()


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
    digest = checksum(trajectory)
    header = {"inertia": trajectory.inertia.tolist(), "meta": trajectory.meta, "extra": list(trajectory._extra),
              "samples": len(trajectory), "sha256": digest}
    if suffix == ".csv":
        header = {"kreisel": "trajectory", "csv": path.name, **header}
        # the CSV is replaced first, its sidecar last: a pair cut between the two fails the checksum
        with atomic_output(sidecar(path)) as side, atomic_output(path) as tmp:
            trajectory.to_pandas().to_csv(tmp, float_format="%.17g", encoding="utf-8")
            side.write_text(json.dumps(header, default=str) + "\n", encoding="utf-8")
        return
    with atomic_output(path) as tmp:
        if suffix == ".nc":
            dataset = cf_labelled(trajectory.to_xarray())
            dataset.attrs["sha256"] = digest
            dataset.to_netcdf(tmp, engine="scipy")
        else:
            frame = trajectory.to_pandas()
            frame.attrs["kreisel"] = json.dumps(header, default=str)
            frame.to_parquet(tmp)


def _check_complete(path: pathlib.Path, frame: Any, header: dict[str, Any]) -> None:
    """Refuse a CSV file cut short: pandas reads the missing fields of a partial last row as NaN."""
    with open(path, "rb") as fh:
        fh.seek(-1, os.SEEK_END)
        if fh.read(1) != b"\n":
            raise TrajectoryFileError(f"{path}: ends within a row (a truncated file?)")
    samples = header.get("samples", len(frame))
    if len(frame) != samples:
        raise TrajectoryFileError(f"{path}: holds {len(frame)} of the {samples} rows it was written with "
                                  "(a truncated file?)")


_WHAT = {".nc": "NetCDF", ".csv": "CSV", ".parquet": "Parquet"}


def load(cls: type[_T], path: str | os.PathLike[str]) -> _T:
    """The trajectory (an instance of ``cls``) in the file ``path``; TrajectoryFileError if it cannot be read."""
    path, suffix = _suffix(path)
    try:
        if suffix == ".nc":
            xr = require("xarray", extra="io", feature="Trajectory.load")
            with xr.open_dataset(path, engine="scipy") as ds:
                ds = ds.load()
            trajectory, digest = cls.from_xarray(ds), ds.attrs.get("sha256")
        else:
            trajectory, digest = _load_table(cls, path, suffix)
    except (TrajectoryFileError, MissingExtraError):
        raise
    except UnicodeDecodeError:
        raise TrajectoryFileError(f"{path}: not UTF-8 text (byte {_first_bad_byte(path)}); a trajectory CSV is "
                                  "UTF-8, as kreisel writes it") from None
    except Exception as exc:  # noqa: BLE001 - a damaged file fails inside the backends in many ways
        if isinstance(exc, OSError) and exc.errno is not None:  # the system's refusal, not the backend's
            raise TrajectoryFileError(f"{path}: cannot read the file ({exc.strerror})") from None
        reason = (str(exc).strip().splitlines() or [""])[0][:200]
        raise TrajectoryFileError(f"{path}: not a readable {_WHAT[suffix]} trajectory file, damaged or cut short? "
                                  f"({type(exc).__name__}: {reason})") from None
    if digest is not None and digest != checksum(trajectory):
        where = f" in {sidecar(path).name}" if suffix == ".csv" else ""
        raise TrajectoryFileError(f"{path}: the data do not match the SHA-256 checksum{where} written with them: the "
                                  "file was damaged or changed after kreisel wrote it")
    return trajectory


def _first_bad_byte(path):
    try:
        path.read_bytes().decode("utf-8")
    except UnicodeDecodeError as exc:
        return exc.start
    return "?"


def _load_table(cls, path, suffix):
    """The trajectory of a CSV or Parquet file and its checksum (None in files written before checksums)."""
    pd = require("pandas", extra="io", feature="Trajectory.load")
    if suffix == ".parquet":
        frame = pd.read_parquet(path)
        header_file = path
        header = _header(path, frame.attrs.get("kreisel", ""))
        first_line = None
    else:
        with open(path, "rb") as fh:
            start = fh.read(len(_CSV_MARK))
        if start[:2] in (b"\xff\xfe", b"\xfe\xff"):
            raise TrajectoryFileError(f"{path}: UTF-16 text (saved again by another program?); a trajectory CSV "
                                      "is UTF-8, as kreisel writes it")
        if start == _CSV_MARK.encode():
            header_file = path
            with open(path, encoding="utf-8") as fh:
                header = _header(path, fh.readline()[len(_CSV_MARK):])
                frame = _read_csv(pd, path, fh)
            first_line = 3  # after the JSON header and the column names
        else:
            side = header_file = sidecar(path)
            frame = _read_csv(pd, path, path)
            first_line = 2  # after the column names
            if side.is_file():
                try:
                    text = side.read_text(encoding="utf-8")
                except UnicodeDecodeError as exc:
                    raise TrajectoryFileError(f"{side}: not UTF-8 text (byte {exc.start}); was the sidecar "
                                              "edited?") from None
                header = _header(side, text)
            else:
                header = _without_sidecar(path, side, _Table(path, frame, first_line))
        _check_complete(path, frame, header)
    if len(frame) == 0:
        raise TrajectoryFileError(f"{path}: holds no samples (cut after its column names?)")
    table = _Table(path, frame, first_line)
    q, omega = table.numbers([f"q{k}" for k in range(4)]), table.numbers([f"omega_{k + 1}" for k in range(3)])
    table.check_unit(q, "q0..q3")
    extra = {}
    for name in header.get("extra", ()):
        columns = [f"{name}_{c}" for c in _AXES]
        extra[name] = table.numbers(columns) if columns[0] in frame else table.numbers([name])[:, 0]
    trajectory = cls(table.times(), q, omega, _inertia(header_file, header), meta=header["meta"], **extra)
    return trajectory, header.get("sha256")


def _without_sidecar(path, side, table):
    """The header of a CSV whose sidecar is missing (the viewer's download), the inertia recovered from its columns.

    J′ = I ω′ at every sample (Theory §4.4), with J′ = Rᵀ J from the ``J_x..z`` and ``q0..q3`` columns: a least-squares
    fit of the symmetric I, accepted only when ω′ spans all three body axes and every sample agrees to 1e-9.
    """
    missing = (f"{path}: its sidecar file {side.name} (inertia and metadata, written with the CSV) is missing: keep "
               "the two together, or save as .nc or .parquet, which hold both in one file")
    needed = [f"q{k}" for k in range(4)] + [f"omega_{k + 1}" for k in range(3)] + [f"J_{c}" for c in _AXES]
    if len(table.frame) == 0 or not set(needed) <= set(table.frame.columns):
        raise TrajectoryFileError(missing)
    q, omega, momentum = (table.numbers(needed[:4]), table.numbers(needed[4:7]), table.numbers(needed[7:]))
    finite = np.isfinite(np.hstack([q, omega, momentum])).all(axis=1)
    q, omega, momentum = q[finite], omega[finite], momentum[finite]
    from ..so3 import quat_apply

    body = quat_apply(q / np.linalg.norm(q, axis=-1, keepdims=True), momentum, inverse=True) if len(q) else q[:, :3]
    spread = np.linalg.svd(omega, compute_uv=False) if len(omega) >= 3 else np.zeros(1)
    if spread.size < 3 or not spread[-1] > 1e-6 * spread[0]:
        raise TrajectoryFileError(missing + "; the inertia cannot be recovered from the columns either, since "
                                  "ω′ does not turn through all three body axes")
    tensor = np.linalg.lstsq(omega, body, rcond=None)[0]
    tensor = 0.5 * (tensor + tensor.T)
    misfit = float(np.max(np.abs(omega @ tensor - body)) / np.max(np.abs(body)))
    if not misfit <= 1e-9:
        raise TrajectoryFileError(missing + f"; the J and ω′ columns do not fit one inertia tensor (misfit "
                                  f"{misfit:.1e}), so it cannot be recovered from them")
    note = (f"{path.name} without its sidecar {side.name}: inertia recovered from the J and ω′ columns (misfit "
            f"{misfit:.1e}); method, torque and extra arrays unknown")
    warnings.warn(note, stacklevel=5)  # at the caller of Trajectory.load
    return {"inertia": tensor.tolist(), "meta": {"note": note, "torque": "unknown"}}


def _read_csv(pd, path, source):
    """The table of a trajectory CSV (``source``: its path, or the open file after the old layout's header line)."""
    try:
        return pd.read_csv(source, index_col=0, encoding="utf-8")
    except pd.errors.EmptyDataError:
        raise TrajectoryFileError(f"{path}: holds no table (cut before its column names?)") from None
    except pd.errors.ParserError as exc:
        reason = (str(exc).strip().splitlines() or [""])[0]
        raise TrajectoryFileError(f"{path}: not a readable CSV table ({reason})") from None


def _header(path, text):
    """The JSON header of a table file, or TrajectoryFileError naming the file."""
    try:
        header = json.loads(text)
    except ValueError as exc:
        raise TrajectoryFileError(f"{path}: the kreisel header is not valid JSON ({exc}); was the file "
                                  "edited?") from None
    if not isinstance(header, dict) or not {"inertia", "meta"} <= header.keys():
        raise TrajectoryFileError(f"{path}: the kreisel header lacks 'inertia' or 'meta'; was the file edited?")
    if not isinstance(header["meta"], dict) or not isinstance(header.get("extra", []), list):
        raise TrajectoryFileError(f"{path}: the kreisel header's 'meta' or 'extra' is not what kreisel writes; "
                                  "was the file edited?")
    return header


def _inertia(path, header):
    """The header's inertia tensor: symmetric and positive definite (textbook bodies outside the triangle
    inequalities, simulated with ``allow_unphysical``, load too)."""
    try:
        tensor = check_inertia_tensor(header["inertia"], "inertia")
        check_principal_moments(np.linalg.eigvalsh(tensor), "inertia", allow_unphysical=True)
    except (TypeError, ValueError) as exc:
        raise TrajectoryFileError(f"{path}: header: {exc}") from None
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
            raise TrajectoryFileError(f"{self.path}: column {name!r}, {self.where(int(bad[0]))}: not a number: "
                             f"{values.iloc[int(bad[0])]!r}")
        return np.asarray(numbers, dtype=float)

    def numbers(self, names):
        missing = [name for name in names if name not in self.frame.columns]
        if missing:
            raise TrajectoryFileError(f"{self.path}: column(s) {', '.join(missing)} not found; the file has columns "
                             f"{[str(c) for c in self.frame.columns][:16]} (saved again with another separator?)")
        return np.column_stack([self._column(name, self.frame[name]) for name in names])

    def times(self):
        import pandas as pd

        # in the order written: an exact solution may be sampled at times in any order
        return self._column("t", pd.Series(self.frame.index))

    def check_unit(self, q, name):
        with np.errstate(over="ignore"):  # a damaged value of 1e300 has an infinite norm: refused below
            norm = np.linalg.norm(q, axis=-1)
        bad = np.flatnonzero(np.abs(norm - 1.0) > UNIT_TOLERANCE)
        if bad.size:
            k = int(bad[0])
            raise TrajectoryFileError(f"{self.path}: columns {name}, {self.where(k)}: quaternion of length {float(norm[k])!r}, not a "
                             f"unit quaternion (to within {UNIT_TOLERANCE:g})")
