"""The ``kreisel`` command line (typer).

Usage errors (bad options, unreadable or invalid input files) print one line
on standard error and exit with status 2; they never show a traceback.
"""

from __future__ import annotations

import pathlib
import sys
from typing import List, Optional

import typer
from rich.console import Console

from .. import __version__

app = typer.Typer(
    name="kreisel",
    help="Rigid-body mechanics: rotations, tops, rotating frames, strapdown attitude.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)
err = Console(stderr=True, highlight=False)
out = Console(highlight=False)


def usage_error(message):
    """Print ``message`` as one line and exit with status 2."""
    err.print(f"[bold red]error:[/] {message}", soft_wrap=True)
    raise typer.Exit(2)


def _version(value: bool):
    if value:
        out.print(f"kreisel {__version__}")
        raise typer.Exit()


@app.callback()
def main(
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                 help="Print the version and exit."),
):
    """kreisel: the rigid-body chapter as software."""


@app.command()
def convert(
    values: Optional[List[float]] = typer.Argument(None, help="Numbers of one rotation; none: read rows from stdin."),
    source: str = typer.Option(..., "--from", help="quat | matrix | rotvec | euler:SEQ | axis_angle | gibbs | mrp"),
    target: str = typer.Option(..., "--to", help="quat | matrix | rotvec | euler:SEQ | axis_angle | gibbs | mrp | su2 | cayley_klein"),
    degrees: bool = typer.Option(False, "--degrees", help="Angles in degrees (euler, axis_angle, rotvec)."),
    input_file: Optional[pathlib.Path] = typer.Option(None, "--input", "-i", help="CSV or whitespace file, one rotation a row."),
):
    """Convert rotations between representations, e.g. --from euler:ZXZ --to quat 30 45 60 --degrees."""
    from .convert import ConversionError, format_rows, read_rows
    from .convert import convert as run

    try:
        if values:
            rows = [list(values)]
        elif input_file is not None:
            try:
                rows = read_rows(input_file.read_text(encoding="utf-8"))
            except OSError as exc:
                usage_error(f"--input: cannot read {input_file} ({exc.strerror})")
        else:
            rows = read_rows(sys.stdin.read())
        if not rows:
            usage_error("no rotation given (pass numbers or rows on stdin)")
        result = run(source, target, rows, degrees=degrees)
    except ConversionError as exc:
        usage_error(str(exc))
    except ValueError as exc:
        usage_error(f"invalid rotation: {exc}")
    for line in format_rows(result):
        typer.echo(line)


@app.command()
def simulate(
    scenario: pathlib.Path = typer.Argument(..., help="Scenario TOML file (see `kreisel examples`)."),
    output: Optional[pathlib.Path] = typer.Option(None, "-o", "--output", help="traj.nc | .csv | .parquet"),
):
    """Run a scenario file and report its first integrals."""
    from ..io.results import SUFFIXES, save_result
    from ..io.run import run_scenario, summary
    from ..io.scenario import ScenarioError, load_scenario

    if output is not None and output.suffix not in SUFFIXES:
        usage_error(f"-o: unsupported output {output.name!r} (expected {', '.join(SUFFIXES)})")
    try:
        spec = load_scenario(scenario)
    except ScenarioError as exc:
        usage_error(str(exc))
    with err.status(f"simulating {spec.title} ..."):
        result = run_scenario(spec)
    for line in summary(result):
        out.print(line)
    if output is not None:
        save_result(result, output)
        out.print(f"wrote {output}")


@app.command()
def plot(
    trajectory: pathlib.Path = typer.Argument(..., help="Trajectory file written by `kreisel simulate`."),
    kind: str = typer.Option("omega", "--kind", "-k", help="omega | energy | euler | polhode | herpolhode | apex"),
    output: pathlib.Path = typer.Option(..., "-o", "--output", help="fig.png | .svg | .pdf"),
):
    """Plot a saved trajectory."""
    from .. import plot as plots
    from ..io.results import ResultError, load_trajectory

    if kind not in plots.KINDS:
        usage_error(f"--kind: unknown plot kind {kind!r} (expected one of {', '.join(plots.KINDS)})")
    try:
        traj = load_trajectory(trajectory)
        fig = plots.KINDS[kind](traj)
        plots.save(fig, output)
    except (ResultError, ValueError) as exc:
        usage_error(str(exc))
    out.print(f"wrote {output}")


