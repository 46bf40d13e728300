"""What the columns of an IMU table hold: quantity, axis and unit, read from its header.

A header cell such as ``"Gyroscope x (rad/s)"``, ``gyro_x_radps``, ``ωₓ``,
``gx`` or ``Magnetic field z (µT)`` names a quantity (time, gyro,
accelerometer, magnetometer), an axis and a unit. Units are matched as whole
tokens — the text in brackets, or the words after the axis — never as
substrings, so ``radps`` is not ``dps`` and ``mdps`` is not ``dps``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Optional

import numpy as np

__all__ = ["Column", "UNITS", "G0", "parse_column", "unit_scale", "known_units", "layout"]

#: standard gravity, m/s² per g (the accelerometer unit)
G0 = 9.80665
_DEG = np.pi / 180.0
_TURN = 2.0 * np.pi
# SI value of one unit, per quantity; keys are normalised spellings (see _normalise)
UNITS = {
    "time": {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9},
    "gyro": {"rad/s": 1.0, "1/s": 1.0, "mrad/s": 1e-3, "urad/s": 1e-6, "deg/s": _DEG, "mdeg/s": _DEG * 1e-3,
             "deg/h": _DEG / 3600.0, "rad/h": 1.0 / 3600.0, "rpm": _TURN / 60.0, "rev/s": _TURN, "hz": _TURN},
    # angle increments of an increment-output gyro
    "increment": {"rad": 1.0, "mrad": 1e-3, "urad": 1e-6, "deg": _DEG, "mdeg": _DEG * 1e-3},
    "accel": {"m/s2": 1.0, "mm/s2": 1e-3, "cm/s2": 1e-2, "gal": 1e-2, "g": G0, "mg": G0 * 1e-3, "ft/s2": 0.3048},
    # magnetometer in µT
    "mag": {"ut": 1.0, "nt": 1e-3, "mt": 1e3, "t": 1e6, "g": 1e2, "mg": 1e-1},
}
# how the units are written in messages, where that differs from the keys above
_SHOWN = {"time": {"us": "µs"}, "gyro": {"urad/s": "µrad/s", "hz": "Hz"}, "increment": {"urad": "µrad"},
          "accel": {"m/s2": "m/s²", "mm/s2": "mm/s²", "cm/s2": "cm/s²", "gal": "Gal", "ft/s2": "ft/s²"},
          "mag": {"ut": "µT", "nt": "nT", "mt": "mT", "t": "T", "g": "G", "mg": "mG"}}
_SPELLINGS = {
    "sec": "s", "secs": "s", "second": "s", "seconds": "s", "msec": "ms", "usec": "us", "nsec": "ns",
    "radps": "rad/s", "rad/sec": "rad/s", "rads": "rad/s", "rads-1": "rad/s", "s-1": "1/s",
    "dps": "deg/s", "degps": "deg/s", "deg/sec": "deg/s", "degs-1": "deg/s", "mradps": "mrad/s", "mdps": "mdeg/s",
    "deg/hr": "deg/h", "dph": "deg/h", "rev/min": "rpm", "r/min": "rpm", "rps": "rev/s", "r/s": "rev/s",
    "ms-2": "m/s2", "m/s/s": "m/s2", "mps2": "m/s2", "mss": "m/s2", "gs": "g", "gauss": "g", "mgauss": "mg",
    "tesla": "t",
}
_QUANTITY_WORDS = {
    "time": ("time", "t", "timestamp", "stamp", "seconds"),
    "gyro": ("gyro", "gyroscope", "gyr", "omega", "ω", "w", "g", "rate", "angular", "angvel", "rot", "rotation"),
    "accel": ("acc", "accel", "acceleration", "accelerometer", "a", "specific", "f"),
    "mag": ("mag", "magnet", "magnetic", "magnetometer", "magn", "m", "b", "field"),
}
# tables of acceleration without gravity or of attitude are not sensor outputs the reader uses
_OTHER_WORDS = ("linear", "gravity", "absolute", "abs", "norm", "total", "roll", "pitch", "yaw", "quat",
                "orientation", "temperature", "temp", "pressure")
_WORD_QUANTITY = {word: quantity for quantity, words in _QUANTITY_WORDS.items() for word in words}
_BRACKETED = re.compile(r"[(\[]\s*([^()\[\]]*?)\s*[)\]]")
_SENSOR = {"gyro": "gyro", "accel": "accelerometer", "mag": "magnetometer"}
_SUBSCRIPTS = str.maketrans({"ₓ": "x", "ᵧ": "y", "ᶻ": "z"})


@dataclass(frozen=True)
class Column:
    """One header cell: ``quantity`` ("time", "gyro", "accel", "mag" or None), ``axis`` (0, 1, 2 or None),
    ``unit`` (the unit token as written, or None) and the cell's text ``name``."""

    name: str
    quantity: Optional[str]
    axis: Optional[int]
    unit: Optional[str]


def _normalise(unit):
    text = unit.strip().lower().replace("µ", "u").replace("μ", "u").replace("°", "deg").replace("²", "2")
    text = re.sub(r"\s+", "", text).replace("^", "").replace("_", "/").replace("·", "")
    text = re.sub(r"degrees?", "deg", text)
    return _SPELLINGS.get(text, text)


def unit_scale(quantity, unit):
    """SI value (µT for the magnetometer) of one ``unit`` of ``quantity``; None if the unit is not one of it.

    Examples
    --------
    >>> unit_scale("gyro", "rpm") * 60 / (2 * np.pi), unit_scale("gyro", "radps"), unit_scale("accel", "g")
    (1.0, 1.0, 9.80665)
    >>> unit_scale("gyro", "furlong/s") is None
    True
    """
    return UNITS[quantity].get(_normalise(unit))


