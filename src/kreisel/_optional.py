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
naming the extra to install. The command line prints that line and exits with
status 2.
"""

from __future__ import annotations

import importlib
from types import ModuleType

__all__ = ["MissingExtraError", "require"]


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
