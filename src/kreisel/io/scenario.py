"""Scenario files: a whole simulation described in TOML.

A scenario names what to simulate and how; :func:`load_scenario` checks every
key and value against the schema below *before* any work starts and names
the file, the key, its line and what was expected when something is wrong.

Three kinds of scenario exist:

``kind = "rigid_body"`` (default)
    ``[body]`` (``moments`` | ``tensor`` | ``shape`` with its dimensions |
    ``mesh``), ``[initial]`` (``omega``, ``frame``, ``[initial.attitude]``),
    optional ``[[torque]]`` entries, ``[integration]``.
``kind = "foucault"``
    ``[foucault]``: the Foucault pendulum of seed 八.3.
``kind = "coning"``
    ``[coning]``: strapdown attitude under coning motion (seed 三.5).

Examples
--------
>>> text = '''
... [body]
... moments = [1.0, 2.0, 3.0]
... [initial]
... omega = [0.01, 1.0, 0.0]
... [integration]
... t_end = 10.0
... '''
>>> scenario = parse_scenario(text)
>>> scenario.kind, scenario.data["integration"]["n_samples"]
('rigid_body', 1001)
"""

from __future__ import annotations

import dataclasses
import pathlib
import re
import tomllib

import numpy as np


class ScenarioError(ValueError):
    """A scenario file that does not follow the schema (names file, key and line)."""


_NUMBER = (int, float)


@dataclasses.dataclass(frozen=True)
class _Key:
    kind: str  # "number", "int", "str", "bool", "vector3", "matrix3", "quat", "table", "tables"
    required: bool = False
    default: object = None
    choices: tuple = ()
    positive: bool = False
    schema: dict | None = None  # for tables
    doc: str = ""


_ATTITUDE = {
    "quat": _Key("quat", doc="unit quaternion [q0, q1, q2, q3], scalar first"),
    "rotvec": _Key("vector3", doc="rotation vector ψ n in radians"),
    "matrix": _Key("matrix3", doc="3x3 rotation matrix, body -> space"),
    "euler": _Key("vector3", doc="Euler angles in the sequence `seq`"),
    "seq": _Key("str", default="ZXZ", doc="Euler sequence, uppercase intrinsic"),
    "degrees": _Key("bool", default=False, doc="Euler angles in degrees"),
}

_TORQUE = {
    "kind": _Key("str", required=True, choices=("gravity", "constant_body", "constant_space", "damping")),
    "weight": _Key("number", positive=True, doc="m g in newtons (gravity)"),
    "lever": _Key("vector3", doc="body vector from pivot to centre of mass, metres (gravity)"),
    "torque": _Key("vector3", doc="torque in N m (constant_body, constant_space)"),
    "coefficient": _Key("number", positive=True, doc="damping coefficient, N m s"),
}

_SCHEMA = {
    "title": _Key("str", default=""),
    "description": _Key("str", default=""),
    "kind": _Key("str", default="rigid_body", choices=("rigid_body", "foucault", "coning")),
    "body": _Key("table", schema={
        "moments": _Key("vector3", doc="principal moments I1, I2, I3 in kg m^2"),
        "tensor": _Key("matrix3", doc="inertia tensor in body axes, kg m^2"),
        "shape": _Key("str", choices=("box", "solid_sphere", "solid_cylinder", "solid_ellipsoid")),
        "size": _Key("vector3", doc="box edge lengths, m"),
        "radius": _Key("number", positive=True),
        "height": _Key("number", positive=True),
        "semi_axes": _Key("vector3", doc="ellipsoid semi-axes, m"),
        "mesh": _Key("str", doc="closed triangle mesh file (STL, OBJ, PLY, ...), relative to the scenario"),
        "density": _Key("number", positive=True, default=1.0),
        "mass": _Key("number", positive=True, default=1.0),
    }),
    "initial": _Key("table", schema={
        "omega": _Key("vector3", required=True, doc="angular velocity in rad/s"),
        "frame": _Key("str", default="body", choices=("body", "space")),
        "attitude": _Key("table", schema=_ATTITUDE),
    }),
    "torque": _Key("tables", schema=_TORQUE),
    "integration": _Key("table", schema={
        "t_end": _Key("number", required=True, positive=True, doc="final time, s"),
        "t_start": _Key("number", default=0.0),
        "n_samples": _Key("int", default=1001, positive=True),
        "method": _Key("str", choices=("dop853", "splitting", "dmv", "rkmk4", "midpoint", "rk4", "scipy")),
        "dt": _Key("number", positive=True, doc="step of fixed-step methods, s"),
    }),
    "foucault": _Key("table", schema={
        "length": _Key("number", required=True, positive=True, doc="pendulum length, m"),
        "latitude_deg": _Key("number", required=True),
        "duration": _Key("number", required=True, positive=True, doc="s"),
        "amplitude": _Key("number", required=True, positive=True, doc="initial string angle from the vertical, rad"),
        "omega": _Key("number", positive=True, doc="Earth's rate, rad/s"),
    }),
    "coning": _Key("table", schema={
        "half_angle_deg": _Key("number", required=True, positive=True),
        "rate_hz": _Key("number", required=True, positive=True, doc="coning frequency Ω/2π"),
        "sample_time": _Key("number", required=True, positive=True, doc="gyro sample interval, s"),
        "n_samples": _Key("int", required=True, positive=True),
        "samples_per_update": _Key("int", default=2, choices=(1, 2, 3, 4)),
    }),
}

