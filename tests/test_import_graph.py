"""The import graph of src/kreisel: no cycles between modules, no import of a higher layer.

The graph is read from the source with :mod:`ast`, so function-local imports
(which hide cycles from Python itself) count like module-level ones.
"""

import ast
import functools
import pathlib

import pytest

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "src" / "kreisel"

#: Layers from the bottom (the private base, then so3 <- kinematics <- inertia/dynamics <-
#: tops/frames/earth/nav/se3 <- io/plot/cli/web/sweep/tour/scipy): a module may import its own layer and those below.
LAYERS = (
    ("_compiled", "_validation", "_norms", "_fileio", "_version", "_html", "_display", "_optional"),
    ("so3",),
    ("kinematics",),
    ("inertia", "dynamics"),
    ("tops", "frames", "earth", "nav", "se3"),
    ("io", "plot", "cli", "web", "sweep", "tour", "notebook", "scipy", "__init__", "__main__"),
)
LAYER = {name: level for level, names in enumerate(LAYERS) for name in names}
#: Packages narrower than their layer: they import only these kreisel packages and the private base
#: (SE(3) is built on SO(3) alone, its exp/log and Jacobians included).
ONLY = {"se3": {"so3"}, "scipy": {"so3", "se3"}}


def _modules(root):
    """Dotted module name -> (path, is_package) for every .py file under ``root``."""
    modules = {}
    for path in root.rglob("*.py"):
        parts = list(path.relative_to(root.parent).with_suffix("").parts)
        is_package = parts[-1] == "__init__"
        modules[".".join(parts[:-1] if is_package else parts)] = (path, is_package)
    return modules


@functools.cache
def _tree(path):
    """The parsed source of ``path`` (each file is read once per test session)."""
    return ast.parse(path.read_text(encoding="utf-8"), str(path))


def _imports(root):
    """``(importer, node, module)`` for every import statement of a kreisel module, ``module`` the dotted name
    ``from ... import`` reads from (None for a plain ``import``)."""
    modules = _modules(root)
    for name, (path, is_package) in sorted(modules.items()):
        package = name if is_package else name.rpartition(".")[0]
        for node in ast.walk(_tree(path)):
            if isinstance(node, ast.Import):
                yield name, node, None
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[: len(package.split(".")) - node.level + 1]
                    yield name, node, ".".join(base + ([node.module] if node.module else []))
                else:
                    yield name, node, node.module or ""


def import_graph(root=PACKAGE):
    """Edges ``(importer, imported, line)`` between kreisel modules, function-local imports included."""
    modules = _modules(root)
    top = root.name
    edges = []
    for name, node, module in _imports(root):
        if module is None:
            targets = [alias.name for alias in node.names if alias.name.split(".")[0] == top]
        elif module.split(".")[0] != top:
            continue
        else:
            # ``from package import submodule`` imports the submodule
            targets = [f"{module}.{alias.name}" if f"{module}.{alias.name}" in modules else module for alias in node.names]
        edges.extend((name, target, node.lineno) for target in targets if target != name)
    unknown = [(a, b, line) for a, b, line in edges if b not in modules]
    assert not unknown, f"imports of modules that do not exist: {unknown}"
    return modules, edges


def compiled_modules(root=PACKAGE):
    """Modules of kreisel's packages (the private base aside) that define compiled functions: a function
    decorated by a name imported from numba or the compiled layer."""
    compilers = {}
    for name, node, module in _imports(root):
        sources = [alias.name for alias in node.names] if module is None else [module] * len(node.names)
        for alias, source in zip(node.names, sources):
            if source.split(".")[0] == "numba" or "._compiled" in f".{source}":
                compilers.setdefault(name, set()).add(alias.asname or alias.name.split(".")[0])
    found = set()
    for name, (path, _) in _modules(root).items():
        if layer(name) == 0 or name not in compilers:
            continue
        for node in ast.walk(_tree(path)):
            for decorator in getattr(node, "decorator_list", []) if isinstance(node, ast.FunctionDef) else []:
                while isinstance(decorator, (ast.Call, ast.Attribute)):
                    decorator = decorator.func if isinstance(decorator, ast.Call) else decorator.value
                if isinstance(decorator, ast.Name) and decorator.id in compilers[name]:
                    found.add(name)
    return found


def private_reaches(root=PACKAGE):
    """Imports of a private compiled module of another package, or of a private name defined in one."""
    modules, compiled = _modules(root), compiled_modules(root)
    found = []
    for name, node, module in _imports(root):
        if module is None or module.split(".")[0] != root.name:
            continue
        for alias in node.names:
            target = f"{module}.{alias.name}" if f"{module}.{alias.name}" in modules else module
            if target not in compiled or package(target) == package(name):
                continue
            if target.rpartition(".")[2].startswith("_") or alias.name.startswith("_"):
                found.append(f"{name}:{node.lineno}: {module}.{alias.name}")
    return found


