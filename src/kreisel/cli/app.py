"""The ``kreisel`` command line (typer).

Usage errors (bad options, unreadable or invalid input files) print one line
on standard error and exit with status 2; they never show a traceback.
"""

from __future__ import annotations

import contextlib
import math
import pathlib
import sys
from typing import List, Optional

import typer

from .._optional import MissingExtraError
from ._output import compile_notice, console, error_line, note, plain, progress, say, usage_error
from ._files import FIGURES as _FIGURES
from ._files import FORCE_HELP as _FORCE_HELP
from ._files import check_output as _check_output
from ._files import check_outputs_in as _check_outputs_in
from ._files import writing as _writing
from ._recordings import units_option
from .attitude import attitude as attitude_command

__all__ = [
    "app",
    "usage_error",
    "say",
    "error_line",
    "main",
    "convert",
    "simulate",
    "plot",
    "animate",
    "examples",
    "tour",
    "sweep",
    "fit",
    "serve",
    "compile_kernels",
    "run",
]


class _Commands(typer.core.TyperGroup):
    """The commands; one whose optional dependencies are not installed names the extra in one line (status 2)."""

    #: Whether a command says so when it compiles (set by :func:`run`: the installed command, not a test's runner)
    announce_compiling = False

    def invoke(self, ctx):
        with contextlib.ExitStack() as scope:
            ctx.meta[_SCOPE] = scope
            try:
                return super().invoke(ctx)
            except MissingExtraError as exc:
                usage_error(str(exc))

    def resolve_command(self, ctx, args):
        name, command, rest = super().resolve_command(ctx, args)
        if self.announce_compiling and name not in _COMPILING_NOTHING and _SCOPE in ctx.meta:
            ctx.meta[_SCOPE].enter_context(compile_notice())
        return name, command, rest

    def format_commands(self, ctx, formatter):
        """Each command with its whole summary (click cuts it to the width with "...")."""
        rows = [(name, command.get_short_help_str(limit=10**6)) for name in self.list_commands(ctx)
                if (command := self.get_command(ctx, name)) is not None and not command.hidden]
        if rows:
            with formatter.section("Commands"):
                formatter.write_dl(rows)


_SCOPE = "kreisel.scope"
# commands that compile nothing (they need not import numba to listen for compilations), or that are the compilation
_COMPILING_NOTHING = ("examples", "compile")


app = typer.Typer(
    cls=_Commands,
    name="kreisel",
    help="Rigid-body mechanics: rotations, tops, rotating frames, strapdown attitude.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    # click's plain help and usage errors: typer's rich help imports rich's Markdown, Syntax and
    # Traceback renderers, which alone take longer than the help's start-up budget
    rich_markup_mode=None,
)




def _version(value: bool):
    if value:
        from .._version import __version__

        say(f"kreisel {__version__}")
        raise typer.Exit()


@app.callback()
def main(
    version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                 help="Print the version and exit."),
):
    """kreisel: the rigid-body chapter as software."""


_CONVERT_HELP = (
    "Convert rotations between representations, e.g. --from euler:ZXZ --to quat 30 45 60 --degrees "
    "(negative numbers as they are: -30 45 60).\n\n"
    "Numbers per rotation, in and out: quat q0 q1 q2 q3, scalar first (--scalar-last: x y z w); "
    "matrix 9 numbers, row-major (R maps body to space); rotvec, gibbs, mrp x y z; "
    "axis_angle x y z angle (the axis, then the angle); euler:SEQ three angles in the order of SEQ "
    "(uppercase intrinsic, lowercase extrinsic); euler_parameters e0 e1 e2 e3, the conjugate quaternion "
    "(Theory §A); su2 and cayley_klein (output only) complex numbers a b -b* a*.\n\n"
)


@app.command(help=_CONVERT_HELP, short_help="Convert rotations between representations.",
             context_settings={"ignore_unknown_options": True})
