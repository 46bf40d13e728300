"""``kreisel convert``: any rotation representation to any other.

Representations are named like ``quat``, ``matrix``, ``rotvec``, ``euler:ZXZ``
(any of the 24 sequences), ``axis_angle``, ``gibbs``, ``mrp``, ``su2`` and
``cayley_klein``. Values come from the command line or, row by row, from
standard input or a CSV file.
"""

from __future__ import annotations

import csv
import io

import numpy as np

from ..so3.rotation import Rotation

# name -> numbers per rotation on input; None: complex, output only
_REPRESENTATIONS = {
    "quat": 4,
    "matrix": 9,
    "rotvec": 3,
    "euler": 3,
    "axis_angle": 4,
    "gibbs": 3,
    "mrp": 3,
    "euler_parameters": 4,
    "su2": None,
    "cayley_klein": None,
}


class ConversionError(ValueError):
    """Usage error of ``kreisel convert`` (reported as a one-line message)."""


def parse_representation(text, option):
    """Split ``"euler:ZXZ"`` into ``("euler", "ZXZ")``; check the name."""
    name, _, seq = text.partition(":")
    if name not in _REPRESENTATIONS:
        raise ConversionError(f"{option}: unknown representation {text!r} (expected one of "
                              f"{', '.join(n + (':SEQ' if n == 'euler' else '') for n in _REPRESENTATIONS)})")
    if (name == "euler") != bool(seq):
        raise ConversionError(f"{option}: give the Euler sequence as euler:SEQ, e.g. euler:ZXZ"
                              if name == "euler" else f"{option}: {name!r} takes no ':' suffix")
    return name, seq


def read_rows(text):
    """Rows of numbers from CSV or whitespace-separated text (comment lines start with #)."""
    rows = []
    for number, line in enumerate(io.StringIO(text), start=1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        fields = next(csv.reader([line])) if "," in line else line.split()
        try:
            rows.append([float(f) for f in fields if f.strip()])
        except ValueError:
            raise ConversionError(f"input line {number}: not a row of numbers: {line!r}") from None
    return rows


def convert(source, target, rows, degrees=False):
    """Convert ``rows`` (a list of equal-length number lists) between representations.

    Returns an array with one output row per input row (complex for ``su2``
    and ``cayley_klein``).

    Examples
    --------
    >>> convert("euler:ZXZ", "quat", [[90, 0, 0]], degrees=True).round(6)
    array([[0.707107, 0.      , 0.      , 0.707107]])
    """
    src, src_seq = parse_representation(source, "--from")
    dst, dst_seq = parse_representation(target, "--to")
    width = _REPRESENTATIONS[src]
    if width is None:
        raise ConversionError(f"--from: {src} has complex entries; convert from a real representation")
    values = np.asarray(rows, dtype=np.float64)
    if values.ndim != 2 or values.shape[1] != width:
        got = values.shape[1] if values.ndim == 2 else "ragged rows of"
        raise ConversionError(f"--from {source} takes {width} numbers per rotation, got {got} numbers")
    if src == "matrix":
        values = values.reshape(-1, 3, 3)
    rotation = _from(src, src_seq, values, degrees)
    out = _as(rotation, dst, dst_seq, degrees)
    return out.reshape(out.shape[0], -1)


def _from(name, seq, values, degrees):
    if name == "euler":
        return Rotation.from_euler(seq, values, degrees=degrees)
    if name == "axis_angle":
        return Rotation.from_axis_angle(values[:, :3], values[:, 3], degrees=degrees)
    if name == "rotvec":
        return Rotation.from_rotvec(values, degrees=degrees)
    return getattr(Rotation, f"from_{name}")(values)


def _as(rotation, name, seq, degrees):
    if name == "euler":
        return rotation.as_euler(seq, degrees=degrees)
    if name == "axis_angle":
        axis, angle = rotation.as_axis_angle(degrees=degrees)
        return np.concatenate([axis, angle[:, None]], axis=1)
    if name == "rotvec":
        return rotation.as_rotvec(degrees=degrees)
    return getattr(rotation, f"as_{name}")()


def format_rows(array, precision=10):
    """Text lines, one per rotation; complex numbers as ``a+bj``."""
    def fmt(x):
        if np.iscomplexobj(x):
            return f"{x.real:.{precision}g}{x.imag:+.{precision}g}j"
        return f"{float(x):.{precision}g}"

    return ["  ".join(fmt(x) for x in row) for row in array]
