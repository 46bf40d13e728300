"""The glyph check of tests/_glyphs.py finds tofu: it passes with the machine's CJK fonts and fails without them."""

import pathlib

import pytest

TEXT = "刚体的进动与章动：欧拉角、惯量椭球、睡陀螺。"
PAGE = f"<!doctype html><html lang='zh-CN'><body><h1>第 7 章 刚体力学</h1><p>{TEXT} (Euler, 1765)</p></body></html>"
#: distinct CJK characters and punctuation marks of the page (23 of its 28)
DISTINCT = len({c for c in "第章刚体力学" + TEXT if not c.isascii()})


def _fontconfig(tmp_path, font_dirs):
    """A fontconfig file that offers only the fonts in ``font_dirs``."""
    dirs = "".join(f"<dir>{d}</dir>" for d in font_dirs)
    path = tmp_path / "fonts.conf"
    path.write_text(f"<?xml version='1.0'?><!DOCTYPE fontconfig SYSTEM 'fonts.dtd'><fontconfig>{dirs}"
                    f"<cachedir>{tmp_path / 'cache'}</cachedir></fontconfig>", encoding="utf-8")
    return path


def _check(browser, glyphs):
    page = browser.new_page()
    try:
        page.set_content(PAGE)
        return glyphs.cjk_glyphs(page)
    finally:
        page.close()


def test_every_character_is_drawn_by_a_cjk_font(chromium, glyphs):
    report = _check(chromium, glyphs)
    assert (report["characters"], report["distinct"]) == (len(TEXT) + 6, DISTINCT)
    assert report["missing"] == []
    assert any("CJK" in name for name in report["fonts"]), report["fonts"]


@pytest.mark.parametrize("fonts", ["none", "latin only"])
def test_without_a_cjk_font_every_character_is_missing(playwright_chromium, glyphs, tmp_path, fonts):
    latin = [d for d in (pathlib.Path("/usr/share/fonts/truetype/dejavu"),) if d.is_dir()]
    if fonts == "latin only" and not latin:
        pytest.skip("needs Debian's fonts-dejavu-core")
    browser = glyphs.launch(playwright_chromium, _fontconfig(tmp_path, latin if fonts == "latin only" else []))
    try:
        report = _check(browser, glyphs)
    finally:
        browser.close()
    assert report["distinct"] == DISTINCT
    assert {c for c, _ in report["missing"]} == {c for c in "第章刚体力学" + TEXT if not c.isascii()}
    assert not any("CJK" in name for name in report["fonts"]), report["fonts"]
