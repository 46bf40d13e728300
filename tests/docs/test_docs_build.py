"""The documentation builds with -W and nitpicky references, offline, and its citations are links.

The build goes to docs/_build/html as ``make docs`` does, so that a second run is
incremental; gallery examples run in quick mode (KREISEL_QUICK=1) and only when
their source changed (sphinx-gallery keeps the outputs of unchanged examples).
"""

import os
import re
import subprocess
import sys

import pytest

from .conftest import DOCS, ROOT

HTML = DOCS / "_build" / "html"


@pytest.fixture(scope="module")
def built():
    if not (DOCS / "node_modules" / "mathjax" / "es5" / "tex-chtml.js").exists():
        subprocess.run(["npm", "ci", "--no-audit", "--no-fund"], cwd=DOCS, check=True, capture_output=True,
                       timeout=600)
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