def convert(
    values: Optional[List[str]] = typer.Argument(
        None, metavar="NUMBERS", help="Numbers of one rotation; none: rows from --input or standard input.",
        show_default=False),
    # --from and --to are checked in the body: NUMBERS take unknown options (negative numbers), so
    # a misspelt option must be named before a missing one is reported
    source: List[str] = typer.Option(
        [], "--from", metavar="REPR", show_default=False,
        help="quat | matrix | rotvec | euler:SEQ | axis_angle | gibbs | mrp | euler_parameters"),
    target: List[str] = typer.Option(
        [], "--to", metavar="REPR", show_default=False,
        help="quat | matrix | rotvec | euler:SEQ | axis_angle | gibbs | mrp | euler_parameters | su2 | cayley_klein"),
    degrees: bool = typer.Option(False, "--degrees", help="Angles in degrees (euler, axis_angle, rotvec)."),
    scalar_last: bool = typer.Option(False, "--scalar-last", help="Quaternions in and out as x y z w."),
    input_file: Optional[pathlib.Path] = typer.Option(
        None, "--input", "-i", help="CSV or whitespace file, one rotation a row; a first line of names is skipped."),
):
    from .convert import ConversionError, format_rows, input_notes, parse_representation, read_rows, width
    from .convert import convert as run

    numbers = [_number(value) for value in values or ()]
    for option, given in (("--from", source), ("--to", target)):
        if not given:
            usage_error(f"missing option {option} REPR")
        if len(given) > 1:
            usage_error(f"{option} given {len(given)} times ({', '.join(given)}); give it once")
    if values and input_file is not None:
        usage_error("give the numbers of a rotation or --input FILE, not both")
    try:
        name, _ = parse_representation(source[0], "--from")
        parse_representation(target[0], "--to")
        if values:
            lines, rows = None, [numbers]
        else:
            lines, rows = read_rows(_read_input(input_file), width(name))
        if not rows:
            usage_error("no rotation given (pass numbers, --input FILE or rows on standard input)")
        result = run(source[0], target[0], rows, degrees=degrees, scalar_last=scalar_last, lines=lines)
    except ConversionError as exc:
        usage_error(str(exc))
    for text in input_notes(source[0], rows, degrees, scalar_last):
        note(text)
    for line in format_rows(result):
        typer.echo(line)


def _number(text):
    try:
        return float(text)
    except ValueError:
        usage_error(f"no such option: {text}" if text.startswith("-") else f"not a number: {text!r}")


def _read_input(path):
    """Text of ``path`` (standard input when None); a usage error if it cannot be read as text."""
    if path is None:
        return sys.stdin.read()
    try:
        return path.read_text(encoding="utf-8-sig")
    except OSError as exc:
        usage_error(f"--input: cannot read {path} ({exc.strerror})")
    except UnicodeDecodeError:
        usage_error(f"--input: {path} is not a text file; expected rows of numbers (CSV or whitespace-separated)")


@app.command()
def simulate(
    scenario: str = typer.Argument(..., help="Scenario TOML file, or the name of a bundled one (`kreisel examples`)."),
    output: Optional[pathlib.Path] = typer.Option(None, "-o", "--output", help="traj.nc | .csv | .parquet"),
    force: bool = typer.Option(
        False, "--force", help="Replace an existing output file, and run a scenario estimated to take over "
                               "10 minutes (without it, either is refused)."),
):
    """Run a scenario file and report its first integrals (a long run shows its progress)."""
    from ..io.results import SUFFIXES, require_backends, save_result
    from ..io.run import run_scenario, summary
    from ..io.scenario import ScenarioError, load_scenario

    if output is not None:
        if output.suffix not in SUFFIXES:
            usage_error(f"-o: unsupported output {output.name!r} (expected {', '.join(SUFFIXES)})")
        _check_output("-o", output, force)
        require_backends(output.suffix, "writing results")  # before the run, not after it
    try:
        spec = load_scenario(scenario)
    except ScenarioError as exc:
        usage_error(str(exc))
    from .watch import RunTooLong, RunWatch

    with RunWatch(f"simulating {spec.title}", force=force) as watch:
        try:
            result = run_scenario(spec, progress=watch)
        except RunTooLong as exc:
            usage_error(f"{spec.path or scenario}: {exc}; shorten integration.t_end, or pass --force to run it anyway")
        except (ValueError, TypeError) as exc:
            usage_error(f"{spec.path or scenario}: cannot run: {exc}")
        except RuntimeError as exc:
            error_line(exc)
            raise typer.Exit(1) from None
    for line in summary(result):
        say(line)
    if output is not None:
        with _writing("-o", output):
            save_result(result, output)


