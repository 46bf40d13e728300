"""Taylor coefficients of the SO(3) and SE(3) coefficient functions, from exact rationals.

Each function of the angle ψ used by the rate maps loses digits to
cancellation when evaluated directly at small ψ; below a switch-over angle
it is summed from its Maclaurin series in ψ² instead. The coefficients are
generated here from exact rational arithmetic (so no coefficient is
mistyped), highest order first, ready for Horner's rule.
"""

from __future__ import annotations

from fractions import Fraction
from math import comb, factorial


def _bernoulli(count):
    """B_0 .. B_{count-1} (B_1 = -1/2) by the standard recurrence."""
    b = [Fraction(1)]
    for m in range(1, count):
        b.append(-sum(comb(m + 1, k) * b[k] for k in range(m)) / (m + 1))
    return b


def horner_order(coefficients):
    """Floats highest order first, for Horner's rule, from coefficients lowest order first."""
    return tuple(float(c) for c in reversed(coefficients))


def bortz_coefficients(terms):
    """(1 - (ψ/2) cot(ψ/2))/ψ² = Σ_{n>=1} |B_2n| ψ^(2n-2)/(2n)!  (1/12, 1/720, 1/30240, ...)."""
    b = _bernoulli(2 * terms + 1)
    return [abs(b[2 * n]) / factorial(2 * n) for n in range(1, terms + 1)]


def sine_remainder_coefficients(terms):
    """(ψ - sin ψ)/ψ³ = Σ_{n>=0} (-1)^n ψ^(2n)/(2n+3)!."""
    return [Fraction((-1) ** n, factorial(2 * n + 3)) for n in range(terms)]


def cosine_remainder_coefficients(terms):
    """(ψ² + 2 cos ψ − 2)/(2ψ⁴) = Σ_{n>=0} (-1)^n ψ^(2n)/(2n+4)!."""
    return [Fraction((-1) ** n, factorial(2 * n + 4)) for n in range(terms)]


def se3_coupling_coefficients(terms):
    """(2ψ − 3 sin ψ + ψ cos ψ)/(2ψ⁵) = Σ_{n>=0} (-1)^n (n+1) ψ^(2n)/(2n+5)!."""
    return [Fraction((-1) ** n * (n + 1), factorial(2 * n + 5)) for n in range(terms)]


def cosine_remainder_slope_coefficients(terms):
    """(d/dψ [(1 - cos ψ)/ψ²])/ψ = Σ_{n>=1} (-1)^n 2n ψ^(2n-2)/(2n+2)!."""
    return [Fraction((-1) ** n * 2 * n, factorial(2 * n + 2)) for n in range(1, terms + 1)]


def sine_remainder_slope_coefficients(terms):
    """(d/dψ [(ψ - sin ψ)/ψ³])/ψ = Σ_{n>=1} (-1)^n 2n ψ^(2n-2)/(2n+3)!."""
    return [Fraction((-1) ** n * 2 * n, factorial(2 * n + 3)) for n in range(1, terms + 1)]


# Switch-over angles and term counts: the first omitted term is below 1e-17
# relative at the switch-over, and the direct formulas above it lose at most
# ~10 ulp (Bortz, ψ - sin ψ) or ~40 ulp (the slopes) to cancellation.
BORTZ_SERIES_BELOW = 1.0
BORTZ_SERIES = horner_order(bortz_coefficients(12))
SINE_REMAINDER_SERIES_BELOW = 1.0
SINE_REMAINDER_SERIES = horner_order(sine_remainder_coefficients(9))
SLOPE_SERIES_BELOW = 2.0
COSINE_REMAINDER_SLOPE_SERIES = horner_order(cosine_remainder_slope_coefficients(16))
SINE_REMAINDER_SLOPE_SERIES = horner_order(sine_remainder_slope_coefficients(16))
# The SE(3) coupling coefficients: 14 terms reach 1e-24 relative at 2, and the
# closed forms lose at most ~5 ulp above it.
SE3_SERIES_BELOW = 2.0
COSINE_REMAINDER_SERIES = horner_order(cosine_remainder_coefficients(14))
SE3_COUPLING_SERIES = horner_order(se3_coupling_coefficients(14))
