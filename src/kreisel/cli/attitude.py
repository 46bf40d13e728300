"""``kreisel attitude``: attitude and heading of an IMU recording, written as CSV (Theory §3.5)."""

from __future__ import annotations

import pathlib
from typing import Optional

import typer

from ._files import FORCE_HELP
from ._recordings import units_option

__all__ = ["METHODS", "attitude", "summary", "write_csv"]

METHODS = ("kreisel", "madgwick", "mahony", "complementary")
# NED ← ENU: a half turn about the horizontal axis between north and east
_NED_FROM_ENU = (0.0, 0.5 ** 0.5, 0.5 ** 0.5, 0.0)


def summary(name, rec, estimate, rate, frame, errors):
    """Lines describing the run on recording ``name``: samples, duration, rate, method, and the errors.

    ``errors`` is ``(total, heading, inclination)`` in degrees, or a string saying why there are none
    (None: the recording has no reference).

    Examples
    --------
    >>> import numpy as np
    >>> from kreisel.io import ImuRecording
    >>> from kreisel.nav import AttitudeEstimate
    >>> rec = ImuRecording(np.arange(3) / 100.0, np.zeros((3, 3)))
    >>> est = AttitudeEstimate(q=np.zeros((3, 4)), bias=None, covariance=None, method="mahony")
    >>> print("\\n".join(summary("imu.csv", rec, est, 100.0, "ENU", (1.0, 0.5, 0.25))))
    imu.csv: 3 samples, 0.02 s at 100 Hz, method mahony, frame ENU ← sensor
      error against the reference (RMSE over all samples): total 1.000°, heading 0.500°, inclination 0.250°
    """
    lines = [f"{name}: {rec.t.size} samples, {rec.t[-1] - rec.t[0]:.6g} s at {rate:.6g} Hz, "
             f"method {estimate.method}, frame {frame} ← sensor"]
    if isinstance(errors, str):
        lines.append(f"  no error against the reference: {errors}")
    elif errors is not None:
        over = "the movement samples" if rec.movement is not None else "all samples"
        lines.append(f"  error against the reference (RMSE over {over}): total {errors[0]:.3f}°, "
                     f"heading {errors[1]:.3f}°, inclination {errors[2]:.3f}°")
    return lines


def write_csv(path, t, estimate):
    """Write ``t`` and ``estimate``'s quaternions (and bias, when estimated) as CSV, atomically.

    Numbers are written with 17 significant digits, so that they read back as
    the same doubles.

    Examples
    --------
    >>> import numpy as np, pathlib, tempfile
    >>> from kreisel.nav import AttitudeEstimate
    >>> est = AttitudeEstimate(q=np.array([[1.0, 0.0, 0.0, 0.0]]), bias=np.array([[0.1, 0.0, 0.0]]),
    ...                        covariance=None, method="kreisel")
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "attitude.csv"
    >>> print(write_csv(path, np.array([0.5]), est).read_text(), end="")
    t,q0,q1,q2,q3,bias_x,bias_y,bias_z
    0.5,1,0,0,0,0.10000000000000001,0,0
    """
    import numpy as np

    from .._fileio import atomic_output

    names = ["t", "q0", "q1", "q2", "q3"]
    columns = [t[:, None], estimate.q]
    if estimate.bias is not None:
        names += ["bias_x", "bias_y", "bias_z"]
        columns.append(estimate.bias)
    with atomic_output(path) as tmp:
        np.savetxt(tmp, np.hstack(columns), fmt="%.17g", delimiter=",", header=",".join(names), comments="")
    return path


def _in_frame(reference, frame):
    """``reference`` (ENU ← sensor, NaN rows where lost) as ``frame`` ← sensor."""
    import numpy as np

    from ..so3 import quat_multiply

    if frame == "ENU":
        return reference
    tracked = np.isfinite(reference).all(axis=1)
    turned = np.full_like(reference, np.nan)
    turned[tracked] = quat_multiply(np.array(_NED_FROM_ENU), reference[tracked])
    return turned


def _reference_errors(estimate, reference, movement):
    """BROAD's three RMSEs of the estimate against ``reference``, or why there are none."""
    from ..nav import attitude_error

    try:
        return attitude_error(estimate.q, reference, movement)
    except ValueError as exc:
        return str(exc)