@app.command()
def plot(
    file: pathlib.Path = typer.Argument(
        ..., help="Result file written by `kreisel simulate`, or a gyroscope recording "
                  "(as `kreisel fit` reads; 'phone_toss' and 'broad_07' are bundled)."),
    kind: Optional[str] = typer.Option(
        None, "--kind", "-k", help="Trajectories: omega (default) | energy | euler | polhode | herpolhode | apex; "
                                   "Foucault results: azimuth; coning results: error; recordings: rates."),
    output: pathlib.Path = typer.Option(..., "-o", "--output", help="fig.png | .svg | .pdf"),
    seq: Optional[str] = typer.Option(
        None, "--seq", help="Axis sequence of --kind euler, e.g. ZXZ (uppercase intrinsic, lowercase extrinsic); "
                            "default: the chapter's ZXZ unless the motion passes near its gimbal lock."),
    start: Optional[float] = typer.Option(
        None, "--start", help="Recordings: the fit window's start, s (as in the file)."),
    stop: Optional[float] = typer.Option(None, "--stop", help="Recordings: the fit window's end, s."),
    units: Optional[str] = units_option(),
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
):
    """Plot a saved result (a trajectory, or what a Foucault or coning run holds) or a recording's rates."""
    from .._optional import require_all
    from .._validation import parse_sequence
    from ..io.results import ResultError, backend_needs, load_result

    # matplotlib and the file's readers, named together in one line before any work
    require_all([("matplotlib", "plot"), *backend_needs(file.suffix)], feature="kreisel plot")
    _check_output("-o", output, force, _FIGURES)
    from .. import plot as plots
    from ..dynamics import Trajectory
    from ..io.gyro import GyroRecording
    from ..io.run import trajectory_integrals

    known = set(plots.KINDS).union(*plots.DATASET_KINDS.values(), ["rates"])
    if kind is not None and kind not in known:
        usage_error(f"--kind: unknown plot kind {kind!r}; kinds are {', '.join(sorted(known))}")
    if seq is not None:
        if kind != "euler":
            usage_error(f"--seq: the axis sequence of --kind euler; got --kind {kind or '(default)'}")
        try:
            parse_sequence(seq)
        except ValueError as exc:
            usage_error(f"--seq {seq}: {exc} (uppercase: intrinsic, lowercase: extrinsic)")
    try:
        result = _plottable(file, units)
        if isinstance(result, GyroRecording):
            kinds = {"rates": lambda recording: plots.gyro_recording(recording, window=(start, stop))}
            what = "a gyroscope recording"
        elif start is not None or stop is not None or units is not None:
            usage_error(f"--start, --stop and --units are for a gyroscope recording; {file} holds a saved result")
        elif isinstance(result, Trajectory):
            kinds, what = plots.KINDS, "a trajectory"
        else:
            what = f"a {result.attrs['kreisel']} result"
            kinds = plots.DATASET_KINDS.get(result.attrs["kreisel"], {})
        kind = kind or next(iter(kinds))
        if kind not in kinds:
            usage_error(f"--kind: {file} holds {what}, which plots as {', '.join(kinds)}; got {kind!r}")
        fig = plots.energy(result, trajectory_integrals(result)) if kind == "energy" else \
            plots.euler(result, seq=seq) if kind == "euler" else kinds[kind](result)
    except (ResultError, ValueError) as exc:
        usage_error(str(exc))
    with _writing("-o", output):
        plots.save(fig, output)


