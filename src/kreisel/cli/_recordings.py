"""The recordings kreisel ships, taken by name wherever a command reads a recording (fit, plot, attitude, serve)."""

from __future__ import annotations

import pathlib

import typer

from ._output import usage_error

__all__ = ["bundled_recordings", "not_a_recording", "read_recording", "recording_file", "units_option"]

def units_option():
    """The ``--units`` option of every command that reads a recording: the gyro's unit where the file names none."""
    return typer.Option(
        None, "--units", help="The gyroscope's unit when the file does not name it: rad/s, deg/s, mdeg/s, rpm…")


def bundled_recordings():
    """``{name: path}`` of every bundled recording: the gyroscope recordings, then the IMU trials."""
    from importlib import resources

    from ..io.gyro import RECORDINGS, TRIALS

    folder = resources.files("kreisel.io.examples")
    return {name: pathlib.Path(str(folder.joinpath(file))) for name, file in {**RECORDINGS, **TRIALS}.items()}


def recording_file(recording):
    """``recording`` if it exists, else the bundled recording of that name; a usage error naming the nearest names."""
    from ..io.bundled import suggestion

    recording = pathlib.Path(recording)
    if recording.exists():
        return recording
    bundled = bundled_recordings()
    if str(recording) in bundled:
        return bundled[str(recording)]
    usage_error(f"{recording}: no such file, and no bundled recording of that name{suggestion(recording, bundled)}")


def not_a_recording(path):
    """Why ``path`` is another of kreisel's files rather than a recording, or None.

    Read as a table, a result or a scenario fails on its first bytes with a
    message about control characters or numbers, which does not tell the
    reader that they passed the wrong kind of file.

    Examples
    --------
    >>> not_a_recording(pathlib.Path("run.nc"))  # doctest: +NORMALIZE_WHITESPACE
    'run.nc is a result file (as kreisel simulate writes), not a sensor recording:
     plot it with kreisel plot run.nc -o fig.png'
    >>> not_a_recording(pathlib.Path("Gyroscope.csv")) is None
    True
    """
    suffix = path.suffix.lower()
    if suffix == ".toml":
        return (f"{path} is a scenario or sweep file, not a sensor recording: kreisel simulate {path} -o traj.nc "
                f"(or kreisel sweep {path}) runs it")
    if suffix in (".nc", ".parquet", ".zarr"):
        return (f"{path} is a result file (as kreisel simulate writes), not a sensor recording: "
                f"plot it with kreisel plot {path} -o fig.png")
    return None


def read_recording(read, path, **options):
    """``read(path, **options)`` (a reader of :mod:`kreisel.io.gyro`), its refusals as one-line usage errors.

    The reader's ValueError is the ``units`` it was given: the ``--units`` option.
    """
    from ..io.gyro import GyroFileError

    mistaken = not_a_recording(path)
    if mistaken is not None:
        usage_error(mistaken)
    try:
        return read(path, **options)
    except OSError as exc:
        usage_error(f"cannot read {path} ({exc.strerror or exc})")
    except GyroFileError as exc:
        usage_error(str(exc))
    except ValueError as exc:
        usage_error(f"--units: {exc}")
