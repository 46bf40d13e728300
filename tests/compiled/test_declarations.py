"""Every compiled array function of so3, kinematics and se3 is one kernel and one declaration."""

import inspect
import pathlib
import re

import pytest

import kreisel
import kreisel.kinematics as kinematics
import kreisel.se3 as se3
import kreisel.so3 as so3
from kreisel._compiled import elementwise

MODULES = (so3, kinematics, se3)
PACKAGE = pathlib.Path(kreisel.__file__).parent

#: What a module holding formulas and declarations only must not contain: hand-written loops over a batch,
#: gufuncs, multi-core twins, the old machinery's helpers.
FORBIDDEN = re.compile(r"\bprange\b|guvectorize|@parallel\b|\bgufunc\b|checked_in_one_pass|piece_results|in_pieces")


#: Modules allowed a compiled loop that is not element-wise, and why.
REDUCTIONS = {"alignment.py": "Wahba's problem sums over each problem's vectors, a core of any length"}


def _sources():
    for package in ("so3", "kinematics", "se3"):
        yield from sorted((PACKAGE / package).glob("*.py"))


@pytest.mark.parametrize("path", [p for p in _sources() if p.name not in REDUCTIONS], ids=lambda p: f"{p.parent.name}/{p.name}")
def test_array_modules_hold_formulas_and_declarations_only(path):
    found = [f"{number}: {line.strip()}" for number, line in enumerate(path.read_text(encoding="utf-8").split("\n"), 1)
             if FORBIDDEN.search(line) and not line.lstrip().startswith("#")]
    assert not found, found


def _array_functions():
    """Public functions of so3, kinematics and se3 that take ``out=`` (the array functions)."""
    seen = {}
    for module in MODULES:
        for name in module.__all__:
            function = getattr(module, name)
            if inspect.isfunction(function) and "out" in inspect.signature(function).parameters:
                seen[name] = function
    return seen


#: Array functions that are no element-wise formula, so no declaration: constants, reductions over a batch,
#: boolean tests (a declaration's result is float64), complex results, a projection by SVD.
NUMPY_EXPRESSIONS = {
    "quat_identity": "a constant", "generators": "a constant", "create_group": "a constant table",
    "quat_mean": "a reduction over the batch", "bch": "a truncated series of matrix commutators",
    "orthonormalize": "the nearest rotation by SVD (numpy.linalg)", "quat_to_cayley_klein": "complex results",
    "gimbal_lock": "a boolean test", "davenport_gimbal_lock": "a boolean test",
    "rotvec_rate_singular": "a boolean test", "euler_rates_singular": "a boolean test",
}


def test_every_compiled_array_function_is_a_declared_operation():
    undeclared = sorted(name for name, function in _array_functions().items()
                        if getattr(function, "__operation__", None) is None and name not in NUMPY_EXPRESSIONS)
    assert not undeclared
    for name, function in _array_functions().items():
        operation = getattr(function, "__operation__", None)
        if operation is not None:
            assert elementwise.REGISTRY.get(operation.name) is not None, name
