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
    fonts-noto-cjk``) is missing from it: the system's font files it does not know yet are added to it.
    """
    from matplotlib import font_manager

    def known():
        return {font.name for font in font_manager.fontManager.ttflist}

    if not known().intersection(_FAMILIES):
        seen = {font.fname for font in font_manager.fontManager.ttflist}
        for path in font_manager.findSystemFonts():
            if path not in seen:
                try:
                    font_manager.fontManager.addfont(path)
                except (OSError, RuntimeError, ValueError):   # a font file FreeType cannot read: not ours to use
                    continue
    names = known()
    return next((family for family in _FAMILIES if family in names), None)
