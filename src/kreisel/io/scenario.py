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
    ``[foucault]``: the Foucault pendulum of Theory §8.3.
``kind = "coning"``
    ``[coning]``: strapdown attitude under coning motion (Theory §3.5).

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

import numpy as np

from .._validation import check_allocation, memory_budget
from ..dynamics.engine import METHODS
from .bundled import scenario_path
from .schema import Document, Key, SchemaError, read_text

__all__ = ["ScenarioError", "Scenario", "load_scenario", "parse_scenario"]


class ScenarioError(SchemaError):
    """A scenario file that does not follow the schema (names file, key and line)."""

    unnamed = "<scenario>"


_ATTITUDE = {
    "quat": Key("quat", doc="unit quaternion [q0, q1, q2, q3], scalar first"),
    "rotvec": Key("vector3", doc="rotation vector ψ n in radians"),
    "matrix": Key("matrix3", doc="3x3 rotation matrix, body -> space"),
    "euler": Key("vector3", doc="Euler angles in the sequence `seq`, radians (at most 2π) unless `degrees`"),
    "seq": Key("str", default="ZXZ", doc="Euler sequence, uppercase intrinsic"),
    "degrees": Key("bool", default=False, doc="Euler angles in degrees"),
}

_TORQUE = {
    "kind": Key("str", required=True, choices=("gravity", "constant_body", "constant_space", "damping"),
                doc="which torque"),
    "weight": Key("number", positive=True, doc="m g in newtons (gravity)"),
    "lever": Key("vector3", doc="body vector from pivot to centre of mass, metres (gravity)"),
    "torque": Key("vector3", doc="torque in N m (constant_body, constant_space)"),
    "coefficient": Key("number", positive=True, doc="damping coefficient, N m s"),
}

_SCHEMA = {
    "title": Key("str", default="", doc="shown by the viewer and in reports (default: the file name)"),
    "description": Key("str", default="", doc="one sentence, listed by `kreisel examples`"),
    "kind": Key("str", default="rigid_body", choices=("rigid_body", "foucault", "coning"), doc="what to simulate"),
    "body": Key("table", schema={
        "moments": Key("vector3", doc="principal moments I1, I2, I3 in kg m^2"),
        "tensor": Key("matrix3", doc="inertia tensor in body axes, kg m^2"),
        "shape": Key("str", choices=("box", "solid_sphere", "solid_cylinder", "solid_ellipsoid"),
                     doc="homogeneous solid of mass `mass`"),
        "size": Key("vector3", doc="box edge lengths, m"),
        "radius": Key("number", positive=True, doc="sphere or cylinder radius, m"),
        "height": Key("number", positive=True, doc="cylinder height, m"),
        "semi_axes": Key("vector3", doc="ellipsoid semi-axes, m"),
        "mesh": Key("str", doc="closed triangle mesh file (STL, OBJ, PLY, ...), relative to the scenario"),
        "density": Key("number", positive=True, default=1.0, doc="mesh density, kg/m^3"),
        "mass": Key("number", positive=True, default=1.0, doc="mass of a shape or of the body, kg"),
    }),
    "initial": Key("table", schema={
        "omega": Key("vector3", required=True, doc="angular velocity in rad/s"),
        "frame": Key("str", default="body", choices=("body", "space"), doc="axes of `omega`"),
        "attitude": Key("table", schema=_ATTITUDE),
    }),
    "torque": Key("tables", schema=_TORQUE),
    "integration": Key("table", schema={
        "t_end": Key("number", required=True, positive=True, doc="final time, s"),
        "t_start": Key("number", default=0.0, doc="initial time, s"),
        "n_samples": Key("int", default=1001, minimum=2, doc="output times, evenly spaced from t_start to t_end"),
        "method": Key("str", choices=tuple(METHODS),
                      doc="integrator (default dop853)"),
        "dt": Key("number", positive=True, doc="step of fixed-step methods, s"),
    }),
    "foucault": Key("table", schema={
        "length": Key("number", required=True, positive=True, doc="pendulum length, m"),
        "latitude_deg": Key("number", required=True, doc="latitude in [-90, 90], degrees"),
        "duration": Key("number", required=True, positive=True, doc="simulated time, s"),
        "amplitude": Key("number", required=True, positive=True, doc="initial string angle from the vertical, rad"),
        "omega": Key("number", positive=True, doc="Earth's rate, rad/s"),
    }),
    "coning": Key("table", schema={
        "half_angle_deg": Key("number", required=True, positive=True, doc="half-cone angle below 90, degrees"),
        "rate_hz": Key("number", required=True, positive=True, doc="coning frequency Ω/2π"),
        "sample_time": Key("number", required=True, positive=True, doc="gyro sample interval, s"),
        "n_samples": Key("int", required=True, positive=True, doc="gyro samples, at least samples_per_update"),
        "samples_per_update": Key("int", default=2, choices=(1, 2, 3, 4), doc="N of the coning correction"),
    }),
}

