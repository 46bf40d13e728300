"""``pip install kreisel`` without extras: the core works alone, and a feature whose extra is missing names it.

A fresh virtual environment gets kreisel from a copy of the repository (not editable) and, as its only other
packages, the core dependencies of ``pyproject.toml`` with what they need in turn, taken from this
interpreter (so the test needs no download beyond pip's build backend). In it, the rotation, dynamics and
tops examples run, and every optional feature answers with the one line naming its extra, from Python and
from the ``kreisel`` command (status 2).
"""

import importlib.metadata
import os
import pathlib
import re
import subprocess
import sys
import tomllib

import pytest
from packaging.requirements import Requirement

ROOT = pathlib.Path(__file__).resolve().parents[1]
#: Packages only the extras install: none of them may be importable in the core environment.
EXTRA_ONLY = ("pandas", "xarray", "pyarrow", "meshio", "matplotlib", "dask", "distributed", "zarr", "fastapi",
              "uvicorn", "websockets", "anywidget")

CORE_EXAMPLES = r'''
import numpy as np
import kreisel as kr

# rotations: ZXZ Euler angles against the product of elementary rotations, exp/log, the object layer
def rz(a):
    return np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
def rx(a):
    return np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])
phi, theta, psi = np.deg2rad([30.0, 45.0, 60.0])
r = kr.Rotation.from_euler("ZXZ", [30.0, 45.0, 60.0], degrees=True)
assert np.allclose(r.as_matrix(), rz(phi) @ rx(theta) @ rz(psi), rtol=0, atol=1e-15)
assert np.allclose(kr.quat_to_matrix(r.as_quat()), r.as_matrix(), rtol=0, atol=1e-15)
assert np.allclose(kr.matrix_to_rotvec(kr.rotvec_to_matrix([0.1, -0.2, 0.3])), [0.1, -0.2, 0.3], rtol=0, atol=1e-15)
assert (r * r.inv()).magnitude() < 1e-15

# dynamics against the exact free top (elliptic functions): two independent solutions of Theory §5.3
t = np.linspace(0.0, 2.0, 101)
numeric = kr.simulate(kr.RigidBody([1.0, 2.0, 3.0]), t, [0.1, 2.0, 0.1], rtol=1e-12)
exact = kr.EulerTop(1.0, 2.0, 3.0).solve(t, [0.1, 2.0, 0.1])
assert np.abs(numeric.omega - exact.omega).max() < 1e-9, np.abs(numeric.omega - exact.omega).max()
assert np.abs(np.abs(np.sum(numeric.q * exact.q, axis=-1)) - 1).max() < 1e-9

# the heavy top starting at rest in nutation: the initial angle is a turning point
lower, upper = kr.LagrangeTop(1.0, 0.5, 1.0).turning_points([0.0, 0.5, 0.0], [0.0, 0.0, 10.0])
assert abs(lower - 0.5) < 1e-12 and 0.5 < upper < np.pi, (lower, upper)
print("core examples ok")
'''

MISSING_EXTRAS = r'''
import numpy as np
import kreisel as kr

trajectory = kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 1.0, 11), [0.1, 2.0, 0.1])

def sweep():
    from kreisel.sweep import sweep
    sweep(lambda x: {"y": x}, {"x": np.arange(3.0)})

def create_app():
    from kreisel.web import create_app

for extra, attempt in [("io", trajectory.to_xarray), ("io", trajectory.to_pandas),
                       ("io", lambda: trajectory.save("t.nc")), ("plot", lambda: kr.plot),
                       ("notebook", lambda: kr.show(trajectory)), ("viewer", create_app), ("sweep", sweep)]:
    try:
        attempt()
    except ImportError as exc:
        assert type(exc).__name__ == "MissingExtraError", repr(exc)
        print(extra, "|", exc)
    else:
        raise AssertionError(f"{attempt} ran without the {extra} extra")
'''