def _plottable(path, units):
    """The saved result (Trajectory or Dataset) or the gyroscope recording (bundled by name) at ``path``.

    ``units``: the gyro's unit (``--units``), for a recording whose file names none.
    """
    from ..io.gyro import GyroFileError, read_gyro
    from ..io.results import ResultError, load_result
    from ._recordings import read_recording, recording_file

    path = recording_file(path)
    if path.suffix.lower() == ".toml":
        raise ResultError(f"{path} is a scenario or sweep file, not a result: kreisel simulate {path} -o traj.nc "
                          f"(or kreisel sweep {path}) runs it, and kreisel plot draws what it wrote")
    try:
        if path.is_dir() or path.suffix.lower() == ".zip":
            return read_recording(read_gyro, path, units=units)
        return load_result(path)
    except ResultError as exc:
        if path.suffix.lower() in (".nc", ".parquet"):
            raise
        try:
            return read_gyro(path, units=units)
        except (GyroFileError, OSError) as gyro:
            raise ResultError(f"{exc}; nor is it a gyroscope recording: {gyro}") from None
        except ValueError as bad_units:
            usage_error(f"--units: {bad_units}")
    except OSError as exc:
        raise ResultError(f"{path}: cannot read ({exc.strerror or exc})") from None


@app.command()
def animate(
    trajectory: pathlib.Path = typer.Argument(..., help="Trajectory file written by `kreisel simulate`."),
    output: pathlib.Path = typer.Option(..., "-o", "--output", help="anim.gif | .mp4"),
    frames: int = typer.Option(120, "--frames", min=2, max=2000, help="Number of frames."),
    fps: int = typer.Option(24, "--fps", min=1, max=120),
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
):
    """Animate a saved trajectory: the body with its axes, ω and J."""
    from .._optional import require_all
    from ..io.results import ResultError, backend_needs, load_trajectory

    require_all([("matplotlib", "plot"), *backend_needs(trajectory.suffix)], feature="kreisel animate")
    _check_output("-o", output, force, (".gif", ".mp4"))
    from ..plot.animation import animate as run

    try:
        traj = load_trajectory(trajectory)
        with _writing("-o", output):
            run(traj, output, frames=frames, fps=fps)
    except (ResultError, ValueError) as exc:
        usage_error(str(exc))


@app.command()
def examples(
    name: Optional[str] = typer.Argument(
        None, help="Scenario or recording to copy out (a sweep's file is named where it lies); none: list them all."),
    directory: pathlib.Path = typer.Option(
        pathlib.Path("."), "--to", help="Directory to copy the example into (made if missing)."),
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
):
    """List the bundled scenarios, gyroscope recordings and sweeps, or copy one out to edit."""
    from .._fileio import atomic_output
    from ..io.bundled import EXAMPLES, copy_example, suggestion
    from ._recordings import bundled_recordings
    from .examples import sections, sweep_files

    if name is None:
        from rich.text import Text

        for number, (heading, entries) in enumerate(sections()):
            say(("\n" if number else "") + heading)
            for example, text in entries.items():
                console().print(Text.assemble(("  " + f"{example:<16}", "bold"), " ", text), soft_wrap=True)
        return
    recordings = bundled_recordings()
    sweeps = sweep_files()
    if name not in EXAMPLES and name in sweeps:
        usage_error(f"{name!r} is a bundled sweep, which `kreisel sweep {name}` runs as it is; "
                    f"to edit it, copy {sweeps[name]}")
    if name not in EXAMPLES and name not in recordings:
        usage_error(f"no bundled example {name!r}{suggestion(name, (*EXAMPLES, *recordings))}")
    if not directory.is_dir():
        if directory.exists():
            usage_error(f"--to: {str(directory)!r} is a file; name the directory to copy into")
        try:
            directory.mkdir(parents=True)
        except OSError as exc:
            usage_error(f"--to: cannot make the directory {str(directory)!r} ({exc.strerror})")
    if name in recordings:
        target = directory / recordings[name].name
        _check_output("--to", target, force)
        with _writing("--to", target), atomic_output(target) as tmp:
            tmp.write_bytes(recordings[name].read_bytes())
        return
    try:
        path = copy_example(name, directory, force=force)
    except (FileExistsError, ValueError) as exc:
        usage_error(str(exc))
    say(f"wrote {path}")


