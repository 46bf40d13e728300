"""Motion observed from moving, rotating frames (Theory §4.7 and §8.1).

The five-term acceleration, the fictitious forces, the moving-frame Lagrangian
and Hamiltonian, and a compiled simulator for a particle in a frame with known
ω(t) and origin acceleration a0(t).
"""

from .relative import *  # noqa: F401,F403
from .relative import __all__ as _relative_all
from .particle import ParticleTrajectory, simulate_particle

__all__ = [*_relative_all, "ParticleTrajectory", "simulate_particle"]
