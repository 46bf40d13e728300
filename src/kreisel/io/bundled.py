"""The scenario files shipped with kreisel, listed and copied by ``kreisel examples``."""

from __future__ import annotations

import difflib
import pathlib
import tomllib
from importlib import resources

from .._fileio import atomic_output

__all__ = ["example_path", "suggestion", "scenario_path", "describe", "copy_example", "EXAMPLES"]

EXAMPLES = ("tennis_racket", "symmetric_top", "lagrange_cusps", "lagrange_loops", "sleeping_top", "fast_top",
            "kovalevskaya", "foucault", "coning")


def example_path(name):
    """Path of the bundled scenario ``name`` inside the installed package.

    Examples
    --------
    >>> path = example_path("tennis_racket")
    >>> path.name, path.is_file()
    ('tennis_racket.toml', True)
    >>> example_path("pendulum")
    Traceback (most recent call last):
        ...
    ValueError: name must be one of tennis_racket, symmetric_top, lagrange_cusps, lagrange_loops, sleeping_top, fast_top, kovalevskaya, foucault, coning, got 'pendulum'
    """
    if name not in EXAMPLES:
        raise ValueError(f"name must be one of {', '.join(EXAMPLES)}, got {name!r}")
    return pathlib.Path(str(resources.files("kreisel.io.examples").joinpath(f"{name}.toml")))


def suggestion(name, names):
    """``"; did you mean 'x'?"`` with the names nearest to ``name``, else all ``names``.

    Examples
    --------
    >>> suggestion("tenis_racket.toml", EXAMPLES)
    "; did you mean 'tennis_racket'?"
    >>> suggestion("pendulum", ("foucault", "coning"))
    ' (expected one of foucault, coning)'
    """
    close = difflib.get_close_matches(pathlib.PurePath(str(name)).stem, names, n=3, cutoff=0.6)
    return f"; did you mean {' or '.join(map(repr, close))}?" if close else f" (expected one of {', '.join(names)})"


def scenario_path(path):
    """``path`` if it is a file, else the bundled scenario of that name; FileNotFoundError naming the nearest.

    Examples
    --------
    >>> scenario_path("tennis_racket").name
    'tennis_racket.toml'
    >>> scenario_path("fast_tops")
    Traceback (most recent call last):
        ...
    FileNotFoundError: fast_tops: no such file, and no bundled scenario of that name; did you mean 'fast_top'?
    """
    file = pathlib.Path(path)
    if file.exists():
        return file
    if str(path) in EXAMPLES:
        return example_path(str(path))
    raise FileNotFoundError(f"{path}: no such file, and no bundled scenario of that name{suggestion(path, EXAMPLES)}")


def describe():
    """``{name: description}`` of every bundled scenario."""
    return {name: tomllib.loads(example_path(name).read_text(encoding="utf-8"))["description"] for name in EXAMPLES}


def copy_example(name, directory=".", force=False):
    """Copy scenario ``name`` to ``directory/name.toml``; an existing file is replaced only with ``force``.

    Raises ``FileExistsError`` (saying so in words) when the file exists and
    ``force`` is false.

    Examples
    --------
    >>> import tempfile
    >>> copy_example("tennis_racket", tempfile.mkdtemp()).name
    'tennis_racket.toml'
    """
    directory = pathlib.Path(directory)
    if not directory.is_dir():
        raise ValueError(f"directory {str(directory)!r} does not exist")
    target = directory / f"{name}.toml"
    text = example_path(name).read_text(encoding="utf-8")
    if force:
        with atomic_output(target) as tmp:
            tmp.write_text(text, encoding="utf-8")
        return target
    try:
        with open(target, "x", encoding="utf-8") as fh:  # "x": refuse to clobber the user's file
            fh.write(text)
    except FileExistsError:
        raise FileExistsError(f"{target} already exists; edit it, or pass --force to replace it "
                              "with the bundled version") from None
    return target
