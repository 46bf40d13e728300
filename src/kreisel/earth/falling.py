"""Free fall and projectiles on the rotating Earth (Theory §8.3: eastward deflection, the shell exercise).

The model (used by every simulation here), in the local ENU frame whose origin
O is on the ground and rotates with the Earth:

    r̈ = -g Up - ω×(ω×r) - 2 ω×ṙ,     ω = ω₀ (0, cos λ, sin λ).

``g`` is the *effective* local gravity at O, the plumb-line acceleration along
-Up: it already contains the gravitational attraction, the centrifugal
acceleration of O itself and the acceleration a0 of the origin (Theory §8.2,
"a0 ... 可归入当地重力加速度之中"), and λ is the latitude of that plumb line.
What remains of the centrifugal force is its part relative to O,
-ω×(ω×r), which vanishes at O and is kept in full, as is the Coriolis term.
The gravitational field itself is taken as uniform over the flight (no
gravity gradient: its relative size is about 3h/R⊕ ≈ 5e-5 for h = 100 m, and it
does not change the east offset at first order).
"""

from __future__ import annotations

import numpy as np

from .._compiled import cached, dop853 as _dop853
from .._validation import as_float_array, out_of_range
from ..frames.particle import builtin_parameters, builtin_rhs
from .enu import OMEGA_EARTH, angular_velocity_enu, check_omega, latitude_cos_sin

__all__ = [
    "eastward_deflection",
    "simulate_drop",
    "shell_deviation",
    "shell_deviation_estimate",
]


def _positive(x, name, strict=True):
    a = as_float_array(x, name)
    if np.any(a <= 0) if strict else np.any(a < 0):
        raise ValueError(f"{name} must be {'positive' if strict else 'non-negative'}")
    return a


def eastward_deflection(height, latitude_deg, g=9.80665, omega=OMEGA_EARTH):
    """Eastward deflection of a body dropped from rest, Theory §8.3: (2/3) ω cos λ √(2h³/g).

    First order in ω (the chapter's Maupertuis solution); the same in both
    hemispheres, zero at the poles.

    Parameters
    ----------
    height : array_like
        Drop height h, m (non-negative).
    latitude_deg : array_like
        Latitude λ, degrees.
    g : array_like
        Effective local gravity (see the module note), m/s².
    omega : array_like
        Earth's rotation rate, rad/s.

    Returns
    -------
    ndarray
        Deflection towards the east, m.

    Examples
    --------
    The chapter's 100 m mine shaft at Hefei:

    >>> round(float(eastward_deflection(100.0, 31.8584, g=9.7947, omega=7.27221e-5)), 4)
    0.0186
    """
    h = _positive(height, "height", strict=False)
    c, _ = latitude_cos_sin(latitude_deg)
    g = _positive(g, "g")
    w = check_omega(omega)
    with out_of_range("height, g and omega", "the deflection") as guard:
        # h √(2h/g), not √(2h³/g): h³ overflows from 1e103 m where the deflection is still representable
        return guard.check((2.0 / 3.0) * w * c * (h * np.sqrt(2.0 * h / g)))


@cached
def _land_kernel(p, y0, rtol, atol, max_step, tables):
    """Integrate :func:`builtin_rhs` from t = 0 until the height ``y[2]`` comes down through zero.

    Returns ``(status, t, y)`` there. The crossing step is found by the adaptive
    loop, then its length is solved for by Newton's method on a single DOP853
    step (dz/dτ = ``y[5]``), so the landing state has the integrator's full order.
    """
    n = y0.size
    k = np.empty(_dop853.N_STAGES_EXTENDED * n)
    y = y0.copy()
    y_new = np.empty(n)
    tmp = np.empty(n)
    t = 0.0
    builtin_rhs(t, y, p, k, 0)
    h = _dop853.initial_step(builtin_rhs, p, t, y, k, max_step, rtol, atol, tmp, y_new)
    while True:
        status, t_new, h_taken, h_next = _dop853.advance(
            builtin_rhs, p, t, y, h, np.inf, max_step, rtol, atol, tables, k, tmp, y_new
        )
        if status != _dop853.OK:
            return status, t, y
        if y_new[2] <= 0.0 and y_new[5] < 0.0:
            if y[2] > 0.0:
                break
            # a launch from the ground that is back below it after one step: shorten
            h = 0.5 * h_taken
            continue
        t = t_new
        h = h_next
        for i in range(n):
            y[i] = y_new[i]
            k[i] = k[_dop853.N_STAGES * n + i]
    # safeguarded Newton (bisection fallback) on the length of the last step
    lo, hi = 0.0, h_taken
    tau = h_taken * y[2] / (y[2] - y_new[2])
    for _ in range(100):
        _dop853.attempt(builtin_rhs, p, t, y, tau, tables, k, tmp, y_new)
        if y_new[2] > 0.0:
            lo = tau
        else:
            hi = tau
        step = -y_new[2] / y_new[5] if y_new[5] != 0.0 else np.inf
        new_tau = tau + step
        if not (lo < new_tau < hi):
            new_tau = 0.5 * (lo + hi)
        converged = abs(new_tau - tau) <= 1e-15 * tau
        tau = new_tau
        if converged:
            break
    _dop853.attempt(builtin_rhs, p, t, y, tau, tables, k, tmp, y_new)
    return _dop853.OK, t + tau, y_new


