"""Result files: trajectories and datasets as NetCDF, CSV or Parquet, written atomically."""

from __future__ import annotations

import json
import pathlib

from .._fileio import atomic_output, cf_labelled
from .._optional import require, require_all
from ..dynamics import _trajectory_files
from ..dynamics.trajectory import Trajectory

__all__ = ["ResultError", "save_result", "load_result", "load_trajectory", "SUFFIXES"]

#: The formats of :meth:`Trajectory.save`, which writes and reads every trajectory file.
SUFFIXES = _trajectory_files.SUFFIXES


class ResultError(ValueError):
    """A result file that cannot be read back (one-line message for the CLI)."""


def save_result(result, path):
    """Write a Trajectory or an ``xarray.Dataset`` to ``path`` (format from the suffix).

    NetCDF keeps everything; CSV and Parquet hold one body, with the
    trajectory's inertia and metadata beside the data (the CSV's sidecar
    ``NAME.csv.json``, Parquet key-value metadata) so :func:`load_trajectory` restores it. The file is
    written atomically; an existing one is replaced (``kreisel simulate -o``
    refuses one unless given ``--force``).

    Examples
    --------
    The bundled tennis-racket run written to CSV in a temporary directory and
    read back: attitude samples, inertia and metadata survive the round trip:

    >>> import os, tempfile
    >>> import numpy as np
    >>> from kreisel.io import example_path, load_scenario, run_scenario
    >>> traj = run_scenario(load_scenario(example_path("tennis_racket")))
    >>> path = save_result(traj, os.path.join(tempfile.mkdtemp(), "racket.csv"))
    >>> back = load_trajectory(path)
    >>> path.name, bool(np.allclose(back.q, traj.q, rtol=0, atol=1e-15)), back.inertia.diagonal().tolist()
    ('racket.csv', True, [1.0, 2.0, 3.0])
    >>> back.meta["scenario"]
    'Tennis racket (Dzhanibekov) flips'
    """
    path = pathlib.Path(path)
    if path.suffix not in SUFFIXES:
        raise ValueError(f"path must end in one of {', '.join(SUFFIXES)}, got {path.name!r}")
    require_backends(path.suffix, "writing results")
    if isinstance(result, Trajectory):
        result.save(path)
        return path
    with atomic_output(path) as tmp:
        if path.suffix == ".nc":
            cf_labelled(result).to_netcdf(tmp, engine="scipy")
        elif path.suffix == ".csv":
            result.to_dataframe().to_csv(tmp, float_format="%.17g")
        else:
            frame = result.to_dataframe()
            frame.attrs["kreisel"] = json.dumps(dict(result.attrs), default=str)
            frame.to_parquet(tmp)
    return path


def load_trajectory(path):
    """Read a trajectory written by :func:`save_result` or :meth:`Trajectory.save`.

    Examples
    --------
    >>> import os, tempfile
    >>> import numpy as np
    >>> from kreisel.io import example_path, load_scenario, run_scenario
    >>> traj = run_scenario(load_scenario(example_path("tennis_racket")))
    >>> back = load_trajectory(save_result(traj, os.path.join(tempfile.mkdtemp(), "racket.nc")))
    >>> len(back), back.meta["method"], bool(np.allclose(back.omega, traj.omega, rtol=0, atol=1e-15))
    (2001, 'dop853', True)
    >>> load_trajectory(os.path.join(tempfile.mkdtemp(), "missing.nc"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    kreisel.io.results.ResultError: ...missing.nc: no such file
    """
    path = pathlib.Path(path)
    if not path.is_file():
        raise ResultError(f"{path}: no such file")
    if path.suffix not in SUFFIXES:
        raise ResultError(f"{path}: unknown trajectory format (expected {', '.join(SUFFIXES)})")
    require_backends(path.suffix, "reading results")
    try:
        return Trajectory.load(path)
    except (OSError, KeyError, ValueError, TypeError) as exc:
        kind = _dataset_kind(path)
        if kind is not None:
            raise ResultError(f"{path}: holds a {kind} result, not a trajectory") from None
        if isinstance(exc, _trajectory_files.TrajectoryFileError):
            raise ResultError(str(exc)) from None
        # backends explain themselves over several lines (xarray suggests installing netcdf4): keep the first
        reason = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        raise ResultError(f"{path}: not a readable kreisel trajectory ({type(exc).__name__}: {reason})") from None


def backend_needs(suffix):
    """The ``(module, extra)`` pairs that read and write ``suffix`` files, for :func:`kreisel._optional.require_all`."""
    return [(module, "io") for module in (("xarray", "pyarrow") if suffix == ".parquet" else ("xarray",))]


def require_backends(suffix, feature):
    """Import what reads and writes ``suffix`` files (the ``io`` extra), or fail with the one line naming it."""
    require_all(backend_needs(suffix), feature=f"{feature} as {suffix}")


def _dataset_kind(path):
    """The ``kreisel`` attribute of a NetCDF result that is not a trajectory (Foucault, coning), else None."""
    if path.suffix != ".nc":
        return None
    xr = require("xarray", extra="io", feature="reading results")
    try:
        with xr.open_dataset(path, engine="scipy") as ds:
            kind = ds.attrs.get("kreisel")
    except (OSError, ValueError, TypeError):
        return None
    return kind if isinstance(kind, str) and not kind.startswith("Trajectory") else None


def load_result(path):
    """A result file written by :func:`save_result`: a Trajectory, or the ``xarray.Dataset`` of a Foucault or
    coning run (its ``kreisel`` attribute names it).

    Examples
    --------
    >>> import os, tempfile
    >>> from kreisel.io import load_scenario, run_scenario
    >>> path = save_result(run_scenario(load_scenario("foucault")), os.path.join(tempfile.mkdtemp(), "f.nc"))
    >>> load_result(path).attrs["kreisel"]
    'Foucault pendulum'
    """
    path = pathlib.Path(path)
    try:
        return load_trajectory(path)
    except ResultError:
        if _dataset_kind(path) is None:
            raise
    xr = require("xarray", extra="io", feature="reading results")
    with xr.open_dataset(path, engine="scipy") as ds:
        return ds.load()
