"""The recordings kreisel ships, taken by name wherever a command reads a recording (fit, plot, attitude, serve)."""

from __future__ import annotations

import pathlib

import typer

from ._output import usage_error

__all__ = ["bundled_recordings", "read_recording", "recording_file", "units_option"]

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


def read_recording(read, path, **options):
    """``read(path, **options)`` (a reader of :mod:`kreisel.io.gyro`), its refusals as one-line usage errors.

    The reader's ValueError is the ``units`` it was given: the ``--units`` option.
    """
    from ..io.gyro import GyroFileError

    try:
        return read(path, **options)
    except OSError as exc:
        usage_error(f"cannot read {path} ({exc.strerror or exc})")
    except GyroFileError as exc:
        usage_error(str(exc))
    except ValueError as exc:
        usage_error(f"--units: {exc}")
