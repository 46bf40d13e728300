"""Motion observed from moving, rotating frames (Theory §4.7 and §8.1).

The five-term acceleration, the fictitious forces, the moving-frame Lagrangian
and Hamiltonian, and a compiled simulator for a particle in a frame with known
ω(t) and origin acceleration a0(t).
"""

from .relative import *  # noqa: F401,F403
from .particle import ParticleTrajectory, simulate_particle

# Literal, so that every type checker reads it (mypy reads neither `+=` nor `*` of another module's list);
# tests/test_public_surface.py checks that it holds exactly the names of the modules imported above.
__all__ = [
    # relative
    "InertialForces", "LagrangianTerms", "HamiltonianTerms", "inertial_forces", "canonical_momentum",
    "velocity_from_momentum", "lagrangian_terms", "lagrangian", "hamiltonian_terms", "hamiltonian",
    # particle
    "ParticleTrajectory", "simulate_particle",
]