@app.command()
def tour(
    out_dir: pathlib.Path = typer.Option(pathlib.Path("tour"), "--out", help="Directory for index.html and figures."),
    quick: bool = typer.Option(False, "--quick", help="Smaller, faster demonstrations."),
    notebooks: Optional[pathlib.Path] = typer.Option(
        None, "--notebooks", metavar="DIR",
        help="Instead of running the tour, write its sections as Jupyter notebooks DIR/01_rotations.ipynb, ... "
             "(needs kreisel[notebook]); with --quick their problems are small."),
    lang: str = typer.Option("en", "--lang", metavar="en|zh",
                             help="Language of the report or notebooks: en (English) or zh (Chinese: prose, tables, "
                                  "captions and figure text; the numbers are the same)."),
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
):
    """Run every demonstration of the chapter and write DIR/index.html, or write the tour as notebooks."""
    from ..tour.i18n import LANGUAGES

    if lang not in LANGUAGES:
        usage_error(f"--lang must be one of {', '.join(LANGUAGES)}, got {lang!r}")
    if notebooks is not None:
        from ..tour.notebooks import NOTEBOOKS, write_notebooks

        _check_outputs_in("--notebooks", notebooks, [f"{name}.ipynb" for name in NOTEBOOKS], force)
        try:
            written = write_notebooks(notebooks, quick=quick, lang=lang)
        except (ImportError, OSError, ValueError) as exc:
            usage_error(f"--notebooks: {exc}")
        for path in written:
            say(f"wrote {path}")
        raise typer.Exit(0)
    from ..tour import run_tour

    _check_outputs_in("--out", out_dir, ["index.html"], force)
    ok = run_tour(out_dir, quick=quick, console=console(), lang=lang)
    raise typer.Exit(0 if ok else 1)


