"""The tour's sections as Jupyter notebooks, made from the section functions themselves.

Each module of the tour becomes one notebook, in the order of the chapter: a first cell with
the module's imports and the ``quick`` switch, then one cell per section holding the
section function's own code, whose last expression is the :class:`Section` (shown with its
checks and figures). The tour code is written once; the notebooks are its text read anew.

The text form is jupytext's percent format (:func:`notebook_text`); jupytext turns it into
a notebook (:func:`notebook`), ``kreisel tour --notebooks DIR`` writes those out
(:func:`write_notebooks`) and the documentation renders the same text as a sphinx-gallery
page. Headings are underlined (setext), which Markdown and reStructuredText read alike.
In Chinese (``lang="zh"``) the markdown cells are translated with the tour's catalog
(:mod:`kreisel.tour.i18n`) and the first code cell shows the sections in Chinese
(:func:`~kreisel.tour.report.use_language`); every other code cell is the English one.
Writing notebooks needs jupytext (``pip install 'kreisel[notebook]'``).
"""

from __future__ import annotations

import ast
import importlib.util
import inspect
import pathlib
import sys
import textwrap
import unicodedata

from .._fileio import atomic_output
from .i18n import catalog, check_language
from .runner import SECTIONS

__all__ = ["NOTEBOOKS", "notebook_text", "notebook", "write_notebooks"]


def _grouped():
    """Tour modules in order of their first section, each with its sections in tour order."""
    groups = {}
    for function in SECTIONS:
        groups.setdefault(function.__module__, []).append(function)
    return {f"{k:02d}_{name.rpartition('.')[2]}": functions for k, (name, functions) in enumerate(groups.items(), 1)}


#: Notebook names (``01_rotations``, ...) -> the section functions they hold, in the order of the chapter.
NOTEBOOKS = _grouped()


def _jupytext():
    try:
        import jupytext
    except ImportError:
        raise ImportError("writing the tour's notebooks needs jupytext: pip install 'kreisel[notebook]'") from None
    return jupytext


def _markdown(text):
    return "# %% [markdown]\n" + "\n".join(f"# {line}".rstrip() for line in text.strip().splitlines()) + "\n"


def _heading(title, underline):
    # as long as the title is wide: a Chinese character takes two columns (reStructuredText counts them so)
    width = sum(2 if unicodedata.east_asian_width(c) in "WF" else 1 for c in title)
    return f"{title}\n{underline * width}"


def _absolute_import(node, package):
    """A module-level import of a tour module, with relative module names made absolute."""
    if isinstance(node, ast.ImportFrom) and node.level:
        name = importlib.util.resolve_name("." * node.level + (node.module or ""), package)
        node = ast.ImportFrom(module=name, names=node.names, level=0)
    return ast.unparse(node)


def _setup_cell(module, functions, quick, lang):
    """Imports of the module, the module-level helpers its sections use, the language and the ``quick`` switch."""
    tree = ast.parse(inspect.getsource(module))
    imports = [_absolute_import(node, module.__package__) for node in tree.body
               if isinstance(node, (ast.Import, ast.ImportFrom)) and getattr(node, "module", None) != "__future__"]
    sections = {f.__name__ for f in functions} | {"SECTIONS", "__all__"}
    defined = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            defined.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            defined.update(n.id for n in ast.walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store))
    used = {n.id for f in functions for n in ast.walk(ast.parse(textwrap.dedent(inspect.getsource(f))))
            if isinstance(n, ast.Name)}
    helpers = sorted((defined - sections) & used)
    if helpers:
        imports.append(f"from {module.__name__} import {', '.join(helpers)}")
    if lang != "en":
        imports += ["from kreisel.tour.report import use_language", "", f"use_language({lang!r})"]
    return "# %%\n" + "\n".join(imports) + f"\n\nquick = {bool(quick)}  # True: smaller problems, the same checks\n"


def _body(function):
    """The code of a section function, run at top level: its body with ``return X`` as the last expression ``X``."""
    source = textwrap.dedent(inspect.getsource(function))
    definition = ast.parse(source).body[0]
    body = definition.body
    if isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
        start = body[0].end_lineno  # the docstring becomes the cell's heading
        body = body[1:]
    else:
        start = definition.body[0].lineno - 1
    last = body[-1]
    nested = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)

    def returns(node):
        if isinstance(node, ast.Return):
            yield node
        if not isinstance(node, nested):
            for child in ast.iter_child_nodes(node):
                yield from returns(child)

    early = [r for stmt in body for r in returns(stmt) if r is not last]
    if not isinstance(last, ast.Return) or last.value is None or early:
        raise ValueError(f"tour section {function.__name__} must end in `return Section(...)` and return nowhere else")
    lines = source.splitlines()
    row = last.lineno - 1
    lines[row] = lines[row][:last.col_offset] + lines[row][last.col_offset + len("return "):]
    return textwrap.dedent("\n".join(lines[start:last.end_lineno])).strip() + "\n"


