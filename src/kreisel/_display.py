"""The notebook player that ``Trajectory.show`` hands itself to, registered from above.

:class:`kreisel.dynamics.Trajectory` sits in a low layer and must not import the notebook widget
(:func:`kreisel.notebook.show`, top layer, ``notebook`` extra). The package facade
(``kreisel/__init__.py``), which runs before any subpackage, registers a loader here; the widget
module is imported only when a trajectory is first shown, so ``import kreisel`` stays light.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

__all__ = ["register_player", "player"]

_loader: Callable[[], Callable[..., Any]] | None = None


def register_player(loader: Callable[[], Callable[..., Any]]) -> None:
    """Make ``loader()`` (returning a function ``show(trajectory, **options)``) the trajectory player.

    Examples
    --------
    >>> import kreisel
    >>> player().__module__
    'kreisel.notebook'
    """
    global _loader
    if not callable(loader):
        raise TypeError(f"loader must be callable, got {type(loader).__name__}")
    _loader = loader


def player() -> Callable[..., Any]:
    """The registered trajectory player (loaded on first use).

    Examples
    --------
    >>> import kreisel
    >>> player().__name__
    'show'
    """
    if _loader is None:
        raise RuntimeError("no trajectory player is registered; it comes with `import kreisel`")
    return _loader()
