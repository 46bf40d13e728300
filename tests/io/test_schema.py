"""kreisel.io.schema: the one checker behind scenario and sweep files (types, defaults, lines, junk values)."""

import datetime
import math
import re

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from kreisel.io import ScenarioError, SchemaError
from kreisel.io.schema import Document, Key, dotted, read_text
from kreisel.sweep import SweepFileError


class RecipeError(SchemaError):
    unnamed = "<recipe>"


SCHEMA = {
    "name": Key("str", required=True, doc="what it is called"),
    "servings": Key("int", default=4, positive=True),
    "hot": Key("bool", default=False),
    "oven": Key("table", schema={
        "mode": Key("str", default="fan", choices=("fan", "top")),
        "temperature": Key("number", positive=True, doc="degrees Celsius"),
    }),
    "step": Key("tables", schema={
        "minutes": Key("int", required=True, minimum=0),
        "axis": Key("vector3"),
    }),
    "notes": Key("table"),
}

GOOD = """\
name = "bread"            # line 1
servings = 2
[oven]
temperature = 220.0
[[step]]
minutes = 5
[[step]]
minutes = 0
axis = [0, 0, 1]
[notes.free]
anything = "goes"
"""


def check(text, path="r.toml"):
    return Document(text, path, RecipeError).table(SCHEMA)


def test_good_text_is_converted_and_defaults_filled():
    data = check(GOOD)
    assert data["name"] == "bread" and data["servings"] == 2 and data["hot"] is False
    assert data["oven"] == {"mode": "fan", "temperature": 220.0}
    assert [step["minutes"] for step in data["step"]] == [5, 0]
    assert data["step"][1]["axis"].dtype == np.float64 and data["step"][1]["axis"].tolist() == [0.0, 0.0, 1.0]
    assert data["notes"] == {"free": {"anything": "goes"}}   # a table without a schema is left to the format


@pytest.mark.parametrize("old, new, message", [
    ("servings = 2", "servings = 2\ncolour = 1", r"^r\.toml:3: colour: unknown key \(expected one of: hot, name, notes"),
    ("temperature = 220.0", "temperature = 'hot'", r"^r\.toml:4: oven\.temperature: expected a finite number, got 'hot'$"),
    ("temperature = 220.0", "temperature = -1", r"^r\.toml:4: oven\.temperature: must be positive, got -1$"),
    ("temperature = 220.0", "temperature = nan", r"^r\.toml:4: oven\.temperature: expected a finite number, got nan$"),
    ("temperature = 220.0", "mode = 'grill'", r"^r\.toml:4: oven\.mode: expected one of 'fan', 'top', got 'grill'$"),
    ("servings = 2", "servings = true", r"^r\.toml:2: servings: expected an integer, got True$"),
    ("servings = 2", "servings = 0", r"^r\.toml:2: servings: must be positive, got 0$"),
    ("minutes = 0", "minutes = -3", r"^r\.toml:8: step\[1\]\.minutes: must be at least 0, got -3$"),
    ("axis = [0, 0, 1]", "axis = [0, 0]", r"^r\.toml:9: step\[1\]\.axis: expected a list of 3 finite numbers"),
    ("minutes = 5\n", "", r"^r\.toml:5: step\[0\]: missing required key 'minutes'$"),
    ('name = "bread"', "title = 1", r"^r\.toml:1: title: unknown key"),
    ("[oven]", "hot = 'yes'\n[oven]", r"^r\.toml:3: hot: expected true or false, got 'yes'$"),
    ("[oven]\ntemperature = 220.0", "oven = 3", r"^r\.toml:3: oven: expected a table, got 3$"),
    ("[oven]\ntemperature = 220.0", "oven = {mode = 'x'}", r"^r\.toml:3: oven\.mode: expected one of"),
])
def test_defects_name_file_line_key_and_expectation(old, new, message):
    assert old in GOOD
    with pytest.raises(RecipeError, match=message):
        check(GOOD.replace(old, new))


def test_missing_top_level_key_quotes_its_doc_without_a_line():
    with pytest.raises(RecipeError, match=r"^<recipe>: name: missing required key 'name' \(what it is called\)$"):
        Document("servings = 1\n", error=RecipeError).table(SCHEMA)


def test_array_of_tables_must_be_one():
    with pytest.raises(RecipeError, match=r"^r\.toml:2: step: expected an array of tables \[\[step\]\], got 3$"):
        check('name = "x"\nstep = 3\n')


