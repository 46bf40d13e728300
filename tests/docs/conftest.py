"""Helpers for the documentation tests: the docs/_ext generators, importable by path."""

import importlib.util
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"


def load_extension(name):
    spec = importlib.util.spec_from_file_location(name, DOCS / "_ext" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def schema_reference():
    return load_extension("schema_reference")


@pytest.fixture(scope="module")
def cli_reference():
    return load_extension("cli_reference")
