"""The scenario and sweep file reference, generated from the schemas that check the files.

:mod:`kreisel.io.scenario` and :mod:`kreisel.sweep.files` describe their keys
with :class:`kreisel.io.schema.Key` specs; the same specs are rendered here as
tables (key, type, default, allowed values, meaning and unit), together with
the rules that tie keys together and every bundled example file, so that the
reference and the checker cannot disagree. ``conf.py`` writes the result to
``_generated/file_reference.rst``; tests/docs/ checks it against the bundled
examples.
"""

from __future__ import annotations

import pathlib
import re

KIND_NAMES = {
    "str": "string", "bool": "boolean", "int": "integer", "number": "number",
    "vector3": "3 numbers", "quat": "4 numbers", "matrix3": "3×3 numbers", "numbers": "array of numbers",
    "table": "table", "tables": "array of tables",
}


def _literal(value):
    if isinstance(value, bool):
        return "``true``" if value else "``false``"
    if isinstance(value, str):
        return f'``"{value}"``'
    return f"``{value!r}``"


def _allowed(key):
    parts = []
    if key.choices:
        parts.append(", ".join(_literal(c) for c in key.choices))
    if key.positive:
        parts.append("> 0")
    if key.minimum is not None:
        parts.append(f"≥ {key.minimum:g}")
    return "; ".join(parts)


def key_rows(schema, prefix=()):
    """(dotted key, key spec) for every key of ``schema``, tables before their keys."""
    rows = []
    for name, key in schema.items():
        path = (*prefix, name)
        rows.append((".".join(path), key))
        if key.schema is not None:
            rows.extend(key_rows(key.schema, path))
    return rows


def key_table(schema, prefix=(), notes=None):
    """A list-table of the keys of ``schema``; ``notes`` adds text to the meaning of some keys."""
    notes = notes or {}
    lines = [".. list-table::", "   :header-rows: 1", "   :widths: 24 14 12 18 32", "",
             "   * - key", "     - type", "     - default", "     - allowed", "     - meaning, unit"]
    for dotted, key in key_rows(schema, prefix):
        default = "*required*" if key.required else ("" if key.default is None else _literal(key.default))
        doc = re.sub(r"(?<!`)`([^`]+)`(?!`)", r"``\1``", key.doc)  # schema docs mark names with single backticks
        meaning = "; ".join(part for part in (doc, notes.get(dotted, "")) if part)
        lines += [f"   * - ``{dotted}``", f"     - {KIND_NAMES[key.kind]}", f"     - {default or '—'}",
                  f"     - {_allowed(key) or '—'}", f"     - {meaning or '—'}"]
    return lines + [""]


def _example_blocks(read, paths, root):
    """A heading, the description (as text, so that its Theory citations become links) and the file."""
    lines = []
    for name, path in paths.items():
        data = read(path)
        heading = f"``{name}``: {data.get('title', '')}"
        relative = pathlib.Path(path).resolve().relative_to(root)
        lines += [heading, "^" * len(heading), "", data.get("description", ""), "",
                  f".. literalinclude:: /../{relative.as_posix()}", "   :language: toml", ""]
    return lines