@app.command()
def sweep(
    sweep_file: pathlib.Path = typer.Argument(
        ..., help="Sweep TOML file, or the name of a bundled sweep: tennis_racket, lagrange_apex, imu_monte_carlo."),
    scheduler: Optional[str] = typer.Option(None, "--scheduler", help="Existing Dask scheduler, tcp://host:8786."),
    workers: Optional[int] = typer.Option(None, "--workers", min=1, help="Worker processes of the local cluster."),
    output: Optional[pathlib.Path] = typer.Option(None, "-o", "--output", help="out.zarr | out.nc"),
    plot_file: Optional[pathlib.Path] = typer.Option(None, "--plot", help="Also draw the map: fig.png | .svg | .pdf"),
    stream: Optional[bool] = typer.Option(
        None, "--stream/--no-stream",
        help="Write each chunk into the .zarr output as it arrives, keeping about one chunk in memory "
             "(default: the file's stream key)."),
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
):
    """Run a parameter sweep on Dask; interrupted sweeps resume from their finished chunks."""
    from .._optional import require_all
    from ..io.bundled import suggestion
    from ..sweep import EXAMPLES, SweepError, example_path, load_sweep_file, plot_sweep, run_sweep_file
    from ..sweep.core import sweep_needs

    if not sweep_file.exists():
        if str(sweep_file) not in EXAMPLES:
            usage_error(f"{sweep_file}: no such file, and no bundled sweep of that name"
                        f"{suggestion(sweep_file, EXAMPLES)}")
        sweep_file = example_path(str(sweep_file))
    try:
        spec = load_sweep_file(sweep_file)
        option = "-o" if output is not None else f"{sweep_file.name}: output" if spec.output else "-o (default)"
        if output is None and spec.output is None:
            # results (and the checkpoint that lets an interrupted run resume) go to the working directory
            output = pathlib.Path(f"{sweep_file.stem}.zarr")
        target = output if output is not None else spec.output
        _check_output(option, target, force, (".zarr", ".nc"), store=target.suffix == ".zarr")
        _check_output("--plot", plot_file, force, _FIGURES)
        if (spec.stream if stream is None else stream) and target.suffix != ".zarr":
            usage_error(f"streaming writes the chunks into a .zarr output as they arrive, not {target.name}: "
                        "pass -o NAME.zarr, or --no-stream")
        # the sweep's packages and, for --plot, matplotlib, named together in one line before any chunk runs
        require_all([*sweep_needs(scheduler, target), *([("matplotlib", "plot")] if plot_file else [])],
                    feature="kreisel sweep")
        dataset = run_sweep_file(sweep_file, scheduler=scheduler, n_workers=workers, output=output,
                                 console=console(stderr=True), stream=stream)
    except SweepError as exc:
        error_line(exc)
        raise typer.Exit(1)
    except ValueError as exc:
        usage_error(str(exc))
    say(f"{math.prod(values.size for values in spec.grid.values())} points: "
        + ", ".join(f"{name} {values.size} values from {values.min():g} to {values.max():g}"
                    for name, values in spec.grid.items()))
    say(f"wrote {target}")
    if plot_file is not None:
        from .. import plot as plots

        with _writing("--plot", plot_file):
            plots.save(plot_sweep(dataset), plot_file)


@app.command()
def fit(
    recording: pathlib.Path = typer.Argument(
        ..., help="Gyroscope recording: phyphox CSV, export folder or zip, or a table t ωx ωy ωz; "
                  "'phone_toss' is a bundled example."),
    start: Optional[float] = typer.Option(None, "--start", help="Fit from this time on, s (as in the file)."),
    stop: Optional[float] = typer.Option(None, "--stop", help="Fit up to this time, s."),
    bias: bool = typer.Option(True, "--bias/--no-bias",
                              help="Also fit a constant gyroscope offset (as the viewer does; real gyros have one)."),
    units: Optional[str] = units_option(),
    align: bool = typer.Option(False, "--align", help="Also fit the rotation from sensor to principal axes."),
    plot_file: Optional[pathlib.Path] = typer.Option(None, "--plot", help="Draw data, fit and residuals: fit.png | .svg | .pdf"),
    json_file: Optional[pathlib.Path] = typer.Option(None, "--json", help="Write the results as JSON."),
    force: bool = typer.Option(False, "--force", help=_FORCE_HELP),
):
    """Fit the free (Euler) top to a gyroscope recording: moment ratios, ω0, bias, regime."""
    import json
    import warnings

    from .._fileio import atomic_output
    from .._optional import require_all
    from ..io.gyro import read_gyro
    from ..tops.fitting import NotFreeRotationWarning, fit_free_rotation
    from ._recordings import read_recording, recording_file
    from .fit import summary

    _check_output("--plot", plot_file, force, _FIGURES)
    if plot_file is not None:
        require_all([("matplotlib", "plot")], feature="kreisel fit --plot")   # before the fit
    _check_output("--json", json_file, force)
    recording = recording_file(recording)
    data = read_recording(read_gyro, recording, units=units)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotFreeRotationWarning)  # the summary reports it
        try:
            result = fit_free_rotation(data.t, data.omega, bias=bias, align=align,
                                       window=None if start is None and stop is None else (start, stop))
        except ValueError as exc:
            usage_error(f"{recording}: {exc}")
    # a refusal is one error line: the reader's notes only go with a recording that is fitted
    for note in data.notes:
        say(f"{recording}: {note}")
    for line in summary(result):
        console(stderr=not result.free_rotation).print(plain(line), soft_wrap=True)
    if plot_file is not None:
        from .. import plot as plots

        with _writing("--plot", plot_file):
            plots.save(plots.gyro_fit(result), plot_file)
    if json_file is not None:
        with _writing("--json", json_file), atomic_output(json_file) as tmp:
            tmp.write_text(json.dumps(result.to_dict(), indent=2) + "\n", encoding="utf-8")
    if not result.free_rotation:
        raise typer.Exit(1)


