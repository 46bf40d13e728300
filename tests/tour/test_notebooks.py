"""The tour as notebooks: made from the section functions, written by ``kreisel tour --notebooks``, executed.

The notebooks a user writes with the command, in English and in Chinese (``--lang zh``), are opened
with nbformat and run with nbclient in an IPython kernel (quick problems); every section shows its
checks passing.
"""

import ast
import inspect
import os
import pathlib
import re
import subprocess
import sys

import pytest

import kreisel
from kreisel.tour import SECTIONS
from kreisel.tour.notebooks import NOTEBOOKS, notebook, notebook_text

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
jupytext = pytest.importorskip("jupytext")


def test_every_section_is_in_one_notebook_in_tour_order():
    flat = [f for functions in NOTEBOOKS.values() for f in functions]
    assert len(flat) == len(SECTIONS) and set(flat) == set(SECTIONS)
    for functions in NOTEBOOKS.values():
        assert len({f.__module__ for f in functions}) == 1
        assert [SECTIONS.index(f) for f in functions] == sorted(SECTIONS.index(f) for f in functions)


@pytest.mark.parametrize("name", list(NOTEBOOKS))
def test_text_is_the_section_code_with_its_result_as_last_expression(name):
    nb = jupytext.reads(notebook_text(name, quick=True), fmt="py:percent")
    code = [c.source for c in nb.cells if c.cell_type == "code"]
    titles = [c.source.splitlines()[0] for c in nb.cells if c.cell_type == "markdown"][1:]
    assert "quick = True" in code[0] and len(code) == len(NOTEBOOKS[name]) + 1
    for function, title, source in zip(NOTEBOOKS[name], titles, code[1:]):
        assert title == inspect.getdoc(function).splitlines()[0].rstrip(".")
        tree = ast.parse(source)
        last = tree.body[-1]
        assert isinstance(last, ast.Expr) and ast.unparse(last.value.func) == "Section"
        assert not any(isinstance(n, ast.Return) for stmt in tree.body for n in ast.walk(stmt)
                       if not isinstance(stmt, (ast.FunctionDef, ast.Lambda)))
        # the cell holds the function's statements, not a call of the tour module
        body = ast.parse(inspect.getsource(function).lstrip()).body[0].body
        assert len(tree.body) == len(body) - 1   # all but the docstring


@pytest.mark.parametrize("name", list(NOTEBOOKS))
def test_notebooks_use_public_names_only(name):
    """The issue: the notebooks imported ``kreisel.tour.free_top._sense``, a private name."""
    tree = ast.parse(jupytext.reads(notebook_text(name), fmt="py:percent").cells[1].source)
    imported = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            imported |= {node.module, *(f"{node.module}.{alias.name}" for alias in node.names)}
        elif isinstance(node, ast.Import):
            imported |= {alias.name for alias in node.names}
    assert imported and not [n for n in imported if any(part.startswith("_") for part in n.split("."))], imported
    for node in ast.walk(ast.parse(notebook_text(name))):
        assert not (isinstance(node, ast.Attribute) and node.attr.startswith("_") and not node.attr.startswith("__")), \
            ast.unparse(node)


def test_section_ids_are_unique_and_from_the_title():
    from kreisel.tour.report import Section, render_html

    sections = [Section(title, "§1", "text", []) for title in ("Euler angles: the nodal line", "Gimbal lock")]
    ids = [re.findall(r"id='([^']+)'", s._repr_html_()) for s in sections]
    assert ids == [["euler-angles-the-nodal-line"], ["gimbal-lock"]]
    page = render_html(sections)
    assert re.findall(r"<section id='([^']+)'", page) == [i[0] for i in ids]
    assert [f"#{i[0]}" for i in ids] == re.findall(r"href='(#[^']+)'", page)


def test_a_section_that_returns_early_is_refused(monkeypatch):
    import kreisel.tour.notebooks as notebooks

    def early(quick):
        """An early exit"""
        if quick:
            return None
        return 1

    monkeypatch.setitem(notebooks.NOTEBOOKS, "99_bad", [early])
    with pytest.raises(ValueError, match="early must end in `return Section"):
        notebook("99_bad")


def test_unknown_name_is_refused():
    with pytest.raises(ValueError, match="name must be one of 01_rotations"):
        notebook_text("rotations")


@pytest.fixture(scope="module", params=["en", "zh"])
def written(tmp_path_factory, request):
    """``kreisel tour --notebooks DIR --quick --lang LANG`` run as a user runs it."""
    out = tmp_path_factory.mktemp(f"class-{request.param}")
    result = subprocess.run([sys.executable, "-m", "kreisel", "tour", "--notebooks", str(out), "--quick",
                             "--lang", request.param], capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split("\n")[0] == f"wrote {out / '01_rotations.ipynb'}"
    return out, request.param


def test_command_writes_one_valid_notebook_per_part(written):
    written, _ = written
    assert sorted(p.name for p in written.iterdir()) == [f"{name}.ipynb" for name in NOTEBOOKS]
    for path in written.iterdir():
        nb = nbformat.read(path, as_version=4)
        nbformat.validate(nb)
        assert nb.metadata.kernelspec.name == "python3"


def test_notebooks_execute_and_every_section_passes(written):
    written, lang = written
    # the kernel imports the kreisel under test (a source tree on PYTHONPATH or an install)
    env = {**os.environ, "MPLBACKEND": "Agg",
           "PYTHONPATH": os.pathsep.join([str(pathlib.Path(kreisel.__file__).parents[1]), os.environ.get("PYTHONPATH", "")])}
    ids = []
    for name, functions in NOTEBOOKS.items():
        nb = nbformat.read(written / f"{name}.ipynb", as_version=4)
        nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                resources={"metadata": {"path": str(written)}}).execute(env=env)
        shown = [o.data["text/html"] for c in nb.cells if c.cell_type == "code" for o in c.outputs
                 if "text/html" in o.get("data", {})]
        assert len(shown) == len(functions), name
        passed = {"en": "<b>all checks pass</b>", "zh": "<b>全部核对通过</b>"}[lang]
        for function, html in zip(functions, shown):
            assert passed in html and "class='fail'" not in html, (name, function.__name__)
        assert sum(html.count("data:image/png;base64,") for html in shown) >= len(functions), name
        ids += [i for html in shown for i in re.findall(r"<section id='([^']+)'", html)]
    assert len(ids) == len(SECTIONS) == len(set(ids)), ids  # one id per section, none twice


@pytest.mark.parametrize("name", list(NOTEBOOKS))
def test_chinese_notebooks_translate_the_markdown_and_keep_the_code(name):
    en, zh = (jupytext.reads(notebook_text(name, quick=True, lang=lang), fmt="py:percent") for lang in ("en", "zh"))
    assert [c.cell_type for c in en.cells] == [c.cell_type for c in zh.cells]
    code_en, code_zh = ([c.source for c in nb.cells if c.cell_type == "code"] for nb in (en, zh))
    assert code_zh[1:] == code_en[1:]   # every section's code, word for word
    assert code_zh[0] == code_en[0].replace("\n\nquick", "\nfrom kreisel.tour.report import use_language\n\n"
                                            "use_language('zh')\n\nquick")
    for cell_en, cell_zh in zip(en.cells, zh.cells):
        if cell_en.cell_type == "markdown":
            assert re.search(r"[\u4e00-\u9fff]", cell_zh.source) and cell_zh.source != cell_en.source
            title = cell_zh.source.splitlines()[0]
            underline = cell_zh.source.splitlines()[1]
            assert set(underline) <= {"=", "-"} and len(underline) >= len(title)
