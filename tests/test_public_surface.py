"""The public surface is declared: every public module has ``__all__``, and each listed name exists."""

import ast
import importlib
import pathlib
import sys

import pytest

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "src" / "kreisel"
PUBLIC = sorted(
    path for path in PACKAGE.rglob("*.py")
    if not any(part.startswith("_") and part != "__init__.py" for part in path.relative_to(PACKAGE).parts)
)


def _module_name(path):
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@pytest.mark.parametrize("path", PUBLIC, ids=_module_name)
def test_public_module_declares_all(path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    if any(isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "__all__" for t in node.targets) for node in tree.body):
        return
    # a lazily importing module (module-level __getattr__) computes it on access
    assert hasattr(importlib.import_module(_module_name(path)), "__all__"), f"{_module_name(path)} has no __all__"


def _all_assignments(tree):
    return [node for node in tree.body
            if any(getattr(target, "id", None) == "__all__" for target in
                   (node.targets if isinstance(node, ast.Assign) else [getattr(node, "target", None)]))
            or isinstance(node, ast.Expr) and isinstance(node.value, ast.Call)
            and getattr(node.value.func, "value", None) is not None and getattr(node.value.func.value, "id", None) == "__all__"]


@pytest.mark.parametrize("path", PUBLIC, ids=_module_name)
def test_all_is_one_literal_list(path):
    """The one form of ``__all__`` every type checker reads: mypy ignores ``+=``/``extend`` of another module's
    list and ``*`` unpacking, and would then see a package export nothing but its literal names."""
    assignments = _all_assignments(ast.parse(path.read_text(encoding="utf-8")))
    if not assignments:
        return  # lazy: computed on access (test_public_module_declares_all)
    assert len(assignments) == 1, f"{_module_name(path)} builds __all__ in {len(assignments)} statements"
    value = getattr(assignments[0], "value", None)
    assert isinstance(assignments[0], (ast.Assign, ast.AnnAssign)) and isinstance(value, (ast.List, ast.Tuple))
    assert all(isinstance(item, ast.Constant) and isinstance(item.value, str) for item in value.elts), (
        f"{_module_name(path)}: write the names of __all__ out")


@pytest.mark.parametrize("name", ["kreisel.so3", "kreisel.kinematics", "kreisel.inertia", "kreisel.dynamics",
                                  "kreisel.tops", "kreisel.se3", "kreisel.frames", "kreisel.earth", "kreisel.nav"])
def test_every_listed_name_exists(name):
    module = importlib.import_module(name)
    assert [n for n in module.__all__ if not hasattr(module, n)] == []


# One re-export convention: a package's __init__ lists in __all__ every public name it binds from its own modules
# (or from the private base layer), and a name it re-exports from a public module is one that module lists in its
# own __all__ (private modules, such as tops._elliptic, have no public surface of their own to agree with). A name
# passed through from another public package is an alias kept for old imports: it stays unlisted, so that it is
# documented once, where it lives.
PACKAGES = sorted(path for path in PUBLIC if path.name == "__init__.py")


def reexports(path):
    """``(name, module)`` for each name ``path`` binds by a relative ``from ... import`` at module level, ``module``
    the dotted module it is read from (None when the name is a submodule)."""
    package = _module_name(path)
    for node in ast.parse(path.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.ImportFrom) and node.level:
            base = package.split(".")[: len(package.split(".")) - node.level + 1]
            module = ".".join(base + ([node.module] if node.module else []))
            for alias in node.names:
                if alias.name == "*":  # the names the module lists
                    yield from ((name, module) for name in importlib.import_module(module).__all__)
                    continue
                is_module = (PACKAGE.parent / module.replace(".", "/") / alias.name).is_dir() or (
                    PACKAGE.parent / module.replace(".", "/") / f"{alias.name}.py").is_file()
                yield alias.asname or alias.name, None if is_module else module


def _top_package(module):
    """``kreisel.so3`` for ``kreisel.so3.rotation``; None for the private base (``kreisel._compiled...``)."""
    parts = module.split(".")
    if len(parts) < 2 or parts[1].startswith("_"):
        return None
    return ".".join(parts[:2])


def convention_breaches(path):
    module = importlib.import_module(_module_name(path))
    listed = set(module.__all__)
    found = []
    for name, source in reexports(path):
        # submodules are attributes of their package whether imported or not: listing them is optional
        if name.startswith("_") or source is None:
            continue
        if _top_package(source) not in (_top_package(module.__name__), None):
            if name in listed:
                found.append(f"{name} (from {source}) is another package's name but listed in __all__")
        elif name not in listed:
            found.append(f"{name} (from {source}) is bound but not in __all__")
        elif not any(part.startswith("_") for part in source.split(".")[1:]):
            if name not in getattr(importlib.import_module(source), "__all__", ()):
                found.append(f"{name} is re-exported from {source}, whose __all__ does not list it")
    return found


@pytest.mark.parametrize("path", PACKAGES, ids=_module_name)
def test_one_reexport_convention(path):
    assert convention_breaches(path) == []


def test_reexport_breaches_are_found(tmp_path, monkeypatch):
    root = tmp_path / "probe"
    for name in ("pkg", "other"):
        (root / name).mkdir(parents=True)
    (root / "__init__.py").write_text("")
    (root / "other" / "__init__.py").write_text("__all__ = ['k', 'm']\ndef k(): pass\ndef m(): pass\n")
    (root / "pkg" / "__init__.py").write_text(
        "from .a import f, g, CONSTANT\nfrom .a import h as public_h\nfrom ..other import k, m\nfrom .b import *\n"
        "__all__ = ['f', 'g', 'k', 'b1']\n")
    (root / "pkg" / "a.py").write_text("__all__ = ['f']\ndef f(): pass\ndef g(): pass\ndef h(): pass\nCONSTANT = 1\n")
    (root / "pkg" / "b.py").write_text("__all__ = ['b1', 'b2']\nb1 = b2 = 1\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(sys.modules[__name__], "PACKAGE", root)
    assert convention_breaches(root / "pkg" / "__init__.py") == [
        "g is re-exported from probe.pkg.a, whose __all__ does not list it",
        "CONSTANT (from probe.pkg.a) is bound but not in __all__",
        "public_h (from probe.pkg.a) is bound but not in __all__",
        "k (from probe.other) is another package's name but listed in __all__",
        "b2 (from probe.pkg.b) is bound but not in __all__",
    ]