@app.command()
def serve(
    scenario: Optional[pathlib.Path] = typer.Argument(
        None, help="Scenario TOML to open in the viewer, or the name of a bundled one (`kreisel examples`)."),
    host: str = typer.Option("127.0.0.1", "--host", help="Interface to bind (loopback by default)."),
    port: int = typer.Option(0, "--port", help="Port; 0 picks a free one."),
    no_browser: bool = typer.Option(False, "--no-browser", help="Do not open a browser window."),
    recording: Optional[pathlib.Path] = typer.Option(
        None, "--recording", help="Recording to replay: with an accelerometer and a reference attitude, kreisel's "
                                  "estimated attitude beside the reference (see `kreisel attitude`); else the free "
                                  "top fitted to the gyro (see `kreisel fit`). 'phone_toss' and 'broad_07' are bundled."),
    token: Optional[str] = typer.Option(
        None, "--token", help="Secret the viewer's URL carries (default: a random one per server)."),
    no_token: bool = typer.Option(False, "--no-token", help="No secret: any local user or process may use the viewer."),
    allow_host: Optional[List[str]] = typer.Option(
        None, "--allow-host", help="Another name the viewer answers to, e.g. this machine's name on the network (repeatable)."),
):
    """Start the interactive 3D viewer in the browser."""
    from ..web import serve as run_server
    from ._recordings import not_a_recording, recording_file

    if recording is not None:
        recording = recording_file(recording)
        mistaken = not_a_recording(recording)
        if mistaken is not None:
            usage_error(f"--recording: {mistaken}")
    try:
        if no_token and token is not None:
            raise ValueError("give --token or --no-token, not both")
        run_server(scenario, host=host, port=port, open_browser=not no_browser, recording=recording,
                   token="" if no_token else token, allow_hosts=allow_host or ())
    except ValueError as exc:
        usage_error(str(exc))


@app.command(name="compile")
def compile_kernels(
    only: Optional[str] = typer.Option(
        None, "--only", metavar="TEXT",
        help="Only the parts whose name holds TEXT: 'integrator', 'array operation', 'quat_multiply', ..."),
):
    """Compile all of kreisel's kernels for this machine now, instead of on their first use."""
    import time

    from .._compiled.cache import cache_root
    from .compile import parts

    chosen = [(label, work) for label, work in parts() if only is None or only in label]
    if not chosen:
        usage_error(f"--only: no part's label holds {only!r}")
    count = f"{len(chosen)} part{'s' if len(chosen) != 1 else ''}"
    start = time.perf_counter()
    bar = progress()
    if bar is None:
        note(f"compiling {count} of kreisel for this machine (minutes for all of them)")
    with bar if bar is not None else contextlib.nullcontext():
        task = bar.add_task("compiling", total=len(chosen)) if bar is not None else None
        for label, work in chosen:
            if bar is not None:
                bar.update(task, description=f"compiling {label}")
            work()
            if bar is not None:
                bar.advance(task)
    say(f"compiled {count} in {time.perf_counter() - start:.0f} s into {cache_root()}")


app.command(name="attitude")(attitude_command)


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
    _Commands.announce_compiling = True
    app()