_REQUIRED_TABLES = {"rigid_body": ("body", "initial", "integration"), "foucault": ("foucault",),
                    "coning": ("coning",)}
_OPTIONAL_TABLES = {"rigid_body": ("torque",)}


@dataclasses.dataclass
class Scenario:
    """A validated scenario: ``kind``, the checked ``data`` and the file it came from.

    Examples
    --------
    Without a title or a file, the kind names the scenario:

    >>> scenario = parse_scenario('''
    ... kind = "foucault"
    ... [foucault]
    ... length = 67.0
    ... latitude_deg = 48.85
    ... duration = 60.0
    ... amplitude = 0.05
    ... ''')
    >>> scenario.kind, scenario.title, scenario.path is None
    ('foucault', 'foucault', True)
    """

    kind: str
    data: dict
    path: pathlib.Path | None = None

    @property
    def title(self):
        return self.data["title"] or (self.path.stem if self.path else self.kind)


def load_scenario(path):
    """Read and validate a scenario file; see the module docstring for the schema.

    Raises
    ------
    ScenarioError
        Unreadable file, TOML syntax error, unknown key, wrong type, missing
        required key or non-physical value, with file, key and line.

    Examples
    --------
    The bundled scenarios load like any file:

    >>> from kreisel.io import example_path
    >>> scenario = load_scenario(example_path("tennis_racket"))
    >>> scenario.kind, scenario.title, scenario.path.name
    ('rigid_body', 'Tennis racket (Dzhanibekov) flips', 'tennis_racket.toml')
    >>> scenario.data["body"]["moments"].tolist(), scenario.data["initial"]["frame"]
    ([1.0, 2.0, 3.0], 'body')
    """
    path = pathlib.Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ScenarioError(f"{path}: cannot read scenario ({exc.strerror})") from None
    return parse_scenario(text, path)


def parse_scenario(text, path=None):
    """Validate scenario TOML ``text`` (``path`` only labels the messages).

    Examples
    --------
    Defaults are filled in; a non-physical value is refused with its key and line:

    >>> text = '''
    ... [body]
    ... moments = [1.0, 2.0, 3.0]
    ... [initial]
    ... omega = [0.0, 0.0, 1.0]
    ... [integration]
    ... t_end = -1.0
    ... '''
    >>> parse_scenario(text.replace("-1.0", "5.0")).data["integration"]
    {'t_end': 5.0, 't_start': 0.0, 'n_samples': 1001}
    >>> parse_scenario(text, "spin.toml")
    Traceback (most recent call last):
        ...
    kreisel.io.scenario.ScenarioError: spin.toml:7: integration.t_end: must be positive, got -1.0
    """
    label = str(path) if path is not None else "<scenario>"
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(f"{label}: {exc}") from None
    checker = _Checker(label, text)
    data = checker.table(raw, _SCHEMA, "")
    kind = data["kind"]
    for name in _REQUIRED_TABLES[kind]:
        if name not in data:
            raise ScenarioError(f"{label}: kind = {kind!r} needs a [{name}] table")
    allowed = _REQUIRED_TABLES[kind] + _OPTIONAL_TABLES.get(kind, ())
    for name, spec in _SCHEMA.items():
        if spec.kind in ("table", "tables") and name in data and name not in allowed:
            raise ScenarioError(f"{label}: [{name}] does not belong to a scenario of kind = {kind!r}")
    if kind == "rigid_body":
        checker.body(data["body"])
        checker.attitude(data["initial"].get("attitude", {}))
        for i, entry in enumerate(data.get("torque", [])):
            checker.torque(entry, i)
    return Scenario(kind, data, pathlib.Path(path) if path is not None else None)