def test_syntax_error_and_unreadable_file_use_the_format_error(tmp_path):
    with pytest.raises(RecipeError, match=r"^r\.toml:1: TOML syntax error: "):
        check("[oven\n")
    with pytest.raises(RecipeError, match=r"absent\.toml: cannot read recipe"):
        read_text(tmp_path / "absent.toml", RecipeError, "recipe")
    (tmp_path / "ok.toml").write_text("é = 1\n", encoding="utf-8")
    assert read_text(tmp_path / "ok.toml", RecipeError, "recipe") == "é = 1\n"


def test_exactly_one():
    document = Document("[shape]\nradius = 1\nsize = 2\n", "s.toml")
    assert document.exactly_one({"radius": 1}, ("radius", "size"), ("shape",)) == "radius"
    with pytest.raises(SchemaError, match=r"^s\.toml:1: shape: give exactly one of radius, size \(got radius, size\)$"):
        document.exactly_one(document.raw["shape"], ("radius", "size"), ("shape",))
    with pytest.raises(SchemaError, match=r"\(got none\)$"):
        document.exactly_one({}, ("radius", "size"), ("shape",))


def test_numbers_keep_integers_and_refuse_junk():
    schema = {"v": Key("numbers")}
    ints = Document("v = [0, 3, -2]").table(schema)["v"]
    assert ints.dtype == np.int64 and ints.tolist() == [0, 3, -2]
    mixed = Document("v = [0, 1.5]").table(schema)["v"]
    assert mixed.dtype == np.float64 and mixed.tolist() == [0.0, 1.5]
    huge = Document(f"v = [{2**70}]").table(schema)["v"]
    assert huge.dtype == np.float64 and huge[0] == 2.0**70
    for junk in ("[]", "[true]", "[1, inf]", "['1']", "[[1]]", "1", f"[{10**400}]"):
        with pytest.raises(SchemaError, match=r"^<toml>:1: v: expected a non-empty array of finite numbers"):
            Document(f"v = {junk}").table(schema)


def test_matrix_shape_is_exact():
    schema = {"m": Key("matrix3")}
    assert Document("m = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]").table(schema)["m"].tolist() == np.eye(3).tolist()
    for junk in ("[[1, 0, 0], [0, 1, 0]]", "[[1, 0], [0, 1], [0, 0]]", "[1, 0, 0, 0, 1, 0, 0, 0, 1]",
                 "[[1, 0, 0], [0, 1, 0], [0, 0, 'x']]"):
        with pytest.raises(SchemaError, match="m: expected a 3x3 nested list of finite numbers"):
            Document(f"m = {junk}").table(schema)


def test_key_refuses_an_unknown_kind():
    with pytest.raises(ValueError, match="kind must be one of"):
        Key("colour")


def test_dotted_paths():
    assert dotted(("torque", 0, "kind")) == "torque[0].kind"
    assert dotted(("a", 1, 2, "b")) == "a[1][2].b"


def test_key_lines_follow_headers_arrays_quotes_and_multiline_values():
    text = """\
title = \"\"\"
x = 1
\"\"\"
[a . "b.c"]       # a comment
d.e = 2
matrix = [
  [1],
]
[[list]]
[[list.inner]]
k = 1
[[list]]
[[list.inner]]
[[list.inner]]
k = 2
'lit' = 3
"""
    document = Document(text)
    assert document.line_of(("x",)) is None            # inside a multi-line string
    assert document.line_of(("a",)) == 4 and document.line_of(("a", "b.c")) == 4
    assert document.line_of(("a", "b.c", "d", "e")) == 5
    assert document.line_of(("a", "b.c", "matrix")) == 6
    assert document.line_of(("1",)) is None            # "[1]" inside the array is no table header
    assert document.line_of(("list", 0, "inner", 0, "k")) == 11
    assert document.line_of(("list", 1, "inner", 1, "k")) == 15
    assert document.line_of(("list", 1, "inner", 1, "lit")) == 16
    assert document.line_of(("list", 1, "inner", 0, "k")) == 13   # absent key: its table's line
    assert document.line_of(("nowhere", "k")) is None


def test_formats_subclass_the_common_base():
    assert issubclass(ScenarioError, SchemaError) and issubclass(SweepFileError, SchemaError)
    assert issubclass(SchemaError, ValueError)
    from kreisel.sweep import parse_sweep_file

    with pytest.raises(SweepFileError, match=r"^<sweep>:2: chunk_size: expected an integer, got 'many'$"):
        parse_sweep_file("model = 'lagrange_apex'\nchunk_size = 'many'\n")


