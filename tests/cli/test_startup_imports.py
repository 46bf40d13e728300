"""`kreisel --help` and `kreisel convert` load only what they need: not the simulation, plotting, Dask or web stacks,
and for the help not even numpy."""

import json
import os
import pathlib
import subprocess
import sys

import kreisel

SRC = pathlib.Path(kreisel.__file__).resolve().parents[1]

PROBE = """
import json, sys
from kreisel.cli import run
sys.argv = ["kreisel", *json.loads(sys.argv[1])]
try:
    run()
except SystemExit:
    pass
print(json.dumps(sorted(sys.modules)), file=sys.stderr)
"""

HEAVY = ("kreisel.dynamics", "kreisel.tops", "kreisel.plot", "kreisel.sweep", "kreisel.web", "kreisel.io.run",
         "matplotlib", "dask", "distributed", "fastapi", "uvicorn", "xarray", "pandas", "zarr")


def loaded(*args):
    env = dict(os.environ, PYTHONPATH=str(SRC))
    process = subprocess.run([sys.executable, "-c", PROBE, json.dumps(args)], env=env, capture_output=True,
                             text=True, timeout=600)
    return set(json.loads(process.stderr.strip().splitlines()[-1]))


def heavy(modules):
    return sorted(m for m in modules if any(m == h or m.startswith(h + ".") for h in HEAVY))


def test_import_kreisel_loads_no_subpackage():
    env = dict(os.environ, PYTHONPATH=str(SRC))
    code = ("import json, sys, kreisel; "
            "print(json.dumps(sorted(m for m in sys.modules if m.startswith(('kreisel.', 'numpy', 'numba')) "
            "or m == 'importlib.metadata')))")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=600).stdout
    modules = json.loads(out)
    # at most small private helpers of the base layer (kreisel._display); no subpackage, no numerics, and
    # not even the version, whose importlib.metadata would take most of the import time
    assert all(m.startswith("kreisel._") and "." not in m.removeprefix("kreisel.") for m in modules), modules
    assert "kreisel._version" not in modules and "kreisel._compiled" not in modules, modules


def test_help_loads_no_numerics_and_no_rich():
    modules = loaded("--help")
    assert heavy(modules) == [] and "numpy" not in modules and "numba" not in modules
    # click's plain help: typer's rich help would load rich's Markdown, Syntax and Traceback renderers
    assert not any(m == "rich" or m.startswith("rich.") for m in modules)


def test_convert_loads_the_rotations_and_no_heavy_stack():
    modules = loaded("convert", "--from", "euler:ZXZ", "--to", "quat", "-30", "45", "60", "--degrees")
    assert "kreisel.so3" in modules
    assert heavy(modules) == []
