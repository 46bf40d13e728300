"""`make docs` works on a fresh clone: the documentation builds with -W and nitpicky references, offline, and its
citations are links.

The build runs the Makefile's ``docs`` recipe in a copy of the committed tree
(``git ls-files``) in docs/_build/fresh-clone, as on a fresh clone, with the
test's Python (the environment ``make docs`` would install:
tests/docs/test_docs_dependencies.py checks that its extras cover every
import) and the repository's MathJax and compiled-code cache (the copy's
sources keep their modification times, so their source state, and so their
cache, is the same). A file the build needs but git does not hold, or one
that only an earlier build generates, fails here; only the copy's own build
directory is kept from run to run, so that Sphinx reads again only the pages
whose sources changed. The gallery's examples are the test of the
scripts in examples/: every build runs each of them once, in quick mode
(KREISEL_QUICK=1), and fails if one raises (sphinx-gallery stops the build on
an example's error).
"""

import os
import re
import shutil
import subprocess
import sys

import pytest

from .conftest import DOCS, ROOT

SCRIPTS = sorted((ROOT / "examples").glob("plot_*.py"))


#: Where the fresh copy is made: only its build directory (Sphinx's output and environment) outlives a run, so
#: that pages whose sources did not change are not read again; everything else is copied anew.
CLONE = DOCS / "_build" / "fresh-clone"


def _fresh_clone(target):
    """Copy the files git holds (as they are in the working tree) to ``target``, modification times kept.

    What ``target`` held is removed first, except ``docs/_build``.
    """
    kept = target / "docs" / "_build"
    for folder in (target, target / "docs"):
        for child in folder.iterdir() if folder.is_dir() else ():
            if child == kept or child == target / "docs":
                continue
            if child.is_symlink() or not child.is_dir():
                child.unlink()
            else:
                shutil.rmtree(child)
    listed = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout
    for name in filter(None, listed.decode().split("\0")):
        source = ROOT / name
        if source.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target / name, follow_symlinks=False)
    return target


@pytest.fixture(scope="module")
def built():
    if not (DOCS / "node_modules" / "mathjax" / "es5" / "tex-chtml.js").exists():
        subprocess.run(["npm", "ci", "--no-audit", "--no-fund"], cwd=DOCS, check=True, capture_output=True,
                       timeout=600)
    CLONE.mkdir(parents=True, exist_ok=True)
    clone = _fresh_clone(CLONE)
    (clone / "docs" / "node_modules").symlink_to(DOCS / "node_modules", target_is_directory=True)
    (ROOT / ".numba_cache").mkdir(exist_ok=True)
    (clone / ".numba_cache").symlink_to(ROOT / ".numba_cache", target_is_directory=True)
    env = {**os.environ, "KREISEL_QUICK": "1",
           "PYTHONPATH": os.pathsep.join([str(clone / "src"), os.environ.get("PYTHONPATH", "")])}
    # the recipe as it is, with the installation steps taken as done (this Python is that installation)
    result = subprocess.run(["make", "docs", f"PY={sys.executable}", "--assume-old=.venv/.installed-docs",
                             "--assume-old=docs/node_modules/.installed"], cwd=clone, env=env, capture_output=True,
                            text=True, timeout=3000)
    assert result.returncode == 0, (result.stdout[-3000:], result.stderr[-6000:])
    return clone / "docs" / "_build" / "html" / "en"


def _current_pages(built):
    """Pages of the current sources (the output directory keeps pages of sources since removed)."""
    docs = built.parents[2]
    for page in built.rglob("*.html"):
        relative = page.relative_to(built)
        if (docs / relative).with_suffix(".rst").exists() or relative.parts[0] == "_modules" or \
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


def test_chinese_pages_are_translated_and_every_page_links_to_its_other_language(built):
    chinese = built.parent / "zh_CN"
    english = (built / "theory" / "1_configuration.html").read_text(encoding="utf-8")
    page = (chinese / "theory" / "1_configuration.html").read_text(encoding="utf-8")
    assert "刚体运动的描述" in page and "Describing the motion of a rigid body" not in page
    assert "十分钟 API 导览" in (chinese / "getting_started.html").read_text(encoding="utf-8")
    assert 'href="../../zh_CN/theory/1_configuration.html"' in english
    assert 'href="../../en/theory/1_configuration.html"' in page
    for root, other in ((built, "zh_CN"), (chinese, "en")):
        for html in _current_pages(root):
            relative = html.relative_to(root)
            assert f'href="{"../" * (len(relative.parts) - 1)}../{other}/{relative.as_posix()}"' in \
                html.read_text(encoding="utf-8"), relative


def test_tutorials_the_scipy_page_and_the_gallery_are_in_chinese(built):
    chinese = built.parent / "zh_CN"
    pages = {"user_guide/05b_phone_laboratory.html": "你的手机：一个自由转动实验室",
             "user_guide/03b_attitude_estimation.html": "由真实 IMU 求姿态",
             "coming_from.html": "从 scipy、pytransform3d 或 numpy-quaternion 迁移过来",
             "auto_examples/plot_06_tennis_racket.html": "网球拍定理（理论 §5.4）"}
    for page, title in pages.items():
        assert title in (chinese / page).read_text(encoding="utf-8"), page
    # the thumbnails' titles and tooltips are raw HTML that sphinx-gallery writes; docs/_ext/gallery_translation.py
    # translates them
    index = (chinese / "auto_examples" / "index.html").read_text(encoding="utf-8")
    assert '<div class="sphx-glr-thumbnail-title">网球拍定理（理论 §5.4）</div>' in index
    assert 'tooltip="自由（欧拉）陀螺 I = (1, 2, 3) 在每个主轴附近旋转。' in index
    assert "Tennis-racket theorem" not in index and "The free (Euler) top" not in index


def test_no_chinese_page_shows_markup_that_was_not_parsed(built):
    # reStructuredText takes ``x`` or :role:`x` for markup only next to a space or punctuation, so a translation
    # that writes it against a Chinese character shows the backticks instead (without a warning)
    from .test_translations import PAGES

    raw = re.compile(r"``|:(?:func|class|meth|mod|math|ref|doc|data|eq|download|attr):`")
    shown = []
    for page in PAGES:
        html = (built.parent / "zh_CN" / f"{page}.html").read_text(encoding="utf-8")
        text = re.sub(r"<[^>]+>", "", re.sub(r"<(pre|script)\b.*?</\1>", "", html, flags=re.S))
        shown += [f"{page}: {text[max(m.start() - 30, 0):m.end() + 30]!r}" for m in raw.finditer(text)]
    assert shown == []


@pytest.mark.parametrize("page", ["theory/5_euler_top.html", "getting_started.html",
                                  "user_guide/05b_phone_laboratory.html", "auto_examples/index.html"])
def test_chromium_draws_every_chinese_character_with_a_cjk_font(built, chromium, glyphs, page):
    tab = chromium.new_page()
    try:
        tab.goto((built.parent / "zh_CN" / page).as_uri(), wait_until="load")
        stack = tab.evaluate("getComputedStyle(document.body).fontFamily")
        report = glyphs.cjk_glyphs(tab)
    finally:
        tab.close()
    assert stack.startswith('"Noto Sans CJK SC"'), stack  # docs/_static/language.css
    assert report["characters"] > 300
    assert report["missing"] == [], (report["missing"][:20], report["fonts"])


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
