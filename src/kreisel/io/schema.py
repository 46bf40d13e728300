"""One checker for every TOML file format of kreisel (scenarios, sweep files).

A format describes its keys with :class:`Key` specs in nested dicts (the
schema); :class:`Document` parses the TOML text, checks tables against the
schema (unknown key, wrong type, missing required key, value not among the
choices, non-positive value), fills in defaults and raises the format's own
error class (a subclass of :class:`SchemaError`) naming the file, the dotted
key, its line and what was expected. Rules that tie several keys together
(exactly one of, needs) stay with the format and report through
:meth:`Document.fail`, so they name the line too.

TOML parsers keep no positions, so :class:`Document` finds lines with a light
scanner of table headers and ``key =`` assignments; a key it cannot place
(inside an inline table, say) is reported at the line of the nearest
enclosing key or table, or without a line.

Examples
--------
>>> class RecipeError(SchemaError):
...     unnamed = "<recipe>"
>>> schema = {"flour": Key("number", required=True, positive=True, doc="grams"),
...           "oven": Key("table", schema={"mode": Key("str", default="fan", choices=("fan", "top"))})}
>>> Document("flour = 500\\n[oven]\\n", error=RecipeError).table(schema)
{'flour': 500.0, 'oven': {'mode': 'fan'}}
>>> Document("flour = 500\\n[oven]\\nmode = 'grill'\\n", "bread.toml", RecipeError).table(schema)
Traceback (most recent call last):
    ...
kreisel.io.schema.RecipeError: bread.toml:3: oven.mode: expected one of 'fan', 'top', got 'grill'
"""

from __future__ import annotations

import dataclasses
import math
import pathlib
import re
import sys
import tomllib

import numpy as np

__all__ = ["SchemaError", "Key", "read_text", "Document", "dotted"]


class SchemaError(ValueError):
    """A TOML file that does not follow its schema; each format subclasses it.

    ``unnamed`` labels messages about text that came from no file.
    """

    unnamed = "<toml>"


_SHAPES = {"vector3": (3,), "quat": (4,), "matrix3": (3, 3)}
_EXPECTED = {
    "str": "a string", "bool": "true or false", "int": "an integer", "number": "a finite number",
    "vector3": "a list of 3 finite numbers", "quat": "a list of 4 finite numbers",
    "matrix3": "a 3x3 nested list of finite numbers", "numbers": "a non-empty array of finite numbers",
    "table": "a table", "tables": "an array of tables",
}


@dataclasses.dataclass(frozen=True)
class Key:
    """What one key of a schema accepts.

    Parameters
    ----------
    kind : str
        ``"str"``, ``"bool"``, ``"int"``, ``"number"`` (finite, returned as float),
        ``"vector3"``, ``"quat"``, ``"matrix3"`` (lists of finite numbers of shape
        (3,), (4,), (3, 3), returned as float arrays), ``"numbers"`` (non-empty
        list of finite numbers, returned as an int array if all are integers,
        else float), ``"table"`` (checked against ``schema``, or any table when
        ``schema`` is None) or ``"tables"`` (an array of tables, each checked
        against ``schema``).
    required : bool
        A missing key is an error.
    default : object
        Value filled in when the key is absent (None: leave it absent).
    choices : tuple
        The only values allowed (scalars).
    positive : bool
        The value must be > 0.
    minimum : number, optional
        The value must be >= ``minimum``.
    schema : dict, optional
        Keys of a ``"table"`` or of each entry of ``"tables"``.
    doc : str
        Meaning and unit, quoted when the key is missing.

    Examples
    --------
    >>> Key("int", default=256, positive=True).expected
    'an integer'
    >>> Key("str", choices=("linear", "log")).expected
    "one of 'linear', 'log'"
    """

    kind: str
    required: bool = False
    default: object = None
    choices: tuple = ()
    positive: bool = False
    minimum: float | None = None
    schema: dict | None = None
    doc: str = ""

    def __post_init__(self):
        if self.kind not in _EXPECTED:
            raise ValueError(f"kind must be one of {', '.join(_EXPECTED)}, got {self.kind!r}")

    @property
    def expected(self):
        """What the key accepts, in words."""
        if self.choices:
            return f"one of {', '.join(map(repr, self.choices))}"
        return _EXPECTED[self.kind]


def read_text(path, error, what):
    """Text of the UTF-8 file ``path``; ``error`` naming the file if it cannot be read.

    Examples
    --------
    >>> read_text("/no/such/recipe.toml", SchemaError, "recipe")
    Traceback (most recent call last):
        ...
    kreisel.io.schema.SchemaError: /no/such/recipe.toml: cannot read recipe (No such file or directory)
    """
    try:
        return pathlib.Path(path).read_text(encoding="utf-8-sig")  # -sig: a byte-order mark is not TOML
    except OSError as exc:
        raise error(f"{path}: cannot read {what} ({exc.strerror})") from None
    except UnicodeDecodeError as exc:
        raise error(f"{path}: not a text file (byte {exc.start} is not UTF-8); expected a TOML {what}") from None


