"""The public surface is declared: every public module has ``__all__``, and each listed name exists."""

import ast
import importlib
import pathlib

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


@pytest.mark.parametrize("name", ["kreisel.so3", "kreisel.kinematics", "kreisel.inertia", "kreisel.dynamics",
                                  "kreisel.tops", "kreisel.se3", "kreisel.frames", "kreisel.earth", "kreisel.nav"])
def test_every_listed_name_exists(name):
    module = importlib.import_module(name)
    assert [n for n in module.__all__ if not hasattr(module, n)] == []
