"""Figures for every part of kreisel, as matplotlib ``Figure`` objects.

The functions use matplotlib's object-oriented API only, so importing this
module never opens a window and needs no display.
"""

from __future__ import annotations

import pathlib

from .. import _fileio, _optional

# every module of the package draws with matplotlib: without it, one line naming the extra
_optional.require("matplotlib", extra="plot", feature="plotting (kreisel.plot)")

from .attitude import attitude_estimate
from .fit import gyro_fit, gyro_recording
from .inertia import inertia_ellipsoid
from .trajectory import (DATASET_KINDS, KINDS, apex, coning, energy, euler, foucault, herpolhode, omega,
                         polhode, regular_sequence)

__all__ = ["KINDS", "DATASET_KINDS", "apex", "attitude_estimate", "coning", "energy", "euler", "foucault", "gyro_fit",
           "gyro_recording", "herpolhode", "inertia_ellipsoid", "omega", "polhode", "regular_sequence", "save"]

_FORMATS = {".png", ".svg", ".pdf"}


def save(fig, path, dpi=120):
    """Write ``fig`` to ``path`` (.png, .svg or .pdf) atomically; an existing file is replaced, as by ``savefig``.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from matplotlib.figure import Figure
    >>> fig = Figure(); _ = fig.add_subplot().plot([0, 1])
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "line.png"
    >>> save(fig, out).stat().st_size > 0
    True
    """
    path = pathlib.Path(path)
    if path.suffix.lower() not in _FORMATS:
        raise ValueError(f"path must end in one of {sorted(_FORMATS)}, got {path.name!r}")
    with _fileio.atomic_output(path) as tmp:
        fig.savefig(tmp, dpi=dpi, format=path.suffix.lower()[1:])
    return path