def _land(position, velocity, latitude_deg, g, omega):
    """Landing time and ENU state of one particle under the model of the module note."""
    p = builtin_parameters(angular_velocity_enu(latitude_deg, omega), field=(0.0, 0.0, -g))
    y0 = np.concatenate([position, velocity]).astype(np.float64)
    # flight time without rotation; steps of an eighth of it keep the landing search well posed
    vz = velocity[2]
    flight = (vz + np.hypot(vz, np.sqrt(2.0 * g * position[2]))) / g  # hypot: vz² overflows from 1e154 m/s
    status, t, y = _land_kernel(p, y0, 1e-13, np.full(6, 1e-13), flight / 8.0, _dop853.tableau())
    _dop853.check_status(status)
    return t, y


def simulate_drop(height, latitude_deg, g=9.80665, omega=OMEGA_EARTH):
    """Landing offset of a body released at rest from height h, by integrating the full equations.

    The body starts at rest (relative to the Earth) at ENU position (0, 0, h)
    above the landing origin and is integrated, with the Coriolis force and the
    whole relative centrifugal term (see the module note for what ``g`` means),
    until it reaches the ground z = 0. Agrees with :func:`eastward_deflection`
    to a relative O(ω² h/g); the north offset is the O(ω²) southward drift
    (northern hemisphere) that the first-order formula omits.

    Parameters
    ----------
    height : array_like
        Drop height, m (positive).
    latitude_deg : array_like
        Latitude, degrees.
    g : array_like
        Effective local gravity along -Up, m/s².
    omega : array_like
        Earth's rotation rate, rad/s.

    Returns
    -------
    east, north : ndarray
        Landing offset, m (broadcast shape of the inputs).

    Examples
    --------
    >>> east, north = simulate_drop(100.0, 31.8584, g=9.7947, omega=7.27221e-5)
    >>> round(float(east), 4), bool(north < 0)
    (0.0186, True)
    """
    h = _positive(height, "height")
    lat = as_float_array(latitude_deg, "latitude_deg")
    latitude_cos_sin(lat)
    g = _positive(g, "g")
    w = check_omega(omega)
    h, lat, g, w = np.broadcast_arrays(h, lat, g, w)
    east = np.empty(h.shape)
    north = np.empty(h.shape)
    zero = np.zeros(3)
    for idx in np.ndindex(h.shape):
        _, y = _land(np.array([0.0, 0.0, h[idx]]), zero, lat[idx], g[idx], w[idx])
        east[idx], north[idx] = y[0], y[1]
    return east, north


def _muzzle_velocity(speed, elevation_deg, azimuth_deg):
    e = np.deg2rad(elevation_deg)
    a = np.deg2rad(azimuth_deg)
    return np.stack([speed * np.cos(e) * np.cos(a), speed * np.cos(e) * np.sin(a), speed * np.sin(e)], axis=-1)


def _shell_inputs(speed, elevation_deg, azimuth_deg, latitude_deg, g, omega):
    speed = _positive(speed, "speed")
    el = as_float_array(elevation_deg, "elevation_deg")
    if np.any((el <= 0) | (el > 90)):
        raise ValueError("elevation_deg must lie in (0, 90] degrees")
    az = as_float_array(azimuth_deg, "azimuth_deg")
    lat = as_float_array(latitude_deg, "latitude_deg")
    latitude_cos_sin(lat)
    g = _positive(g, "g")
    w = check_omega(omega)
    return np.broadcast_arrays(speed, el, az, lat, g, w)


#: Smallest turn ω T (rad) of the Earth during a shell's flight T = 2 v sin(e)/g that
#: :func:`shell_deviation` integrates: the deviation is about ω T times the range, and it is the
#: difference of two ranges that carry a round-off of ~1e-16 of the range, so below 1e-10 rad it
#: would keep fewer than six digits (and a 1e-161 m/s shell flies a subnormal 1e-323 m).
SHORTEST_TURN = 1e-10


