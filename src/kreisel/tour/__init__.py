"""The executable chapter: every demonstration of the chapter, checked and reported.

:func:`run_tour` runs one section per theory section, each computing the
chapter's numbers with kreisel, comparing them with the chapter's (or an
independent reference) and drawing its figures, then writes a
self-contained ``index.html``.
"""

from .. import _optional

# the sections draw their figures with matplotlib: without it, one line naming the extra
_optional.require("matplotlib", extra="plot", feature="the tour (kreisel tour)")

from .report import Check, Section, render_html
from .runner import SECTIONS, run_tour

__all__ = ["Check", "Section", "render_html", "SECTIONS", "run_tour"]