def package(module):
    """The subpackage (or top-level module) of kreisel that ``module`` belongs to."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def layer(module):
    """Layer index of a dotted module name (the package facade ``kreisel`` is in the top layer)."""
    return LAYER[package(module)]


def cycles(nodes, edges):
    """Strongly connected components with more than one module (Tarjan, iterative)."""
    successors = {n: sorted({b for a, b, _ in edges if a == n}) for n in nodes}
    index, low, stack, on_stack, found = {}, {}, [], set(), []
    counter = 0
    for start in sorted(nodes):
        if start in index:
            continue
        work = [(start, iter(successors[start]))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(successors[child])))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    found.append(sorted(component))
    return found


def test_no_import_cycles():
    modules, edges = import_graph()
    assert cycles(modules, edges) == []


def test_no_import_of_a_higher_layer():
    _, edges = import_graph()
    upward = [f"{a} -> {b} (line {line})" for a, b, line in edges if layer(b) > layer(a)]
    assert upward == []


def narrower_than_layer(edges):
    """Edges from a package of :data:`ONLY` to a kreisel package it may not import."""
    return [(a, b, line) for a, b, line in edges if package(a) in ONLY and package(b) != package(a)
            and layer(b) > 0 and package(b) not in ONLY[package(a)]]


def test_se3_imports_only_so3():
    _, edges = import_graph()
    assert [f"{a} -> {b} (line {line})" for a, b, line in narrower_than_layer(edges)] == []


def test_no_package_reaches_into_another_packages_compiled_internals():
    # shared compiled code lives in kreisel._compiled; a package's own kernels and their layouts stay its own
    assert private_reaches() == []


def test_every_package_has_a_layer():
    assert {path.name for path in PACKAGE.iterdir() if path.is_dir() and (path / "__init__.py").exists()} <= set(LAYER)
    assert {path.stem for path in PACKAGE.glob("*.py")} <= set(LAYER)


def test_the_checks_see_function_local_imports_and_upward_imports(tmp_path):
    root = tmp_path / "kreisel"
    for name in ("so3", "kinematics", "se3"):
        (root / name).mkdir(parents=True)
        (root / name / "__init__.py").write_text("")
    (root / "__init__.py").write_text("")
    (root / "so3" / "a.py").write_text("def f():\n    from . import b\n")
    (root / "so3" / "b.py").write_text("from .a import f\n")
    (root / "so3" / "c.py").write_text("import kreisel.kinematics\n")
    (root / "se3" / "d.py").write_text("from ..kinematics import c\n")
    (root / "kinematics" / "e.py").write_text("def g():\n    from ..se3 import d\n")
    modules, edges = import_graph(root)
    assert cycles(modules, edges) == [["kreisel.so3.a", "kreisel.so3.b"]]
    assert [(a, b) for a, b, _ in edges if layer(b) > layer(a)] == [("kreisel.kinematics.e", "kreisel.se3.d"),
                                                                     ("kreisel.so3.c", "kreisel.kinematics")]
    assert [(a, b) for a, b, _ in narrower_than_layer(edges)] == [("kreisel.se3.d", "kreisel.kinematics")]


def test_reaching_into_compiled_internals_is_found(tmp_path):
    root = tmp_path / "kreisel"
    for name in ("_compiled", "so3", "frames", "earth"):
        (root / name).mkdir(parents=True)
        (root / name / "__init__.py").write_text("")
    (root / "__init__.py").write_text("")
    (root / "so3" / "_kernels.py").write_text("from .._compiled import cached\n@cached\ndef g():\n    pass\n")
    # calls compiled code without compiling any: a private helper, not compiled machinery
    (root / "so3" / "_plain.py").write_text("from .._compiled import kernels\nX = 1\n")
    (root / "frames" / "particle.py").write_text("import numba\n_NPAR = 14\nbuiltin = 1\n"
                                                 "@numba.njit(cache=True)\ndef rhs():\n    pass\n")
    (root / "frames" / "other.py").write_text("from .particle import _NPAR\n")
    (root / "earth" / "falling.py").write_text(
        "from ..so3 import _kernels, _plain\nfrom ..frames.particle import _NPAR, builtin\n"
        "def f():\n    from kreisel.so3._kernels import g\n")
    assert compiled_modules(root) == {"kreisel.so3._kernels", "kreisel.frames.particle"}
    assert private_reaches(root) == ["kreisel.earth.falling:1: kreisel.so3._kernels",
                                     "kreisel.earth.falling:2: kreisel.frames.particle._NPAR",
                                     "kreisel.earth.falling:4: kreisel.so3._kernels.g"]


@pytest.mark.parametrize("module", ["kreisel", "kreisel.__main__", "kreisel._compiled.elementwise", "kreisel.tour.runner"])
def test_layer_of_the_facade_private_base_and_user_layers(module):
    assert layer(module) == {"kreisel._compiled.elementwise": 0}.get(module, len(LAYERS) - 1)


#: Aliases every reader knows; any other module alias spells out what it stands for.
CONVENTIONAL_ALIASES = {"np", "pd", "xr", "plt", "mp"}


def short_aliases(root=PACKAGE):
    """``import x as y`` / ``from x import y as z`` with an alias of at most two letters (underscores aside)."""
    found = []
    for path in sorted(root.rglob("*.py")):
        for node in ast.walk(_tree(path)):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                found.extend(f"{path.relative_to(root.parent)}:{node.lineno}: {ast.unparse(node)}" for alias in node.names
                             if alias.asname and len(alias.asname.strip("_")) <= 2
                             and alias.asname not in CONVENTIONAL_ALIASES)
    return found


def test_no_short_module_aliases():
    assert short_aliases() == []


def test_short_aliases_are_found(tmp_path):
    root = tmp_path / "kreisel"
    root.mkdir()
    (root / "a.py").write_text("import numpy as np\nfrom . import kernels as _k\n\ndef f():\n    import math as m\n")
    assert short_aliases(root) == ["kreisel/a.py:2: from . import kernels as _k", "kreisel/a.py:5: import math as m"]
