"""Sweep files: a bundled sweep, its grid and constants described in TOML.

Schema (every key is checked before any work starts; an unknown key, a wrong
type or a value out of range raises :class:`SweepFileError` naming the file,
the key and its line; the checks are those of :mod:`kreisel.io.schema`)::

    title = "..."                  # optional
    description = "..."            # optional
    model = "tennis_racket"        # "tennis_racket" | "lagrange_apex" | "imu_monte_carlo"
    chunk_size = 64                # optional, grid points per task (default 256)
    retries = 2                    # optional, resubmissions of a failing chunk
    output = "map.zarr"            # optional, .zarr or .nc, relative to the file
    stream = false                 # optional, write chunks into the .zarr output as they arrive

    [grid.<parameter>]             # one table per grid parameter of the model, each exactly one of:
    values = [1.0, 2.0]            #   explicit values
    start = 0.0                    #   num points from start to stop
    stop = 1.0
    num = 11
    spacing = "log"                #   optional with start/stop/num: "linear" (default) or "log"
    count = 20                     #   the integers 0 .. count-1 (Monte Carlo trials)

    [constants]                    # optional, the model's keyword constants

Examples
--------
>>> sweep_file = load_sweep_file(example_path("lagrange_apex"))
>>> sweep_file.model, list(sweep_file.grid)
('lagrange_apex', ['phi_dot', 'psi_dot'])
"""

from __future__ import annotations

import dataclasses
import pathlib
from importlib import resources

import numpy as np

from ..io.schema import Document, Key, SchemaError, read_text
from .core import sweep
from .models import MODELS

__all__ = [
    "SweepFileError",
    "SweepFile",
    "example_path",
    "parse_sweep_file",
    "load_sweep_file",
    "run_sweep_file",
    "plot_sweep",
    "EXAMPLES",
]

EXAMPLES = ("tennis_racket", "lagrange_apex", "imu_monte_carlo")

_TOP = {
    "title": Key("str", default=""),
    "description": Key("str", default=""),
    "model": Key("str", required=True, choices=tuple(MODELS), doc=f"one of {', '.join(MODELS)}"),
    "chunk_size": Key("int", default=256, positive=True, doc="grid points per task"),
    "retries": Key("int", default=2, minimum=0, doc="resubmissions of a failing chunk"),
    "output": Key("str", doc=".zarr or .nc, relative to the file"),
    "stream": Key("bool", default=False, doc="write each chunk into the .zarr output as it arrives and keep none "
                  "in memory, which then holds about one chunk whatever the sweep's size"),
    "grid": Key("table"),  # its keys depend on the model: checked once the model is known
    "constants": Key("table"),
}
_AXIS = {
    "values": Key("numbers"),
    "start": Key("number"),
    "stop": Key("number"),
    "num": Key("int", positive=True),
    "count": Key("int", positive=True),
    "spacing": Key("str", choices=("linear", "log")),
}
_FORMS = {"values": ("values",), "start": ("start", "stop", "num"), "count": ("count",)}


class SweepFileError(SchemaError):
    """A sweep file that does not follow the schema (names the file, the key and its line)."""

    unnamed = "<sweep>"


@dataclasses.dataclass(frozen=True)
class SweepFile:
    """A validated sweep file: model name, grid arrays, constants and run options.

    Examples
    --------
    >>> spec = load_sweep_file(example_path("tennis_racket"))
    >>> spec.model, spec.chunk_size, spec.grid["middle_moment"].round(2).tolist()[:3]
    ('tennis_racket', 16, [1.05, 1.15, 1.25])
    >>> round(float(spec.grid["tilt_deg"][-1] / spec.grid["tilt_deg"][-2]), 6) == round(float(spec.grid["tilt_deg"][1] / spec.grid["tilt_deg"][0]), 6)
    True
    """

    path: pathlib.Path | None
    title: str
    description: str
    model: str
    grid: dict
    constants: dict
    chunk_size: int
    retries: int
    output: pathlib.Path | None
    stream: bool = False


def example_path(name):
    """Path of the bundled sweep file ``name`` (one of :data:`EXAMPLES`).

    Examples
    --------
    >>> example_path("lagrange_apex").name
    'lagrange_apex.toml'
    >>> sorted(EXAMPLES)
    ['imu_monte_carlo', 'lagrange_apex', 'tennis_racket']
    """
    if name not in EXAMPLES:
        raise ValueError(f"name must be one of {', '.join(EXAMPLES)}, got {name!r}")
    return pathlib.Path(str(resources.files("kreisel.sweep.examples").joinpath(f"{name}.toml")))


def _axis(document, name, axis):
    key = ("grid", name)
    form = _FORMS[document.exactly_one(axis, tuple(_FORMS), key)]
    extra = sorted(set(axis) - set(form) - ({"spacing"} if form[0] == "start" else set()))
    if extra:
        document.fail(key + (extra[0],), f"not used with {'/'.join(form)}")
    missing = [name for name in form if name not in axis]
    if missing:
        document.fail(key, f"missing {missing[0]!r} (start, stop and num go together)")
    if form[0] == "values":
        return axis["values"]
    if form[0] == "count":
        return np.arange(axis["count"])
    if axis.get("spacing", "linear") == "log":
        if axis["start"] <= 0 or axis["stop"] <= 0:
            document.fail(key + ("start",), "log spacing needs positive start and stop")
        return np.geomspace(axis["start"], axis["stop"], axis["num"])
    return np.linspace(axis["start"], axis["stop"], axis["num"])


