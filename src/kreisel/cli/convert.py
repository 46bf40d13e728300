"""``kreisel convert``: any rotation representation to any other.

Representations are named like ``quat``, ``matrix``, ``rotvec``, ``euler:ZXZ``
(any of the 24 sequences), ``axis_angle``, ``gibbs``, ``mrp``, ``su2`` and
``cayley_klein``. Values come from the command line or, row by row, from
standard input or a CSV file. Every conversion goes through unit quaternions,
each step made by the public function of :mod:`kreisel.so3` for it.
"""

from __future__ import annotations

import csv
import io

import numpy as np

from .. import so3
from .._validation import parse_sequence

__all__ = ["ConversionError", "parse_representation", "width", "read_rows", "convert", "format_rows",
           "input_notes"]

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
    if seq:
        try:
            parse_sequence(seq)
        except ValueError as exc:
            raise ConversionError(f"{option} {text}: {exc} (uppercase: intrinsic, lowercase: extrinsic)") from None
    return name, seq


def width(name):
    """Numbers per rotation that representation ``name`` reads (None: it is output only)."""
    return _REPRESENTATIONS[name]


def read_rows(text, width=None):
    r"""Rows of numbers from CSV or whitespace-separated text, with their line numbers.

    Comment lines start with ``#``; a first line of column names (``phi,theta,psi``)
    is skipped. With ``width``, every row must hold that many numbers.

    Returns
    -------
    lines : list of int
        Line number (from 1) of each row.
    rows : list of list of float

    Examples
    --------
    >>> read_rows("phi, theta, psi\n30, 45, 60\n\n0 90 0\n", width=3)
    ([2, 4], [[30.0, 45.0, 60.0], [0.0, 90.0, 0.0]])
    >>> read_rows("1 2 3\n4 5\n", width=3)
    Traceback (most recent call last):
        ...
    kreisel.cli.convert.ConversionError: input line 2: expected 3 numbers per rotation, got 2
    """
    if "\x00" in text:
        raise ConversionError("input: not a text file (it contains NUL bytes); expected rows of numbers")
    lines, rows = [], []
    for number, line in enumerate(io.StringIO(text), start=1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        fields = [f.strip() for f in (next(csv.reader([line])) if "," in line else line.split())]
        try:
            values = [float(f) for f in fields if f]
        except ValueError:
            if not rows and not any(_is_number(f) for f in fields):
                continue  # a header line of column names
            raise ConversionError(f"input line {number}: not a row of numbers: {line[:60]!r}") from None
        if width is not None and len(values) != width:
            raise ConversionError(f"input line {number}: expected {width} numbers per rotation, got {len(values)}")
        lines.append(number)
        rows.append(values)
    return lines, rows


def _is_number(text):
    try:
        float(text)
    except ValueError:
        return False
    return True


def convert(source, target, rows, degrees=False, scalar_last=False, lines=None):
    """Convert ``rows`` (a list of equal-length number lists) between representations.

    Returns an array with one output row per input row (complex for ``su2``
    and ``cayley_klein``). ``scalar_last`` reads and writes quaternions as
    ``[x, y, z, w]`` instead of kreisel's ``[w, x, y, z]``. ``lines`` (the
    input line of each row) lets an invalid rotation be reported by its line.

    Examples
    --------
    >>> convert("euler:ZXZ", "quat", [[90, 0, 0]], degrees=True).round(6)
    array([[0.707107, 0.      , 0.      , 0.707107]])
    >>> convert("euler:ZXZ", "quat", [[90, 0, 0]], degrees=True, scalar_last=True).round(6)
    array([[0.      , 0.      , 0.707107, 0.707107]])
    >>> convert("quat", "matrix", [[1, 0, 0, 0], [0, 0, 0, 0]], lines=[3, 4])
    Traceback (most recent call last):
        ...
    kreisel.cli.convert.ConversionError: input line 4: invalid quat: q must be nonzero quaternions (a zero quaternion is not a rotation)
    """
    src, src_seq = parse_representation(source, "--from")
    dst, dst_seq = parse_representation(target, "--to")
    count = _REPRESENTATIONS[src]
    if count is None:
        raise ConversionError(f"--from: {src} has complex entries; convert from a real representation")
    values = np.asarray(rows, dtype=np.float64)
    if values.ndim != 2 or values.shape[1] != count:
        got = values.shape[1] if values.ndim == 2 else "ragged rows of"
        raise ConversionError(f"--from {source} takes {count} numbers per rotation, got {got} numbers")
    if src == "matrix":
        values = values.reshape(-1, 3, 3)
    if src == "quat" and scalar_last:
        values = np.roll(values, 1, axis=-1)
    try:
        q = _to_quat(src, src_seq, values, degrees)
        out = _from_quat(q, dst, dst_seq, degrees)
    except ValueError as exc:
        raise ConversionError(_first_invalid(src, src_seq, dst, dst_seq, values, degrees, lines, exc)) from None
    if dst == "quat" and scalar_last:
        out = np.roll(out, -1, axis=-1)
    return out


def input_notes(source, rows, degrees=False, scalar_last=False):
    """Notes on input that is valid but looks like a slip of convention.

    An angle beyond a full turn is a valid rotation, and so is the
    quaternion [0, 0, 0, 1] (a half turn about z); both are converted as
    given. But a reader who forgot ``--degrees``, or pasted the identity
    from a scalar-last library, gets a wrong rotation without any error,
    and these notes are what tell them.

    Examples
    --------
    >>> input_notes("euler:ZXZ", [[30, 45, 60]])
    ['note: angles are read as radians (60 rad is 9.5 turns); pass --degrees if you meant degrees']
    >>> input_notes("euler:ZXZ", [[30, 45, 60]], degrees=True)
    []
    >>> input_notes("axis_angle", [[0, 0, 1, 1.5]])
    []
    >>> input_notes("quat", [[0, 0, 0, 1]])  # doctest: +NORMALIZE_WHITESPACE
    ['note: quaternions are read scalar first, q0 q1 q2 q3, so 0 0 0 1 is a half turn about z;
      pass --scalar-last if it is x y z w (the identity)']
    """
    name, _ = parse_representation(source, "--from")
    values = np.asarray(rows, dtype=np.float64)
    notes = []
    if name == "quat" and not scalar_last:
        norms = np.linalg.norm(values, axis=-1)
        if np.any((norms > 0.0) & (np.abs(values[:, 3]) >= norms * (1.0 - 1e-12))):
            notes.append("note: quaternions are read scalar first, q0 q1 q2 q3, so 0 0 0 1 is a half turn about z; "
                         "pass --scalar-last if it is x y z w (the identity)")
    if degrees or name not in ("euler", "axis_angle", "rotvec"):
        return notes
    if name == "euler":
        angles = np.abs(values)
    elif name == "axis_angle":
        angles = np.abs(values[:, 3])
    else:
        angles = np.linalg.norm(values, axis=-1)
    largest = float(np.max(angles, initial=0.0))
    if largest > 2.0 * np.pi:
        notes.append(f"note: angles are read as radians ({largest:g} rad is {largest / (2.0 * np.pi):.1f} turns); "
                     "pass --degrees if you meant degrees")
    return notes


def _radians(values, degrees):
    return np.deg2rad(values) if degrees else values


def _degrees(values, degrees):
    return np.rad2deg(values) if degrees else values


def _to_quat(name, seq, values, degrees=False):
    """Unit quaternions ``(n, 4)`` of rotations given as rows in representation ``name``.

    Parameters
    ----------
    name : str
        ``quat``, ``matrix`` (rows ``(n, 3, 3)``), ``rotvec``, ``euler`` (with
        ``seq``), ``axis_angle`` (axis, then angle), ``gibbs``, ``mrp`` or
        ``euler_parameters``.
    seq : str
        Euler axis sequence for ``euler``, else ignored.
    values : ndarray, shape (n, k)
    degrees : bool
        Angles (``euler``, ``axis_angle``, ``rotvec``) in degrees.

    Returns
    -------
    ndarray, shape (n, 4)

    Raises
    ------
    ValueError
        For values that are no rotation, with the message of the
        :mod:`kreisel.so3` function that reads them.

    Examples
    --------
    >>> _to_quat("euler", "ZXZ", np.array([[90.0, 0.0, 0.0]]), degrees=True).round(6) + 0.0
    array([[0.707107, 0.      , 0.      , 0.707107]])
    """
    if name == "quat":
        return so3.quat_normalize(values)
    if name == "euler_parameters":
        return so3.euler_parameters_to_quat(values)
    if name == "matrix":
        return so3.matrix_to_quat(values)
    if name == "euler":
        return so3.euler_to_quat(seq, values, degrees=degrees)
    if name == "rotvec":
        return so3.rotvec_to_quat(_radians(values, degrees))
    if name == "axis_angle":
        return so3.rotvec_to_quat(so3.axis_angle_to_rotvec(values[..., :3], values[..., 3], degrees=degrees))
    if name == "gibbs":
        return so3.gibbs_to_quat(values)
    if name == "mrp":
        return so3.mrp_to_quat(values)
    raise ValueError(f"cannot read rotations from {name!r}")


def _from_quat(q, name, seq="", degrees=False):
    """Rotations given by unit quaternions ``q`` as rows of representation ``name``.

    Parameters
    ----------
    q : ndarray, shape (n, 4)
    name : str
        One of :func:`_to_quat`'s names, or ``su2`` and ``cayley_klein``
        (complex rows ``a, b, -b*, a*``).
    seq : str
        Euler axis sequence for ``euler``, else ignored.
    degrees : bool
        Angles (``euler``, ``axis_angle``, ``rotvec``) in degrees.

    Returns
    -------
    ndarray, shape (n, k)
        Real, or complex for ``su2`` and ``cayley_klein``.

    Raises
    ------
    ValueError
        For the Gibbs vector of a half turn, which is infinite.

    Examples
    --------
    >>> q = np.array([[np.sqrt(0.5), 0.0, 0.0, np.sqrt(0.5)]])
    >>> _from_quat(q, "euler", "ZXZ", degrees=True).round(9) + 0.0
    array([[90.,  0.,  0.]])
    >>> _from_quat(q, "axis_angle", degrees=True).round(9) + 0.0
    array([[ 0.,  0.,  1., 90.]])
    """
    if name == "quat":
        return q
    if name == "matrix":
        return so3.quat_to_matrix(q).reshape(q.shape[:-1] + (9,))
    if name == "rotvec":
        return _degrees(so3.quat_to_rotvec(q), degrees)
    if name == "euler":
        return so3.quat_to_euler(seq, q, degrees=degrees)
    if name == "axis_angle":
        axis, angle = so3.rotvec_to_axis_angle(so3.quat_to_rotvec(q))
        return np.concatenate([axis, _degrees(angle, degrees)[..., None]], axis=-1)
    if name == "euler_parameters":
        return so3.quat_to_euler_parameters(q)
    if name == "su2":
        return so3.quat_to_su2(q).reshape(q.shape[:-1] + (4,))
    if name == "cayley_klein":
        return so3.quat_to_cayley_klein(q)
    if name == "gibbs":
        return so3.quat_to_gibbs(q)
    if name == "mrp":
        return so3.quat_to_mrp(q)
    raise ValueError(f"cannot write rotations as {name!r}")


def _first_invalid(src, src_seq, dst, dst_seq, values, degrees, lines, batch_error):
    """Message naming the first row that cannot be converted (and its input line)."""
    for index in range(len(values)):
        what = f"invalid {src}"
        try:
            q = _to_quat(src, src_seq, values[index:index + 1], degrees)
            what = f"no {dst} of this rotation"
            _from_quat(q, dst, dst_seq, degrees)
        except ValueError as exc:
            where = f"input line {lines[index]}: " if lines is not None and len(values) > 1 else ""
            return f"{where}{what}: {exc}"
    return f"invalid {src}: {batch_error}"


def format_rows(array, precision=10):
    """Text lines, one per rotation; complex numbers as ``a+bj``."""
    def fmt(x):
        if np.iscomplexobj(x):
            return f"{x.real:.{precision}g}{x.imag:+.{precision}g}j"
        return f"{float(x):.{precision}g}"

    return ["  ".join(fmt(x) for x in row) for row in array]
