"""A translated page that falls behind its English source fails the build.

A page is translated when the language has a catalog for it (``locale/<language>/LC_MESSAGES/<page>.po``). Sphinx
shows an English paragraph that its catalog lacks in English, silently; here every such message is a warning, so that
``make docs`` (``-W``) fails until ``make docs-po`` has brought the catalog up to date and the new entries are
translated. Messages kept verbatim in the catalog (display equations) count as translated.
"""

from __future__ import annotations

from sphinx.locale import init as init_locale
from sphinx.transforms import SphinxTransform
from sphinx.util import logging
from sphinx.util.i18n import docname_to_domain
from sphinx.util.nodes import extract_messages

logger = logging.getLogger(__name__)


def _messages(catalog):
    """Every message with a non-empty translation in ``catalog`` and its fallbacks, and those translations.

    The translations count too: Sphinx puts an image's translated ``alt`` text in place without marking the image
    translated.
    """
    translated = set()
    while catalog is not None:
        pairs = [(msgid, msgstr) for msgid, msgstr in getattr(catalog, "_catalog", {}).items() if msgstr.strip()]
        translated |= {text for pair in pairs for text in pair}
        catalog = catalog._fallback
    return translated


class UntranslatedMessages(SphinxTransform):
    #: after Sphinx's Locale transform (20), which marks each message it translated
    default_priority = 21

    def apply(self, **kwargs):
        if self.config.language in (None, "en"):
            return
        docname = self.env.current_document.docname
        dirs = [self.env.srcdir / directory for directory in self.config.locale_dirs]
        catalog, has_catalog = init_locale(dirs, self.config.language, docname_to_domain(docname, self.config.gettext_compact))
        if not has_catalog:
            return
        translated = _messages(catalog)
        for node, message in extract_messages(self.document):
            if not node.get("translated") and message not in translated:
                logger.warning("untranslated in the %s catalog (run `make docs-po` and translate): %s",
                               self.config.language, " ".join(message.split())[:80], location=node,
                               type="i18n", subtype="untranslated")


def setup(app):
    app.add_transform(UntranslatedMessages)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
