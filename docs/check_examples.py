"""List the public functions, classes and methods whose docstring has no ``Examples`` section.

Run ``python docs/check_examples.py`` (exit status 1 if any are missing, 0 otherwise);
``--all`` also lists the names that are fine. Public names are those in each module's
``__all__`` (the modules the API reference documents), plus the public methods and
properties of the exported classes.
"""

from __future__ import annotations

import importlib
import inspect
import re
import sys

MODULES = ("kreisel.so3", "kreisel.kinematics", "kreisel.inertia", "kreisel.dynamics", "kreisel.tops",
           "kreisel.frames", "kreisel.earth", "kreisel.nav", "kreisel.se3", "kreisel.scipy", "kreisel.io", "kreisel.plot",
           "kreisel.sweep", "kreisel.web", "kreisel.cli")
_EXAMPLES = re.compile(r"^\s*Examples\s*\n\s*-{3,}\s*$", re.MULTILINE)


def has_example(obj):
    doc = inspect.getdoc(obj) or ""
    return bool(_EXAMPLES.search(doc)) and ">>>" in doc


def _members(cls):
    for name, member in vars(cls).items():
        if name.startswith("_"):
            continue
        if isinstance(member, (staticmethod, classmethod)):
            member = member.__func__
        if inspect.isfunction(member) or isinstance(member, property):
            yield name, member


def public_objects():
    """Yield (qualified name, kind, object) for every public function, class and method."""
    for modname in MODULES:
        try:
            module = importlib.import_module(modname)
        except Exception as exc:  # still being written
            print(f"# {modname}: not importable ({type(exc).__name__}: {exc})", file=sys.stderr)
            continue
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name, None)
            if inspect.isclass(obj):
                if issubclass(obj, Warning | Exception):
                    continue
                yield f"{modname}.{name}", "class", obj
                for member_name, member in _members(obj):
                    kind = "property" if isinstance(member, property) else "method"
                    if kind == "method":
                        yield f"{modname}.{name}.{member_name}", kind, member
            elif inspect.isfunction(obj) or hasattr(obj, "py_func"):
                yield f"{modname}.{name}", "function", obj


def main(argv):
    show_all = "--all" in argv
    missing = []
    total = 0
    for qualname, kind, obj in public_objects():
        total += 1
        ok = has_example(obj)
        if not ok:
            missing.append((qualname, kind, "no docstring" if not inspect.getdoc(obj) else "no example"))
        elif show_all:
            print(f"ok       {kind:8} {qualname}")
    for qualname, kind, why in missing:
        print(f"MISSING  {kind:8} {qualname}  ({why})")
    print(f"{total - len(missing)} of {total} public functions, classes and methods have a docstring example")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
