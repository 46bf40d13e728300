"""tops layer of kreisel: the Euler, symmetric, Lagrange and Kovalevskaya tops (Theory §5–§7).

Exact solutions (no time stepping) by elliptic functions and integrals of the
third kind (``_elliptic``, built on Carlson's integrals), the stability and
Poinsot geometry of the free top, regular precession and the body and space
cones, the Lagrange top's integrals, nutation and apex locus, and the
Kovalevskaya integral; the free top fitted to gyroscope recordings.
"""

from ._elliptic import complete_elliptic_pi, elliptic_f, elliptic_k, elliptic_pi, jacobi_elliptic
from .euler_top import EulerTop, Regime, SolutionAccuracy, SteadyRotation, solve_free_batch
from .fitting import FreeRotationFit, NotFreeRotationWarning, fit_free_rotation
from .integrals import FirstIntegral, FirstIntegrals, first_integrals
from .kovalevskaya import KovalevskayaIntegrals, KovalevskayaTop
from .poinsot import PoinsotGeometry, poinsot
from .lagrange import FastTop, LagrangeConstants, LagrangeTop, larmor_precession_rate
from .symmetric import Cones, SymmetricTop

__all__ = [
    "first_integrals",
    "FirstIntegral",
    "FirstIntegrals",
    "EulerTop",
    "SteadyRotation",
    "fit_free_rotation",
    "FreeRotationFit",
    "NotFreeRotationWarning",
    "Regime",
    "SolutionAccuracy",
    "solve_free_batch",
    "poinsot",
    "PoinsotGeometry",
    "SymmetricTop",
    "Cones",
    "LagrangeTop",
    "LagrangeConstants",
    "FastTop",
    "larmor_precession_rate",
    "KovalevskayaTop",
    "KovalevskayaIntegrals",
    "elliptic_pi",
    "complete_elliptic_pi",
    "elliptic_f",
    "elliptic_k",
    "jacobi_elliptic",
]
