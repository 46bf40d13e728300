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

from .._fileio import atomic_output, cf_labelled
from .._optional import require

SUFFIXES = (".nc", ".csv", ".parquet")

_CSV_MARK = "# kreisel-trajectory "
_TABLES = {".csv": "CSV", ".parquet": "Parquet"}
_AXES = ("x", "y", "z")

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
        header = json.loads(frame.attrs["kreisel"])
    else:
        with open(path, encoding="utf-8") as fh:
            first = fh.readline()
            if not first.startswith(_CSV_MARK):
                raise ValueError(f"{path} is not a kreisel trajectory CSV")
            header = json.loads(first[len(_CSV_MARK):])
            frame = pd.read_csv(fh, index_col=0)
        _check_complete(path, frame, header)
    extra = {}
    for name in header.get("extra", ()):
        columns = [f"{name}_{c}" for c in _AXES]
        extra[name] = frame[columns].to_numpy() if columns[0] in frame else frame[name].to_numpy()
    return cls(frame.index.to_numpy(), frame[[f"q{k}" for k in range(4)]].to_numpy(),
               frame[[f"omega_{k + 1}" for k in range(3)]].to_numpy(), header["inertia"],
               meta=header["meta"], **extra)
