"""The wheel a user installs holds the whole package: every module and every file the docs and commands use.

``pip install kreisel`` is not editable: what is not in the wheel does not exist for the user, however well the
tests pass on the source tree. The wheel is built from a copy of the repository as a clone has it.
"""

import os
import subprocess
import sys
import zipfile

import pytest

from kreisel.cli.examples import sweep_files
from kreisel.io.bundled import EXAMPLES
from kreisel.io.gyro import RECORDINGS, TRIALS

#: What the README, the getting-started page and the commands open by name inside the installed package.
USED_BY_NAME = (
    *(f"kreisel/io/examples/{name}.toml" for name in EXAMPLES),
    *(f"kreisel/io/examples/{file}" for file in (*RECORDINGS.values(), *TRIALS.values())),
    "kreisel/io/examples/broad/README.md",   # the BROAD trial's source and licence travel with it
    *(f"kreisel/sweep/examples/{name}.toml" for name in sweep_files()),
    *(f"kreisel/web/static/{name}" for name in ("index.html", "viewer.js", "widget.js", "favicon.svg")),
    "kreisel/py.typed",
)


@pytest.fixture(scope="module")
def wheel(tmp_path_factory, repository_copy):
    """The names in the wheel ``pip wheel --no-deps`` builds from the repository."""
    out = tmp_path_factory.mktemp("wheel")
    env = {key: value for key, value in os.environ.items() if key != "PYTHONPATH"}
    done = subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "-w", str(out),
                           str(repository_copy)], env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    [built] = out.glob("kreisel-*.whl")
    return set(zipfile.ZipFile(built).namelist())


def test_the_wheel_holds_every_file_of_the_package_and_nothing_else(wheel, repository_copy):
    source = repository_copy / "src"
    package = {path.relative_to(source).as_posix() for path in (source / "kreisel").rglob("*")
               if path.is_file() and "__pycache__" not in path.parts}
    installed = {name for name in wheel if ".dist-info/" not in name}
    assert sorted(package - installed) == [] and sorted(installed - package) == []


def test_the_wheel_holds_what_the_docs_open_by_name(wheel):
    assert [name for name in USED_BY_NAME if name not in wheel] == []
