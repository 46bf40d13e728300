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

from .._compiled import cached, dop853 as _dop853, generic, inlined
from .._validation import as_float_array, out_of_range, positive_array
from ..frames.particle import builtin_parameters, builtin_rhs
from .enu import OMEGA_EARTH, angular_velocity_enu, check_omega, latitude_cos_sin

__all__ = [
    "eastward_deflection",
    "simulate_drop",
    "shell_deviation",
    "shell_deviation_estimate",
]




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
    h = positive_array(height, "height", allow_zero=True)
    c, _ = latitude_cos_sin(latitude_deg)
    g = positive_array(g, "g")
    w = check_omega(omega)
    with out_of_range("height, g and omega", "the deflection") as guard:
        # h √(2h/g), not √(2h³/g): h³ overflows from 1e103 m where the deflection is still representable
        return guard.check((2.0 / 3.0) * w * c * (h * np.sqrt(2.0 * h / g)))


@generic
def _landing(height, marks, t, y, t_new, y_new):
    """The crossing hook of a flight (:func:`kreisel._compiled.dop853.advance`) down to ``height(t, y, p) = 0``.

    ``marks = (p, peak, ends)``: the run stops before the step that comes
    down through zero, whose ends ``(t, t_new)`` go to ``ends``; ``peak``
    receives the largest magnitude of each component over the other steps.
    """
    p, peak, ends = marks
    if height(t_new, y_new, p) <= 0.0:
        if height(t, y, p) > 0.0:
            ends[0], ends[1] = t, t_new
            return _dop853.STOP
        # a launch from the ground that is back below it after one step: shorten
        return _dop853.RETRY
    for i in range(y_new.size):
        peak[i] = max(peak[i], abs(y_new[i]))
    return _dop853.ONWARD


@generic
def _fly(rhs, crossing, p, y0, t_out, rtol, atol, max_step, tables, peak):
    """Adaptive DOP853 steps of ``rhs`` from ``(0, y0)`` that stop exactly at ``t_out`` on the way, to the landing.

    Returns ``(status, runs, work, ends)``: :data:`kreisel._compiled.dop853.STOPPED`
    and, when so, the run at the start ``ends[0]`` of the step across the
    ground, its end ``ends[1]`` in ``work``; ``crossing`` is the hook
    :func:`_landing` of the height.
    """
    n = y0.size
    runs = _dop853.new_runs(y0.reshape((1, n)))
    work = _dop853.new_work(n)
    ends = np.zeros(2)
    status = _dop853.advance(rhs, p, crossing, _dop853.no_record, (p, peak, ends), t_out, runs, 0, work, rtol, atol,
                             max_step, tables, np.empty((t_out.size, n)), True, 2**62, -1, True)
    return status, runs, work, ends


@cached
def _particle_height(t, y, p):
    return y[2]


@inlined
def _particle_landing(marks, t, y, t_new, y_new):
    return _landing(_particle_height, marks, t, y, t_new, y_new)


@cached
def _land_kernel(p, y0, rtol, atol, max_step, tables):
    """Integrate :func:`builtin_rhs` from t = 0 until the height ``y[2]`` comes down through zero.

    Returns ``(status, t, y)`` there. The crossing step is found by the adaptive
    loop, then its length is solved for by Newton's method on a single DOP853
    step (dz/dτ = ``y[5]``), so the landing state has the integrator's full order.
    """
    t_out = np.array([0.0, np.inf])
    status, runs, work, ends = _fly(builtin_rhs, _particle_landing, p, y0, t_out, rtol, atol, max_step, tables,
                                    np.zeros(y0.size))
    if status != _dop853.STOPPED:
        return status, 0.0, y0
    y, y_new = runs.y[0], work.y_new
    t, h_taken = ends[0], ends[1] - ends[0]
    # safeguarded Newton (bisection fallback) on the length of the last step
    lo, hi = 0.0, h_taken
    tau = h_taken * y[2] / (y[2] - y_new[2])
    converged = False
    for iteration in range(101):
        runs.h[0] = tau
        _dop853.step_exactly(builtin_rhs, p, t_out, runs, 0, work, tables)
        if converged or iteration == 100:
            break
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
    h = positive_array(height, "height")
    lat = as_float_array(latitude_deg, "latitude_deg")
    latitude_cos_sin(lat)
    g = positive_array(g, "g")
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
    # cos e as sin(90° - e): exactly 0 for a vertical shot, not 6e-17
    cos_e, sin_e = np.sin(np.deg2rad(90.0 - elevation_deg)), np.sin(np.deg2rad(elevation_deg))
    a = np.deg2rad(azimuth_deg)
    return np.stack([speed * cos_e * np.cos(a), speed * cos_e * np.sin(a), speed * sin_e], axis=-1)


