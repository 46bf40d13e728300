"""The first run says that it compiles, and `kreisel compile` compiles ahead of it (a fresh cache, as a user has)."""

import functools

import pytest

from kreisel._compiled.elementwise import REGISTRY
from kreisel.cli._output import COMPILING
from kreisel.cli.compile import parts
from kreisel.dynamics.engine import METHODS


@pytest.fixture
def kreisel(kreisel, tmp_path):
    """The command with a numba cache of its own in ``tmp_path``, empty as a new installation's."""
    return functools.partial(kreisel, env={"NUMBA_CACHE_DIR": str(tmp_path)})


def test_a_cold_cache_is_announced_once_and_a_warm_one_not(kreisel, tmp_path):
    first = kreisel("convert", "--from", "rotvec", "--to", "quat", "0", "0", "1")
    assert first.returncode == 0 and first.stderr.splitlines() == [COMPILING], first.stderr
    again = kreisel("convert", "--from", "rotvec", "--to", "quat", "0", "0", "1")
    assert again.returncode == 0 and again.stderr == "" and again.stdout == first.stdout


def test_compile_fills_the_cache_ahead_of_the_first_run(kreisel, tmp_path):
    done = kreisel("compile", "--only", "quat_normalize")
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("compiled 1 part in ") and str(tmp_path / "kreisel") in done.stdout
    assert done.stderr.startswith("compiling 1 part of kreisel for this machine"), done.stderr
    assert COMPILING not in done.stderr
    run = kreisel("convert", "--from", "quat", "--to", "quat", "2", "0", "0", "0")
    assert run.returncode == 0 and run.stderr == "" and run.stdout.split() == ["1", "0", "0", "0"], run.stderr


def test_compile_covers_every_array_operation_and_integrator():
    labels = {label for label, _ in parts()}
    assert {f"array operation {name}" for name in REGISTRY} <= labels
    assert {f"integrator {method}" for method, code in METHODS.items() if code is not None} <= labels
