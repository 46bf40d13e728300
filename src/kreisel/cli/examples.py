"""``kreisel examples``: what kreisel ships to try (scenarios, recordings, sweeps), listed by use."""

from __future__ import annotations

import importlib.util
import pathlib
import tomllib

__all__ = ["RECORDING_NOTES", "sections", "sweep_files"]

#: What each bundled recording (:data:`kreisel.io.gyro.RECORDINGS`, the IMU trials of ``kreisel attitude``) holds.
RECORDING_NOTES = {
    "phone_toss": "A phone (146 × 71 × 8 mm) tossed about its middle axis: 0.65 s of free flight with one flip, "
                  "phyphox's CSV format, 0.05 rad/s noise and a gyro bias (Theory §5.4).",
    "broad_07": "BROAD trial 07 (CC BY 4.0), 60 s at 285.7 Hz: gyro, accelerometer and magnetometer at rest, then "
                "turned fast by hand, with the optical reference attitude (Theory §3.5).",
}


def sweep_files():
    """``{name: path}`` of the bundled sweep files, found without importing :mod:`kreisel.sweep` (Dask, numba)."""
    package = importlib.util.find_spec("kreisel.sweep")
    folder = pathlib.Path(next(iter(package.submodule_search_locations))) / "examples"
    return {path.stem: path for path in sorted(folder.glob("*.toml"))}


def sections():
    """``[(heading, {name: description})]``: the bundled scenarios, recordings and sweeps.

    Examples
    --------
    >>> [(heading.split(" (")[0], sorted(entries)[:2]) for heading, entries in sections()]
    [('scenarios', ['coning', 'fast_top']), ('gyroscope recordings', ['phone_toss']), ('IMU recordings', ['broad_07']), ('sweeps', ['imu_monte_carlo', 'lagrange_apex'])]
    """
    from ..io.bundled import describe
    from ..io.gyro import RECORDINGS, TRIALS

    sweeps = {name: tomllib.loads(path.read_text(encoding="utf-8")).get("description", "")
              for name, path in sweep_files().items()}
    return [
        ("scenarios (kreisel simulate NAME; kreisel examples NAME copies one out to edit)", describe()),
        ("gyroscope recordings (kreisel fit NAME, kreisel plot NAME; kreisel examples NAME copies one out)",
         {name: RECORDING_NOTES.get(name, "") for name in RECORDINGS}),
        ("IMU recordings (kreisel attitude NAME, kreisel plot NAME; kreisel examples NAME copies one out)",
         {name: RECORDING_NOTES.get(name, "") for name in TRIALS}),
        ("sweeps (kreisel sweep NAME)", sweeps),
    ]
