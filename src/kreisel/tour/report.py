"""Sections, checks and the self-contained HTML report of the tour."""

from __future__ import annotations

import base64
import dataclasses
import html
import io
import re

import numpy as np
from matplotlib.figure import Figure

__all__ = ["Check", "Section", "panel", "plain", "render_html"]


@dataclasses.dataclass
class Check:
    """One number kreisel computed, next to the value it must reproduce.

    ``ok`` is decided by the section (relative or absolute tolerance, or an
    inequality); ``expected`` is shown as given, e.g. ``"0.0186 m (chapter)"``.
    """

    label: str
    value: object
    expected: str
    ok: bool

    @classmethod
    def close(cls, label, value, target, rtol=None, atol=None, source="", unit=""):
        """Check ``|value - target| <= atol + rtol |target|``."""
        rtol = 0.0 if rtol is None else rtol
        atol = 0.0 if atol is None else atol
        ok = bool(np.isfinite(value) and abs(value - target) <= atol + rtol * abs(target))
        tol = f"rtol {rtol:g}" if rtol else f"atol {atol:g}"
        text = f"{target:.6g}{' ' + unit if unit else ''} ({source + ', ' if source else ''}{tol})"
        return cls(label, float(value), text, ok)

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
        mark = "all checks pass" if self.ok else "FAIL"
        return _section_html(self, self.anchor) + f"<p><b>{mark}</b> ({sum(c.ok for c in self.checks)}/{len(self.checks)})</p>"


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


def _png(fig):
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100)
    return base64.b64encode(buf.getvalue()).decode("ascii")


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


def render_html(sections, title="kreisel — the rigid-body chapter, executed"):
    """The report as one HTML string with figures embedded as PNG data."""
    passed = sum(s.ok for s in sections)
    parts = [
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
        f"<title>{html.escape(title)}</title><style>",
        "body{font-family:system-ui,sans-serif;max-width:980px;margin:2em auto;padding:0 1em;color:#222}",
        "table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #ccc;padding:.25em .6em;text-align:left}",
        ".pass{color:#17702a;font-weight:bold}.fail{color:#b00020;font-weight:bold}",
        "figure{margin:1em 0}figcaption{color:#555;font-size:.9em}img{max-width:100%}",
        "section{border-top:1px solid #ddd;margin-top:2em}code{background:#f4f4f4;padding:0 .2em}",
        "</style></head><body>",
        f"<h1>{html.escape(title)}</h1>",
        f"<p>{passed} of {len(sections)} sections pass. Each section computes the chapter's results with "
        "kreisel and checks them against the chapter's numbers or an independent reference.</p>",
        "<table><tr><th>section</th><th>theory</th><th>checks</th><th>time</th></tr>",
    ]
    for s in sections:
        mark = "<span class='pass'>pass</span>" if s.ok else "<span class='fail'>FAIL</span>"
        parts.append(f"<tr><td><a href='#{s.anchor}'>{html.escape(s.title)}</a></td><td>{html.escape(s.seed)}</td>"
                     f"<td>{mark} {sum(c.ok for c in s.checks)}/{len(s.checks)}</td><td>{s.seconds:.1f} s</td></tr>")
    parts.append("</table>")
    parts += [_section_html(s, s.anchor) for s in sections]
    parts.append("</body></html>")
    return "\n".join(parts)


def _section_html(s, anchor):
    """One section: title, what the theory says, the checks, the figures (PNG data)."""
    parts = [f"<section id='{anchor}'><h2>{html.escape(s.title)} <small>(Theory {html.escape(s.seed)})</small></h2>",
             f"<p>{s.text}</p>"]
    if s.error:
        parts.append(f"<p class='fail'>error: {html.escape(s.error)}</p>")
    if s.checks:
        parts.append("<table><tr><th>quantity</th><th>kreisel</th><th>expected</th><th></th></tr>")
        for c in s.checks:
            mark = "<span class='pass'>✓</span>" if c.ok else "<span class='fail'>✗</span>"
            parts.append(f"<tr><td>{html.escape(c.label)}</td><td>{html.escape(plain(c.value))}</td>"
                         f"<td>{html.escape(c.expected)}</td><td>{mark}</td></tr>")
        parts.append("</table>")
    for fig, caption in s.figures:
        parts.append(f"<figure><img alt='{html.escape(caption)}' src='data:image/png;base64,{_png(fig)}'>"
                     f"<figcaption>{html.escape(caption)}</figcaption></figure>")
    parts.append("</section>")
    return "\n".join(parts)
