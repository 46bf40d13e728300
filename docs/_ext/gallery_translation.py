"""The gallery's pages in translation.

- The running time that sphinx-gallery adds to an example's page, "Total running time of the script: (0 minutes
  10.151 seconds)", changes with every run of the example: as a message its translation would go stale on every
  machine. It is marked untranslatable before Sphinx's Locale transform (priority 20) and before the gettext builder
  collects the messages, so it stays out of the catalogs and is shown as sphinx-gallery wrote it.
- The gallery's index shows each example's title under its thumbnail as raw HTML, which no catalog reaches; it is
  replaced by the title of the example's page as built, which is the translated one in a translation.
"""

from __future__ import annotations

import html
import re

from docutils import nodes
from sphinx.transforms import SphinxTransform

#: how sphinx-gallery begins the paragraph that reports an example's running time
RUNNING_TIME = "Total running time of the script:"
_THUMBNAIL_TITLE = re.compile(r'(<div class="sphx-glr-thumbnail-title">)(.*?)(</div>)', re.S)


class KeepRunningTime(SphinxTransform):
    default_priority = 15

    def apply(self, **kwargs):
        for paragraph in self.document.findall(nodes.paragraph):
            if paragraph.astext().startswith(RUNNING_TIME):
                paragraph["translatable"] = False


def thumbnail_titles(doctree, docname, titles):
    """Set each thumbnail title of a gallery index to ``titles[target]``, the title of the page its link points to.

    sphinx-gallery writes, per example, a link to the example's page (resolved here into a reference to
    ``<name>.html``) followed by the raw HTML of its title.
    """
    folder = docname.rpartition("/")[0]
    target = None
    for node in list(doctree.findall(lambda n: isinstance(n, (nodes.reference, nodes.raw)))):
        if isinstance(node, nodes.reference) and node.get("internal") and node.get("refuri", "").endswith(".html"):
            target = f"{folder}/{node['refuri'][:-5]}" if folder else node["refuri"][:-5]
        elif isinstance(node, nodes.raw) and target in titles and _THUMBNAIL_TITLE.search(node.astext()):
            title = html.escape(titles[target].astext(), quote=False)
            text = _THUMBNAIL_TITLE.sub(lambda m: m[1] + title + m[3], node.astext())
            node.replace(node[0], nodes.Text(text))
            target = None


def _translate_thumbnail_titles(app, doctree, docname):
    if app.config.language not in (None, "en") and docname.endswith("index"):
        thumbnail_titles(doctree, docname, app.env.titles)


def setup(app):
    app.add_transform(KeepRunningTime)
    app.connect("doctree-resolved", _translate_thumbnail_titles)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
