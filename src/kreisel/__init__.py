"""kreisel — rigid-body mechanics after a lecture chapter on rigid-body mechanics (see the Theory pages of the docs).

Layers, each depending only on the ones before it (and se3 on so3 alone)::

    so3 <- kinematics <- inertia, dynamics <- tops, frames, earth, nav, se3
        <- io, plot, cli, web, sweep, tour

Conventions: scalar-first Hamilton quaternions, active rotations, ``R`` maps
body components to space components, uppercase Euler sequences intrinsic and
lowercase extrinsic, SI units, ``frame="space" | "body"``.
"""

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    # what __getattr__ returns, spelled out for type checkers and editors (tests/test_typing.py checks that
    # every name of __all__ is here)
    from ._version import __version__ as __version__
    from . import dynamics, earth, frames, inertia, io, kinematics, nav, se3, so3, sweep, tops
    from .dynamics import *  # noqa: F403
    from .inertia import RigidBody as RigidBody
    from .kinematics import *  # noqa: F403
    from .notebook import show as show
    from .se3 import *  # noqa: F403
    from .so3 import *  # noqa: F403
    from .tops import *  # noqa: F403

from . import _display

# Names are imported on first use (module __getattr__), so that ``import kreisel`` and the command line's
# help and ``convert`` do not load the simulation, plotting, Dask or web stacks they do not need; even
# ``__version__``, whose importlib.metadata takes most of a bare ``import kreisel``.
_STAR = ("so3", "kinematics", "dynamics", "tops", "se3")   # subpackages whose public names kreisel re-exports
_SUBPACKAGES = ("so3", "kinematics", "inertia", "dynamics", "tops", "se3", "frames", "earth", "nav", "io", "sweep",
                "plot", "cli", "web")
_FROM = {"RigidBody": "inertia", "show": "notebook"}
# Trajectory.show (a lower layer) plays through kreisel.notebook, imported when first used
_display.register_player(lambda: importlib.import_module(f"{__name__}.notebook").show)


def __getattr__(name: str) -> Any:
    value: Any
    if name == "__all__":
        names = [n for package in _STAR for n in importlib.import_module(f"{__name__}.{package}").__all__]
        value = [*names, "inertia", "RigidBody", "frames", "earth", "nav", "io", "sweep", "show", "__version__"]
    elif name in _SUBPACKAGES:
        value = importlib.import_module(f"{__name__}.{name}")
    elif name in _FROM:
        value = getattr(importlib.import_module(f"{__name__}.{_FROM[name]}"), name)
    elif name == "__version__":
        from ._version import __version__ as value
    elif name.startswith("__"):
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    else:
        for package in _STAR:
            module = importlib.import_module(f"{__name__}.{package}")
            if name in module.__all__:
                value = getattr(module, name)
                break
        else:
            raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__getattr__("__all__")))
