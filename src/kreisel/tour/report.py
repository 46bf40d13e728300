"""Sections, checks and the self-contained HTML report of the tour."""

from __future__ import annotations

import base64
import contextlib
import dataclasses
import html
import io
import re

import numpy as np
from matplotlib.figure import Figure
from matplotlib.text import Text

from ._fonts import cjk_family
from .i18n import catalog, check_language

__all__ = ["Check", "Section", "panel", "plain", "render_html", "use_language", "NO_CJK_FONT"]

#: The note of a Chinese report whose figures keep their English text (see :func:`render_html`).
NO_CJK_FONT = ("no CJK font found for matplotlib (on Debian: apt-get install fonts-noto-cjk): "
               "the figures keep their English text")

_shown = {"lang": "en"}


def use_language(lang):
    """Show sections in a notebook (their ``_repr_html_``) in ``lang``, one of :data:`~kreisel.tour.i18n.LANGUAGES`.

    The tour's Chinese notebooks call ``use_language("zh")`` in their first cell; their section cells are the
    English ones, word for word.

    Examples
    --------
    >>> use_language("zh"); "万向节锁" in Section("Gimbal lock", "§2.3", "", [])._repr_html_()
    True
    >>> use_language("en")
    """
    _shown["lang"] = check_language(lang)


@dataclasses.dataclass
class Check:
    """One number kreisel computed, next to the value it must reproduce.

    ``ok`` is decided by the section (relative or absolute tolerance, or an
    inequality); ``expected`` is shown as given, e.g. ``"0.0186 m (chapter, atol 5e-05)"``,
    with ``source`` (``"chapter"``), the words in it that a translation translates.
    """

    label: str
    value: object
    expected: str
    ok: bool
    source: str = ""

    @classmethod
    def close(cls, label, value, target, rtol=None, atol=None, source="", unit=""):
        """Check ``|value - target| <= atol + rtol |target|``."""
        rtol = 0.0 if rtol is None else rtol
        atol = 0.0 if atol is None else atol
        ok = bool(np.isfinite(value) and abs(value - target) <= atol + rtol * abs(target))
        tol = f"rtol {rtol:g}" if rtol else f"atol {atol:g}"
        text = f"{target:.6g}{' ' + unit if unit else ''} ({source + ', ' if source else ''}{tol})"
        return cls(label, float(value), text, ok, source)

    @classmethod
    def below(cls, label, value, bound, unit=""):
        """Check ``value <= bound`` (an error, a drift)."""
        return cls(label, float(value), f"≤ {bound:.1e}{' ' + unit if unit else ''}",
                   bool(np.isfinite(value) and value <= bound))

    @classmethod
    def equal(cls, label, value, target):
        """Check a discrete outcome (a classification, a count), shown in words."""
        return cls(label, value, plain(target), value == target)


@dataclasses.dataclass
class Section:
    """A tour section: what the theory says, what kreisel computed, and figures."""

    title: str
    seed: str
    text: str
    checks: list
    figures: list = dataclasses.field(default_factory=list)  # (Figure, caption)
    error: str = ""
    seconds: float = 0.0

    @property
    def ok(self):
        return not self.error and all(c.ok for c in self.checks)

    @property
    def anchor(self):
        """The HTML id of the section, from its title: unique within a notebook and the report.

        Examples
        --------
        >>> Section("Gimbal lock: the lost degree of freedom", "§2.3", "", []).anchor
        'gimbal-lock-the-lost-degree-of-freedom'
        """
        return "-".join(re.findall(r"\w+", self.title.lower())) or "section"

    def _repr_html_(self):
        # in a notebook (the tour's notebooks end each section cell with its Section)
        tr = catalog(_shown["lang"])
        mark = tr("all checks pass" if self.ok else "FAIL")
        return (_section_html(self, self.anchor, tr, _figure_font(tr))
                + f"<p><b>{mark}</b> ({sum(c.ok for c in self.checks)}/{len(self.checks)})</p>")


def panel(xlabel, ylabel, title, figsize=(7, 3.8)):
    """A figure with one axes, labelled and titled: ``(fig, ax)``, the plot most sections draw.

    Examples
    --------
    >>> fig, ax = panel("t (s)", "ω′ (rad/s)", "spin")
    >>> ax.get_xlabel(), ax.get_title(), fig.axes == [ax], fig.get_size_inches().tolist()
    ('t (s)', 'spin', True, [7.0, 3.8])
    """
    fig = Figure(figsize=figsize, layout="constrained")
    ax = fig.add_subplot()
    ax.set(xlabel=xlabel, ylabel=ylabel, title=title)
    return fig, ax


def _png(fig, tr=None, font=None):
    """The figure as base64 PNG data; with ``tr`` and a CJK ``font`` family, its text translated while it is drawn."""
    with _translated(fig, tr, font):
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=100)
    return base64.b64encode(buf.getvalue()).decode("ascii")


@contextlib.contextmanager
def _translated(fig, tr, font):
    """Every text of ``fig`` (titles, axis labels, legends, annotations) translated, and restored afterwards."""
    changed = []
    try:
        if tr is not None and font is not None:
            for text in fig.findobj(Text):
                old = text.get_text()
                if "$" in old:   # mathtext (log-axis tick labels): symbols only
                    continue
                new = tr(old)
                if new != old:
                    changed.append((text, old, text.get_fontfamily()))
                    # the figure's own font first (Latin, Greek, math symbols), the CJK font for the rest
                    text.set_fontfamily([*text.get_fontfamily(), font])
                    text.set_text(new)
        yield
    finally:
        for text, old, family in changed:
            text.set_text(old)
            text.set_fontfamily(family)


