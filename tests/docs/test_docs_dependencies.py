"""`make docs` installs what the documentation runs: every import of the gallery and the docs' own code.

`make docs` installs kreisel with the extras ``all`` and ``docs`` only (the
Makefile), so a package that the examples import but only ``dev`` brings
(mpmath once) breaks the build on a fresh clone while ``make test`` passes.
"""

import ast
import importlib.metadata
import re
import sys
import tomllib

from packaging.requirements import Requirement

from .conftest import DOCS, ROOT

#: The extras the Makefile's docs target installs.
DOCS_EXTRAS = ("all", "docs")


def _name(distribution):
    return re.sub(r"[-_.]+", "-", distribution).lower()


def _installed_closure(requirements):
    """Distributions that installing ``requirements`` (Requirement objects) brings, through installed metadata."""
    seen, pending = set(), list(requirements)
    while pending:
        requirement = pending.pop()
        name = _name(requirement.name)
        extras = sorted(requirement.extras)
        key = (name, tuple(extras))
        if key in seen:
            continue
        seen.add(key)
        try:
            requires = importlib.metadata.requires(requirement.name) or []
        except importlib.metadata.PackageNotFoundError:
            continue
        for text in requires:
            nested = Requirement(text)
            if nested.marker is None or any(nested.marker.evaluate({"extra": extra}) for extra in ["", *extras]):
                pending.append(nested)
    return {name for name, _ in seen}


def _docs_install():
    """Distributions of ``pip install -e ".[all,docs]"``: kreisel's own requirements, then theirs."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    extras, wanted, requirements = project["optional-dependencies"], list(DOCS_EXTRAS), list(project["dependencies"])
    while wanted:
        for text in extras[wanted.pop()]:
            requirement = Requirement(text)
            if requirement.name == project["name"]:
                wanted += sorted(requirement.extras)
            else:
                requirements.append(text)
    return _installed_closure(Requirement(text) for text in requirements)


def _imports(path):
    """Top-level module names ``path`` imports (absolute imports only, anywhere in the file)."""
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            yield from (alias.name.partition(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0:
            yield node.module.partition(".")[0]


def test_every_import_of_the_documentation_is_installed_by_make_docs():
    scripts = sorted((ROOT / "examples").glob("*.py")) + sorted(DOCS.glob("*.py")) + sorted(DOCS.glob("_ext/*.py"))
    local = {path.stem for path in scripts} | {"kreisel"}
    installed = _docs_install()
    providers = importlib.metadata.packages_distributions()
    missing = {}
    for script in scripts:
        for module in set(_imports(script)) - local - set(sys.stdlib_module_names):
            if not any(_name(d) in installed for d in providers.get(module, [])):
                missing.setdefault(module, []).append(str(script.relative_to(ROOT)))
    assert missing == {}, f"imported, but not installed by the extras {DOCS_EXTRAS}: {missing}"
