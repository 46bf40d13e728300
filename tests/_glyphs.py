"""Missing glyphs ("tofu") on a page shown by Debian's chromium, found by drawing each character.

:func:`missing_glyphs` draws every character of the page's text on a canvas in the font of the element
that holds it, and compares it with the drawing of a character no font has (U+10FFFD, private use):
the same pixels mean that chromium found no font for the character and drew the empty box. A test
proves it can fail with :func:`fontconfig_without` (a fontconfig that hides, e.g., every Chinese font).
"""

import pathlib

#: Debian's chromium, driven by Playwright (tests/web/test_browser.py).
CHROMIUM = pathlib.Path("/usr/bin/chromium")
ARGS = ["--no-sandbox", "--headless=new", "--disable-background-networking", "--disable-component-update",
        "--disable-sync", "--no-first-run"]

_SCRIPT = """() => {
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  const byFont = new Map();
  for (let node = walker.nextNode(); node; node = walker.nextNode()) {
    const style = getComputedStyle(node.parentElement);
    const font = `${style.fontStyle} ${style.fontWeight} 32px ${style.fontFamily}`;
    if (!byFont.has(font)) byFont.set(font, new Set());
    for (const ch of node.textContent) if (ch.trim()) byFont.get(font).add(ch);
  }
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = 64;
  const ctx = canvas.getContext('2d', {willReadFrequently: true});
  const draw = (font, ch) => {
    ctx.clearRect(0, 0, 64, 64);
    ctx.font = font;
    ctx.fillText(ch, 8, 44);
    return Array.from(ctx.getImageData(0, 0, 64, 64).data).join(',');
  };
  const missing = [];
  for (const [font, chars] of byFont) {
    const tofu = draw(font, '\\u{10FFFD}');
    for (const ch of chars) if (draw(font, ch) === tofu) missing.push(ch);
  }
  return [...new Set(missing)].sort();
}"""


def missing_glyphs(page):
    """The characters of ``page`` (a Playwright page, loaded) that chromium draws as an empty box."""
    page.evaluate("document.fonts.ready")
    return page.evaluate(_SCRIPT)


def fontconfig_without(tmp_path, lang="zh-cn"):
    """A fontconfig file for ``FONTCONFIG_FILE`` that sees the system's fonts except every one that covers ``lang``
    (a fontconfig language tag): chromium started with it has no font for, e.g., Chinese characters."""
    config = tmp_path / "fonts.conf"
    config.write_text(f"""<?xml version="1.0"?>
<!DOCTYPE fontconfig SYSTEM "fonts.dtd">
<fontconfig>
  <dir>/usr/share/fonts</dir>
  <cachedir>{tmp_path / "fontconfig-cache"}</cachedir>
  <selectfont><rejectfont><pattern><patelt name="lang"><string>{lang}</string></patelt></pattern></rejectfont></selectfont>
</fontconfig>
""", encoding="utf-8")
    return config
