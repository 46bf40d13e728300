"""Whether chromium draws every CJK character of a page with a font that has it, rather than a tofu box.

Used by the tests of the Chinese documentation (tests/docs/test_docs_build.py) and of the Chinese tour report, through
the fixtures ``chromium`` and ``cjk_glyphs`` of tests/conftest.py. Two independent witnesses:

- **canvas**: each distinct character is drawn, in the font its element computes, next to a code point no font has
  (U+10FFFD); a character drawn pixel for pixel like that one, or not at all, is missing from every font the browser
  could fall back to;
- **CDP** ``CSS.getPlatformFontsForNode``: the names of the fonts the browser actually used for the elements that hold
  CJK text, so that a failure says which fonts were chosen.
"""

from __future__ import annotations

import os
import pathlib

CHROMIUM = pathlib.Path("/usr/bin/chromium")
ARGS = ["--no-sandbox", "--headless=new", "--disable-gpu", "--disable-background-networking",
        "--disable-component-update", "--disable-sync", "--no-first-run"]

#: CJK ideographs (with extension A and the compatibility block), CJK punctuation and full-width forms; not the
#: ideographic space U+3000, which every font draws blank
CJK = r"[\u3001-\u303f\u3400-\u4dbf\u4e00-\u9fff\uf900-\ufaff\uff01-\uffef]"

_MEASURE = r"""
async (cjk) => {
  await document.fonts.ready;
  const pattern = new RegExp(cjk, "gu");
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  const byFont = new Map();
  let characters = 0, marked = 0;
  for (let node = walker.nextNode(); node; node = walker.nextNode()) {
    const element = node.parentElement;
    if (!element || element.closest("script, style, noscript, template")) continue;
    const found = node.data.match(pattern);
    if (!found) continue;
    characters += found.length;
    if (!element.hasAttribute("data-glyph-check")) { element.setAttribute("data-glyph-check", ""); marked++; }
    const s = getComputedStyle(element);
    const font = `${s.fontStyle} ${s.fontWeight} 32px ${s.fontFamily}`;
    if (!byFont.has(font)) byFont.set(font, new Set());
    found.forEach(c => byFont.get(font).add(c));
  }
  const canvas = document.createElement("canvas");
  canvas.width = canvas.height = 48;
  const ctx = canvas.getContext("2d", {willReadFrequently: true});
  const draw = (font, text) => {
    ctx.clearRect(0, 0, 48, 48);
    ctx.font = font;
    ctx.fillText(text, 4, 36);
    return Array.from(ctx.getImageData(0, 0, 48, 48).data.filter((v, k) => k % 4 === 3)).join(",");
  };
  const blank = draw("32px serif", "");
  const missing = [];
  for (const [font, chars] of byFont) {
    const tofu = draw(font, "\u{10FFFD}");
    for (const c of chars) {
      const drawn = draw(font, c);
      if (drawn === tofu || drawn === blank) missing.push([c, font]);
    }
  }
  return {characters, distinct: new Set([...byFont.values()].flatMap(s => [...s])).size, marked, missing};
}
"""


def cjk_glyphs(page, characters=CJK):
    r"""Check the page loaded in ``page`` (a Playwright page of chromium).

    ``characters`` is the (JavaScript) regular expression of the characters checked: CJK by default, ``r"\S"``
    for every visible character (the tour report: Greek, math symbols, ✓ too).

    Returns a dict: ``characters`` (checked characters in the page's text), ``distinct``, ``missing`` (a list of
    ``[character, css font]`` that no font draws) and ``fonts`` (font family → glyphs it drew in the elements that
    hold CJK text, as chromium reports them).
    """
    report = page.evaluate(_MEASURE, characters)
    session = page.context.new_cdp_session(page)
    try:
        session.send("DOM.enable")
        session.send("CSS.enable")
        root = session.send("DOM.getDocument", {"depth": 0})["root"]["nodeId"]
        nodes = session.send("DOM.querySelectorAll", {"nodeId": root, "selector": "[data-glyph-check]"})["nodeIds"]
        fonts: dict[str, int] = {}
        for node in nodes:
            for font in session.send("CSS.getPlatformFontsForNode", {"nodeId": node})["fonts"]:
                fonts[font["familyName"]] = fonts.get(font["familyName"], 0) + font["glyphCount"]
    finally:
        session.detach()
    return {**report, "fonts": fonts}


def launch(playwright, fontconfig_file=None):
    """Debian's chromium, headless; ``fontconfig_file`` replaces the fonts it may use (a fontconfig file)."""
    env = dict(os.environ)
    if fontconfig_file is not None:
        env["FONTCONFIG_FILE"] = str(fontconfig_file)
    return playwright.chromium.launch(executable_path=str(CHROMIUM), args=ARGS, env=env, timeout=120_000)