# Junk values: anything TOML can hold, checked against every kind. The checker must either
# accept and convert, or raise the format's error naming the key and line: never crash otherwise.
_scalars = st.one_of(
    st.booleans(), st.integers(min_value=-2**63, max_value=2**63 - 1), st.integers(), st.floats(),
    st.text(max_size=8), st.datetimes(max_value=datetime.datetime(9999, 1, 1)), st.dates(), st.times(),
)
_values = st.recursive(_scalars, lambda children: st.lists(children, max_size=4)
                       | st.dictionaries(st.from_regex(r"[a-z]{1,4}", fullmatch=True), children, max_size=3),
                       max_leaves=12)
_KINDS = ("str", "bool", "int", "number", "vector3", "quat", "matrix3", "numbers", "table", "tables")


_REFUSED = object()


def _finite(v):
    return (type(v) is int and abs(v) < 2**1000) or (type(v) is float and math.isfinite(v))


def _expected(value, kind):
    """Independent statement of what each kind makes of ``value`` (``_REFUSED`` if it must refuse it)."""
    if kind in ("str", "bool", "int"):
        return value if type(value) is {"str": str, "bool": bool, "int": int}[kind] else _REFUSED
    if kind == "number":
        return float(value) if _finite(value) else _REFUSED
    if kind in ("vector3", "quat", "matrix3"):
        rows = value if kind == "matrix3" else [value]
        n_rows, n_columns = {"vector3": (1, 3), "quat": (1, 4), "matrix3": (3, 3)}[kind]
        ok = (type(value) is list and len(rows) == n_rows
              and all(type(row) is list and len(row) == n_columns and all(map(_finite, row)) for row in rows))
        return [[float(v) for v in row] for row in rows] if ok else _REFUSED
    if kind == "numbers":
        ok = type(value) is list and len(value) > 0 and all(map(_finite, value))
        return [float(v) for v in value] if ok else _REFUSED
    if kind == "table":   # an empty schema: any key is unknown
        return value if type(value) is dict and not value else _REFUSED
    return value if type(value) is list and all(type(v) is dict and not v for v in value) else _REFUSED


@settings(max_examples=400, deadline=None)
@given(value=_values, kind=st.sampled_from(_KINDS))
def test_junk_values_are_converted_exactly_or_refused_with_key_and_line(value, kind):
    document = Document("[outer]\nfirst = 1\nvalue = 0\n", "junk.toml", RecipeError)
    expected = _expected(value, kind)
    try:
        result = document.value(value, Key(kind, schema={}), ("outer", "value"))
    except RecipeError as exc:
        assert expected is _REFUSED, (value, kind, str(exc))
        assert re.match(r"junk\.toml:3: outer\.value(\[\d+\])?(\.\w+: unknown key|: expected )", str(exc)), str(exc)
    else:
        assert expected is not _REFUSED, (value, kind, result)
        converted = result.reshape(-1, result.shape[-1]).tolist() if kind in ("vector3", "quat", "matrix3") else result
        assert np.array_equal(converted, expected) if kind == "numbers" else converted == expected
        assert type(result) is {"number": float, "numbers": np.ndarray}.get(kind, type(result))


@settings(max_examples=150, deadline=None)
@given(layout=st.lists(st.tuples(st.sampled_from(["[t]", "[[arr]]", "[u.v]", ""]),
                                 st.lists(st.sampled_from(["k", "m", "n"]), unique=True, max_size=3)),
                       min_size=1, max_size=6),
       pick=st.integers(min_value=0))
def test_the_line_of_a_bad_value_is_where_the_text_puts_it(layout, pick):
    # Build TOML text table by table with integer values, make one value a string and check
    # that the refusal names exactly that key path and line.
    lines, places, arrays, seen = [], [], 0, set()
    for header, keys in layout:
        if header in seen and header != "[[arr]]" or (header == "" and lines):
            continue   # a table may be declared once; top-level keys only come first
        seen.add(header)
        if header:
            lines.append(header)
        path = {"": (), "[t]": ("t",), "[u.v]": ("u", "v"), "[[arr]]": ("arr", arrays)}[header]
        arrays += header == "[[arr]]"
        for key in keys:
            lines.append(f"{key} = 1")
            places.append((path + (key,), len(lines)))
    if not places:
        return
    path, line = places[pick % len(places)]
    lines[line - 1] = lines[line - 1].replace("= 1", '= "junk"')
    leaf = {name: Key("int") for name in "kmn"}
    schema = {**leaf, "t": Key("table", schema=leaf), "u": Key("table", schema={"v": Key("table", schema=leaf)}),
              "arr": Key("tables", schema=leaf)}
    with pytest.raises(RecipeError) as refusal:
        Document("\n".join(lines), "l.toml", RecipeError).table(schema)
    assert str(refusal.value) == f"l.toml:{line}: {dotted(path)}: expected an integer, got 'junk'"
