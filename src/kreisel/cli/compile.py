"""``kreisel compile``: compile kreisel's kernels into the on-disk cache before the first run needs them.

kreisel compiles each kernel for this machine on first use and keeps the
machine code in its cache (:mod:`kreisel._compiled.cache`); a fresh install
pays for that once, spread over the first runs. ``kreisel compile`` pays it at
once, part by part:

- every declared array operation (:data:`kreisel._compiled.elementwise.REGISTRY`:
  rotations, kinematics, rigid transforms), its serial, checking and
  multi-core loops, compiled for the one signature each has;
- the integrators and the models, which numba compiles for the argument types
  they are called with: each is called once on a tiny problem, with the types
  kreisel's own functions pass, so that the cache holds what those calls load.
"""

from __future__ import annotations

import functools
import importlib

import numpy as np

__all__ = ["PACKAGES", "parts"]

#: The packages that hold compiled code (imported so that every array operation is declared).
PACKAGES = ("so3", "se3", "kinematics", "inertia", "dynamics", "tops", "frames", "earth", "nav")


def _operation(operation):
    for variant in ("serial", "valid", "parallel"):
        operation._loop(variant)


def _integrator(method):
    from ..dynamics import simulate, simulate_batch
    from ..dynamics.engine import ADAPTIVE
    from ..dynamics.torques import GravityTorque
    from ..inertia import RigidBody

    dt = None if method in ADAPTIVE else 1e-2
    t = np.linspace(0.0, 0.05, 3)
    body = RigidBody([1.0, 2.0, 3.0])
    simulate(body, t, [0.1, 1.0, 0.1], method=method, dt=dt)
    simulate(body, t, [0.1, 1.0, 0.1], method=method, dt=dt, torque=GravityTorque(1.0, [0.0, 0.0, 1.0]))
    simulate_batch(np.ones((2, 3)) + np.arange(3.0), t, [0.1, 1.0, 0.1], method=method, dt=dt)


def _tops():
    from ..tops import EulerTop, fit_free_rotation, solve_free_batch
    from ..tops.kovalevskaya import KovalevskayaTop
    from ..tops.lagrange import LagrangeTop

    t = np.linspace(0.0, 1.0, 60)
    EulerTop(1.0, 2.0, 3.0).solve(t, [0.01, 1.0, 0.01])
    solve_free_batch(np.array([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]]), t, [0.1, 1.0, 0.1])
    LagrangeTop(1.0, 0.5, 1.0).solve(t, [0.0, 0.8, 0.0], [0.0, 0.0, 40.0])
    KovalevskayaTop(1.0, 1.0).integrals([[0.5, 0.2, 1.0]], [[0.0, 0.0, 1.0]])
    fit_free_rotation(t, EulerTop(0.2, 0.8, 1.0).omega(t, [0.5, 12.0, 0.3]), bias=True)


def _earth_and_frames():
    from ..earth import foucault_pendulum, shell_deviation, simulate_drop
    from ..frames import simulate_particle

    simulate_drop(100.0, 31.8584)
    shell_deviation(500.0, 45.0, 90.0, 45.0)
    foucault_pendulum(1.0, 48.0, 2.0, 0.1)
    simulate_particle([0.0, 0.5], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0])


def _navigation():
    from ..nav import attitude_from_increments, attitude_from_rates, coning_motion

    motion = coning_motion(0.1, 2.0 * np.pi, 0.01, 8)
    attitude_from_increments(motion.q[0], motion.dtheta, samples_per_update=2)
    t = np.linspace(0.0, 1.0, 11)
    for method in ("quaternion", "bortz"):
        attitude_from_rates([1.0, 0.0, 0.0, 0.0], t, np.tile([0.0, 0.0, np.pi], (11, 1)), method=method)


def parts():
    """``[(label, compile)]``: every part of kreisel that compiles, and the call that compiles it.

    Examples
    --------
    >>> labels = [label for label, _ in parts()]
    >>> "array operation quat_multiply" in labels, "integrator splitting" in labels
    (True, True)
    """
    for name in PACKAGES:
        importlib.import_module(f"kreisel.{name}")
    from .._compiled.elementwise import REGISTRY
    from ..dynamics.engine import METHODS

    found = [(f"array operation {name}", functools.partial(_operation, operation))
             for name, operation in sorted(REGISTRY.items())]
    found += [(f"integrator {method}", functools.partial(_integrator, method)) for method in METHODS
              if METHODS[method] is not None]
    found += [("exact tops and the free-top fit", _tops), ("rotating frames and the Earth", _earth_and_frames),
              ("strapdown navigation", _navigation)]
    return found
