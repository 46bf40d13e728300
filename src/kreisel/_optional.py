"""Optional dependencies: the one place kreisel imports a package that only an extra installs.

``pip install kreisel`` installs the core (numpy, scipy, numba, and typer and
rich for the ``kreisel`` command); each feature beyond it names its extra in
``pyproject.toml``: ``io`` (xarray, pandas, pyarrow, meshio: result files,
``Trajectory.to_xarray``/``to_pandas``/``save``/``load``, meshes in
scenarios, IMU logs), ``plot`` (matplotlib: ``kreisel.plot``, the tour),
``sweep`` (Dask, Zarr), ``viewer`` (FastAPI, uvicorn: ``kreisel serve``),
``notebook`` (anywidget: ``kreisel.show``) and ``all``.

:func:`require` imports such a package; when it is missing, the error is
:class:`MissingExtraError`, an ``ImportError`` whose message is one line
naming the extra to install. A feature that needs packages of several extras
asks for them all at once with :func:`require_all`, so that its one line names
every extra (not one, then after installing it the next). The command line prints that line and exits with
status 2.
"""

from __future__ import annotations

import importlib
from types import ModuleType

__all__ = ["MissingExtraError", "require", "require_all"]


class MissingExtraError(ImportError):
    """A feature's optional dependency is not installed; the message is the one line that says which extra to install.

    Examples
    --------
    >>> error = MissingExtraError("kreisel.plot needs matplotlib", extra="plot", name="matplotlib")
    >>> str(error)
    'kreisel.plot needs matplotlib: pip install "kreisel[plot]"'
    >>> error.extra, isinstance(error, ImportError)
    ('plot', True)
    """

    def __init__(self, need: str, extra: str, name: str | None = None) -> None:
        super().__init__(f'{need}: pip install "kreisel[{extra}]"', name=name)
        self.extra = extra


def require(module: str, extra: str, feature: str) -> ModuleType:
    """Import ``module``, which the extra ``extra`` installs, for ``feature``.

    Parameters
    ----------
    module : str
        The module to import, e.g. ``"xarray"`` or ``"matplotlib.figure"``.
    extra : str
        The extra of kreisel that installs it (``"io"``, ``"plot"``, ``"sweep"``, ``"viewer"``,
        ``"notebook"``).
    feature : str
        What needs it, as the user knows it (``"kreisel serve"``, ``"Trajectory.to_xarray"``).

    Returns
    -------
    module
        The imported module.

    Raises
    ------
    MissingExtraError
        If ``module`` or a package it needs is not installed; the message is one line, e.g.
        ``kreisel serve needs fastapi: pip install "kreisel[viewer]"``.

    Examples
    --------
    >>> require("json", extra="io", feature="reading results").dumps([1])
    '[1]'
    >>> require("no_such_package_here", extra="viewer", feature="kreisel serve")
    Traceback (most recent call last):
    ...
    kreisel._optional.MissingExtraError: kreisel serve needs no_such_package_here: pip install "kreisel[viewer]"
    """
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        # a package the optional one needs may be the missing one: name what is really absent
        missing = (exc.name or module).partition(".")[0]
        raise MissingExtraError(f"{feature} needs {missing}", extra=extra, name=missing) from None


def require_all(needs: list[tuple[str, str]], feature: str) -> list[ModuleType]:
    """Import every ``(module, extra)`` of ``needs`` for ``feature``; all that are missing in one error.

    Parameters
    ----------
    needs : list of (str, str)
        The modules and the extras that install them, as for :func:`require`.
    feature : str
        What needs them, as the user knows it (``"kreisel plot"``).

    Returns
    -------
    list of module
        The imported modules, in the order of ``needs``.

    Raises
    ------
    MissingExtraError
        If any is missing: one line naming every missing package and every extra to install,
        e.g. ``kreisel plot needs matplotlib and xarray: pip install "kreisel[plot,io]"``.

    Examples
    --------
    >>> [m.__name__ for m in require_all([("json", "io"), ("math", "plot")], feature="a feature")]
    ['json', 'math']
    >>> require_all([("no_such_one", "plot"), ("json", "io"), ("no_such_two", "io")], feature="kreisel plot")
    Traceback (most recent call last):
    ...
    kreisel._optional.MissingExtraError: kreisel plot needs no_such_one and no_such_two: pip install "kreisel[plot,io]"
    >>> require_all([("no_such_a", "sweep"), ("no_such_b", "sweep"), ("no_such_c", "plot")], feature="a sweep")
    Traceback (most recent call last):
    ...
    kreisel._optional.MissingExtraError: a sweep needs no_such_a, no_such_b and no_such_c: pip install "kreisel[sweep,plot]"
    """
    modules: list[ModuleType] = []
    missing: list[str] = []
    extras: list[str] = []
    for module, extra in needs:
        try:
            modules.append(require(module, extra=extra, feature=feature))
        except MissingExtraError as exc:
            missing.append(exc.name or module)
            extras.append(extra)
    if missing:
        *others, last = dict.fromkeys(missing)
        listed = f"{', '.join(others)} and {last}" if others else last
        raise MissingExtraError(f"{feature} needs {listed}", extra=",".join(dict.fromkeys(extras)), name=missing[0])
    return modules
