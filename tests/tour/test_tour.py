"""``kreisel tour --quick`` writes a self-contained report in which every section passes, in English and in
Chinese (``--lang zh``), with the same numbers in the same table cells and no missing glyph in chromium."""

import html.parser
import re

import pytest
from typer.testing import CliRunner

from kreisel.cli import app
from kreisel.tour import SECTIONS

#: every visible character, not only the Chinese ones; combining marks (the dot of q̇) are drawn with their letter
VISIBLE = r"[^\s\p{M}]"


@pytest.fixture(scope="module")
def reports(tmp_path_factory):
    """The report of each language, written by the command as a user runs it."""
    out, pages = tmp_path_factory.mktemp("tour"), {}
    for lang in ("en", "zh"):
        result = CliRunner().invoke(app, ["tour", "--quick", "--lang", lang, "--out", str(out / lang)])
        assert result.exit_code == 0, result.output
        assert "FAIL" not in result.output and "report:" in result.output   # the summary stays English
        pages[lang] = out / lang / "index.html"
    return pages


@pytest.mark.parametrize("lang", ["en", "zh"])
def test_quick_tour_passes_and_is_self_contained(reports, lang):
    html = reports[lang].read_text(encoding="utf-8")
    summary = {"en": f"{len(SECTIONS)} of {len(SECTIONS)} sections pass",
               "zh": f"{len(SECTIONS)} 节中 {len(SECTIONS)} 节通过"}[lang]
    assert summary in html
    # the text without the embedded figures, whose base64 may spell FAIL by chance
    text = re.sub(r"data:image/png;base64,[A-Za-z0-9+/=]+", "", html)
    assert "FAIL" not in text and "未通过" not in text
    assert html.count("data:image/png;base64,") >= len(SECTIONS)
    assert not re.search(r"(src|href)=['\"]https?://", html)  # nothing fetched from the network


def test_an_unknown_language_is_refused_before_any_work():
    result = CliRunner().invoke(app, ["tour", "--lang", "de"])
    assert result.exit_code == 2 and "--lang must be one of en, zh, got 'de'" in result.output


class _Tables(html.parser.HTMLParser):
    """The cells of every table, row by row, as text."""

    def __init__(self):
        super().__init__()
        self.tables, self._cell = [], None

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self.tables[-1].append([])
        elif tag in ("td", "th"):
            self._cell = ""

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self.tables[-1][-1].append(self._cell)
            self._cell = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data


def _numbers(cell):
    return re.findall(r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?", cell)


def test_both_reports_have_the_same_numbers_in_the_same_cells(reports):
    tables = {}
    for lang, path in reports.items():
        parser = _Tables()
        parser.feed(path.read_text(encoding="utf-8"))
        tables[lang] = parser.tables
    en, zh = tables["en"], tables["zh"]
    assert len(en) == len(zh) == 1 + len(SECTIONS)
    assert [[len(row) for row in t] for t in en] == [[len(row) for row in t] for t in zh]
    compared = 0
    for k, (table_en, table_zh) in enumerate(zip(en, zh)):
        for row_en, row_zh in zip(table_en, table_zh):
            # the overview's last column is the time each section took: a measurement of this run, not the chapter's
            cells = zip(row_en[:-1], row_zh[:-1]) if k == 0 else zip(row_en, row_zh)
            for cell_en, cell_zh in cells:
                assert _numbers(cell_zh) == _numbers(cell_en), (cell_en, cell_zh)
                compared += len(_numbers(cell_en))
    assert compared > 200
    assert zh[1][0][:3] == ["量", "kreisel", "应得值"] and en[1][0][:3] == ["quantity", "kreisel", "expected"]


@pytest.mark.parametrize("lang", ["en", "zh"])
def test_chromium_draws_every_character_of_the_report(reports, chromium, glyphs, lang):
    page = chromium.new_page(viewport={"width": 1000, "height": 1400})
    try:
        page.goto(reports[lang].as_uri(), wait_until="load", timeout=120_000)
        shown = glyphs.cjk_glyphs(page, characters=VISIBLE)
    finally:
        page.close()
    assert shown["missing"] == [] and shown["distinct"] > 60
    if lang == "zh":
        assert any("CJK" in name for name in shown["fonts"]), shown["fonts"]


def test_the_glyph_check_fails_where_chromium_has_no_chinese_font(reports, playwright_chromium, glyphs, tmp_path):
    config = tmp_path / "fonts.conf"   # the machine's fonts less every one that has Chinese characters
    config.write_text(f"""<?xml version="1.0"?><!DOCTYPE fontconfig SYSTEM "fonts.dtd"><fontconfig>
<dir>/usr/share/fonts</dir><cachedir>{tmp_path / "cache"}</cachedir>
<selectfont><rejectfont><pattern><patelt name="lang"><string>zh-cn</string></patelt></pattern></rejectfont>
</selectfont></fontconfig>""", encoding="utf-8")
    browser = glyphs.launch(playwright_chromium, config)
    try:
        page = browser.new_page()
        page.goto(reports["zh"].as_uri(), wait_until="load", timeout=120_000)
        missing = {c for c, _ in glyphs.cjk_glyphs(page, characters=VISIBLE)["missing"]}
    finally:
        browser.close()
    assert {"进", "动", "节"} <= missing and not missing & set("kreisel0123456789ωθ≤✓")
