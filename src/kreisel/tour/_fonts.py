"""A font for Chinese figure text, if the machine has one matplotlib can use."""

from __future__ import annotations

import functools

__all__ = ["cjk_family"]

# Simplified Chinese first; a Japanese or Traditional face of the same family still draws every character
_FAMILIES = ("Noto Sans CJK SC", "Source Han Sans SC", "Source Han Sans CN", "Noto Sans SC", "WenQuanYi Zen Hei",
             "WenQuanYi Micro Hei", "Microsoft YaHei", "PingFang SC", "Hiragino Sans GB", "SimHei",
             "Noto Sans CJK JP", "Noto Sans CJK TC", "Source Han Sans")


@functools.cache
def cjk_family():
    """The family name of an installed CJK font matplotlib can draw with, or None.

    matplotlib caches its font list the first time it runs, so a font installed later (``apt-get install
    fonts-noto-cjk``) is missing from it: the first such CJK font file of the system is added to it.
    """
    from matplotlib import font_manager, ft2font

    def known():
        return {font.name for font in font_manager.fontManager.ttflist}

    if not known().intersection(_FAMILIES):
        seen = {font.fname for font in font_manager.fontManager.ttflist}
        for path in font_manager.findSystemFonts():
            if path in seen:
                continue
            try:
                font = ft2font.FT2Font(path)
            except (OSError, RuntimeError, ValueError):   # a font file FreeType cannot read: not ours to use
                continue
            if font.family_name in _FAMILIES and font.style_name == "Regular":
                font_manager.fontManager.addfont(path)   # this one file only: the rest of the list stays as it was
                break
    names = known()
    return next((family for family in _FAMILIES if family in names), None)