def _figure_font(tr):
    """The CJK family for the figures of a translated report; None for English or when there is none."""
    return None if tr.lang == "en" else cjk_family()


def plain(v):
    """``v`` as a reader expects it in a table: numbers to 6 digits, yes/no, sequences as "a, b, c", no quotes.

    Examples
    --------
    >>> plain(["stable", "unstable"]), plain((45, 28)), plain(True), plain(0.1 + 0.2), plain("loop")
    ('stable, unstable', '45, 28', 'yes', '0.3', 'loop')
    """
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    if isinstance(v, (int, float, np.integer, np.floating)):
        return f"{v:.6g}"
    if isinstance(v, (list, tuple, np.ndarray)):
        return ", ".join(plain(x) for x in v)
    return str(v)


def render_html(sections, title="kreisel — the rigid-body chapter, executed", lang="en"):
    """The report as one HTML string with figures embedded as PNG data.

    Parameters
    ----------
    sections : list of Section
    title : str
        English; translated with the rest.
    lang : {"en", "zh"}
        The language of the prose, tables, captions and figure text (numbers, units and symbols are the same
        in both). Chinese figure text needs a CJK font (:data:`NO_CJK_FONT`); without one the figures keep their
        English text and the report says so once.
    """
    tr = catalog(check_language(lang))
    font = _figure_font(tr)
    passed = sum(s.ok for s in sections)
    parts = [
        f"<!DOCTYPE html><html lang='{'zh-CN' if lang == 'zh' else lang}'><head><meta charset='utf-8'>",
        f"<title>{html.escape(tr(title))}</title><style>",
        "body{font-family:system-ui,sans-serif;max-width:980px;margin:2em auto;padding:0 1em;color:#222}",
        "table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #ccc;padding:.25em .6em;text-align:left}",
        ".pass{color:#17702a;font-weight:bold}.fail{color:#b00020;font-weight:bold}",
        "figure{margin:1em 0}figcaption{color:#555;font-size:.9em}img{max-width:100%}",
        "section{border-top:1px solid #ddd;margin-top:2em}code{background:#f4f4f4;padding:0 .2em}",
        "</style></head><body>",
        f"<h1>{html.escape(tr(title))}</h1>",
        "<p>" + html.escape(tr(f"{passed} of {len(sections)} sections pass. Each section computes the chapter's "
                               "results with kreisel and checks them against the chapter's numbers or an independent "
                               "reference.")) + "</p>",
    ]
    if lang != "en" and font is None:
        parts.append(f"<p class='note'>{html.escape(tr(NO_CJK_FONT))}</p>")
    parts.append("<table><tr>" + "".join(f"<th>{tr(h)}</th>" for h in ("section", "theory", "checks", "time"))
                 + "</tr>")
    for s in sections:
        mark = f"<span class='pass'>{tr('pass')}</span>" if s.ok else f"<span class='fail'>{tr('FAIL')}</span>"
        parts.append(f"<tr><td><a href='#{s.anchor}'>{html.escape(tr(s.title))}</a></td><td>{html.escape(s.seed)}</td>"
                     f"<td>{mark} {sum(c.ok for c in s.checks)}/{len(s.checks)}</td><td>{s.seconds:.1f} s</td></tr>")
    parts.append("</table>")
    parts += [_section_html(s, s.anchor, tr, font) for s in sections]
    parts.append("</body></html>")
    return "\n".join(parts)


def _section_html(s, anchor, tr, font):
    """One section: title, what the theory says, the checks, the figures (PNG data), in the language of ``tr``."""
    parts = [f"<section id='{anchor}'><h2>{html.escape(tr(s.title))} "
             f"<small>({html.escape(tr(f'Theory {s.seed}'))})</small></h2>",
             f"<p>{tr(s.text)}</p>"]
    if s.error:
        parts.append(f"<p class='fail'>{html.escape(tr(f'error: {s.error}'))}</p>")
    if s.checks:
        parts.append("<table><tr>" + "".join(f"<th>{tr(h)}</th>" for h in ("quantity", "kreisel", "expected", ""))
                     + "</tr>")
        for c in s.checks:
            mark = "<span class='pass'>✓</span>" if c.ok else "<span class='fail'>✗</span>"
            # Check.close writes "target (source, tolerance)": only the source is words
            expected = (c.expected.replace(f"({c.source}, ", f"({tr(c.source)}, ", 1) if c.source
                        else tr(c.expected))
            parts.append(f"<tr><td>{html.escape(tr(c.label))}</td><td>{html.escape(tr(plain(c.value)))}</td>"
                         f"<td>{html.escape(expected)}</td><td>{mark}</td></tr>")
        parts.append("</table>")
    for fig, caption in s.figures:
        parts.append(f"<figure><img alt='{html.escape(tr(caption))}' src='data:image/png;base64,{_png(fig, tr, font)}'>"
                     f"<figcaption>{html.escape(tr(caption))}</figcaption></figure>")
    parts.append("</section>")
    return "\n".join(parts)
