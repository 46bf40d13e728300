"""The local East-North-Up frame on the rotating Earth (Theory §8.2)."""

from __future__ import annotations

import numpy as np

from .._validation import as_float_array

__all__ = ["OMEGA_EARTH", "angular_velocity_enu", "enu_to_ecef_matrix"]

OMEGA_EARTH = 7.2921159e-5
"""Sidereal rotation rate of the Earth, rad/s (IERS). Theory §8.2 uses 7.27221e-5 (2π per solar day)."""


def latitude_cos_sin(latitude_deg, name="latitude_deg"):
    """(cos λ, sin λ) of a latitude in degrees, exactly 0 at the equator and the poles."""
    lat = as_float_array(latitude_deg, name)
    if np.any(np.abs(lat) > 90.0):
        raise ValueError(f"{name} must lie in [-90, 90] degrees")
    # cos λ as sin(90° - |λ|) so that it is exactly 0 at the poles, not 6e-17
    return np.sin(np.deg2rad(90.0 - np.abs(lat))), np.sin(np.deg2rad(lat))


def check_omega(omega):
    """Validate an Earth rotation rate (rad/s, finite, non-negative)."""
    w = as_float_array(omega, "omega")
    if np.any(w < 0):
        raise ValueError("omega must be non-negative (rad/s); the hemisphere is set by the latitude")
    return w


def angular_velocity_enu(latitude_deg, omega=OMEGA_EARTH):
    """Earth's angular velocity in the local ENU frame: ω (0, cos λ, sin λ) (Theory §8.2).

    Parameters
    ----------
    latitude_deg : array_like
        Latitude λ in degrees (astronomical: the angle between the local
        vertical and the equatorial plane).
    omega : float or array_like
        Rotation rate, rad/s.

    Returns
    -------
    (..., 3) ndarray
        East, North, Up components, rad/s.

    Examples
    --------
    >>> angular_velocity_enu(90.0, omega=1.0).tolist()
    [0.0, 0.0, 1.0]
    """
    c, s = latitude_cos_sin(latitude_deg)
    w = check_omega(omega)
    c, s, w = np.broadcast_arrays(c, s, w)
    return np.stack([np.zeros_like(w), w * c, w * s], axis=-1)


def enu_to_ecef_matrix(latitude_deg, longitude_deg=0.0):
    """Matrix whose columns are the East, North, Up unit vectors in Earth-fixed (ECEF) axes.

    ``a_ecef = M @ a_enu``; ECEF has z along the rotation axis and x at
    longitude 0 in the equator (spherical-Earth directions).

    Examples
    --------
    >>> import numpy as np
    >>> M = enu_to_ecef_matrix(0.0, 0.0)
    >>> (np.round(M, 12) + 0.0).tolist()
    [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    """
    c, s = latitude_cos_sin(latitude_deg)
    lon = np.deg2rad(as_float_array(longitude_deg, "longitude_deg"))
    c, s, lon = np.broadcast_arrays(c, s, lon)
    cl, sl = np.cos(lon), np.sin(lon)
    zero = np.zeros_like(c)
    east = np.stack([-sl, cl, zero], axis=-1)
    north = np.stack([-s * cl, -s * sl, c], axis=-1)
    up = np.stack([c * cl, c * sl, s], axis=-1)
    return np.stack([east, north, up], axis=-1)
