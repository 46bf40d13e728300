"""Sphinx extension: resolve the short names docstrings use for kreisel's API.

kreisel re-exports every public name at the top level (``kr.simulate``), and
docstrings refer to objects the way users call them: ``kreisel.RigidBody``,
``kreisel.EulerTop.solve``, or, inside a class, ``from_datasheet``. Each object
is documented once, in the subpackage that defines it. When the Python domain
cannot resolve such a reference, this resolver looks for the documented object
it names: the same dotted path under a documented subpackage, or a unique
documented object whose name ends with the reference (preferring the class the
reference sits in). A reference that stays ambiguous or unknown is left to
Sphinx, which warns under ``-n``.
"""

from __future__ import annotations

from sphinx.util.nodes import make_refnode


def _candidates(objects, target, context_class):
    suffix = "." + target
    found = [name for name in objects if name.endswith(suffix) and name.startswith("kreisel.")]
    if context_class:
        inside = [name for name in found if name.rsplit(".", 1)[0].endswith("." + context_class)
                  or name.rsplit(".", 1)[0] == context_class]
        if inside:
            return inside
    return found


def _documented_module(domain, target):
    """The nearest documented package of a module ``target`` (submodules have no page of their own)."""
    while target:
        if target in domain.modules:
            return target
        target = target.rpartition(".")[0]
    return None


def _is_top_level_object(documented, target):
    """Whether the documented ``kreisel.<sub>.<target>`` is the object that ``kreisel.<target>`` names."""
    import importlib

    import kreisel

    package, _, path = documented.partition(".")[2].partition(".")
    try:
        alias, obj = kreisel, importlib.import_module(f"kreisel.{package}")
        for part in target.split("."):
            alias = getattr(alias, part)
        for part in path.split("."):
            obj = getattr(obj, part)
    except (AttributeError, ImportError):
        return False
    return obj is alias


def _resolve(app, env, node, contnode):
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"].lstrip("~.")
    domain = env.get_domain("py")
    if node.get("reftype") == "mod":
        module = _documented_module(domain, target) if target.startswith("kreisel.") else None
        if module is None:
            return None
        entry = domain.modules[module]
        return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id, contnode, module)
    objects = domain.objects
    if target.startswith("kreisel."):
        target = target[len("kreisel."):]
        # a top-level alias: the same name in the subpackage that documents it
        exact = [name for name in objects if name.count(".") == target.count(".") + 2
                 and name.startswith("kreisel.") and name.split(".", 2)[2] == target]
        if len(exact) > 1:
            # kreisel.Rotation is kreisel.so3.Rotation, not the scipy drop-in's class of the same name
            exact = [name for name in exact if _is_top_level_object(name, target)]
        if len(exact) == 1:
            entry = objects[exact[0]]
            return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id, contnode, exact[0])
    candidates = _candidates(objects, target, node.get("py:class"))
    if len(candidates) != 1:
        return None
    entry = objects[candidates[0]]
    return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id, contnode, candidates[0])


def setup(app):
    app.connect("missing-reference", _resolve)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
