"""The compact HTML tables that kreisel objects show in Jupyter (``_repr_html_``).

One helper for every layer, so that all summaries look alike and escape
their text the same way.
"""

from __future__ import annotations

import html
from collections.abc import Iterable

import numpy as np
from numpy.typing import ArrayLike


def number(x: ArrayLike, digits: int = 6) -> str:
    """A float or an array of floats as short text, e.g. ``"[1, 2.5, 3]"``.

    Examples
    --------
    >>> number([1.0, 2.5, 1 / 3], digits=3)
    '[1, 2.5, 0.333]'
    >>> number(1e-12)
    '1e-12'
    """
    a = np.asarray(x, dtype=float)
    if a.ndim == 0:
        return f"{float(a):.{digits}g}"
    return "[" + ", ".join(number(v, digits) for v in a) + "]"


def _text(value: object) -> str:
    """Numbers and tuples of numbers through :func:`number`, everything else through ``str``."""
    if isinstance(value, (str, bool, np.bool_)) or (isinstance(value, tuple) and all(isinstance(v, int) for v in value)):
        return str(value)
    try:
        return number(value)
    except (TypeError, ValueError):
        return str(value)


def html_table(title: str, rows: Iterable[tuple[str, object]], note: str | None = None) -> str:
    """An HTML summary: a bold title, a two-column table of ``(label, value)`` rows, a note.

    Every label, value and the note are escaped, so user text (meta data,
    names) cannot break the notebook's page.

    Parameters
    ----------
    title : str
    rows : iterable of (str, object)
        Numbers and arrays of numbers are shown by :func:`number`, other values with ``str``.
    note : str, optional
        A line under the table (conventions).

    Examples
    --------
    >>> html_table("Top", [("I", "1 < 2")], note="SI")
    '<div class="kreisel-repr"><strong>Top</strong><table><tr><th style="text-align:left">I</th><td style="text-align:left">1 &lt; 2</td></tr></table><small>SI</small></div>'
    """
    cells = "".join(
        f'<tr><th style="text-align:left">{html.escape(str(label))}</th>'
        f'<td style="text-align:left">{html.escape(_text(value))}</td></tr>'
        for label, value in rows
    )
    tail = f"<small>{html.escape(note)}</small>" if note else ""
    return f'<div class="kreisel-repr"><strong>{html.escape(title)}</strong><table>{cells}</table>{tail}</div>'