def _refuse_short_flight(speed, el, g, w):
    """ValueError naming ``speed`` (and g, omega) when the Earth turns less than :data:`SHORTEST_TURN` during a flight."""
    with np.errstate(under="ignore"):
        turn = w * (2.0 * speed * np.sin(np.deg2rad(el)) / g)
    short = (w > 0) & (turn < SHORTEST_TURN)
    if np.any(short):
        first = np.argmax(short)
        raise ValueError(
            f"speed, elevation_deg, g and omega are out of range: the Earth turns {turn.flat[first]:.3g} rad, less than "
            f"{SHORTEST_TURN:g} rad, during the flight of a speed = {speed.flat[first]:.3g} m/s shell, so the deviation is below the round-off of the integrated range; "
            "use shell_deviation_estimate (exact to relative order omega*T) for so short a flight"
        )


def shell_deviation(speed, elevation_deg, azimuth_deg, latitude_deg, g=9.80665, omega=OMEGA_EARTH):
    """Deviation of a shell's impact point caused by the Earth's rotation (Theory §8.3 exercise), simulated.

    The shell leaves the ground at the origin with the given muzzle speed,
    elevation and azimuth (no air drag), and is integrated under the full
    rotating-frame equations of the module note until it returns to z = 0.
    The deviation is the impact point minus the impact point without rotation,
    (v² sin 2e / g) along the azimuth.

    Parameters
    ----------
    speed : array_like
        Muzzle speed relative to the ground, m/s. Flights during which the
        Earth turns less than ``SHORTEST_TURN`` = 1e-10 rad (below ~7e-6 m/s
        on Earth) are refused: use :func:`shell_deviation_estimate` there.
    elevation_deg : array_like
        Elevation above the horizon, degrees, in (0, 90].
    azimuth_deg : array_like
        Firing direction, degrees counter-clockwise from east (the kreisel
        convention, as ``swing_azimuth``; north is 90).
    latitude_deg : array_like
        Latitude, degrees.
    g, omega : array_like
        Effective gravity, m/s², and rotation rate, rad/s.

    Returns
    -------
    east, north : ndarray
        Deviation, m.

    Examples
    --------
    A shell fired north at 45° in the northern hemisphere lands to the east:

    >>> east, north = shell_deviation(500.0, 45.0, 90.0, 45.0)
    >>> bool(east > 0)
    True
    """
    speed, el, az, lat, g, w = _shell_inputs(speed, elevation_deg, azimuth_deg, latitude_deg, g, omega)
    _refuse_short_flight(speed, el, g, w)
    v0 = _muzzle_velocity(speed, el, az)
    east = np.empty(speed.shape)
    north = np.empty(speed.shape)
    with out_of_range("speed, g and omega", "the range of the shell") as guard:
        for idx in np.ndindex(speed.shape):
            _, y = _land(np.zeros(3), v0[idx], lat[idx], g[idx], w[idx])
            reach = speed[idx] * (speed[idx] * np.sin(2.0 * np.deg2rad(el[idx])) / g[idx])
            direction = np.deg2rad(az[idx])
            east[idx] = y[0] - reach * np.cos(direction)
            north[idx] = y[1] - reach * np.sin(direction)
        return guard.check(east, north)


def shell_deviation_estimate(speed, elevation_deg, azimuth_deg, latitude_deg, g=9.80665, omega=OMEGA_EARTH):
    """First-order (in ω) estimate of :func:`shell_deviation`.

    With T = 2 v_z/g the flight time without rotation, the Coriolis
    displacement is r₁(T) = -ω×v₀ T² - ⅓ ω×g T³; its vertical part changes the
    flight time by r₁,z/v_z, which moves the impact along the horizontal
    velocity:  Δ = r₁,h(T) + (r₁,z(T)/v_z) v₀,h. The neglected terms are of
    relative order ωT.

    Parameters and returns are those of :func:`shell_deviation`.

    Examples
    --------
    >>> east, north = shell_deviation_estimate(500.0, 45.0, 90.0, 45.0)
    >>> round(float(east), 3)
    63.187
    """
    speed, el, az, lat, g, w = _shell_inputs(speed, elevation_deg, azimuth_deg, latitude_deg, g, omega)
    v0 = _muzzle_velocity(speed, el, az)
    omega_vec = angular_velocity_enu(lat, w)
    gravity = np.stack([np.zeros_like(g), np.zeros_like(g), -g], axis=-1)
    T = (2.0 * v0[..., 2] / g)[..., None]
    with out_of_range("speed, g and omega", "the deviation") as guard:
        # one factor of T at a time: T³ alone overflows before the deviation does
        r1 = -(np.cross(omega_vec, v0) * T) * T - (np.cross(omega_vec, gravity) * T) * T * T / 3.0
        shift = r1[..., 2:3] / v0[..., 2:3]
        dev = guard.check(r1[..., :2] + shift * v0[..., :2])
    return dev[..., 0], dev[..., 1]
