"""The scenario and sweep file reference is the schema that checks the files, and covers the bundled examples."""

import re
import tomllib

import numpy as np
import pytest

from kreisel.io import EXAMPLES, example_path, parse_scenario
from kreisel.io import scenario as scenario_module
from kreisel.sweep import files as sweep_files
from kreisel.sweep.models import MODELS

from .conftest import ROOT


@pytest.fixture(scope="module")
def reference(schema_reference):
    return schema_reference.file_reference(ROOT)


def _dotted_keys(table, prefix=()):
    keys = []
    for name, value in table.items():
        if isinstance(value, dict):
            keys.append(".".join((*prefix, name)))
            keys += _dotted_keys(value, (*prefix, name))
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            keys.append(".".join((*prefix, name)))
            for entry in value:
                keys += _dotted_keys(entry, (*prefix, name))
        else:
            keys.append(".".join((*prefix, name)))
    return keys


@pytest.mark.parametrize("name", EXAMPLES)
def test_every_key_of_a_bundled_scenario_is_documented_and_the_file_is_shown(reference, name):
    path = example_path(name)
    for key in _dotted_keys(tomllib.loads(path.read_text(encoding="utf-8"))):
        assert f"``{key}``" in reference, key
    assert f"{path.relative_to(ROOT).as_posix()}" in reference


@pytest.mark.parametrize("name", sweep_files.EXAMPLES)
def test_every_key_of_a_bundled_sweep_is_documented_and_the_file_is_shown(reference, name):
    path = sweep_files.example_path(name)
    for key in _dotted_keys(tomllib.loads(path.read_text(encoding="utf-8"))):
        key = re.sub(r"^grid\.[^.]+", "grid.NAME", key)
        if key.startswith("constants."):
            assert f"``{key}``" in reference.split(f'``model = "{tomllib.loads(path.read_text())["model"]}"``')[1]
        else:
            assert f"``{key}``" in reference, key
    assert f"{path.relative_to(ROOT).as_posix()}" in reference


def test_every_schema_key_is_documented_with_its_default(schema_reference, reference):
    rows = schema_reference.key_rows(scenario_module._SCHEMA)
    assert len(rows) > 40
    for dotted, key in rows:
        block = reference.split(f"   * - ``{dotted}``\n", 1)[1].split("   * - ", 1)[0]
        if key.required:
            assert "*required*" in block, dotted
        elif key.default is not None:
            assert schema_reference._literal(key.default) in block, dotted
        for choice in key.choices:
            assert schema_reference._literal(choice) in block, dotted


def test_documented_defaults_are_the_ones_the_checker_fills_in(schema_reference):
    scenario = parse_scenario("[body]\nmoments = [1.0, 2.0, 3.0]\n[initial]\nomega = [0.0, 0.0, 1.0]\n"
                              "[initial.attitude]\neuler = [0.1, 0.2, 0.3]\n[integration]\nt_end = 1.0\n")
    documented = {dotted: key.default for dotted, key in schema_reference.key_rows(scenario_module._SCHEMA)
                  if key.default is not None}
    for dotted, default in documented.items():
        table = scenario.data
        *parents, leaf = dotted.split(".")
        if parents and parents[0] not in ("body", "initial", "integration"):
            continue  # tables of other scenario kinds
        for parent in parents:
            table = table[parent]
        assert np.all(table[leaf] == default), dotted


def test_every_sweep_model_and_constant_is_documented(reference):
    for name, model in MODELS.items():
        section = reference.split(f'``model = "{name}"``', 1)[1]
        for grid in model.grid:
            assert f"``{grid}``" in section
        for constant in model.constants:
            assert f"``constants.{constant}``" in section


def test_the_reference_page_includes_the_generated_tables():
    page = (ROOT / "docs" / "scenario_reference.rst").read_text(encoding="utf-8")
    assert ".. include:: _generated/file_reference.rst" in page