#: Largest departure of ``initial.attitude.quat`` from unit length: a quaternion typed to 7 digits passes, one
#: further off is a mistake (a scalar-last or unnormalised quaternion), not rounding.
QUAT_TOLERANCE = 1e-6

# Peak memory of a run per output sample, measured with `kreisel simulate` (a rigid body: 175 bytes at 2e6 and
# 4e6 samples; times, integrator states, q, ω′ and the first integrals of the summary), with a margin. Coning
# holds time, the motion's q and increments, the estimate, the truth and the error.
_PEAK_BYTES_PER_SAMPLE = {"rigid_body": 24 * 8, "coning": 30 * 8}

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
    """Read and validate a scenario file or bundled scenario; see the module docstring for the schema.

    ``path`` is a file, or the name of a bundled scenario (``kreisel examples``
    lists them) when no file of that name exists. This and
    :func:`parse_scenario` are the one place scenarios are checked: the
    command line and the viewer both call them.

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
    >>> load_scenario("fast_top").title
    'Fast top'
    """
    try:
        path = scenario_path(path)
    except FileNotFoundError as exc:
        raise ScenarioError(str(exc)) from None
    return parse_scenario(read_text(path, ScenarioError, "scenario"), path)


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
    document = Document(text, path, ScenarioError)
    data = document.table(_SCHEMA)
    kind = data["kind"]
    if not document.raw:
        raise ScenarioError(f"{document.label}: the file is empty; a scenario needs [body], [initial] and "
                            "[integration] tables (`kreisel examples NAME` copies a complete one)")
    for name in _REQUIRED_TABLES[kind]:
        if name not in data:
            raise ScenarioError(f"{document.label}: kind = {kind!r} needs a [{name}] table")
    allowed = _REQUIRED_TABLES[kind] + _OPTIONAL_TABLES.get(kind, ())
    for name, spec in _SCHEMA.items():
        if spec.kind in ("table", "tables") and name in data and name not in allowed:
            raise ScenarioError(f"{document.label}: [{name}] does not belong to a scenario of kind = {kind!r}")
    if kind == "rigid_body":
        _check_body(document, data["body"], path)
        if data["initial"].get("attitude"):
            _check_attitude(document, data["initial"]["attitude"])
        for index, entry in enumerate(data.get("torque", [])):
            _check_torque(document, entry, ("torque", index))
        _check_integration(document, data["integration"])
    elif kind == "foucault":
        _check_foucault(document, data["foucault"])
    elif kind == "coning":
        _check_coning(document, data["coning"])
    return Scenario(kind, data, pathlib.Path(path) if path is not None else None)


_SHAPE_NEEDS = {"box": ("size",), "solid_sphere": ("radius",), "solid_cylinder": ("radius", "height"),
                "solid_ellipsoid": ("semi_axes",)}
_TORQUE_NEEDS = {"gravity": ("weight", "lever"), "constant_body": ("torque",), "constant_space": ("torque",),
                 "damping": ("coefficient",)}


def _check_body(document, body, path):
    source = document.exactly_one(body, ("moments", "tensor", "shape", "mesh"), ("body",))
    if source == "mesh":
        mesh = pathlib.Path(path).parent / body["mesh"] if path is not None else pathlib.Path(body["mesh"])
        if not mesh.is_file():
            document.fail(("body", "mesh"), f"expected a mesh file, but {str(mesh)!r} does not exist")
        return
    from ..inertia import RigidBody

    if source == "shape":
        needs = _SHAPE_NEEDS[body["shape"]]
        for name in needs:
            if name not in body:
                document.fail(("body", "shape"), f"shape {body['shape']!r} needs body.{name}")
        try:
            getattr(RigidBody, body["shape"])(body["mass"], *(body[name] for name in needs))
        except ValueError as exc:
            document.fail(("body", needs[0]), f"not a physical {body['shape'].replace('_', ' ')}: {exc}")
        return
    try:
        RigidBody(body[source], mass=body["mass"])
    except ValueError as exc:
        document.fail(("body", source), f"not a physical rigid body: {exc}")


_ATTITUDE_EXPECTED = {
    "quat": "a unit quaternion [q0, q1, q2, q3], scalar first",
    "matrix": "a rotation matrix (orthonormal rows, determinant +1), body -> space",
    "rotvec": "a rotation vector in radians",
    "euler": "Euler angles",
}