class Document:
    """A TOML text, parsed and with the lines of its keys, checked against schemas.

    Parameters
    ----------
    text : str
        The TOML text.
    path : str or path-like, optional
        Labels the messages (``error.unnamed`` when None).
    error : type
        Subclass of :class:`SchemaError` raised for every defect, a TOML
        syntax error included.

    Attributes
    ----------
    label : str
        The file name used in messages.
    raw : dict
        The parsed TOML, unchecked.

    Examples
    --------
    Keys are paths: strings for table keys, integers for entries of an array
    of tables, written dotted in messages:

    >>> text = "[[step]]\\nminutes = 5\\n[[step]]\\nminutes = -1\\n"
    >>> steps = {"step": Key("tables", schema={"minutes": Key("int", positive=True)})}
    >>> Document(text, "soup.toml").table(steps)
    Traceback (most recent call last):
        ...
    kreisel.io.schema.SchemaError: soup.toml:4: step[1].minutes: must be positive, got -1
    >>> Document(text).line_of(("step", 1))
    3
    """

    def __init__(self, text, path=None, error=SchemaError):
        self.error = error
        self.label = str(path) if path is not None else error.unnamed
        text = text.removeprefix("\ufeff")
        try:
            self.raw = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            # the parser says "what (at line L, column C)": put the line where every other message has it
            match = re.fullmatch(r"(.*) \(at line (\d+), column (\d+)\)", str(exc))
            where, what = (f":{match[2]}", f"{match[1]} (column {match[3]})") if match else ("", str(exc))
            raise error(f"{self.label}{where}: TOML syntax error: {what}") from None
        except RecursionError:
            raise error(f"{self.label}: arrays or tables nested too deeply to read") from None
        except ValueError as exc:
            # Python refuses to convert decimal integers beyond sys.get_int_max_str_digits() (a guard against
            # quadratic-time parsing), and tomllib lets that ValueError out without a line
            self._lines = _key_lines(text)
            self._too_many_digits(text, exc)
        self._lines = _key_lines(text)

    def _too_many_digits(self, text, exc):
        """Raise the document's error for an integer literal longer than Python converts, at its key and line."""
        limit = sys.get_int_max_str_digits()
        for number, line in enumerate(text.splitlines(), start=1):
            for match in _DIGITS.finditer(_STRING.sub('""', line).split("#", 1)[0]):
                digits = len(match[0].replace("_", ""))
                if limit and digits > limit:
                    keys = [key for key, at in self._lines.items() if at <= number]
                    key = max(keys, key=lambda k: (self._lines[k], len(k))) if keys else ()
                    self.fail(key, f"expected a number, got an integer of {digits} digits "
                                   f"(at most {limit} can be read)")
        raise self.error(f"{self.label}: cannot read the TOML: {exc}") from None

    def line_of(self, key):
        """Line (from 1) of ``key`` (a path tuple), else of its nearest enclosing key; None if not found."""
        key = tuple(key)
        while key:
            if key in self._lines:
                return self._lines[key]
            key = key[:-1]
        return None

    def fail(self, key, message):
        """Raise the document's error: ``file:line: dotted.key: message``."""
        line = self.line_of(key)
        where = f":{line}" if line else ""
        raise self.error(f"{self.label}{where}: {dotted(key) or 'top level'}: {message}")

    def table(self, schema, raw=None, key=()):
        """Check table ``raw`` (default: the whole document) found at ``key``; return it with defaults filled."""
        raw = self.raw if raw is None else raw
        if not isinstance(raw, dict):
            self.fail(key, f"expected a table, got {_shown(raw)}")
        unknown = sorted(set(raw) - set(schema))
        if unknown:
            self.fail(key + (unknown[0],), f"unknown key (expected one of: {', '.join(sorted(schema))})")
        out = {}
        for name, spec in schema.items():
            if name in raw:
                out[name] = self.value(raw[name], spec, key + (name,))
            elif spec.required:
                doc = f" ({spec.doc})" if spec.doc else ""
                self.fail(key or (name,), f"missing required key {name!r}{doc}")
            elif spec.default is not None:
                out[name] = spec.default
        return out

    def value(self, value, spec, key):
        """Check one ``value`` found at ``key`` against ``spec``; return it converted."""
        kind = spec.kind
        if kind == "table":
            if spec.schema is None and isinstance(value, dict):
                return value  # free-form: the format checks it once it knows what belongs there
            return self.table(spec.schema or {}, value, key)
        if kind == "tables":
            if not isinstance(value, list):
                self.fail(key, f"expected an array of tables [[{dotted(key)}]], got {_shown(value)}")
            return [self.table(spec.schema, entry, key + (i,)) for i, entry in enumerate(value)]
        checked = _converted(value, kind)
        if checked is None:
            self.fail(key, f"expected {_EXPECTED[kind]}, got {_shown(value)}")
        if spec.choices and checked not in spec.choices:
            self.fail(key, f"expected {spec.expected}, got {_shown(value)}")
        if spec.positive and checked <= 0:
            self.fail(key, f"must be positive, got {_shown(value)}")
        if spec.minimum is not None and checked < spec.minimum:
            self.fail(key, f"must be at least {spec.minimum}, got {_shown(value)}")
        return checked

    def exactly_one(self, table, names, key):
        """The one of ``names`` that ``table`` (found at ``key``) gives; fail if none or several."""
        given = [name for name in names if name in table]
        if len(given) != 1:
            self.fail(key, f"give exactly one of {', '.join(names)} (got {', '.join(given) or 'none'})")
        return given[0]


