"""The gallery's pages in translation.

- The running time that sphinx-gallery adds to an example's page, "Total running time of the script: (0 minutes
  10.151 seconds)", changes with every run of the example: as a message its translation would go stale on every
  machine. It is marked untranslatable before Sphinx's Locale transform (priority 20) and before the gettext builder
  collects the messages, so it stays out of the catalogs and is shown as sphinx-gallery wrote it.
- The gallery's index shows each example's title under its thumbnail, and its first paragraph when the pointer is
  over it, as raw HTML, which no catalog reaches; in a translation they are replaced by the title and the first
  paragraph of the example's page as built, which are the translated ones.
"""

from __future__ import annotations

import html
import re

from docutils import nodes
from sphinx.transforms import SphinxTransform

#: how sphinx-gallery begins the paragraph that reports an example's running time
RUNNING_TIME = "Total running time of the script:"
_THUMBNAIL_TITLE = re.compile(r'(<div class="sphx-glr-thumbnail-title">)(.*?)(</div>)', re.S)
_TOOLTIP = re.compile(r'(<div class="sphx-glr-thumbcontainer" tooltip=")(.*?)(">)', re.S)


class KeepRunningTime(SphinxTransform):
    default_priority = 15

    def apply(self, **kwargs):
        for paragraph in self.document.findall(nodes.paragraph):
            if paragraph.astext().startswith(RUNNING_TIME):
                paragraph["translatable"] = False


def translate_thumbnails(doctree, docname, titles, summary):
    """Give each thumbnail of a gallery index the title and the first paragraph of the page its link points to.

    sphinx-gallery writes, per example, the raw HTML that opens the thumbnail (the first paragraph is its
    ``tooltip``), a link to the example's page (resolved here into a reference to ``<name>.html``), and the raw HTML of
    its title. ``titles`` maps a document to its title node, ``summary(docname)`` gives its first paragraph's text or
    None; a thumbnail whose page has neither keeps what sphinx-gallery wrote.
    """
    folder = docname.rpartition("/")[0]
    opening = target = None
    for node in list(doctree.findall(lambda n: isinstance(n, (nodes.reference, nodes.raw)))):
        if isinstance(node, nodes.raw) and _TOOLTIP.search(node.astext()):
            opening = node
        elif isinstance(node, nodes.reference) and node.get("internal") and node.get("refuri", "").endswith(".html"):
            target = f"{folder}/{node['refuri'][:-5]}" if folder else node["refuri"][:-5]
            text = summary(target) if opening is not None else None
            if text is not None:
                _replace(opening, _TOOLTIP, html.escape(text, quote=True))
            opening = None
        elif isinstance(node, nodes.raw) and target in titles and _THUMBNAIL_TITLE.search(node.astext()):
            _replace(node, _THUMBNAIL_TITLE, html.escape(titles[target].astext(), quote=False))
            target = None


def _replace(raw, pattern, text):
    raw.replace(raw[0], nodes.Text(pattern.sub(lambda m: m[1] + text + m[3], raw.astext(), count=1)))


def _first_paragraph(env, docname):
    """The first paragraph under the title of ``docname`` (sphinx-gallery's download note stands before the title)."""
    if docname not in env.all_docs:
        return None
    section = next(iter(env.get_doctree(docname).findall(nodes.section)), [])
    paragraph = next((child for child in section if isinstance(child, nodes.paragraph)), None)
    return None if paragraph is None else " ".join(paragraph.astext().split())


def _translate_thumbnails(app, doctree, docname):
    if app.config.language not in (None, "en") and docname.endswith("index"):
        translate_thumbnails(doctree, docname, app.env.titles, lambda target: _first_paragraph(app.env, target))


def setup(app):
    app.add_transform(KeepRunningTime)
    app.connect("doctree-resolved", _translate_thumbnails)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