def _check_attitude(document, attitude):
    """Convert the attitude as the run will, so that every value the run would refuse is refused here."""
    from ..so3.euler import parse_sequence
    from ..so3.rotation import Rotation

    key = ("initial", "attitude")
    source = document.exactly_one(attitude, ("quat", "rotvec", "matrix", "euler"), key)
    if source != "euler":
        for name in ("seq", "degrees"):
            if name in document.raw.get("initial", {}).get("attitude", {}):
                document.fail(key + (name,), f"only used with euler, not with {source}")
    if source == "euler":
        try:
            parse_sequence(attitude["seq"])
        except ValueError as exc:
            document.fail(key + ("seq",), "expected an Euler sequence of 3 letters x, y, z, all uppercase "
                                          "(intrinsic) or all lowercase (extrinsic), no axis twice in a row "
                                          f"(e.g. 'ZXZ', 'xyz'): {_reason(exc)}")
    if source == "euler" and not attitude["degrees"]:
        angles = attitude["euler"]
        if np.any(np.abs(angles) > 2 * np.pi):
            document.fail(key + ("euler",), f"expected angles in radians, at most 2π = 6.283 in size, got "
                                            f"{_listed(angles)}: for degrees set degrees = true")
    if source == "quat":
        norm = float(np.linalg.norm(attitude["quat"]))
        if not abs(norm - 1.0) <= QUAT_TOLERANCE:
            document.fail(key + ("quat",), f"expected a unit quaternion (norm within {QUAT_TOLERANCE:g} of 1), got "
                                           f"{_listed(attitude['quat'])} of norm {norm:.9g}: divide it by its norm "
                                           "or give rotvec, matrix or euler")
    try:
        if source == "euler":
            Rotation.from_euler(attitude["seq"], attitude["euler"], degrees=attitude["degrees"])
        elif source == "quat":
            Rotation.from_quat(attitude["quat"])
        elif source == "matrix":
            Rotation.from_matrix(attitude["matrix"])
        else:
            Rotation.from_rotvec(attitude["rotvec"])
    except ValueError as exc:
        document.fail(key + (source,), f"expected {_ATTITUDE_EXPECTED[source]}: {_reason(exc)}")


def _listed(values):
    return "[" + ", ".join(f"{float(v):g}" for v in values) + "]"


def _reason(exc):
    """The library's message without its argument name, which the scenario key replaces."""
    text = str(exc)
    first, _, rest = text.partition(" ")
    return rest if rest and first.isidentifier() and rest.startswith(("must", "may", "has", "is")) else text


def _check_memory(document, key, count, bytes_per_sample):
    """Refuse, before any work, a run whose arrays would not fit in memory (``bytes_per_sample`` at its peak)."""
    try:
        check_allocation(count * bytes_per_sample, f"{count} samples")
    except ValueError as exc:
        document.fail(key, f"expected at most {memory_budget() // bytes_per_sample} samples on this machine: {exc}; "
                           "lower n_samples, or split the run into consecutive scenarios")


def _check_coning(document, spec):
    if spec["half_angle_deg"] >= 90.0:
        document.fail(("coning", "half_angle_deg"), f"expected a half-angle below 90 degrees, got {spec['half_angle_deg']:g}")
    if spec["n_samples"] < spec["samples_per_update"]:
        document.fail(("coning", "n_samples"), f"expected at least samples_per_update = {spec['samples_per_update']} "
                                               f"samples, got {spec['n_samples']}")
    _check_memory(document, ("coning", "n_samples"), spec["n_samples"], _PEAK_BYTES_PER_SAMPLE["coning"])


def _check_integration(document, grid):
    from ..dynamics.engine import ADAPTIVE

    _check_memory(document, ("integration", "n_samples"), grid["n_samples"], _PEAK_BYTES_PER_SAMPLE["rigid_body"])

    method = grid.get("method", "dop853")
    if method in ADAPTIVE and "dt" in grid:
        document.fail(("integration", "dt"), f"only used by fixed-step methods; {method!r} chooses its own steps")
    if method not in ADAPTIVE and "dt" not in grid:
        document.fail(("integration", "method"), f"method {method!r} is fixed-step: give integration.dt (seconds)")


def _check_foucault(document, spec):
    if not -90.0 <= spec["latitude_deg"] <= 90.0:
        document.fail(("foucault", "latitude_deg"), f"expected a latitude in [-90, 90] degrees, got {spec['latitude_deg']:g}")
    if spec["amplitude"] >= 1.5707963267948966:
        document.fail(("foucault", "amplitude"), f"expected an angle below pi/2 rad, got {spec['amplitude']:g}")


def _check_torque(document, entry, key):
    needed = _TORQUE_NEEDS[entry["kind"]]
    for name in needed:
        if name not in entry:
            document.fail(key + ("kind",), f"torque kind {entry['kind']!r} needs {name!r}")
    extra = sorted(set(entry) - set(needed) - {"kind"})
    if extra:
        document.fail(key + (extra[0],), f"not used by torque kind {entry['kind']!r}")
