"""Sphinx configuration for the kreisel documentation.

The build needs no network: no intersphinx, every figure is produced locally
(sphinx-gallery runs ``examples/``), and the API pages are generated here from
each subpackage's ``__all__`` so that modules still being written appear as
soon as they export names.
"""

from __future__ import annotations

import inspect
import os
import pathlib
import re
import sys

os.environ.setdefault("MPLBACKEND", "Agg")

import kreisel  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE / "_ext"))

project = "kreisel"
author = "the kreisel developers"
copyright = "the kreisel developers"
release = kreisel.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "theory_citations",
    "api_aliases",
    "language_switch",
    "gallery_translation",
]

# Translations (issue 36): English is the source; docs/locale/<language>/LC_MESSAGES holds one catalog per page
# (`make docs-po` updates them from the English text). `make docs` builds each language with -D language=...
locale_dirs = ["locale"]
gettext_compact = False
gettext_uuid = False
# code blocks and the gallery's printed output are not messages (Sphinx translates literal blocks only when
# "literal-block" is listed here), so a catalog holds prose, titles and captions only
gettext_additional_targets = []

# Private base classes (kreisel.*._module.Name) are not documented by design; the standard library
# and scipy are not linked because the docs build without network access (no intersphinx).
nitpick_ignore_regex = [("py:class", r"kreisel\.(\w+\.)*_\w+\.\w+"), ("py:(func|class|meth)", r"(functools|numpy|scipy|enum)\..*")]

# Equations are numbered by theory section: (5.12) is the twelfth of section 5.
numfig = True
math_numfig = True
numfig_secnum_depth = 1
math_eqref_format = "({number})"

