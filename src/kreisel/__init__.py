"""kreisel — rigid-body mechanics after a lecture chapter on rigid-body mechanics (see the Theory pages of the docs).

Layers, each depending only on the ones before it::

    so3 <- kinematics <- inertia, dynamics <- tops, frames, earth, nav, se3

Conventions: scalar-first Hamilton quaternions, active rotations, ``R`` maps
body components to space components, uppercase Euler sequences intrinsic and
lowercase extrinsic, SI units, ``frame="space" | "body"``.
"""

from .so3 import *  # noqa: F401,F403
from .so3 import __all__ as _so3_all
from .kinematics import *  # noqa: F401,F403
from .kinematics import __all__ as _kinematics_all
from . import inertia  # noqa: F401
from .inertia import RigidBody  # noqa: F401
from .dynamics import *  # noqa: F401,F403
from .dynamics import __all__ as _dynamics_all
from .tops import *  # noqa: F401,F403
from .tops import __all__ as _tops_all
from .se3 import *  # noqa: F401,F403
from .se3 import __all__ as _se3_all
from . import frames, earth, nav  # noqa: F401
from . import io, sweep  # noqa: F401  (user-facing layers; neither imports dask or the web stack)
from ._version import __version__

__all__ = [
    *_so3_all,
    *_kinematics_all,
    *_dynamics_all,
    *_tops_all,
    *_se3_all,
    "inertia",
    "RigidBody",
    "frames",
    "earth",
    "nav",
    "io",
    "sweep",
    "__version__",
]
