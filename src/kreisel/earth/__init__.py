"""The rotating Earth seen from the local East-North-Up frame (Theory §8.2–§8.3).

Falling bodies (eastward deflection), shells (the chapter's exercise) and the
Foucault pendulum, each as the chapter's analytic result and as a simulation of
the full rotating-frame equations. Every function takes ``omega=`` (default the
sidereal rate :data:`OMEGA_EARTH`) so the chapter's figures, which use
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
