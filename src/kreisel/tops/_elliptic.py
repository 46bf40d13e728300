"""Elliptic integrals of the third kind, which scipy does not provide.

Built from Carlson's symmetric integrals ``scipy.special.elliprf`` and
``scipy.special.elliprj`` (DLMF 19.25.14), with the quasi-periodic extension
past ``pi/2`` (DLMF 19.2.10 analogue for Pi). Parameter convention as scipy's
``ellipkinc``: ``m = k**2``; characteristic ``n`` as in

    Pi(phi, n | m) = integral_0^phi dtheta / ((1 - n sin^2 theta) sqrt(1 - m sin^2 theta)).

Used by the exact free top (precession angle, Theory §5.3) and by the
Lagrange top quadrature (Theory §6.3).
"""

from __future__ import annotations

import numpy as np
from scipy import special

from .._validation import as_float_array

__all__ = ["elliptic_pi", "complete_elliptic_pi"]


def _check_parameters(n, m):
    if np.any(m > 1.0):
        raise ValueError("m must be <= 1 (parameter m = k**2)")
    if np.any(n >= 1.0):
        raise ValueError("n must be < 1 (the circular case n > 1 has a pole on the path)")


def complete_elliptic_pi(n, m):
    """Complete elliptic integral of the third kind Π(n | m) = Π(π/2, n | m).

    Parameters
    ----------
    n : array_like
        Characteristic, ``n < 1``.
    m : array_like
        Parameter ``m = k**2 < 1`` (Π diverges at ``m = 1``).

    Returns
    -------
    ndarray
        Π(n | m) = R_F(0, 1 − m, 1) + (n/3) R_J(0, 1 − m, 1, 1 − n) (DLMF 19.25.2).

    Examples
    --------
    >>> import numpy as np
    >>> bool(np.isclose(complete_elliptic_pi(0.0, 0.5), special.ellipk(0.5)))
    True
    """
    n = as_float_array(n, "n")
    m = as_float_array(m, "m")
    _check_parameters(n, m)
    return _complete_pi(n, m)


def _complete_pi(n, m):
    mc = 1.0 - m
    return special.elliprf(0.0, mc, 1.0) + n / 3.0 * special.elliprj(0.0, mc, 1.0, 1.0 - n)


def _pi_principal(phi, n, m):
    """Π(φ, n | m) for |φ| <= π/2 by DLMF 19.25.14 (no range check)."""
    s = np.sin(phi)
    c = np.cos(phi)
    s2 = s * s
    delta2 = 1.0 - m * s2
    rf = special.elliprf(c * c, delta2, 1.0)
    rj = special.elliprj(c * c, delta2, 1.0, 1.0 - n * s2)
    return s * rf + n / 3.0 * (s * s2) * rj


def _pi_reduced(phi, j, n, m):
    """Π(φ + jπ, n | m) with |φ| <= π/2 and integer j: Π(φ) + 2jΠ(n | m).

    Callers that know the number of half periods ``j`` exactly (the tops
    reduce the elliptic argument modulo 2K themselves) avoid the rounding of
    a large amplitude.
    """
    principal = _pi_principal(phi, n, m)
    j = np.asarray(j, dtype=np.float64)
    if not np.any(j != 0.0):
        return principal
    return principal + 2.0 * j * _complete_pi(n, m)


def elliptic_pi(phi, n, m):
    """Incomplete elliptic integral of the third kind Π(φ, n | m), any real φ.

    Parameters
    ----------
    phi : array_like
        Amplitude in radians (any real value; quasi-periodic extension
        Π(φ + jπ) = Π(φ) + 2jΠ(n | m) beyond ±π/2).
    n : array_like
        Characteristic, ``n < 1``.
    m : array_like
        Parameter ``m = k**2 <= 1`` (``m = 1`` only for |φ| < π/2).

    Returns
    -------
    ndarray
        Π(φ, n | m), broadcast over the inputs. Accuracy: a few ulp of the
        Carlson integrals for |φ| <= π/2; beyond, the absolute error of
        reducing φ modulo π (≈ |φ|·eps) adds.

    Examples
    --------
    >>> import numpy as np
    >>> bool(np.isclose(elliptic_pi(1.0, 0.0, 0.3), special.ellipkinc(1.0, 0.3)))
    True
    >>> float(elliptic_pi(0.5, 0.0, 0.0))
    0.5
    """
    phi = as_float_array(phi, "phi")
    n = as_float_array(n, "n")
    m = as_float_array(m, "m")
    _check_parameters(n, m)
    j = np.round(phi / np.pi)
    if np.any((j != 0.0) & (m >= 1.0)):
        raise ValueError("phi must satisfy |phi| < pi/2 when m = 1 (the integral diverges)")
    return _pi_reduced(phi - j * np.pi, j, n, m)