def attitude(
    recording: pathlib.Path = typer.Argument(
        ..., help="IMU recording with gyroscope and accelerometer (and magnetometer): phyphox export (CSV, "
                  "folder or zip), CSV/TSV table, or BROAD .npz; 'broad_07' is a bundled BROAD trial."),
    output: pathlib.Path = typer.Option(
        ..., "-o", "--output", help="CSV to write: t (s), q0 q1 q2 q3 (scalar first, frame ← sensor) and, "
                                    "where the method estimates it, bias_x bias_y bias_z (rad/s)."),
    method: str = typer.Option(
        "kreisel", "--method", help="kreisel (kreisel's own estimator) | madgwick | mahony | complementary."),
    offline: bool = typer.Option(
        False, "--offline", help="kreisel's estimator only: fuse a forward and a backward pass (recorded data)."),
    frame: str = typer.Option("ENU", "--frame", help="Earth frame of the attitude: ENU or NED (magnetic north)."),
    no_mag: bool = typer.Option(
        False, "--no-mag", help="Ignore the magnetometer: the heading comes from the gyro alone."),
    rate: Optional[float] = typer.Option(
        None, "--rate", help="Sampling rate, Hz, of a table without a time column (its rows evenly spaced)."),
    units: Optional[str] = units_option(),
    plot_file: Optional[pathlib.Path] = typer.Option(
        None, "--plot", help="Draw yaw, pitch and roll (and, with a reference in the file, its angles and "
                             "the errors): attitude.png | .svg | .pdf"),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
):
    """Estimate attitude and heading from gyro, accelerometer and magnetometer; write them as CSV."""
    from .._optional import require_all
    from ..io.gyro import read_imu
    from ..nav import estimate_attitude
    from ._files import FIGURES, check_output, writing
    from ._output import note, say, usage_error
    from ._recordings import read_recording, recording_file

    if method not in METHODS:
        usage_error(f"--method: unknown method {method!r}; methods are {', '.join(METHODS)}")
    if offline and method != "kreisel":
        usage_error(f"--offline: only kreisel's estimator has an offline variant, not --method {method}")
    if frame not in ("ENU", "NED"):
        usage_error(f"--frame: expected ENU or NED, got {frame!r}")
    if rate is not None and not 0.0 < rate < float("inf"):
        usage_error(f"--rate: expected a positive sampling rate in Hz, got {rate:g}")
    check_output("-o", output, force)
    check_output("--plot", plot_file, force, FIGURES)
    if plot_file is not None:
        require_all([("matplotlib", "plot")], feature="kreisel attitude --plot")  # before the estimate
    path = recording_file(recording)
    rec = read_recording(read_imu, path, units=units, rate=rate)
    if rec.accel is None:
        usage_error(f"{path}: no accelerometer columns; attitude estimation needs gyro and accelerometer")
    try:
        sample_rate = rec.sampling_rate()
    except ValueError as exc:
        usage_error(str(exc))
    # a refusal is one error line: the reader's notes only go with a recording that is used
    for line in rec.notes:
        note(f"{path}: {line}")
    mag = None if no_mag else rec.mag
    if mag is None and not no_mag:
        note(f"{path}: no magnetometer: the heading comes from the gyro alone")
    try:
        estimate = estimate_attitude(rec.omega, rec.accel, mag, rate=sample_rate, offline=offline, frame=frame,
                                     method=None if method == "kreisel" else method)
    except ValueError as exc:
        usage_error(f"{path}: {exc}")
    reference = None if rec.reference is None else _in_frame(rec.reference, frame)
    errors = None if reference is None else _reference_errors(estimate, reference, rec.movement)
    for line in summary(recording, rec, estimate, sample_rate, frame, errors):
        say(line)
    with writing("-o", output):
        write_csv(output, rec.t, estimate)
    if plot_file is not None:
        from .. import plot as plots

        with writing("--plot", plot_file):
            plots.save(plots.attitude_estimate(rec.t, estimate.q, reference, rec.movement,
                                               title=f"{path.name}: {estimate.method}, {frame} ← sensor"), plot_file)
