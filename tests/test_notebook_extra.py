"""``pip install "kreisel[notebook]"`` is enough to open and run the tour's notebooks and ``kreisel.show``.

A metadata check, as in test_core_install.py but without building an environment: the extra (with the
extras it names) must list JupyterLab, a kernel, the widget, jupytext and nbformat, and every package the
generated notebooks import that the core does not already install.
"""

import importlib.metadata
import pathlib
import sys
import tomllib

import pytest
from packaging.requirements import Requirement

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _names(requirements):
    return {Requirement(text).name.lower().replace("_", "-") for text in requirements}


def _extra(name):
    """The distributions an extra installs by name, with the kreisel extras it includes resolved."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    extras = project["optional-dependencies"]
    found, todo = set(), [name]
    while todo:
        for text in extras[todo.pop()]:
            requirement = Requirement(text)
            if requirement.name == "kreisel":
                todo += sorted(requirement.extras)
            else:
                found.add(requirement.name.lower().replace("_", "-"))
    return found, _names(project["dependencies"])


def test_the_notebook_extra_holds_jupyterlab_a_kernel_and_the_widget():
    extra, _ = _extra("notebook")
    assert {"jupyterlab", "ipykernel", "anywidget", "jupytext", "nbformat", "matplotlib"} <= extra, extra


def test_every_package_the_tour_notebooks_import_is_installed_by_the_extra():
    jupytext = pytest.importorskip("jupytext")
    from kreisel.tour.notebooks import NOTEBOOKS, notebook, notebook_text

    extra, core = _extra("notebook")
    providers = importlib.metadata.packages_distributions()
    modules = set()
    for name in NOTEBOOKS:
        cells = jupytext.reads(notebook_text(name), fmt="py:percent").cells
        for line in cells[1].source.splitlines():
            if line.startswith(("import ", "from ")):
                modules.add(line.split()[1].split(".")[0])
    third_party = modules - set(sys.stdlib_module_names) - {"kreisel"}
    assert {"numpy", "matplotlib"} <= third_party
    for module in third_party:
        distributions = {d.lower().replace("_", "-") for d in providers[module]}
        assert distributions & (extra | core), (module, distributions)
    # the notebooks ask for the kernel ipykernel installs
    assert notebook(next(iter(NOTEBOOKS))).metadata.kernelspec.name == "python3"
