"""The Chinese catalogs (docs/locale/zh_CN) keep up with the English pages they translate and use the glossary.

A page listed in the Makefile's ``TRANSLATED`` has every entry of its catalog translated and none fuzzy, so that an
edit of the English page without its translation fails here (``make docs-po`` then marks what changed). Wherever an
English text contains a term of docs/locale/zh_CN/glossary.toml, its translation contains the chapter's Chinese term.
Every number of an English text is in its translation.
"""

import re
import tomllib
from collections import Counter

import polib
import pytest

from .conftest import DOCS, ROOT

LOCALE = DOCS / "locale" / "zh_CN"


def _translated_pages():
    """The Makefile's ``TRANSLATED := ...`` and ``TRANSLATED += ...`` lines, in order."""
    lines = [re.split(r"[:+]=", line, maxsplit=1)[1] for line in (ROOT / "Makefile").read_text(encoding="utf-8").splitlines()
             if re.match(r"TRANSLATED [:+]=", line)]
    return " ".join(lines).split()


def _source(page):
    """The English source of ``page``: a page of docs/, or for a gallery page (written by sphinx-gallery at build
    time) its script in examples/ or the gallery's README."""
    if page.startswith("auto_examples/"):
        name = page.split("/", 1)[1]
        return ROOT / "examples" / ("README.rst" if name == "index" else f"{name}.py")
    return DOCS / f"{page}.rst"


PAGES = _translated_pages()
GLOSSARY = tomllib.loads((LOCALE / "glossary.toml").read_text(encoding="utf-8"))["terms"]

#: Code, roles and links: their text is not prose, so it neither needs nor gets a glossary term.
_MARKUP = re.compile(r"``.+?``|:[a-z:]+:`[^`]*`|`[^`]*`_")


def _catalog(page):
    return polib.pofile(str(LOCALE / "LC_MESSAGES" / f"{page}.po"))


def _prose(text):
    return re.sub(r"\s+", " ", _MARKUP.sub(" ", text)).lower()


def _uses(prose, english):
    """Whether ``prose`` contains the term ``english`` as words ("rigid-body" counts, "numpy-quaternion" not)."""
    words = r"[-\s]+".join(map(re.escape, english.lower().split()))
    return re.search(rf"(?<![\w-]){words}(?![\w-])", prose) is not None


def test_the_translated_pages_include_getting_started_and_exist():
    assert "getting_started" in PAGES
    for page in PAGES:
        assert _source(page).is_file(), page
        assert (LOCALE / "LC_MESSAGES" / f"{page}.po").is_file(), page


@pytest.mark.parametrize("page", PAGES)
def test_every_entry_is_translated_and_none_is_fuzzy(page):
    catalog = _catalog(page)
    assert [e.msgid for e in catalog.untranslated_entries()] == []
    assert [e.msgid for e in catalog.fuzzy_entries()] == []
    assert [e.msgid for e in catalog.obsolete_entries()] == []


def _missing_terms(entry):
    if entry.msgstr == entry.msgid and "\\" in entry.msgid:
        return []  # a display equation, kept verbatim (its \text{...} included)
    prose = _prose(entry.msgid)
    return [english for english, chinese in GLOSSARY.items() if _uses(prose, english) and chinese not in entry.msgstr]


@pytest.mark.parametrize("page", PAGES)
def test_the_glossary_terms_are_used(page):
    missing = [(terms, entry.msgid[:60]) for entry in _catalog(page).translated_entries()
               if (terms := _missing_terms(entry))]
    assert missing == []


@pytest.mark.parametrize("page", PAGES)
def test_math_code_and_references_are_unchanged(page):
    for entry in _catalog(page).translated_entries():
        assert _references(entry.msgstr) == _references(entry.msgid), entry.msgid[:60]


def _references(text):
    """Literals, roles' and links' targets and math of ``text``: what a translation keeps (a title may be translated)."""
    kept = [re.sub(r"^(:[a-z:]+:)?`[^`<]*<([^>]*)>`(_?)$", r"\1`\2`\3", token) for token in _MARKUP.findall(text)]
    return sorted(kept)


#: A number of a text (``45``, ``0.0186``, ``1776``): digits not inside a word, so "3D" (三维) is not one.
_NUMBER = re.compile(r"(?<![0-9A-Za-z_.])\d+(?:\.\d+)?(?![0-9A-Za-z])")


def _changed_numbers(entry):
    """The numbers of ``entry.msgid`` that its translation lacks (a number retyped wrongly, or dropped)."""
    return sorted((Counter(_NUMBER.findall(entry.msgid)) - Counter(_NUMBER.findall(entry.msgstr))).elements())


@pytest.mark.parametrize("page", PAGES)
def test_every_number_of_the_english_text_is_in_its_translation(page):
    changed = [(numbers, entry.msgid[:60]) for entry in _catalog(page).translated_entries()
               if (numbers := _changed_numbers(entry))]
    assert changed == []


def test_the_number_check_would_catch_a_retyped_number_and_not_3d():
    entry = polib.POEntry(msgid="At Hefei the plane turns once in 45 h 28 min; the 3D viewer shows it.",
                          msgstr="在合肥，摆动平面每 45 h 23 min 转一周；三维查看器显示了这一点。")
    assert _changed_numbers(entry) == ["28"]


def test_the_glossary_has_one_chinese_term_per_english_term():
    assert len(GLOSSARY) >= 20
    assert all(re.search(r"[\u4e00-\u9fff]", chinese) for chinese in GLOSSARY.values())


def test_the_glossary_test_would_catch_a_missing_term():
    entry = polib.POEntry(msgid="The precession of a sleeping top, in rigid-body terms (numpy-quaternion)",
                          msgstr="用刚体的语言说，睡陀螺的转动（numpy-quaternion）")
    assert _missing_terms(entry) == ["precession"]


def test_the_user_guide_tutorials_the_scipy_page_and_the_whole_gallery_are_translated():
    gallery = {f"auto_examples/{script.stem}" for script in (ROOT / "examples").glob("plot_*.py")}
    required = {"user_guide/05b_phone_laboratory", "user_guide/03b_attitude_estimation", "coming_from",
                "auto_examples/index"} | gallery
    assert len(gallery) >= 10 and required - set(PAGES) == set()


@pytest.mark.parametrize("page", [page for page in PAGES if page.startswith("auto_examples/")])
def test_a_gallery_catalog_holds_no_running_time(page):
    # sphinx-gallery's "Total running time of the script" changes with every run (docs/_ext/gallery_translation.py)
    assert [e.msgid for e in _catalog(page) if "running time" in e.msgid.lower()] == []
