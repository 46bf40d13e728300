"""Parameter sweeps on Dask: chunks, retries, checkpoints, Zarr/NetCDF output, bundled sweeps.

:func:`sweep` runs any function over a parameter grid; :func:`run_sweep_file`
runs a TOML sweep file (``kreisel sweep SWEEP.toml``); three sweeps are
bundled (:data:`EXAMPLES`): the tennis-racket stability map, the Lagrange-top
apex-locus map and an attitude-error Monte Carlo under gyro noise, each with
a plot. Dask, xarray and matplotlib are imported only when used.

Sweeps too large for memory: ``sweep(..., stream=True)`` (a sweep file's
``stream = true``, ``kreisel sweep --stream``) writes each chunk into the
``.zarr`` output as it arrives, so memory holds about one chunk whatever the
sweep's size, and returns the dataset reading the store lazily. Decimate what
each point stores: :func:`kreisel.simulate_batch` keeps every k-th sample with
``every=k`` in a sweep function of your own, and the bundled tennis-racket
sweep stores the angular-velocity histories with ``store_omega = true`` and
``every = k`` among its constants.
"""

from .core import SweepError, SweepProgress, sweep, write_dataset
from .files import (EXAMPLES, SweepFile, SweepFileError, example_path, load_sweep_file, parse_sweep_file,
                    plot_sweep, run_sweep_file)
from .models import (APEX_LOCUS_KINDS, imu_attitude_error, lagrange_apex_locus, plot_imu_attitude_error,
                     plot_lagrange_apex_locus, plot_tennis_racket, tennis_racket_flip)

__all__ = [
    "sweep",
    "SweepError",
    "SweepProgress",
    "write_dataset",
    "run_sweep_file",
    "load_sweep_file",
    "parse_sweep_file",
    "SweepFile",
    "SweepFileError",
    "EXAMPLES",
    "example_path",
    "plot_sweep",
    "tennis_racket_flip",
    "lagrange_apex_locus",
    "imu_attitude_error",
    "APEX_LOCUS_KINDS",
    "plot_tennis_racket",
    "plot_lagrange_apex_locus",
    "plot_imu_attitude_error",
]