def known_units(quantity):
    """The units of ``quantity`` as a message lists them.

    Examples
    --------
    >>> known_units("mag")
    'µT, nT, mT, T, G, mG'
    """
    return ", ".join(_SHOWN[quantity].get(unit, unit) for unit in UNITS[quantity])


def _words(text):
    """Words of a header cell outside brackets; ``gx``/``accX``/``ωx`` split into the quantity and the axis."""
    words = [w for w in re.split(r"[\s_.:,]+", text.translate(_SUBSCRIPTS).lower()) if w]
    split = []
    for word in words:
        head, last = word[:-1], word[-1:]
        if last in "xyz" and head in _WORD_QUANTITY:
            split += [head, last]
        else:
            split.append(word)
    return split


def _is_other(name):
    """Whether the header cell ``name`` names a quantity the reader does not use (a norm, gravity, attitude)."""
    return any(word in _OTHER_WORDS for word in _words(_BRACKETED.sub(" ", name)))


def parse_column(name):
    """Quantity, axis and unit of the header cell ``name``.

    The unit is the text in the first brackets (its first word when it goes on,
    as in ``[ms since boot]``), else the words after the axis (``gyro_x_radps``)
    or after the time word (``time_ms``).

    Examples
    --------
    >>> parse_column("Gyroscope z (rad/s)")
    Column(name='Gyroscope z (rad/s)', quantity='gyro', axis=2, unit='rad/s')
    >>> c = parse_column("gyro_x_radps"); (c.quantity, c.axis, c.unit)
    ('gyro', 0, 'radps')
    >>> c = parse_column("ax"); (c.quantity, c.axis, c.unit)
    ('accel', 0, None)
    """
    bracket = _BRACKETED.search(name)
    unit = None
    if bracket is not None:
        inside = bracket.group(1).split()
        unit = inside[0] if len(inside) > 1 and unit_scale("time", inside[0]) else bracket.group(1) or None
    words = _words(_BRACKETED.sub(" ", name))
    axes = [k for k, w in enumerate(words) if w in ("x", "y", "z")]
    axis = "xyz".index(words[axes[0]]) if axes else None
    # a one-letter word names a quantity only with its axis ("gx", "a_x"); "t" alone is time
    named = [k for k, w in enumerate(words) if w in _WORD_QUANTITY
             and (len(w) > 1 or w == "t" or (k + 1 < len(words) and words[k + 1] in ("x", "y", "z")))]
    quantity = None
    if named and not _is_other(name):
        quantity = _WORD_QUANTITY[words[named[0]]]
    if unit is None and quantity is not None:
        rest = words[max([named[0], *axes]) + 1:]
        unit = "/".join(w for w in rest if len(w) == 1 or w not in _WORD_QUANTITY) or None
    return Column(name, quantity, axis, unit)


def layout(columns, source, default="gyro"):
    """Column indices of time and of each quantity's x, y, z, from parsed header cells.

    Named axes decide the order; columns of a quantity without axes keep the file's order. When the
    header names no gyro, the first three columns after time that no other quantity claims are the
    gyro's. Returns ``{"time": i, "gyro": [i, j, k], "accel": [...] or absent, "mag": ...}``.

    Raises
    ------
    ValueError
        A quantity with an axis named twice, or with fewer or more than three columns; a header that names
        no ``default`` columns and leaves fewer than three columns for them.
    """
    found = {}
    time = next((k for k, c in enumerate(columns) if c.quantity == "time"), 0)
    for quantity in ("gyro", "accel", "mag"):
        members = [k for k, c in enumerate(columns) if c.quantity == quantity and k != time]
        if not members:
            continue
        axes = [columns[k].axis for k in members]
        if all(a is not None for a in axes):
            for a in range(3):
                if axes.count(a) > 1:
                    named = [columns[k].name for k, b in zip(members, axes) if b == a]
                    raise ValueError(f"{source}: the {_SENSOR[quantity]} {'xyz'[a]} axis is named by more than one "
                                     f"column: {', '.join(map(repr, named))}")
            members = sorted(members, key=lambda k: columns[k].axis)
        if len(members) != 3:
            raise ValueError(f"{source}: {len(members)} {_SENSOR[quantity]} column(s) "
                             f"({', '.join(repr(columns[k].name) for k in members)}); expected x, y and z")
        found[quantity] = members
    if default not in found:
        claimed = {time, *[k for members in found.values() for k in members]}
        # a norm ("Absolute (rad/s)") or linear acceleration is no sensor axis, even where nothing else is named
        free = [k for k in range(len(columns)) if k not in claimed and not _is_other(columns[k].name)]
        if len(free) < 3:
            others = " and the ".join(f"{_SENSOR[q]}'s" for q in found)
            names = ", ".join(repr(columns[k].name) for k in free)
            left = (f"{len(free)} other column{'s' * (len(free) != 1)} ({names}) {'is' if len(free) == 1 else 'are'}"
                    if free else "no other column is")
            raise ValueError(f"{source}: the header names no {_SENSOR[default]} columns"
                             f"{f' (it names the {others})' if found else ''}, and {left} left; expected three "
                             f"{_SENSOR[default]} columns x, y, z: name them with columns=")
        free = free[:3]
        if sorted(columns[k].axis for k in free if columns[k].axis is not None) == [0, 1, 2]:
            free.sort(key=lambda k: columns[k].axis)
        found[default] = free
    return {"time": time, **found}