templates_path = ["_templates"]
exclude_patterns = ["_build", "_generated", "node_modules", "**/sg_execution_times.rst", "sg_execution_times.rst", "api/generated/*.rst.txt", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.md5", "auto_examples/*.codeobj.json",
                    "tour_notebooks/*.ipynb", "tour_notebooks/*.py", "tour_notebooks/*.zip", "tour_notebooks/*.md5",
                    "tour_notebooks/*.codeobj.json"]
html_theme = "pydata_sphinx_theme"
html_title = f"kreisel {release}"
html_theme_options = {"navigation_with_keys": False, "show_toc_level": 2,
                      "navbar_end": ["language-switch", "theme-switcher", "navbar-icon-links"]}
html_last_updated_fmt = None

autosummary_generate = True
autosummary_imported_members = True
# (no autodoc_default_options: Sphinx 9 lets a default "members" override the class template's :members:)
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

# MathJax is served with the pages (docs/package.json pins it; `npm ci` in docs/ installs it),
# so that no page loads anything from the internet.
_MATHJAX = HERE / "node_modules" / "mathjax" / "es5"


def _bundle_mathjax():
    """Copy the parts of MathJax the pages use (TeX input, CommonHTML output, its fonts)."""
    import shutil

    if not (_MATHJAX / "tex-chtml.js").exists():
        raise RuntimeError("MathJax is missing: run `npm ci --no-audit --no-fund` in docs/ "
                           "(`make docs` does it) so that the docs render equations offline")
    target = HERE / "_generated" / "static" / "mathjax"
    fonts = target / "output" / "chtml" / "fonts" / "woff-v2"
    fonts.mkdir(parents=True, exist_ok=True)
    shutil.copy2(_MATHJAX / "tex-chtml.js", target / "tex-chtml.js")
    for font in (_MATHJAX / "output" / "chtml" / "fonts" / "woff-v2").iterdir():
        shutil.copy2(font, fonts / font.name)


_bundle_mathjax()
html_static_path = ["_static", "_generated/static"]
# the font stack of the Chinese pages (it applies to <html lang="zh-CN"> only)
html_css_files = ["language.css"]
mathjax_path = "mathjax/tex-chtml.js"

sphinx_gallery_conf = {
    "examples_dirs": [str(ROOT / "examples"), str(HERE / "_generated" / "tour")],
    "gallery_dirs": ["auto_examples", "tour_notebooks"],
    "filename_pattern": r"/(plot_|tour_)",
    "ignore_pattern": r"(__init__|_quick)\.py",
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("matplotlib", "_gallery.figure_scraper"),
    "download_all_examples": False,
    "remove_config_comments": True,
    "reset_modules": ("matplotlib",),
    "min_reported_time": 1,
    "plot_gallery": "True",
    # the timing page loads jQuery and DataTables from CDNs; the docs load nothing from the internet
    "write_computation_times": False,
}

# --------------------------------------------------------------------------------------------
# API pages: one page per public module, generated from its __all__.
# --------------------------------------------------------------------------------------------
API_MODULES = [
    ("kreisel.so3", "Rotations: quaternions, matrices, rotation vectors, Euler angles, SU(2)"),
    ("kreisel.kinematics", "Angular velocity, rate maps, point motion, screw axis, centrodes"),
    ("kreisel.inertia", "Mass properties, primitive solids, meshes, rigid bodies"),
    ("kreisel.dynamics", "Euler's equations, integrators, torques, trajectories"),
    ("kreisel.tops", "Euler, symmetric, Lagrange and Kovalevskaya tops"),
    ("kreisel.frames", "Particles in rotating frames"),
    ("kreisel.earth", "The Earth frame: falling bodies, Foucault pendulum"),
    ("kreisel.nav", "Strapdown attitude, coning, gyro errors, IMU logs"),
    ("kreisel.se3", "Rigid transforms, screws, SE(3)"),
    ("kreisel.scipy", "scipy's transform interface on kreisel's kernels: a drop-in for scipy code"),
    ("kreisel.io", "Scenario files, results, bundled examples"),
    ("kreisel.plot", "Figures"),
    ("kreisel.sweep", "Parameter sweeps"),
    ("kreisel.web", "The local web viewer"),
    ("kreisel.notebook", "Jupyter: the 3D trajectory player (the notebook extra)"),
    ("kreisel.cli", "The command line (Python entry points)"),
]


def _public_names(module):
    names = getattr(module, "__all__", None)
    if names is None:
        return None
    return [n for n in names if not n.startswith("_")]


def _api_page(modname, title):
    import importlib

    heading = f"``{modname}``"
    lines = [heading, "=" * len(heading), "", title + ".", ""]
    try:
        module = importlib.import_module(modname)
    except Exception as exc:  # a module still being written must not break the site
        return "\n".join(lines + [f".. note:: ``{modname}`` could not be imported while building "
                                  f"({type(exc).__name__}); it is still being written.", ""])
    names = _public_names(module)
    if module.__doc__:
        lines += [f".. automodule:: {modname}", "   :no-members:", ""]
    else:
        lines += [f".. module:: {modname}", ""]
    if not names:
        return "\n".join(lines + [".. note:: This module does not export public names yet.", ""])
    functions, classes, data = [], [], []
    for name in names:
        obj = getattr(module, name, None)
        if inspect.isclass(obj):
            classes.append(name)
        elif inspect.isfunction(obj) or inspect.isbuiltin(obj) or hasattr(obj, "py_func"):
            functions.append(name)
        else:
            data.append(name)
    for label, group, template in (("Functions", functions, None), ("Classes", classes, "class")):
        if group:
            lines += [label, "-" * len(label), "", f".. currentmodule:: {modname}", "",
                      ".. autosummary::", "   :toctree: generated", "   :nosignatures:"]
            if template:
                lines.append(f"   :template: {template}")
            lines += [""] + [f"   {n}" for n in group] + [""]
    if data:
        lines += ["Constants", "---------", ""]
        for name in data:
            value = getattr(module, name)
            if isinstance(value, dict):
                text = "{" + ", ".join(map(repr, value)) + "}"
            elif isinstance(value, (int, float, str, tuple, frozenset)):
                text = repr(value)
            else:
                text = f"{type(value).__module__}.{type(value).__qualname__} instance"
            lines += [f".. data:: {name}", "", f"   ``{text}``", ""]
    return "\n".join(lines)


def _top_level_page():
    """The ``kreisel`` namespace: where each re-exported name is documented."""
    rows = []
    for name in kreisel.__all__:
        obj = getattr(kreisel, name)
        if name == "__version__":
            continue
        home = getattr(obj, "__name__", "") if isinstance(obj, type(kreisel)) else getattr(obj, "__module__", "")
        exporters = [m for m, _ in API_MODULES if name in (getattr(sys.modules.get(m), "__all__", None) or ())]
        # documented in the subpackage that defines it, or else in the one that exports it
        sub = next((m for m in exporters if home == m or home.startswith(m + ".")), exporters[0] if exporters else None)
        if isinstance(obj, type(kreisel)):
            rows.append((name, f":doc:`{obj.__name__} <{obj.__name__}>`"))
        elif sub is not None:
            rows.append((name, f":py:obj:`{sub}.{name}`"))
    lines = ["``kreisel`` (top level)", "=" * 25, "",
             ".. module:: kreisel", "",
             "``import kreisel as kr`` gives the names below directly (``kr.quat_multiply``, ``kr.simulate``, ...).",
             "Each is documented once, in the subpackage that defines it.", "",
             ".. list-table::", "   :header-rows: 1", "   :widths: 30 70", "",
             "   * - name", "     - documented as"]
    for name, target in rows:
        lines += [f"   * - ``kr.{name}``", f"     - {target}"]
    return "\n".join(lines) + "\n"


def _write_if_changed(path, text):
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def _generate_api():
    import shutil

    api = HERE / "api"
    shutil.rmtree(api / "generated", ignore_errors=True)  # no stale pages of names since removed
    for modname, title in API_MODULES:
        _write_if_changed(api / f"{modname}.rst", _api_page(modname, title))
    _write_if_changed(api / "kreisel.rst", _top_level_page())


# --------------------------------------------------------------------------------------------
# Benchmark tables: bench/results/*.md (pipe tables) -> reStructuredText for inclusion.
# --------------------------------------------------------------------------------------------
def markdown_tables_to_rst(text):
    """Convert the simple markdown of bench/results (headings, paragraphs, pipe tables)."""
    out, table = [], []

    def flush():
        if not table:
            return
        header, *body = [r for r in table if not re.fullmatch(r"\|?[\s:|-]+\|?", r)]
        cells = lambda row: [c.strip().replace("`", "``") or "\\" for c in row.strip().strip("|").split("|")]
        out.extend(["", ".. list-table::", "   :header-rows: 1", ""])
        for row in [header, *body]:
            for k, cell in enumerate(cells(row)):
                out.append(("   * - " if k == 0 else "     - ") + cell)
        out.append("")
        table.clear()

    for line in text.splitlines():
        if line.lstrip().startswith("|"):
            table.append(line)
            continue
        flush()
        if line.startswith("#"):
            title = line.lstrip("#").strip()
            out += ["", f"**{title}**", ""]
        else:
            # a bare |x| in prose would be read as a reST substitution reference
            out.append(line.replace("`", "``").replace("|", "\\|"))
    flush()
    return "\n".join(out) + "\n"


def _generate_bench():
    target = HERE / "_generated"
    for topic in ("dynamics", "so3", "kinematics", "se3", "nav", "earth"):
        source = ROOT / "bench" / "results" / f"{topic}.md"
        if source.exists():
            text = markdown_tables_to_rst(source.read_text(encoding="utf-8"))
        else:
            text = (f".. note:: ``bench/results/{topic}.md`` has not been produced yet; "
                    f"run ``make bench`` and rebuild.\n")
        _write_if_changed(target / f"bench_{topic}.rst", text)


def _generate_references():
    """CLI and file-format references, generated from the commands and the schemas themselves."""
    from cli_reference import cli_reference
    from schema_reference import file_reference

    _write_if_changed(HERE / "_generated" / "cli_reference.rst", cli_reference())
    _write_if_changed(HERE / "_generated" / "file_reference.rst", file_reference(ROOT))


def _generate_tour_notebooks():
    """The tour's notebooks (kreisel.tour.notebooks) as a second sphinx-gallery: jupytext writes each as a script."""
    import jupytext

    from kreisel.tour.notebooks import NOTEBOOKS, notebook

    quick = os.environ.get("KREISEL_QUICK", "") not in ("", "0")
    target = HERE / "_generated" / "tour"
    _write_if_changed(target / "README.txt", "The tour as notebooks\n=====================\n\n"
                      "The sections of ``kreisel tour``, one notebook per part of the course, run here; "
                      "``kreisel tour --notebooks DIR`` writes them out as Jupyter notebooks.\n")
    for name in NOTEBOOKS:
        _write_if_changed(target / f"tour_{name}.py", jupytext.writes(notebook(name, quick), fmt="py:sphinx"))


_generate_api()
_generate_bench()
_generate_references()
_generate_tour_notebooks()


# --------------------------------------------------------------------------------------------
# Docstrings write norms as |ψ|, which reStructuredText reads as a substitution reference.
# Escape bars outside literals, roles and doctest lines before numpydoc parses the text.
# --------------------------------------------------------------------------------------------
_CODE = re.compile(r"(``.*?``|:[a-z:]+:`[^`]*`|`[^`]*`_?)")


def _escape_bars(line):
    if line.lstrip().startswith((">>>", "...")):
        return line
    parts = _CODE.split(line)
    return "".join(p if k % 2 else re.sub(r"(?<!\\)\|", r"\\|", p) for k, p in enumerate(parts))


def _escape_docstring(app, what, name, obj, options, lines):
    in_literal = False
    literal_indent = 0
    for k, line in enumerate(lines):
        stripped = line.strip()
        indent = len(line) - len(line.lstrip())
        if in_literal and stripped and indent <= literal_indent:
            in_literal = False
        if not in_literal:
            lines[k] = _escape_bars(line)
        if stripped.endswith("::") and not stripped.startswith(".. "):
            in_literal, literal_indent = True, indent
        elif stripped.startswith((".. math::", ".. code-block::")):
            in_literal, literal_indent = True, indent


def setup(app):
    app.connect("autodoc-process-docstring", _escape_docstring, priority=100)