@app.command()
def animate(
    trajectory: pathlib.Path = typer.Argument(..., help="Trajectory file written by `kreisel simulate`."),
    output: pathlib.Path = typer.Option(..., "-o", "--output", help="anim.gif | .mp4"),
    frames: int = typer.Option(120, "--frames", min=2, max=2000, help="Number of frames."),
    fps: int = typer.Option(24, "--fps", min=1, max=120),
):
    """Animate a saved trajectory: the body with its axes, ω and J."""
    from ..io.results import ResultError, load_trajectory
    from ..plot.animation import animate as run

    try:
        traj = load_trajectory(trajectory)
        run(traj, output, frames=frames, fps=fps)
    except (ResultError, ValueError) as exc:
        usage_error(str(exc))
    out.print(f"wrote {output}")


@app.command()
def examples(
    name: Optional[str] = typer.Argument(None, help="Example to copy out; none: list them."),
    directory: pathlib.Path = typer.Option(pathlib.Path("."), "--to", help="Where to copy the example."),
):
    """List the bundled scenario files, or copy one out to edit."""
    from ..io.bundled import EXAMPLES, copy_example, describe

    if name is None:
        for example, text in describe().items():
            out.print(f"[bold]{example:<16}[/] {text}")
        return
    if name not in EXAMPLES:
        usage_error(f"unknown example {name!r} (expected one of {', '.join(EXAMPLES)})")
    try:
        path = copy_example(name, directory)
    except (FileExistsError, ValueError) as exc:
        usage_error(str(exc))
    out.print(f"wrote {path}")


@app.command()
def tour(
    out_dir: pathlib.Path = typer.Option(pathlib.Path("tour"), "--out", help="Directory for index.html and figures."),
    quick: bool = typer.Option(False, "--quick", help="Smaller, faster demonstrations."),
):
    """Run every demonstration of the chapter and write DIR/index.html."""
    from ..tour import run_tour

    ok = run_tour(out_dir, quick=quick, console=out)
    raise typer.Exit(0 if ok else 1)


@app.command()
def sweep(
    sweep_file: pathlib.Path = typer.Argument(
        ..., help="Sweep TOML file, or the name of a bundled sweep: tennis_racket, lagrange_apex, imu_monte_carlo."),
    scheduler: Optional[str] = typer.Option(None, "--scheduler", help="Existing Dask scheduler, tcp://host:8786."),
    workers: Optional[int] = typer.Option(None, "--workers", min=1, help="Worker processes of the local cluster."),
    output: Optional[pathlib.Path] = typer.Option(None, "-o", "--output", help="out.zarr | out.nc"),
    plot_file: Optional[pathlib.Path] = typer.Option(None, "--plot", help="Also draw the map: fig.png | .svg | .pdf"),
):
    """Run a parameter sweep on Dask; interrupted sweeps resume from their finished chunks."""
    from .. import plot as plots
    from ..sweep import EXAMPLES, SweepError, example_path, load_sweep_file, plot_sweep, run_sweep_file

    if not sweep_file.exists() and str(sweep_file) in EXAMPLES:
        sweep_file = example_path(str(sweep_file))
    try:
        if output is None and load_sweep_file(sweep_file).output is None:
            # results (and the checkpoint that lets an interrupted run resume) go to the working directory
            output = pathlib.Path(f"{sweep_file.stem}.zarr")
        dataset = run_sweep_file(sweep_file, scheduler=scheduler, n_workers=workers, output=output, console=err)
    except SweepError as exc:
        err.print(f"[bold red]error:[/] {exc}", soft_wrap=True)
        raise typer.Exit(1)
    except ValueError as exc:
        usage_error(str(exc))
    out.print(f"{dict(dataset.sizes)} points" + (f", wrote {output}" if output else ""))
    if plot_file is not None:
        plots.save(plot_sweep(dataset), plot_file)
        out.print(f"wrote {plot_file}")