def _core_distributions():
    """Distributions of this interpreter the core dependencies need, recursively (markers evaluated)."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    todo = [Requirement(text) for text in project["dependencies"]]
    found = {}
    while todo:
        requirement = todo.pop()
        name = requirement.name.lower().replace("_", "-")
        if name in found:
            continue
        found[name] = distribution = importlib.metadata.distribution(requirement.name)
        for text in distribution.requires or ():
            needed = Requirement(text)
            wanted = [""] + sorted(requirement.extras)
            if needed.marker is None or any(needed.marker.evaluate({"extra": extra}) for extra in wanted):
                todo.append(needed)
    return found


def _link_packages(distributions, target):
    """Symbolic links in ``target`` to the importable top-level files and metadata of ``distributions``."""
    target.mkdir()
    for distribution in distributions.values():
        for top in {pathlib.PurePath(path).parts[0] for path in distribution.files}:
            source = pathlib.Path(distribution.locate_file(top))
            if top not in ("..", "__pycache__") and not top.endswith(".pth") and not (target / top).exists():
                (target / top).symlink_to(source)


def _run(args, base, check=True):
    env = {key: value for key, value in os.environ.items() if key not in ("PYTHONPATH", "NUMBA_CACHE_DIR")}
    done = subprocess.run([str(arg) for arg in args], cwd=base, env=env, capture_output=True, text=True,
                          timeout=600)
    if check:
        assert done.returncode == 0, f"{args} failed:\n{done.stdout}\n{done.stderr}"
    return done


@pytest.fixture(scope="module")
def core(tmp_path_factory, repository_copy):
    """A fresh virtual environment holding kreisel and its core dependencies only: its bin directory."""
    base = tmp_path_factory.mktemp("core")
    distributions = _core_distributions()
    assert not set(distributions) & set(EXTRA_ONLY), "the core depends on a package of an extra"
    _link_packages(distributions, base / "core-packages")
    venv = base / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=300)
    own = _run([venv / "bin" / "python", "-c", "import site; print(site.getsitepackages()[0])"], base).stdout
    pathlib.Path(own.strip(), "core-packages.pth").write_text(f"{base / 'core-packages'}\n", encoding="utf-8")
    before = {path.name for path in pathlib.Path(own.strip()).glob("*.dist-info")}
    # the dependencies are satisfied by the linked packages: pip fetches only the build backend
    _run([venv / "bin" / "python", "-m", "pip", "install", "--quiet", repository_copy], base)
    added = {path.name for path in pathlib.Path(own.strip()).glob("*.dist-info")} - before
    assert [name.split("-")[0] for name in added] == ["kreisel"], f"pip installed more than kreisel: {added}"
    return venv / "bin", base


def test_core_environment_lacks_the_extras(core):
    bin_dir, base = core
    probe = f"import importlib.util; print([m for m in {EXTRA_ONLY!r} if importlib.util.find_spec(m)])"
    assert _run([bin_dir / "python", "-c", probe], base).stdout.strip() == "[]"


def test_rotation_dynamics_and_tops_examples_run_on_the_core(core):
    bin_dir, base = core
    done = _run([bin_dir / "python", "-c", CORE_EXAMPLES], base)
    assert done.stdout.strip() == "core examples ok"
    assert str(base / "venv") in _run([bin_dir / "python", "-c", "import kreisel; print(kreisel.__file__)"],
                                      base).stdout


def test_a_missing_extra_is_named_in_one_line(core):
    bin_dir, base = core
    lines = _run([bin_dir / "python", "-c", MISSING_EXTRAS], base).stdout.strip().splitlines()
    assert [line.split(" | ")[0] for line in lines] == ["io", "io", "io", "plot", "notebook", "viewer", "sweep"]
    for line in lines:
        extra, message = line.split(" | ")
        assert re.fullmatch(rf'.+ needs [\w.]+: pip install "kreisel\[{extra}\]"', message), message


def test_the_command_runs_on_the_core_and_names_a_missing_extra(core):
    bin_dir, base = core
    done = _run([bin_dir / "kreisel", "convert", "--from", "euler:ZXZ", "--to", "quat", "0", "0", "90",
                 "--degrees"], base)
    assert [float(x) for x in done.stdout.split()] == pytest.approx([0.5 ** 0.5, 0, 0, 0.5 ** 0.5], abs=1e-10)  # 10 digits
    # the extra is named before any work: a long simulation or fit does not run only to fail at its output
    for args, extra in ((["tour", "--out", "tour"], "plot"), (["serve", "--no-browser"], "viewer"),
                        (["sweep", "tennis_racket"], "sweep"), (["simulate", "tennis_racket", "-o", "t.nc"], "io"),
                        (["simulate", "tennis_racket", "-o", "t.parquet"], "io"),
                        (["fit", "phone_toss", "--plot", "fit.png"], "plot"),
                        # two extras in the one line, not one and after installing it the other
                        (["plot", "t.nc", "-o", "fig.png"], "plot,io"), (["animate", "t.nc", "-o", "a.gif"], "plot,io"),
                        (["sweep", "tennis_racket", "--plot", "fig.png"], "sweep,plot")):
        done = _run([bin_dir / "kreisel", *args], base, check=False)
        assert done.returncode == 2, (args, done.stdout, done.stderr)
        assert done.stderr.count("\n") == 1 and f'pip install "kreisel[{extra}]"' in done.stderr, done.stderr
        assert "Traceback" not in done.stderr + done.stdout
        assert done.stdout == "", (args, done.stdout)
