"""A link on every page to the same page in the other language.

``make docs`` builds the English source into ``docs/_build/html/en`` and its Chinese translation (the catalogs in
``docs/locale``) into ``docs/_build/html/zh_CN``, side by side, so the same page in the other language is at
``../<language>/<pagename>.html`` relative to the root of the current one.
"""

from __future__ import annotations

#: The languages built, as (Sphinx language, label shown in the switch).
LANGUAGES = (("en", "English"), ("zh_CN", "中文"))


def other_language_links(pagename, language):
    """Relative links ``(language, label, url)`` from page ``pagename`` built in ``language`` to the same page in the
    other languages.

    Examples
    --------
    >>> other_language_links("theory/index", "en")
    [('zh_CN', '中文', '../../zh_CN/theory/index.html')]
    """
    current = language or "en"
    to_root = "../" * pagename.count("/")
    return [(code, label, f"{to_root}../{code}/{pagename}.html") for code, label in LANGUAGES if code != current]


def _add_links(app, pagename, templatename, context, doctree):
    context["language_links"] = other_language_links(pagename, app.config.language)


def setup(app):
    app.connect("html-page-context", _add_links)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
