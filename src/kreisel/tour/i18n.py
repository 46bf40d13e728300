"""The tour in another language: its English text looked up in a catalog shipped with kreisel.

English is the single source. The sections write English; rendering in another language looks
each string up in ``locale/<lang>.toml``, keyed by the English text. A key may hold ``{name}``
fields where a section formats a value into its text at run time (an f-string): the field
matches whatever stands there (a number, a symbol, a word of the catalog, which is translated
too) and the translation puts it back in its own place, so a translator works on templates and
never retypes a number. Only a field named ``english`` may hold English words (an error message). A string without an entry
stays English; the tour's tests fail on it, and on an entry that no string uses any more.
"""

from __future__ import annotations

import functools
import importlib.resources
import re
import tomllib

__all__ = ["LANGUAGES", "Catalog", "catalog", "check_language", "needs_translation"]

#: Languages of the tour: English (the source) and Chinese.
LANGUAGES = ("en", "zh")

_FIELD = re.compile(r"\{(\w+)\}")


def check_language(lang):
    """``lang`` if it is one of :data:`LANGUAGES`, else ValueError naming the argument."""
    if lang not in LANGUAGES:
        raise ValueError(f"lang must be one of {', '.join(map(repr, LANGUAGES))}, got {lang!r}")
    return lang


def _pattern(key):
    """The regular expression of a template key: its literal text, each ``{name}`` a non-empty group."""
    parts, last = [], 0
    for field in _FIELD.finditer(key):
        parts += [re.escape(key[last:field.start()]), f"(?P<{field[1]}>.+?)"]
        last = field.end()
    parts.append(re.escape(key[last:]))
    return re.compile("".join(parts), re.DOTALL)


class Catalog:
    """English text -> its translation; calling it translates one string.

    ``used`` holds the keys that translated something, ``missing`` the strings that
    :func:`needs_translation` says need an entry and had none (the tests read both).

    Examples
    --------
    >>> zh = Catalog("zh")
    >>> zh("Gimbal lock")
    '万向节锁'
    >>> zh("N = 2: log–log slope at small λ")
    'N = 2：小 λ 处的双对数斜率'
    >>> Catalog("en")("Gimbal lock")
    'Gimbal lock'
    """

    def __init__(self, lang):
        self.lang = check_language(lang)
        self.entries, self.neutral_words = {}, frozenset()
        if lang != "en":
            data = tomllib.loads(importlib.resources.files(__package__).joinpath(f"locale/{lang}.toml")
                                 .read_text(encoding="utf-8"))
            self.entries = {m["en"]: m[lang] for m in data["message"]}
            self.neutral_words = frozenset(data["neutral"]["words"])
        self._exact = {k: v for k, v in self.entries.items() if not _FIELD.search(k)}
        self._templates = {k: _pattern(k) for k in self.entries if _FIELD.search(k)}
        self.used, self.missing = set(), set()

    def matches(self, text):
        """The keys that ``text`` matches: its exact entry, else every template it fits."""
        if text in self._exact:
            return [text]
        return [key for key, pattern in self._templates.items() if pattern.fullmatch(text)]

    def __call__(self, text):
        if self.lang == "en" or not text:
            return text
        keys = self.matches(text)
        if not keys:
            if needs_translation(text, self.neutral_words):
                self.missing.add(text)
            return text
        key = keys[0]
        self.used.add(key)
        if key in self._exact:
            return self._exact[key]
        values = self._templates[key].fullmatch(text).groupdict()
        for name, value in values.items():
            if value in self._exact:   # a word of the catalog (a locus kind, a case) is translated too
                self.used.add(value)
                values[name] = self._exact[value]
            elif name != "english" and needs_translation(value, self.neutral_words):
                # English words in a field: the text needs an entry of its own, not this template
                self.missing.add(text)
        return self.entries[key].format(**values)


@functools.cache
def catalog(lang):
    """The :class:`Catalog` of ``lang``, loaded once."""
    return Catalog(lang)


def needs_translation(text, neutral_words=frozenset()):
    """Whether ``text`` holds English words, not only symbols, numbers, units and ``neutral_words``.

    Examples
    --------
    >>> needs_translation("ω′ (rad/s)", {"rad"}), needs_translation("drift rate (rad/s)", {"rad"})
    (False, True)
    """
    return any(word not in neutral_words for word in re.findall(r"[A-Za-z]{3,}", text))
