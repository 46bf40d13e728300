"""Every docstring example in kreisel.inertia runs as printed."""

import doctest
import importlib
import pkgutil

import pytest

import kreisel.inertia

MODULES = [
    importlib.import_module(f"kreisel.inertia.{info.name}")
    for info in pkgutil.iter_modules(kreisel.inertia.__path__)
]


@pytest.mark.parametrize("module", [kreisel.inertia, *MODULES], ids=lambda m: m.__name__)
def test_docstring_examples(module):
    result = doctest.testmod(module, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0
