"""The public API's annotations hold, as a type checker reads them.

mypy, strict, checks the modules listed in ``[tool.mypy] files`` of ``pyproject.toml``, together with a
probe that names every attribute of ``kreisel.__all__``: the package imports them lazily (module
``__getattr__``), so its ``TYPE_CHECKING`` block must list each one for type checkers and editors. A probe
per subpackage star-imports it and names each of its ``__all__``: mypy reads only a literal ``__all__``.
"""

import importlib
import os
import pathlib
import subprocess
import sys
import tomllib

import pytest

import kreisel

ROOT = pathlib.Path(__file__).resolve().parents[1]

pytest.importorskip("mypy")

#: The subpackages whose star import the probes check (those that need no optional dependency).
PACKAGES = ("so3", "kinematics", "inertia", "dynamics", "tops", "se3", "frames", "earth", "nav")


def test_mypy_strict_passes_and_sees_every_public_name(tmp_path):
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["tool"]["mypy"]
    probe = tmp_path / "public_names.py"
    probe.write_text("import kreisel\n\n" + "".join(f"kreisel.{name}\n" for name in kreisel.__all__),
                     encoding="utf-8")
    probes = [str(probe)]
    for package in PACKAGES:
        names = importlib.import_module(f"kreisel.{package}").__all__
        probes.append(str(tmp_path / f"star_{package}.py"))
        pathlib.Path(probes[-1]).write_text(f"from kreisel.{package} import *\n\n" + "".join(f"{name}\n" for name in names),
                                            encoding="utf-8")
    env = {key: value for key, value in os.environ.items() if key != "MYPYPATH"}
    done = subprocess.run([sys.executable, "-m", "mypy", "--config-file", "pyproject.toml", *config["files"],
                           *probes], cwd=ROOT, capture_output=True, text=True, env=env, timeout=900)
    assert done.returncode == 0, done.stdout + done.stderr