@app.command()
def fit(
    recording: pathlib.Path = typer.Argument(
        ..., help="Gyroscope recording: phyphox CSV, export folder or zip, or a table t ωx ωy ωz; "
                  "'phone_toss' is a bundled example."),
    start: Optional[float] = typer.Option(None, "--start", help="Fit from this time on, s (as in the file)."),
    stop: Optional[float] = typer.Option(None, "--stop", help="Fit up to this time, s."),
    bias: bool = typer.Option(False, "--bias", help="Also fit a constant gyroscope offset."),
    align: bool = typer.Option(False, "--align", help="Also fit the rotation from sensor to principal axes."),
    plot_file: Optional[pathlib.Path] = typer.Option(None, "--plot", help="Draw data, fit and residuals: fit.png | .svg | .pdf"),
    json_file: Optional[pathlib.Path] = typer.Option(None, "--json", help="Write the results as JSON."),
):
    """Fit the free (Euler) top to a gyroscope recording: moment ratios, ω0, bias, regime."""
    import json
    import warnings

    from .._fileio import atomic_output
    from ..io.gyro import RECORDINGS, GyroFileError, read_gyro, recording_path
    from ..tops.fitting import NotFreeRotationWarning, fit_free_rotation
    from .fit import as_dict, summary

    if plot_file is not None and plot_file.suffix.lower() not in (".png", ".svg", ".pdf"):
        usage_error(f"--plot: unsupported output {plot_file.name!r} (expected .png, .svg or .pdf)")
    for option, target in (("--plot", plot_file), ("--json", json_file)):
        if target is not None and not target.parent.is_dir():
            usage_error(f"{option}: directory {str(target.parent)!r} does not exist")
    if not recording.exists() and str(recording) in RECORDINGS:
        recording = recording_path(str(recording))
    try:
        data = read_gyro(recording)
    except OSError as exc:
        usage_error(f"cannot read {recording} ({exc.strerror or exc})")
    except GyroFileError as exc:
        usage_error(str(exc))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotFreeRotationWarning)  # the summary reports it
        try:
            result = fit_free_rotation(data.t, data.omega, bias=bias, align=align,
                                       window=None if start is None and stop is None else (start, stop))
        except ValueError as exc:
            usage_error(f"{recording}: {exc}")
    for line in summary(result):
        (out if result.free_rotation else err).print(line, soft_wrap=True)
    if plot_file is not None:
        from .. import plot as plots

        plots.save(plots.gyro_fit(result), plot_file)
        out.print(f"wrote {plot_file}")
    if json_file is not None:
        with atomic_output(json_file) as tmp:
            tmp.write_text(json.dumps(as_dict(result), indent=2) + "\n", encoding="utf-8")
        out.print(f"wrote {json_file}")
    if not result.free_rotation:
        raise typer.Exit(1)


@app.command()
def serve(
    scenario: Optional[pathlib.Path] = typer.Argument(None, help="Scenario TOML to open in the viewer."),
    host: str = typer.Option("127.0.0.1", "--host", help="Interface to bind (loopback by default)."),
    port: int = typer.Option(0, "--port", help="Port; 0 picks a free one."),
    no_browser: bool = typer.Option(False, "--no-browser", help="Do not open a browser window."),
):
    """Start the interactive 3D viewer in the browser."""
    from ..web import serve as run_server

    try:
        run_server(scenario, host=host, port=port, open_browser=not no_browser)
    except ValueError as exc:
        usage_error(str(exc))


def run():
    """Console-script entry point.

    Examples
    --------
    ``run`` reads ``sys.argv`` like the installed ``kreisel`` command and exits
    with its status: 0 on success, 2 for a usage error (one line on standard
    error, no traceback):

    >>> import sys
    >>> from unittest import mock
    >>> def kreisel(*args):
    ...     with mock.patch.object(sys, "argv", ["kreisel", *args]):
    ...         try:
    ...             run()
    ...         except SystemExit as exit:
    ...             print("exit status", exit.code)
    >>> kreisel("--version")  # doctest: +ELLIPSIS
    kreisel ...
    exit status 0
    >>> kreisel("run", "no-such-scenario.toml")
    exit status 2
    """
    app()
