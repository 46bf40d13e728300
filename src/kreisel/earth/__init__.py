"""The rotating Earth seen from the local East-North-Up frame (seed 八.2–八.3).

Falling bodies (eastward deflection), shells (the seed's exercise) and the
Foucault pendulum, each as the seed's analytic result and as a simulation of
the full rotating-frame equations. Every function takes ``omega=`` (default the
sidereal rate :data:`OMEGA_EARTH`) so the seed's figures, which use
ω₀ = 7.27221e-5 rad/s, are reproduced exactly.
"""

from .enu import OMEGA_EARTH, angular_velocity_enu, enu_to_ecef_matrix
from .falling import eastward_deflection, shell_deviation, shell_deviation_estimate, simulate_drop
from .foucault import FoucaultSwing, foucault_pendulum, foucault_period, foucault_precession_rate

__all__ = [
    "OMEGA_EARTH",
    "angular_velocity_enu",
    "enu_to_ecef_matrix",
    "eastward_deflection",
    "simulate_drop",
    "shell_deviation",
    "shell_deviation_estimate",
    "foucault_period",
    "foucault_precession_rate",
    "foucault_pendulum",
    "FoucaultSwing",
]