def notebook_text(name, quick=False, lang="en"):
    """The notebook ``name`` (a key of :data:`NOTEBOOKS`) in jupytext's percent format.

    Parameters
    ----------
    name : str
        ``"01_rotations"``, ... (see :data:`NOTEBOOKS`).
    quick : bool
        The value of the ``quick`` switch in the first code cell.
    lang : {"en", "zh"}
        The language of the markdown cells and of the sections' results; the code is the same.

    Returns
    -------
    str
        Python source whose ``# %%`` comments separate the cells.

    Examples
    --------
    >>> text = notebook_text("02_kinematics")
    >>> text.splitlines()[:3]
    ['# %% [markdown]', '# Theory §3: instantaneous centre and centrodes, the Bortz coefficient', '# ====================================================================']
    >>> "quick = False" in text, text.count("# %%\\n")
    (True, 3)
    """
    if name not in NOTEBOOKS:
        raise ValueError(f"name must be one of {', '.join(NOTEBOOKS)}, got {name!r}")
    tr = catalog(check_language(lang))
    functions = NOTEBOOKS[name]
    module = sys.modules[functions[0].__module__]
    topic = module.__doc__.strip().splitlines()[0].rstrip(".")
    topic = topic.split(" for ", 1)[1] if topic.startswith("Tour section") and " for " in topic else topic
    topic = topic.removeprefix("Tour section: ")
    topic = tr(topic[0].upper() + topic[1:])
    intro = tr("Each code cell below is one section of ``kreisel tour``: the tour's own code, which "
                          "computes the chapter's results with kreisel and shows them next to the values they must "
                          "reproduce, with its figures. Change a cell and run it again. In the first cell, "
                          "``quick = True`` makes the problems smaller; the checks stay the same.")
    cells = [_markdown(_heading(topic, "=") + "\n\n" + (textwrap.fill(intro, 98) if lang == "en" else intro)),
             _setup_cell(module, functions, quick, lang)]
    for function in functions:
        title = tr(inspect.getdoc(function).splitlines()[0].rstrip("."))
        cells += [_markdown(_heading(title, "-")), "# %%\n" + _body(function)]
    return "\n".join(cells)


def notebook(name, quick=False, lang="en"):
    """The notebook ``name`` as an ``nbformat`` notebook (Python 3 kernel), read from :func:`notebook_text`.

    Parameters
    ----------
    name : str
        A key of :data:`NOTEBOOKS`.
    quick : bool
        The value of the ``quick`` switch in the first code cell.
    lang : {"en", "zh"}
        The language of the markdown cells and of the sections' results.

    Returns
    -------
    nbformat.NotebookNode

    Examples
    --------
    >>> nb = notebook("03_navigation")
    >>> [cell.cell_type for cell in nb.cells]
    ['markdown', 'code', 'markdown', 'code']
    """
    jupytext = _jupytext()
    nb = jupytext.reads(notebook_text(name, quick, lang), fmt="py:percent")
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nb.metadata.pop("jupytext", None)
    return nb


def write_notebooks(out_dir, quick=False, lang="en"):
    """Write every tour notebook to ``out_dir/<name>.ipynb`` (each file replaced atomically).

    Parameters
    ----------
    out_dir : str or os.PathLike
        Created if missing.
    quick : bool
        The value of the ``quick`` switch in each notebook's first code cell.
    lang : {"en", "zh"}
        The language of the markdown cells and of the sections' results.

    Returns
    -------
    list of pathlib.Path
        The files written, in the order of the chapter.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     [p.name for p in write_notebooks(d)][:2]
    ['01_rotations.ipynb', '02_kinematics.ipynb']
    """
    check_language(lang)
    jupytext = _jupytext()
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for name in NOTEBOOKS:
        path = out_dir / f"{name}.ipynb"
        with atomic_output(path) as tmp:
            tmp.write_text(jupytext.writes(notebook(name, quick, lang), fmt="ipynb"), encoding="utf-8")
        written.append(path)
    return written
