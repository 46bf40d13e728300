"""tops layer of kreisel: the Euler, symmetric, Lagrange and Kovalevskaya tops (seed 五–七)."""

from ._elliptic import complete_elliptic_pi, elliptic_pi
from .euler_top import EulerTop, SteadyRotation

__all__ = ["EulerTop", "SteadyRotation", "elliptic_pi", "complete_elliptic_pi"]