def parse_sweep_file(text, path=None):
    """Validate sweep TOML ``text``; ``path`` labels messages and anchors a relative ``output``.

    Examples
    --------
    Grids are built from ``values``, ``start/stop/num`` or ``count``; a key the
    model does not know is refused before any work:

    >>> text = '''
    ... model = "lagrange_apex"
    ... [grid.phi_dot]
    ... values = [0.0, 1.0]
    ... [grid.psi_dot]
    ... start = 2.0
    ... stop = 12.0
    ... num = 3
    ... '''
    >>> parse_sweep_file(text).grid["psi_dot"].tolist()
    [2.0, 7.0, 12.0]
    >>> parse_sweep_file(text + "[constants]\\nmass = 1.0\\n", "apex.toml")
    Traceback (most recent call last):
        ...
    kreisel.sweep.files.SweepFileError: apex.toml:10: constants.mass: unknown key (expected one of: I1, I3, mgl, theta0_deg)
    """
    document = Document(text, path, SweepFileError)
    data = document.table(_TOP)
    model = MODELS[data["model"]]
    axes_schema = {name: Key("table", required=True, schema=_AXIS, doc=f"model {data['model']!r} sweeps "
                             f"{', '.join(model.grid)}") for name in model.grid}
    axes = document.table(axes_schema, data.get("grid", {}), ("grid",))
    grid = {name: _axis(document, name, axis) for name, axis in axes.items()}
    constants_schema = {name: Key(kind, default=default, doc=model.notes.get(name, ""))
                        for name, (kind, default) in model.constants.items()}
    constants = document.table(constants_schema, data.get("constants", {}), ("constants",))
    try:
        model.check(grid, constants)
    except ValueError as exc:
        raise SweepFileError(f"{document.label}: {exc}") from None
    output = None
    if "output" in data:
        output = pathlib.Path(data["output"])
        if output.suffix not in (".zarr", ".nc"):
            document.fail(("output",), f"must end in .zarr or .nc, got {data['output']!r}")
        if path is not None and not output.is_absolute():
            output = pathlib.Path(path).parent / output
    if data["stream"] and output is not None and output.suffix != ".zarr":
        document.fail(("stream",), f"streams into a .zarr output, not {data['output']!r}")
    return SweepFile(pathlib.Path(path) if path is not None else None, data["title"], data["description"],
                     data["model"], grid, constants, data["chunk_size"], data["retries"], output, data["stream"])


def load_sweep_file(path):
    """Read and validate a sweep file (see the module docstring for the schema).

    Examples
    --------
    The bundled Lagrange-top map: 25 × 11 initial precession and spin rates:

    >>> spec = load_sweep_file(example_path("lagrange_apex"))
    >>> spec.title, {name: axis.size for name, axis in spec.grid.items()}
    ('Lagrange-top apex-locus map', {'phi_dot': 25, 'psi_dot': 11})
    >>> spec.constants
    {'I1': 1.0, 'I3': 0.5, 'mgl': 1.0, 'theta0_deg': 60.0}
    """
    return parse_sweep_file(read_text(path, SweepFileError, "sweep file"), path)


def run_sweep_file(path, scheduler=None, n_workers=None, output=None, console=None, progress=None, stream=None):
    """Run the sweep a TOML file describes; return its dataset (written to ``output`` if given).

    ``output`` overrides the file's own ``output`` key, ``stream`` (True or
    False) its ``stream`` key: a streamed sweep writes each chunk into the
    ``.zarr`` output as it arrives and returns the dataset reading it lazily
    (see :func:`kreisel.sweep.sweep`). The checkpoint lives next to the output
    (``<output>.chunks``), so running the same command again after an
    interruption resumes.

    Examples
    --------
    >>> ds = run_sweep_file(example_path("lagrange_apex"), scheduler="serial")  # doctest: +SKIP
    """
    spec = load_sweep_file(path)
    model = MODELS[spec.model]
    attrs = {"title": spec.title, "description": spec.description, "sweep_model": spec.model}
    return sweep(model.function, spec.grid, constants=spec.constants, chunk_size=spec.chunk_size,
                 scheduler=scheduler, n_workers=n_workers, output=output if output is not None else spec.output,
                 retries=spec.retries, progress=progress, console=console, variable_attrs=model.units, attrs=attrs,
                 stream=spec.stream if stream is None else stream)


def plot_sweep(dataset):
    """The bundled plot of a dataset made by :func:`run_sweep_file` (a matplotlib Figure).

    Examples
    --------
    The figure is chosen by the dataset's ``sweep_model`` attribute, which
    :func:`run_sweep_file` sets:

    >>> from kreisel.sweep import lagrange_apex_locus, sweep
    >>> ds = sweep(lagrange_apex_locus, {"phi_dot": [-1.0, 0.0, 2.0], "psi_dot": [4.0, 10.0]}, scheduler="serial")
    >>> plot_sweep(ds)
    Traceback (most recent call last):
        ...
    ValueError: dataset: attribute sweep_model must name a bundled sweep, got None
    >>> ds.attrs["sweep_model"] = "lagrange_apex"
    >>> type(plot_sweep(ds)).__name__
    'Figure'
    """
    name = dataset.attrs.get("sweep_model")
    if name not in MODELS:
        raise ValueError(f"dataset: attribute sweep_model must name a bundled sweep, got {name!r}")
    return MODELS[name].plot(dataset)
