"""Sweep files: a bundled sweep, its grid and constants described in TOML.

Schema (every key is checked before any work starts; an unknown key, a wrong
type or a value out of range raises :class:`SweepFileError` naming the file
and the key)::

    title = "..."                  # optional
    description = "..."            # optional
    model = "tennis_racket"        # "tennis_racket" | "lagrange_apex" | "imu_monte_carlo"
    chunk_size = 64                # optional, grid points per task (default 256)
    retries = 2                    # optional, resubmissions of a failing chunk
    output = "map.zarr"            # optional, .zarr or .nc, relative to the file

    [grid.<parameter>]             # one table per grid parameter of the model, each exactly one of:
    values = [1.0, 2.0]            #   explicit values
    start = 0.0                    #   num points from start to stop (spacing "linear" or "log")
    stop = 1.0
    num = 11
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
import tomllib
from importlib import resources

import numpy as np

from .core import sweep
from .models import MODELS

EXAMPLES = ("tennis_racket", "lagrange_apex", "imu_monte_carlo")

_TOP = {"title": "str", "description": "str", "model": "str", "chunk_size": "int", "retries": "int",
        "output": "str", "grid": "table", "constants": "table"}
_AXIS = {"values": "list", "start": "number", "stop": "number", "num": "int", "count": "int", "spacing": "str"}


class SweepFileError(ValueError):
    """A sweep file that does not follow the schema (names the file and the key)."""


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


def _type_ok(value, kind):
    if kind == "str":
        return isinstance(value, str)
    if kind == "bool":
        return isinstance(value, bool)
    if kind == "int":
        return isinstance(value, int) and not isinstance(value, bool)
    if kind == "number":
        return isinstance(value, (int, float)) and not isinstance(value, bool) and bool(np.isfinite(value))
    if kind == "table":
        return isinstance(value, dict)
    return isinstance(value, list)


_EXPECTED = {"str": "a string", "bool": "true or false", "int": "an integer", "number": "a finite number",
             "table": "a table", "list": "an array"}


def _checked(label, table, schema, prefix):
    for key, value in table.items():
        dotted = f"{prefix}{key}"
        if key not in schema:
            raise SweepFileError(f"{label}: {dotted}: unknown key (expected one of: {', '.join(sorted(schema))})")
        if not _type_ok(value, schema[key]):
            raise SweepFileError(f"{label}: {dotted}: expected {_EXPECTED[schema[key]]}, got {value!r}")
    return table


def _axis(label, name, table):
    prefix = f"grid.{name}."
    _checked(label, table, _AXIS, prefix)
    forms = [form for form in (("values",), ("start", "stop", "num"), ("count",)) if form[0] in table]
    if len(forms) != 1:
        raise SweepFileError(f"{label}: grid.{name}: give exactly one of values, start/stop/num or count")
    form = forms[0]
    extra = sorted(set(table) - set(form) - ({"spacing"} if form[0] == "start" else set()))
    if extra:
        raise SweepFileError(f"{label}: {prefix}{extra[0]}: not used with {'/'.join(form)}")
    missing = [key for key in form if key not in table]
    if missing:
        raise SweepFileError(f"{label}: grid.{name}: missing {missing[0]!r} (start, stop and num go together)")
    if form[0] == "values":
        values = table["values"]
        if not values or not all(_type_ok(v, "number") for v in values):
            raise SweepFileError(f"{label}: {prefix}values: expected a non-empty array of finite numbers")
        return np.array(values, dtype=int if all(isinstance(v, int) for v in values) else float)
    if form[0] == "count":
        if table["count"] < 1:
            raise SweepFileError(f"{label}: {prefix}count: must be positive, got {table['count']}")
        return np.arange(table["count"])
    if table["num"] < 1:
        raise SweepFileError(f"{label}: {prefix}num: must be positive, got {table['num']}")
    spacing = table.get("spacing", "linear")
    if spacing not in ("linear", "log"):
        raise SweepFileError(f"{label}: {prefix}spacing: expected 'linear' or 'log', got {spacing!r}")
    if spacing == "log":
        if table["start"] <= 0 or table["stop"] <= 0:
            raise SweepFileError(f"{label}: {prefix}start: log spacing needs positive start and stop")
        return np.geomspace(table["start"], table["stop"], table["num"])
    return np.linspace(table["start"], table["stop"], table["num"])


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
    kreisel.sweep.files.SweepFileError: apex.toml: constants.mass: unknown key (expected one of: I1, I3, mgl, theta0_deg)
    """
    label = str(path) if path is not None else "<sweep>"
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SweepFileError(f"{label}: {exc}") from None
    _checked(label, raw, _TOP, "")
    if "model" not in raw:
        raise SweepFileError(f"{label}: model: missing required key (one of {', '.join(MODELS)})")
    if raw["model"] not in MODELS:
        raise SweepFileError(f"{label}: model: expected one of {', '.join(map(repr, MODELS))}, got {raw['model']!r}")
    model = MODELS[raw["model"]]
    grid_table = raw.get("grid", {})
    _checked(label, grid_table, dict.fromkeys(model.grid, "table"), "grid.")
    missing = [name for name in model.grid if name not in grid_table]
    if missing:
        raise SweepFileError(f"{label}: grid.{missing[0]}: missing (model {raw['model']!r} sweeps "
                             f"{', '.join(model.grid)})")
    grid = {name: _axis(label, name, grid_table[name]) for name in model.grid}
    constants_table = raw.get("constants", {})
    _checked(label, constants_table, {name: kind for name, (kind, _) in model.constants.items()}, "constants.")
    constants = {name: default for name, (_, default) in model.constants.items() if default is not None}
    constants.update({k: float(v) if model.constants[k][0] == "number" else v for k, v in constants_table.items()})
    for key in ("chunk_size", "retries"):
        if key in raw and raw[key] < (1 if key == "chunk_size" else 0):
            raise SweepFileError(f"{label}: {key}: must be {'positive' if key == 'chunk_size' else 'non-negative'}")
    try:
        model.check(grid, constants)
    except ValueError as exc:
        raise SweepFileError(f"{label}: {exc}") from None
    output = None
    if "output" in raw:
        output = pathlib.Path(raw["output"])
        if output.suffix not in (".zarr", ".nc"):
            raise SweepFileError(f"{label}: output: must end in .zarr or .nc, got {raw['output']!r}")
        if path is not None and not output.is_absolute():
            output = pathlib.Path(path).parent / output
    return SweepFile(pathlib.Path(path) if path is not None else None, raw.get("title", ""),
                     raw.get("description", ""), raw["model"], grid, constants, raw.get("chunk_size", 256),
                     raw.get("retries", 2), output)


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
    path = pathlib.Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise SweepFileError(f"{path}: cannot read sweep file ({exc.strerror})") from None
    return parse_sweep_file(text, path)


def run_sweep_file(path, scheduler=None, n_workers=None, output=None, console=None, progress=None):
    """Run the sweep a TOML file describes; return its dataset (written to ``output`` if given).

    ``output`` overrides the file's own ``output`` key. The checkpoint lives
    next to the output (``<output>.chunks``), so running the same command
    again after an interruption resumes.

    Examples
    --------
    >>> ds = run_sweep_file(example_path("lagrange_apex"), scheduler="serial")  # doctest: +SKIP
    """
    spec = load_sweep_file(path)
    model = MODELS[spec.model]
    attrs = {"title": spec.title, "description": spec.description, "sweep_model": spec.model}
    return sweep(model.function, spec.grid, constants=spec.constants, chunk_size=spec.chunk_size,
                 scheduler=scheduler, n_workers=n_workers, output=output if output is not None else spec.output,
                 retries=spec.retries, progress=progress, console=console, variable_attrs=model.units, attrs=attrs)


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
