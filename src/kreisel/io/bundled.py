"""The scenario files shipped with kreisel, listed and copied by ``kreisel examples``."""

from __future__ import annotations

import pathlib
import tomllib
from importlib import resources

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


def describe():
    """``{name: description}`` of every bundled scenario."""
    return {name: tomllib.loads(example_path(name).read_text(encoding="utf-8"))["description"] for name in EXAMPLES}


def copy_example(name, directory="."):
    """Copy scenario ``name`` to ``directory/name.toml``; never overwrites an existing file.

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
    with open(target, "x", encoding="utf-8") as fh:  # "x": refuse to clobber the user's file
        fh.write(text)
    return target
