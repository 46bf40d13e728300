"""The Chinese tour keeps up with the English one: every English string the tour writes has a translation,
every translation is still used, keeps the English numbers, symbols and fields, and uses the chapter's terms."""

import re
import tomllib
import warnings

import pytest

from kreisel.tour import report
from kreisel.tour.i18n import Catalog, catalog, check_language, needs_translation
from kreisel.tour.notebooks import NOTEBOOKS, notebook_text
from kreisel.tour.report import Check, Section, render_html

from ..conftest import ROOT

GLOSSARY = tomllib.loads((ROOT / "docs" / "locale" / "zh_CN" / "glossary.toml").read_text(encoding="utf-8"))["terms"]
ZH = Catalog("zh")


def _render_everything(sections):
    """Every text the tour can write in Chinese, through a fresh catalog: its ``used`` and ``missing`` after."""
    catalog.cache_clear()
    render_html(sections, lang="zh")
    for name in NOTEBOOKS:
        notebook_text(name, lang="zh")
    failing = Section("Gimbal lock", "§2.3", "", [Check.equal("intermediate axis", False, True)],
                      error="ValueError: something English")
    render_html([failing], lang="zh")
    report.use_language("zh")
    try:
        failing._repr_html_(), sections[0]._repr_html_()
    finally:
        report.use_language("en")
    zh = catalog("zh")
    zh(report.NO_CJK_FONT)  # shown only on a machine without a CJK font (test_figures_without_a_cjk_font_...)
    return zh


def test_every_english_string_has_an_entry_and_every_entry_is_used(sections):
    zh = _render_everything(sections)
    assert sorted(zh.missing) == [], "English text of the tour without a Chinese entry in locale/zh.toml"
    assert sorted(set(zh.entries) - zh.used) == [], "entries of locale/zh.toml that the tour no longer writes"


def test_the_check_would_catch_a_new_english_string_and_a_stale_entry(sections):
    zh = Catalog("zh")
    assert zh("Precession of a spinning coin on a table") == "Precession of a spinning coin on a table"
    assert zh.missing == {"Precession of a spinning coin on a table"}
    zh("ω′ (rad/s)"), zh("N = 1, α²Ωλ^2·c_N")   # symbols and units need no entry
    assert len(zh.missing) == 1 and "Gimbal lock" not in zh.used


def _numbers(text):
    return sorted(re.findall(r"\d+(?:\.\d+)?(?:e-?\d+)?", text))


def _symbols(text):
    """Greek letters, subscripted or numbered names (I_C, ω′2, e3, J3²) and fields."""
    return sorted(re.findall(r"[α-ωΑ-Ω]|\b[A-Za-z]{1,2}(?:_\w+|\d\w*)|\{\w+\}", text))


@pytest.mark.parametrize("english", list(ZH.entries))
def test_a_translation_keeps_numbers_fields_and_symbols(english):
    chinese = ZH.entries[english]
    assert _numbers(chinese) == _numbers(english)
    assert re.findall(r"\{(\w+)\}", chinese) and set(re.findall(r"\{(\w+)\}", chinese)) == set(
        re.findall(r"\{(\w+)\}", english)) or "{" not in english + chinese
    # the English words go, the symbols (θ, ω′, I_C, Rz, ...) stay
    assert [s for s in _symbols(english) if s not in chinese] == [], english
    if needs_translation(re.sub(r"\{\w+\}", "", english), ZH.neutral_words):   # not "{name} ({err}°)"
        assert re.search(r"[\u4e00-\u9fff]", chinese), english


def _uses(english_text, term):
    """Whether ``english_text`` contains ``term`` as whole words, case and hyphens ignored."""
    words = [w for w in re.split(r"[\s-]+", english_text.lower())]
    term_words = term.lower().replace("-", " ").split()
    return any(words[k:k + len(term_words)] == term_words for k in range(len(words)))


@pytest.mark.parametrize("term", list(GLOSSARY))
def test_the_chapters_terms_are_used(term):
    wrong = [english for english, chinese in ZH.entries.items()
             if _uses(re.sub(r"[^\w\s'-]", " ", english), term) and GLOSSARY[term] not in chinese]
    assert wrong == []


def test_a_string_matches_one_entry_at_most(sections):
    texts = {s.title for s in sections} | {c.label for s in sections for c in s.checks}
    texts |= {caption for s in sections for _, caption in s.figures}
    ambiguous = {t: ZH.matches(t) for t in texts if len(ZH.matches(t)) > 1}
    assert ambiguous == {}


def test_templates_translate_the_values_that_are_words():
    assert ZH("loop: largest θ on the sampled path (rad)") == "环圈：采样轨迹上 θ 的最大值 (rad)"
    assert ZH("N = 3: drift at λ = 0.209 (rad/s)") == "N = 3：λ = 0.209 处的漂移 (rad/s)"


def test_an_unknown_language_is_refused():
    with pytest.raises(ValueError, match="lang must be one of 'en', 'zh', got 'de'"):
        check_language("de")
    with pytest.raises(ValueError, match="lang must be one of"):
        render_html([], lang="zh_CN")


def _glyph_warnings(sections, lang):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        render_html(sections, lang=lang)
    return [str(w.message) for w in caught if "missing from font" in str(w.message) or "Glyph" in str(w.message)]


def test_every_figure_renders_in_chinese_without_a_missing_glyph(sections):
    if report.cjk_family() is None:
        pytest.skip("no CJK font (.ci/run installs fonts-noto-cjk)")
    assert _glyph_warnings(sections, "zh") == []
    fig = sections[0].figures[0][0]
    with report._translated(fig, ZH, report.cjk_family()):
        texts = [t.get_text() for t in fig.findobj(report.Text)]
    assert "节线 N" in texts and "nodal line N" not in texts
    assert "nodal line N" in [t.get_text() for t in fig.findobj(report.Text)]   # restored


def test_the_glyph_check_would_catch_chinese_text_without_a_cjk_font(sections, monkeypatch):
    monkeypatch.setattr(report, "cjk_family", lambda: "DejaVu Sans")   # a font without Chinese characters
    assert any("节线" in message or "Glyph" in message for message in _glyph_warnings(sections[:1], "zh"))


def test_figures_without_a_cjk_font_keep_english_text_and_the_report_says_so(sections, monkeypatch):
    monkeypatch.setattr(report, "cjk_family", lambda: None)
    page = render_html(sections[:2], lang="zh")
    assert page.count(ZH(report.NO_CJK_FONT)) == 1
    assert _glyph_warnings(sections[:2], "zh") == []
    assert ZH(report.NO_CJK_FONT) not in render_html(sections[:2], lang="en")


def test_a_cjk_font_installed_after_matplotlibs_font_cache_is_found(monkeypatch):
    from matplotlib import font_manager

    from kreisel.tour import _fonts

    if not any("CJK" in path for path in font_manager.findSystemFonts()):
        pytest.skip("no Noto CJK font (.ci/run installs fonts-noto-cjk)")
    monkeypatch.setattr(font_manager.fontManager, "ttflist",
                        [font for font in font_manager.fontManager.ttflist if "CJK" not in font.name])
    assert _fonts.cjk_family.__wrapped__() == "Noto Sans CJK SC"
    added = [font for font in font_manager.fontManager.ttflist if "CJK" in font.name]
    assert {font.fname for font in added} == {next(f.fname for f in added)} and all(f.weight == 400 for f in added)