def dotted(key):
    """A key path written as in messages: ``("torque", 0, "kind")`` -> ``'torque[0].kind'``.

    Examples
    --------
    >>> dotted(("torque", 0, "kind")), dotted(("grid", "phi_dot")), dotted(())
    ('torque[0].kind', 'grid.phi_dot', '')
    """
    text = ""
    for part in key:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else part)
    return text


def _converted(value, kind):
    """``value`` as ``kind`` wants it, or None if it is not one (bool is never a number)."""
    if kind == "str":
        return value if isinstance(value, str) else None
    if kind == "bool":
        return value if isinstance(value, bool) else None
    if kind == "int":
        return value if isinstance(value, int) and not isinstance(value, bool) else None
    if kind == "number":
        return _finite_float(value)
    if not isinstance(value, list) or not value:
        return None
    if kind == "numbers":
        numbers = [_finite_float(v) for v in value]
        if any(v is None for v in numbers):
            return None
        integers = all(isinstance(v, int) and np.iinfo(np.int64).min <= v <= np.iinfo(np.int64).max for v in value)
        return np.array(value, dtype=np.int64) if integers else np.array(numbers)
    shape = _SHAPES[kind]
    rows = value if len(shape) == 2 else [value]
    if len(rows) != math.prod(shape[:-1]) or not all(isinstance(row, list) and len(row) == shape[-1] for row in rows):
        return None
    numbers = [_finite_float(v) for row in rows for v in row]
    return None if any(v is None for v in numbers) else np.array(numbers).reshape(shape)


def _finite_float(value):
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    try:
        number = float(value)
    except OverflowError:  # TOML integers are unbounded in tomllib; beyond float range is not a number we can use
        return None
    return number if math.isfinite(number) else None


def _shown(value, limit=80):
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


_PART = r"""(?:[A-Za-z0-9_-]+|"(?:[^"\\]|\\.)*"|'[^']*')"""
_DOTTED = rf"{_PART}(?:\s*\.\s*{_PART})*"
_ARRAY_HEADER = re.compile(rf"\s*\[\[\s*({_DOTTED})\s*\]\]\s*(#.*)?$")
_HEADER = re.compile(rf"\s*\[\s*({_DOTTED})\s*\]\s*(#.*)?$")
_ASSIGNMENT = re.compile(rf"\s*({_DOTTED})\s*=")
_STRING = re.compile(r"""\"(?:[^"\\]|\\.)*"|'[^']*'""")
_DIGITS = re.compile(r"(?<![\w.])\d[\d_]*")


def _key_lines(text):
    """First line of every key path (and of every table, by its header or first key) in TOML ``text``."""
    lines = {}
    arrays = {}  # path of an array of tables -> entries so far
    table = ()
    depth = 0  # open brackets of a value that spans lines
    in_string = None  # delimiter of an open multi-line string
    for number, line in enumerate(text.splitlines(), start=1):
        if in_string:
            if line.count(in_string) % 2:
                in_string = None
            continue
        if depth == 0:
            if match := _ARRAY_HEADER.match(line):
                parts = _parts(match[1])
                array = _resolved(parts[:-1], arrays) + parts[-1:]
                arrays[array] = arrays.get(array, 0) + 1
                table = array + (arrays[array] - 1,)
                _record(lines, table, number)
                continue
            if match := _HEADER.match(line):
                table = _resolved(_parts(match[1]), arrays)
                _record(lines, table, number)
                continue
            if match := _ASSIGNMENT.match(line):
                _record(lines, table + _parts(match[1]), number)
        for delimiter in ('"""', "'''"):
            if line.count(delimiter) % 2:
                in_string = delimiter
        bare = _STRING.sub('""', line).split("#", 1)[0]
        depth = max(depth + bare.count("[") + bare.count("{") - bare.count("]") - bare.count("}"), 0)
    return lines


def _parts(dotted_key):
    return tuple(tomllib.loads(f"k = {part}")["k"] if part[0] in "\"'" else part
                 for part in re.findall(_PART, dotted_key))


def _resolved(parts, arrays):
    """Path of header ``parts``: a name that is an array of tables means its latest entry."""
    path = ()
    for part in parts:
        path += (part,)
        if path in arrays:
            path += (arrays[path] - 1,)
    return path


def _record(lines, path, number):
    for end in range(1, len(path) + 1):
        lines.setdefault(path[:end], number)
