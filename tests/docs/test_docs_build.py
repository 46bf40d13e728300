"""The documentation builds with -W and nitpicky references, offline, and its citations are links.

The build goes to docs/_build/html as ``make docs`` does, so that a second run is
incremental, except for the gallery: its examples are the test of the scripts in
examples/, so every test build runs each of them once, in quick mode (KREISEL_QUICK=1),
and fails if one raises (sphinx-gallery stops the build on an example's error).
"""

import os
import re
import subprocess
import sys

import pytest

from .conftest import DOCS, ROOT

HTML = DOCS / "_build" / "html"
SCRIPTS = sorted((ROOT / "examples").glob("plot_*.py"))


@pytest.fixture(scope="module")
def built():
    if not (DOCS / "node_modules" / "mathjax" / "es5" / "tex-chtml.js").exists():
        subprocess.run(["npm", "ci", "--no-audit", "--no-fund"], cwd=DOCS, check=True, capture_output=True,
                       timeout=600)
    # sphinx-gallery skips an example whose source checksum is unchanged; kreisel may have changed since
    for checksum in (DOCS / "auto_examples").glob("*.md5"):
        checksum.unlink()
    env = {**os.environ, "KREISEL_QUICK": "1", "MPLBACKEND": "Agg",
           "PYTHONPATH": os.pathsep.join([str(ROOT / "src"), os.environ.get("PYTHONPATH", "")])}
    result = subprocess.run([sys.executable, "-m", "sphinx", "-b", "html", "-W", "-n", "--keep-going", "-q",
                             str(DOCS), str(HTML)], env=env, capture_output=True, text=True, timeout=3000)
    assert result.returncode == 0, result.stderr[-6000:]
    return HTML


def _current_pages(built):
    """Pages of the current sources (the output directory keeps pages of sources since removed)."""
    for page in built.rglob("*.html"):
        relative = page.relative_to(built)
        if (DOCS / relative).with_suffix(".rst").exists() or relative.parts[0] == "_modules" or \
                str(relative) in ("genindex.html", "search.html", "py-modindex.html"):
            yield page


def test_no_page_loads_anything_from_the_internet(built):
    loads = re.compile(r"<(?:script|img|iframe|source)\b[^>]*\bsrc=[\"'](https?:)?//|"
                       r"<link\b[^>]*\bhref=[\"'](https?:)?//[^>]*>|@import\s+url\([\"']?(https?:)?//", re.I)
    offending = []
    for page in _current_pages(built):
        for match in loads.finditer(page.read_text(encoding="utf-8", errors="replace")):
            if "rel=\"canonical\"" not in match.group(0):
                offending.append(f"{page.relative_to(built)}: {match.group(0)[:100]}")
    assert offending == []


def test_math_is_rendered_by_the_bundled_mathjax(built):
    page = (built / "theory" / "3_angular_velocity.html").read_text(encoding="utf-8")
    assert re.search(r"<script[^>]+src=\"\.\./_static/mathjax/tex-chtml\.js", page)
    assert (built / "_static" / "mathjax" / "output" / "chtml" / "fonts" / "woff-v2").is_dir()


def test_theory_citations_are_links(built):
    page = (built / "api" / "generated" / "kreisel.so3.rotvec_to_matrix.html").read_text(encoding="utf-8")
    assert re.search(r'href="\.\./\.\./theory/2_rotation_group\.html#theory-2-2-3"[^>]*><span[^>]*>Theory §2\.2 \(3\)',
                     page)


def test_sections_are_numbered_as_in_the_chapter(built):
    page = (built / "theory" / "3_angular_velocity.html").read_text(encoding="utf-8")
    assert re.search(r'<span class="section-number">3\.5\. </span>The Bortz equation', page)
    assert re.search(r'<span class="eqno">\(3\.\d+\)', page)


def test_notebook_module_is_in_the_api_reference(built):
    page = (built / "api" / "kreisel.notebook.html").read_text(encoding="utf-8")
    assert "kreisel.notebook.show" in page
    assert (built / "api" / "generated" / "kreisel.notebook.show.html").exists()
    assert 'href="api/kreisel.notebook.html"' in (built / "reference.html").read_text(encoding="utf-8")


def test_gallery_is_not_empty():
    assert len(SCRIPTS) >= 10


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_every_example_ran_and_printed_a_result(built, script):
    page = (built / "auto_examples" / f"{script.stem}.html").read_text(encoding="utf-8")
    assert "sphx-glr-script-out" in page, "an example should print at least one result"


def test_tour_notebooks_are_pages_with_their_results(built):
    from kreisel.tour.notebooks import NOTEBOOKS

    index = (built / "tour_notebooks" / "index.html").read_text(encoding="utf-8")
    for name, functions in NOTEBOOKS.items():
        assert f"tour_{name}.html" in index
        page = (built / "tour_notebooks" / f"tour_{name}.html").read_text(encoding="utf-8")
        assert page.count("<b>all checks pass</b>") == len(functions), name
        assert page.count("data:image/png;base64,") >= len(functions), name