def _shell_inputs(speed, elevation_deg, azimuth_deg, latitude_deg, g, omega):
    speed = positive_array(speed, "speed")
    el = as_float_array(elevation_deg, "elevation_deg")
    if np.any((el <= 0) | (el > 90)):
        raise ValueError("elevation_deg must lie in (0, 90] degrees")
    az = as_float_array(azimuth_deg, "azimuth_deg")
    lat = as_float_array(latitude_deg, "latitude_deg")
    latitude_cos_sin(lat)
    g = positive_array(g, "g")
    w = check_omega(omega)
    return np.broadcast_arrays(speed, el, az, lat, g, w)


@cached
def _deviation_rhs(t, y, p, out, offset):
    """Scaled deviation from the shell's path without rotation: u = (r - r0)/(L W), y = (u, u').

    Lengths in L = v²/g, times in v/g; r0 = d t - ẑ t²/2 is the path without rotation
    (unit muzzle direction d = ``p[0:3]``), n = ``p[3:6]`` = (0, cos λ, sin λ) and W = ``p[6]``
    = ω v/g. Subtracting r0'' = -ẑ from the equation of the module note and dividing by W:
    u'' = -2 n×(r0' + W u') - W n×(n×(r0 + W u)), whose terms are all of order one, so u
    keeps its relative accuracy however small W is, and W = 0 is exactly no deviation.
    """
    c, s, w = p[4], p[5], p[6]
    ax = p[0] + w * y[3]
    ay = p[1] + w * y[4]
    az = p[2] - t + w * y[5]
    bx = p[0] * t + w * y[0]
    by = p[1] * t + w * y[1]
    bz = t * (p[2] - 0.5 * t) + w * y[2]
    # n×b with n = (0, c, s), then n×(n×b)
    mx, my, mz = c * bz - s * by, s * bx, -c * bx
    for i in range(3):
        out[offset + i] = y[3 + i]
    out[offset + 3] = -2.0 * (c * az - s * ay) - w * (c * mz - s * my)
    out[offset + 4] = -2.0 * (s * ax) - w * (s * mx)
    out[offset + 5] = 2.0 * (c * ax) + w * (c * mx)


@cached
def _scaled_height(t, uz, s, w):
    """Height z/L of the shell at scaled time t: z0(t) + W u_z, z0 = t (sin e - t/2) to relative round-off.

    Past half the flight T0 = 2 sin e, z0 = -(t - T0)(sin e + (t - T0)/2): t - T0 is exact there
    (Sterbenz), so z0 does not carry the round-off of the maximum height near the landing.
    """
    if t >= s:
        late = t - 2.0 * s
        return -late * (s + 0.5 * late) + w * uz
    return t * (s - 0.5 * t) + w * uz


@cached
def _deviation_height(t, y, p):
    return _scaled_height(t, y[2], p[2], p[6])


@inlined
def _shell_landing(marks, t, y, t_new, y_new):
    return _landing(_deviation_height, marks, t, y, t_new, y_new)