class _Checker:
    def __init__(self, label, text):
        self.label = label
        self.lines = text.splitlines()

    def fail(self, key, message):
        line = self.line_of(key)
        where = f":{line}" if line else ""
        raise ScenarioError(f"{self.label}{where}: {key or 'scenario'}: {message}")

    def line_of(self, dotted):
        """First line that assigns the last component of ``dotted`` (TOML keeps no positions)."""
        if not dotted:
            return None
        last = re.escape(dotted.rsplit(".", 1)[-1].split("[")[0])
        pattern = re.compile(rf"^\s*(\[\[?\s*)?([\w.]*\.)?{last}\s*(=|\]|\.)")
        for number, line in enumerate(self.lines, start=1):
            if pattern.match(line):
                return number
        return None

    def table(self, raw, schema, prefix):
        if not isinstance(raw, dict):
            self.fail(prefix, "expected a table")
        unknown = sorted(set(raw) - set(schema))
        if unknown:
            known = ", ".join(sorted(schema))
            self.fail(_join(prefix, unknown[0]), f"unknown key (expected one of: {known})")
        out = {}
        for name, spec in schema.items():
            key = _join(prefix, name)
            if name not in raw:
                if spec.required:
                    self.fail(prefix or name, f"missing required key {name!r}" + (f" ({spec.doc})" if spec.doc else ""))
                if spec.default is not None:
                    out[name] = spec.default
                continue
            out[name] = self.value(raw[name], spec, key)
        return out

    def value(self, value, spec, key):
        kind = spec.kind
        if kind == "table":
            return self.table(value, spec.schema, key)
        if kind == "tables":
            if not isinstance(value, list):
                self.fail(key, f"expected an array of tables [[{key}]]")
            return [self.table(v, spec.schema, f"{key}[{i}]") for i, v in enumerate(value)]
        if kind == "str":
            if not isinstance(value, str):
                self.fail(key, f"expected a string, got {value!r}")
        elif kind == "bool":
            if not isinstance(value, bool):
                self.fail(key, f"expected true or false, got {value!r}")
        elif kind == "int":
            if isinstance(value, bool) or not isinstance(value, int):
                self.fail(key, f"expected an integer, got {value!r}")
        elif kind == "number":
            if isinstance(value, bool) or not isinstance(value, _NUMBER) or not np.isfinite(value):
                self.fail(key, f"expected a finite number, got {value!r}")
            value = float(value)
        else:
            shape = {"vector3": (3,), "quat": (4,), "matrix3": (3, 3)}[kind]
            array = _numeric_array(value)
            if array is None or array.shape != shape or not np.all(np.isfinite(array)):
                self.fail(key, f"expected {_describe(shape)} of finite numbers, got {value!r}")
            return array
        if spec.choices and value not in spec.choices:
            self.fail(key, f"expected one of {', '.join(map(repr, spec.choices))}, got {value!r}")
        if spec.positive and value <= 0:
            self.fail(key, f"must be positive, got {value!r}")
        return value

    def exactly_one(self, table, names, prefix):
        given = [n for n in names if n in table]
        if len(given) != 1:
            self.fail(prefix, f"give exactly one of {', '.join(names)} (got {', '.join(given) or 'none'})")
        return given[0]

    def body(self, body):
        source = self.exactly_one(body, ("moments", "tensor", "shape", "mesh"), "body")
        if source == "shape":
            needed = {"box": ("size",), "solid_sphere": ("radius",), "solid_cylinder": ("radius", "height"),
                      "solid_ellipsoid": ("semi_axes",)}[body["shape"]]
            for name in needed:
                if name not in body:
                    self.fail("body.shape", f"shape {body['shape']!r} needs body.{name}")
        if source in ("moments", "tensor"):
            from ..inertia import RigidBody

            try:
                RigidBody(body[source], mass=body["mass"])
            except ValueError as exc:
                self.fail(f"body.{source}", f"not a physical rigid body: {exc}")

    def attitude(self, attitude):
        if attitude:
            self.exactly_one(attitude, ("quat", "rotvec", "matrix", "euler"), "initial.attitude")

    def torque(self, entry, index):
        needed = {"gravity": ("weight", "lever"), "constant_body": ("torque",), "constant_space": ("torque",),
                  "damping": ("coefficient",)}[entry["kind"]]
        for name in needed:
            if name not in entry:
                self.fail(f"torque[{index}].kind", f"torque kind {entry['kind']!r} needs {name!r}")
        extra = set(entry) - set(needed) - {"kind"}
        if extra:
            self.fail(f"torque[{index}].{sorted(extra)[0]}", f"not used by torque kind {entry['kind']!r}")


def _join(prefix, name):
    return f"{prefix}.{name}" if prefix else name


def _describe(shape):
    return "a list of 3" if shape == (3,) else "a list of 4" if shape == (4,) else "a 3x3 nested list"


def _numeric_array(value):
    if not isinstance(value, list):
        return None
    flat = np.array(value, dtype=object).ravel()
    if any(isinstance(v, bool) or not isinstance(v, _NUMBER) for v in flat):
        return None
    try:
        return np.array(value, dtype=np.float64)
    except ValueError:
        return None
