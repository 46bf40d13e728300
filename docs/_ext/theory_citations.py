"""Sphinx extension: every "Theory §N.M" citation becomes a link into the theory pages.

Docstrings, gallery examples and pages cite the course as ``Theory §5.3``,
``Theory §2.2 (3)`` (paragraph (3) of §2.2) or ``Theory §A (2)``. The theory pages
define one label per cited unit: ``theory-5``, ``theory-5.3``, ``theory-2.2-3``,
``theory-A``, ``theory-A-2``. After a document is parsed (autodoc and
sphinx-gallery content included), this transform replaces each citation in
running text by a ``:ref:`` to its label; text inside literals, code, math and
existing links is left alone. A citation of a section the theory pages do not
have is reported as a warning naming the citation, so ``-W`` turns it into an
error.
"""

from __future__ import annotations

import re

from docutils import nodes
from sphinx import addnodes
from sphinx.transforms import SphinxTransform
from sphinx.util import logging

logger = logging.getLogger(__name__)

CITATION = re.compile(r"Theory §(?P<section>\d+|A\b)(?:\.(?P<subsection>\d+))?(?: ?\((?P<paragraph>\d+)\))?")

_SKIP = (nodes.literal, nodes.literal_block, nodes.reference, nodes.math, nodes.math_block, nodes.raw,
         nodes.comment, nodes.target, nodes.title, addnodes.pending_xref, addnodes.desc_signature)


def citation_label(match):
    """The label a citation match points at, e.g. ``theory-2.2-3`` for "Theory §2.2 (3)"."""
    label = "theory-" + match["section"]
    if match["subsection"]:
        label += "." + match["subsection"]
    if match["paragraph"]:
        label += "-" + match["paragraph"]
    return label


def _inside_skipped(node):
    parent = node.parent
    while parent is not None:
        if isinstance(parent, _SKIP):
            return True
        parent = parent.parent
    return False


class TheoryCitations(SphinxTransform):
    """Turn "Theory §N.M" in running text into cross-references to the theory pages."""

    default_priority = 500

    def apply(self, **kwargs):
        for text in list(self.document.findall(nodes.Text)):
            source = text.astext()
            if "Theory §" not in source or _inside_skipped(text):
                continue
            pieces, start = [], 0
            for match in CITATION.finditer(source):
                if match.start() > start:
                    pieces.append(nodes.Text(source[start:match.start()]))
                xref = addnodes.pending_xref(
                    "", nodes.inline(match.group(0), match.group(0), classes=["xref", "std", "std-ref"]),
                    refdomain="std", reftype="ref", reftarget=citation_label(match).lower(), refexplicit=True,
                    refwarn=True, refdoc=self.env.docname, theory_citation=match.group(0))
                xref.source, xref.line = text.parent.source, text.parent.line
                pieces.append(xref)
                start = match.end()
            if not pieces:
                continue
            if start < len(source):
                pieces.append(nodes.Text(source[start:]))
            text.parent.replace(text, pieces)


def _warn_missing(app, domain, node):
    citation = node.get("theory_citation")
    if citation is None:
        return None
    logger.warning("%r cites a section the theory pages do not have (no label %r)", citation,
                   node["reftarget"], location=node, type="ref", subtype="theory")
    return True


def setup(app):
    app.add_transform(TheoryCitations)
    app.connect("warn-missing-reference", _warn_missing)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