@cached
def _deviation_kernel(p, rtol, atol, max_step, tables, peak):
    """Integrate :func:`_deviation_rhs` to the landing; returns ``(status, sigma, u_x, u_y)`` there.

    ``peak`` receives the largest magnitude of each state component over the accepted steps.

    The landing time is T0 + W σ (scaled units), and the deviation is L W (d_h σ + u_h). The
    adaptive loop stops exactly at T0 on the way, so T0 is a step boundary; the landing is then
    solved for (safeguarded Newton on σ, one DOP853 step from an anchor) from the end of the
    crossing step nearest T0: σ = (anchor - T0)/W + τ/W with τ of the same sign, so σ keeps its
    relative accuracy when the landing is within round-off of T0 (τ and W σ may even underflow).
    """
    n = 6
    s, w = p[2], p[6]
    flight = 2.0 * s
    t_out = np.array([0.0, flight, np.inf])
    status, runs, work, ends = _fly(_deviation_rhs, _shell_landing, p, np.zeros(n), t_out, rtol, atol, max_step,
                                    tables, peak)
    if status != _dop853.STOPPED:
        return status, 0.0, 0.0, 0.0
    t, t_new = ends[0], ends[1]
    y, y_new, k = runs.y[0], work.y_new, work.k
    # the steps of Newton's method start from the anchor, the end of the crossing step nearest T0 (T0 is one of
    # its ends or outside it)
    late_anchor = t_new <= flight
    t_anchor = t_new if late_anchor else t
    for i in range(n):
        y[i] = y_new[i] if late_anchor else y[i]
        runs.f[0, i] = k[_dop853.N_STAGES * n + i] if late_anchor else k[i]
    runs.t[0] = t_anchor
    lo, hi = t - flight, t_new - flight
    offset = t_anchor - flight
    sigma = offset / w
    uz, vz = y[2], y[5]
    ux, uy = y[0], y[1]
    for _ in range(100):
        late = w * sigma
        g = uz - sigma * (s + 0.5 * late)
        if g > 0.0:
            lo = max(lo, late)
        else:
            hi = min(hi, late)
        slope_g = w * vz - (s + late)
        new_sigma = sigma - g / slope_g if slope_g != 0.0 else np.nan
        if not (lo <= w * new_sigma <= hi):
            new_sigma = 0.5 * (lo + hi) / w
        converged = g == 0.0 or abs(new_sigma - sigma) <= 1e-15 * abs(new_sigma)
        sigma = new_sigma
        runs.h[0] = w * sigma - offset
        if runs.h[0] == 0.0:
            ux, uy, uz, vz = y[0], y[1], y[2], y[5]
        else:
            _dop853.step_exactly(_deviation_rhs, p, t_out, runs, 0, work, tables)
            ux, uy, uz, vz = y_new[0], y_new[1], y_new[2], y_new[5]
        if converged:
            break
    return _dop853.OK, sigma, ux, uy


#: Smallest turn ω T (rad) of the Earth during a shell's flight T = 2 v sin(e)/g that
#: :func:`shell_deviation` integrates: below it the scaled rotation rate of ``_deviation_rhs``
#: nears the subnormal doubles and the deviation's parts of second order in ω T underflow.
SHORTEST_TURN = 1e-300


def _refuse_short_flight(speed, el, g, w):
    """ValueError naming ``speed`` (and g, omega) when the Earth turns less than :data:`SHORTEST_TURN` during a flight."""
    with np.errstate(under="ignore"):
        turn = w * (2.0 * speed * np.sin(np.deg2rad(el)) / g)
    short = (w > 0) & (turn < SHORTEST_TURN)
    if np.any(short):
        first = np.argmax(short)
        raise ValueError(
            f"speed, elevation_deg, g and omega are out of range: the Earth turns {turn.flat[first]:.3g} rad, less than "
            f"{SHORTEST_TURN:g} rad, during the flight of a speed = {speed.flat[first]:.3g} m/s shell, so the "
            "deviation's terms of second order in that turn fall below the smallest double; "
            "use shell_deviation_estimate (exact to relative order omega*T) for so short a flight"
        )