def file_reference(root):
    """reStructuredText of the scenario and sweep references (``root``: the repository)."""
    import tomllib

    from kreisel.dynamics.engine import ADAPTIVE
    from kreisel.io import EXAMPLES, example_path
    from kreisel.io import scenario as scenario_module
    from kreisel.sweep import files as sweep_files
    from kreisel.sweep.models import MODELS

    read = lambda path: tomllib.loads(pathlib.Path(path).read_text(encoding="utf-8"))
    schema = scenario_module._SCHEMA
    lines = ["Scenario files", "--------------", "",
             "Top-level keys and tables. Which tables a scenario needs depends on ``kind``:", ""]
    for kind, tables in scenario_module._REQUIRED_TABLES.items():
        optional = scenario_module._OPTIONAL_TABLES.get(kind, ())
        text = ", ".join(f"``[{t}]``" for t in tables)
        if optional:
            text += "; optional " + ", ".join(f"``[[{t}]]``" for t in optional)
        lines.append(f"* ``kind = \"{kind}\"``: {text}.")
    lines += ["", "Other tables are refused for that kind.", ""]
    shape_needs = scenario_module._SHAPE_NEEDS
    torque_needs = scenario_module._TORQUE_NEEDS
    notes = {
        "body": "exactly one of ``moments``, ``tensor``, ``shape``, ``mesh``",
        "body.shape": "; ".join(f"``{s}`` needs {', '.join(f'``{n}``' for n in needs)}"
                                for s, needs in shape_needs.items()),
        "initial.attitude": "identity when absent; else exactly one of ``quat``, ``rotvec``, ``matrix``, "
                            "``euler`` (``seq`` and ``degrees`` only with ``euler``)",
        "torque.kind": "; ".join(f"``{k}`` needs {', '.join(f'``{n}``' for n in needs)}"
                                 for k, needs in torque_needs.items()),
        "integration.dt": "required by the fixed-step methods, refused by the adaptive ones ("
                          + ", ".join(f"``{m}``" for m in sorted(ADAPTIVE)) + ")",
    }
    lines += key_table(schema, notes=notes)
    lines += ["A ``[[torque]]`` entry may appear several times; the torques add.", "",
              "Bundled scenarios", "~~~~~~~~~~~~~~~~~", "",
              "Each is complete and valid; ``kreisel examples NAME`` copies one out to edit.", ""]
    lines += _example_blocks(read, {name: example_path(name) for name in EXAMPLES}, root)

    lines += ["Sweep files", "-----------", "", "Top-level keys:", ""]
    lines += key_table(sweep_files._TOP, notes={
        "grid": "one table ``[grid.NAME]`` per grid parameter of the model (below)",
        "constants": "the model's constants (below); absent ones take their defaults"})
    forms = " or ".join("+".join(f"``{k}``" for k in keys) for keys in sweep_files._FORMS.values())
    lines += [f"Each ``[grid.NAME]`` table gives its values in exactly one form: {forms}.", ""]
    from kreisel.io.schema import Key

    axis = {"NAME": Key("table", schema=sweep_files._AXIS, doc="the values of one grid parameter")}
    lines += key_table(axis, ("grid",), notes={
        "grid.NAME.values": "explicit values", "grid.NAME.start": "first of ``num`` points",
        "grid.NAME.stop": "last of ``num`` points", "grid.NAME.num": "number of points from start to stop",
        "grid.NAME.count": "the integers 0 … count − 1 (e.g. Monte Carlo trials)",
        "grid.NAME.spacing": "with start/stop/num; default ``\"linear\"``"})
    lines += ["Models", "~~~~~~", ""]
    for name, model in MODELS.items():
        summary = (model.function.__doc__ or "").strip().splitlines()[0]
        title = f"``model = \"{name}\"``"
        lines += [title, "^" * len(title), "", summary, "",
                  "Grid parameters: " + ", ".join(f"``{g}``" for g in model.grid) + ".", ""]
        constants = {c: _constant_key(kind, default, model.notes.get(c, "")) for c, (kind, default) in model.constants.items()}
        lines += key_table(constants, ("constants",))
        outputs = ", ".join(f"``{v}``" + (f" ({meta['units']})" if "units" in meta else "")
                            for v, meta in model.units.items())
        lines += [f"Output variables with metadata: {outputs}.", ""]
    lines += ["Bundled sweeps", "~~~~~~~~~~~~~~", "", "``kreisel sweep NAME`` runs one.", ""]
    lines += _example_blocks(read, {n: sweep_files.example_path(n) for n in sweep_files.EXAMPLES}, root)
    return "\n".join(lines) + "\n"


def _constant_key(kind, default, doc):
    from kreisel.io.schema import Key

    return Key(kind, default=default, doc=doc)