def _small_turn_deviation(d, cos_lat, sin_lat, rate, tables):
    """The deviation over L W (L = v²/g, W = ω v/g) when the Earth turns less than a radian, from :func:`_deviation_kernel`."""
    p = np.array([d[0], d[1], d[2], 0.0, cos_lat, sin_lat, rate])
    # Components of u differ in size by powers of W (some vanish at first order) and cross zero:
    # a first run with a tolerance on the size of the first-order ones (about sin² e) measures
    # each component's largest size, and the second holds every component to 1e-16 of its own
    # (not to below the smallest normal double: the state starts at exactly 0).
    peak = np.zeros(6)
    atol = np.full(6, 1e-16 * d[2] * d[2])
    for _ in range(2):
        status, sigma, ux, uy = _deviation_kernel(p, 1e-13, atol, 0.25 * d[2], tables, peak)
        _dop853.check_status(status)
        atol = np.maximum(1e-16 * peak, np.finfo(float).tiny)
    return d[0] * sigma + ux, d[1] * sigma + uy


def _large_turn_deviation(speed, d, lat, g, w):
    """The deviation by integrating the whole path: the Earth turns a radian or more, the deviation is of the range's size."""
    _, y = _land(np.zeros(3), speed * d, lat, g, w)
    reach = speed * (speed * 2.0 * d[2] / g)
    return y[0] - reach * d[0], y[1] - reach * d[1]


def shell_deviation(speed, elevation_deg, azimuth_deg, latitude_deg, g=9.80665, omega=OMEGA_EARTH):
    """Deviation of a shell's impact point caused by the Earth's rotation (Theory §8.3 exercise), simulated.

    The shell leaves the ground at the origin with the given muzzle speed,
    elevation and azimuth (no air drag) and follows the full rotating-frame
    equations of the module note until it returns to z = 0. The deviation is
    the impact point minus the impact point without rotation, (v² sin 2e / g)
    along the azimuth.

    While the Earth turns less than half a radian during the flight, the
    deviation is integrated directly, as the departure from the parabola
    without rotation, in units of the first-order deviation ω v³/g² (see
    ``_deviation_rhs``): it is accurate to about 1e-13 of its own size however
    small it is against the range (the difference of two integrated ranges
    would keep only 1e-16 of the range), and ``omega = 0`` gives exactly 0.
    A component that is much smaller than the deviation (the north one of a
    shot due north, of third order in ω at λ = e = 45°) is accurate to 1e-13
    of the deviation, not of itself. For longer flights the whole path is
    integrated and the deviation is of the range's own size.

    Parameters
    ----------
    speed : array_like
        Muzzle speed relative to the ground, m/s. Flights during which the
        Earth turns less than ``SHORTEST_TURN`` = 1e-300 rad are refused:
        the deviation's terms of second order in the turn would fall below
        the smallest double.
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
    >>> round(float(east), 6)
    63.18795
    >>> shell_deviation(500.0, 45.0, 90.0, 45.0, omega=0.0)
    (array(0.), array(0.))
    """
    speed, el, az, lat, g, w = _shell_inputs(speed, elevation_deg, azimuth_deg, latitude_deg, g, omega)
    _refuse_short_flight(speed, el, g, w)
    d = _muzzle_velocity(1.0, el, az)
    cos_lat, sin_lat = latitude_cos_sin(lat)
    east = np.zeros(speed.shape)
    north = np.zeros(speed.shape)
    tables = _dop853.tableau()
    with out_of_range("speed, g and omega", "the range of the shell") as guard:
        for idx in np.ndindex(speed.shape):
            if w[idx] == 0.0:
                continue  # no rotation, no deviation: exactly zero
            rate = w[idx] * (speed[idx] / g[idx])  # W = ω v/g, the turn per unit of scaled time
            if rate * d[idx][2] < 0.5:
                east[idx], north[idx] = _small_turn_deviation(d[idx], cos_lat[idx], sin_lat[idx], rate, tables)
                east[idx] *= speed[idx] * (speed[idx] / g[idx]) * rate
                north[idx] *= speed[idx] * (speed[idx] / g[idx]) * rate
            else:
                east[idx], north[idx] = _large_turn_deviation(speed[idx], d[idx], lat[idx], g[idx], w[idx])
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
