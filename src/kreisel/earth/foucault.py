"""The Foucault pendulum (Theory §8.3): analytic period and a full spherical-pendulum simulation.

The simulated pendulum is the exact spherical pendulum in the rotating ENU
frame (no small-angle or small-ω approximation): pivot at (0, 0, l), bob at
r = (0, 0, l) + l u with |u| = 1, under r̈ = -g Up - ω×(ω×r) - 2 ω×ṙ + tension
(``g`` is the effective gravity at the bob's rest point, see
:mod:`kreisel.earth.falling`). The tension is eliminated:

    ü = (f - (f·u) u)/l - |u̇|² u,   f = -g Up - ω×(ω×r) - 2 l ω×u̇.
"""

from __future__ import annotations

import math

import numpy as np

from .._compiled import cached, dop853 as _dop853, inlined
from .._compiled.chunks import check_max_steps, run_resumable
from .._validation import as_float, check_allocation, positive_float, refuse_long_turn
from .enu import OMEGA_EARTH, angular_velocity_enu, check_omega, latitude_cos_sin

__all__ = ["FoucaultSwing", "foucault_period", "foucault_precession_rate", "foucault_pendulum"]


def foucault_precession_rate(latitude_deg, omega=OMEGA_EARTH):
    """Rate at which the swing plane turns, counter-clockwise positive: -ω sin λ (rad/s).

    Negative (clockwise seen from above) in the northern hemisphere, positive
    in the southern, zero at the equator (Theory §8.3).

    Examples
    --------
    >>> float(foucault_precession_rate(90.0, omega=1.0))
    -1.0
    """
    _, s = latitude_cos_sin(latitude_deg)
    return -check_omega(omega) * s


def foucault_period(latitude_deg, omega=OMEGA_EARTH):
    """Time for the swing plane to turn once, 2π/(ω |sin λ|), seconds (Theory §8.3).

    One sidereal day at the poles (with the sidereal ``omega``). At the
    equator the swing plane does not turn at all, so it has no period: a
    latitude of 0, or one so close to 0 that the period would exceed the
    largest float (about 1e-300 degrees), raises ``ValueError`` saying so
    rather than returning ``inf`` or overflowing. Use
    :func:`foucault_precession_rate`, which is 0 at the equator, for tables
    that include it.

    Examples
    --------
    The chapter's Hefei value, 45 h 28 min:

    >>> T = float(foucault_period(31.8584, omega=7.27221e-5))
    >>> int(T // 3600), int(T % 3600 // 60)
    (45, 28)
    >>> foucault_period([0.0, 45.0])
    Traceback (most recent call last):
        ...
    ValueError: latitude_deg: at the equator (latitude 0) the swing plane of a Foucault pendulum does not turn, so it has no period; foucault_precession_rate is 0 there
    """
    rate = np.abs(foucault_precession_rate(latitude_deg, omega))
    smallest = 2.0 * np.pi / np.finfo(float).max   # below this rate the period overflows
    still = rate <= smallest
    if np.any(still):
        latitude = np.asarray(latitude_deg, dtype=float)[still] if np.ndim(latitude_deg) else latitude_deg
        shown = float(np.ravel(latitude)[0]) if np.ndim(latitude) else float(latitude)
        if shown == 0.0:
            raise ValueError("latitude_deg: at the equator (latitude 0) the swing plane of a Foucault pendulum "
                             "does not turn, so it has no period; foucault_precession_rate is 0 there")
        if np.all(np.abs(check_omega(omega)) <= smallest):
            raise ValueError(f"omega = {float(np.ravel(omega)[0]):g} rad/s: the swing plane turns so slowly that "
                             f"its period exceeds the largest float ({np.finfo(float).max:.1e} s); "
                             "foucault_precession_rate gives the rate")
        raise ValueError(f"latitude_deg: at latitude {shown:g}°, this close to the equator, the swing plane turns "
                         f"so slowly that its period exceeds the largest float ({np.finfo(float).max:.1e} s); "
                         "foucault_precession_rate gives the rate")
    return (2.0 * np.pi / rate)[()]


@cached
def pendulum_rhs(t, y, p, out, offset):
    """Spherical pendulum in a frame turning at constant ω: y = (u, u̇), p = (ω, g, l).

    The right-hand side of :mod:`kreisel._compiled.dop853`: dy/dt into ``out[offset:offset + 6]``.
    """
    wx, wy, wz, g, length = p[0], p[1], p[2], p[3], p[4]
    ux, uy, uz, vx, vy, vz = y[0], y[1], y[2], y[3], y[4], y[5]
    rx, ry, rz = length * ux, length * uy, length * (1.0 + uz)
    # ω×r and ω×(ω×r)
    ax, ay, az = wy * rz - wz * ry, wz * rx - wx * rz, wx * ry - wy * rx
    cx, cy, cz = wy * az - wz * ay, wz * ax - wx * az, wx * ay - wy * ax
    # Coriolis with ṙ = l u̇
    kx, ky, kz = wy * vz - wz * vy, wz * vx - wx * vz, wx * vy - wy * vx
    fx = -cx - 2.0 * length * kx
    fy = -cy - 2.0 * length * ky
    fz = -g - cz - 2.0 * length * kz
    fu = fx * ux + fy * uy + fz * uz
    vv = vx * vx + vy * vy + vz * vz
    out[offset], out[offset + 1], out[offset + 2] = vx, vy, vz
    out[offset + 3] = (fx - fu * ux) / length - vv * ux
    out[offset + 4] = (fy - fu * uy) / length - vv * uy
    out[offset + 5] = (fz - fu * uz) / length - vv * uz


@inlined
def _swing_maximum(record, t, y, t_new, y_new):
    """The crossing hook of :func:`_swing`: a maximum of the excursion, where s = u_h·u̇_h falls through zero."""
    s_old = y[0] * y[3] + y[1] * y[4]
    s_new = y_new[0] * y_new[3] + y_new[1] * y_new[4]
    return _dop853.LOCATE if s_old > 0.0 and s_new <= 0.0 else _dop853.ONWARD


@inlined
def _record_maximum(record, n, t, y):
    """The record hook of :func:`_swing`: (time, azimuth, tilt) of maximum ``n`` into column ``n`` of ``record``."""
    if n == record.shape[1]:
        return False
    record[0, n] = t
    record[1, n] = math.atan2(y[1], y[0])
    record[2, n] = math.atan2(math.hypot(y[0], y[1]), -y[2])
    return True


@cached
def _swing(p, runs, duration, rtol, atol, max_step, tables, record, budget):
    """Integrate to ``duration`` recording each maximum of the horizontal excursion, at most ``budget`` steps.

    Each maximum is located inside its step by bisection on the integrator's
    7th-order dense output, and its (time, azimuth, tilt) is written to
    column ``runs.found[0]`` of ``record (3, capacity)``. Returns a status of
    :func:`kreisel._compiled.dop853.advance`: ``PAUSED`` when the budget ran
    out or ``record`` is full.
    """
    t_out = np.array([0.0, duration])
    return _dop853.advance(pendulum_rhs, p, _swing_maximum, _record_maximum, record, t_out, runs, 0,
                           _dop853.new_work(runs.y.shape[1]), rtol, atol, max_step, tables, np.empty((2, 6)), False,
                           budget, -1, True)


class FoucaultSwing:
    """The swing plane of a simulated Foucault pendulum (see :func:`foucault_pendulum`).

    Attributes
    ----------
    t : (n,) ndarray
        Times of the maximal horizontal excursions (t[0] = 0, the release), s.
    swing_azimuth : (n,) ndarray
        Azimuth of the swing plane at those times, rad, counter-clockwise from
        east, unwrapped (the plane is a line, so values are continuous modulo π).
    tilt : (n,) ndarray
        Angle of the string from the vertical at each excursion, rad.
    precession_rate : float
        Least-squares slope of ``swing_azimuth`` against ``t``, rad/s
        (counter-clockwise positive).
    jacobi : (2,) ndarray
        Jacobi integral per unit mass ½ṙ² - ½(ω×r)² + g z at release and at the
        end, J/kg (conserved by the exact motion).
    final_state : (6,) ndarray
        (u, u̇) at the end of the run.

    Examples
    --------
    At latitude 30° on a fast planet (ω = 0.01 rad/s) the measured swing plane
    turns clockwise at ω sin λ (:func:`foucault_precession_rate`), and the
    Jacobi integral is kept by the integrator:

    >>> import numpy as np
    >>> swing = foucault_pendulum(1.0, 30.0, 100.0, 0.05, omega=0.01)
    >>> round(swing.precession_rate / float(foucault_precession_rate(30.0, omega=0.01)), 2)
    1.0
    >>> float(swing.t[0]), bool(np.all(np.diff(swing.t) > 0))
    (0.0, True)
    >>> bool(abs(swing.jacobi[1] - swing.jacobi[0]) < 1e-8)
    True
    """

    def __init__(self, t, swing_azimuth, tilt, jacobi, final_state):
        self.t = t
        self.swing_azimuth = swing_azimuth
        self.tilt = tilt
        self.jacobi = jacobi
        self.final_state = final_state
        self.precession_rate = float(np.polyfit(t, swing_azimuth, 1)[0])

    def __repr__(self):
        return f"FoucaultSwing(n={self.t.size}, precession_rate={self.precession_rate:.6g} rad/s)"


def _jacobi(y, p):
    w, g, length = p[:3], p[3], p[4]
    r = length * (y[:3] + np.array([0.0, 0.0, 1.0]))
    v = length * y[3:]
    wr = np.cross(w, r)
    return 0.5 * v @ v - 0.5 * wr @ wr + g * r[2]


def foucault_pendulum(
    length,
    latitude_deg,
    duration,
    amplitude,
    *,
    azimuth_deg=0.0,
    g=9.80665,
    omega=OMEGA_EARTH,
    rtol=1e-10,
    atol=1e-12,
    max_steps=None,
):
    """Simulate a Foucault pendulum and measure its swing plane (Theory §8.3).

    The exact spherical pendulum in the rotating ENU frame (module note) is
    released from rest relative to the Earth and integrated by the compiled
    adaptive DOP853 integrator. At each maximal horizontal excursion the azimuth of
    the bob is recorded; the swing plane's precession (clockwise at ω sin λ in
    the north) is then a measurement, not an input. Finite amplitude adds
    Airy's precession, of relative size about (3/8) amplitude².

    Parameters
    ----------
    length : float
        String length l, m.
    latitude_deg : float
        Latitude, degrees.
    duration : float
        Simulated time, s.
    amplitude : float
        Initial angle of the string from the vertical, rad, in (0, π/2).
    azimuth_deg : float
        Initial swing direction, degrees counter-clockwise from east.
    g : float
        Effective gravity at the bob's rest point, m/s².
    omega : float
        Earth's rotation rate, rad/s (a larger value shortens experiments).
    rtol, atol : float
        Integrator tolerances.
    max_steps : int, optional
        Step budget, as in :func:`kreisel.frames.simulate_particle` (Ctrl-C stops any
        run with a ``KeyboardInterrupt``).

    Returns
    -------
    FoucaultSwing
        The sampled swing of the bob.

    Raises
    ------
    ValueError
        Bad arguments; an amplitude below 1e-150 rad (its squared excursions
        underflow); ``omega`` not below the pendulum's own frequency √(g/l)
        (the hanging bob is then not a stable rest state: e.g. a 1e300 m
        string, or ω = 1e300 rad/s); a pendulum that swings through more than 1e15 rad of
        phase in ``duration`` (its steps would be lost in the rounding of t);
        a run that ends before the first excursion after the release (less
        than about half a period), which leaves no swing plane to measure.

    Examples
    --------
    A 1 m pendulum at the North Pole of a fast planet (ω = 0.01 rad/s):

    >>> res = foucault_pendulum(1.0, 90.0, 200.0, 0.05, omega=0.01)
    >>> round(res.precession_rate / -0.01, 2)
    1.0
    """
    length = positive_float(length, "length")
    duration = positive_float(duration, "duration")
    amplitude = as_float(amplitude, "amplitude")
    if not 0 < amplitude < np.pi / 2:
        raise ValueError(f"amplitude must be an angle in (0, pi/2) rad, got {amplitude}")
    if amplitude < 1e-150:
        # the swing is found from squared excursions, ~amplitude², which leave the normal doubles below 1e-154
        raise ValueError(f"amplitude = {amplitude:g} rad is out of range: below 1e-150 rad the squared excursions "
                         "that locate the swing plane underflow double precision")
    g = positive_float(g, "g")
    omega = float(check_omega(as_float(omega, "omega")))
    natural = math.sqrt(g) / math.sqrt(length)  # √(g/l) without overflowing g/l
    if not omega < natural:
        # the centrifugal pull ω² × displacement then beats gravity's g/l × displacement across ω: the
        # hanging bob is not a stable rest state and there is no swing plane to follow
        raise ValueError(f"omega and length: the frame turns at {omega:.3g} rad/s, not slower than the pendulum's "
                         f"own frequency √(g/l) = {natural:.3g} rad/s of a {length:g} m pendulum, so the hanging bob "
                         "is not a stable rest state (ω²·l >= g) and there is no swing plane; a Foucault "
                         "pendulum needs ω much below √(g/l)")
    latitude = as_float(latitude_deg, "latitude_deg")
    azimuth = np.deg2rad(as_float(azimuth_deg, "azimuth_deg"))
    p = np.concatenate([angular_velocity_enu(latitude, omega), [g, length]])
    y0 = np.array(
        [np.sin(amplitude) * np.cos(azimuth), np.sin(amplitude) * np.sin(azimuth), -np.cos(amplitude), 0.0, 0.0, 0.0]
    )
    period = 2.0 * np.pi * np.sqrt(length / g)
    phase = 2.0 * np.pi * (duration / period)
    refuse_long_turn(phase, "length and duration", f"a {length:g} m pendulum swinging {duration:g} s "
                     f"(period {period:.3g} s) goes through a phase of", "resolves its steps")
    # several steps per swing keep at most one excursion maximum inside a step
    max_step = period / 16.0
    max_steps = check_max_steps(max_steps)
    tables = _dop853.tableau()
    atol = np.full(y0.size, float(atol))
    rtol = float(rtol)
    record = [np.empty((3, 64))]

    def advance(runs, budget):
        # two maxima a period, at least 16 steps a period: room for all maxima of the chunk
        count = int(runs.found[0])
        needed = count + budget // 8 + 2
        if needed > record[0].shape[1]:
            size = max(needed, 2 * record[0].shape[1])
            check_allocation(3 * 8.0 * size, f"the record of {size} swing maxima")
            grown = np.empty((3, size))
            grown[:, :count] = record[0][:, :count]
            record[0] = grown
        return _swing(p, runs, duration, rtol, atol, max_step, tables, record[0], budget)

    runs = _dop853.new_runs(y0[None])
    _dop853.check_status(run_resumable(advance, runs, duration, max_steps, 2**14, _dop853.PAUSED))
    count = int(runs.found[0])
    if count == 0:
        raise ValueError(f"duration and length: in {duration:g} s the bob of a {length:g} m pendulum (period "
                         f"{period:.3g} s) reached no excursion after its release, so there is no swing plane to "
                         "measure; simulate for more than half a period")
    times, az, tilt = record[0][:, :count]
    y_end = runs.y[0].copy()
    t = np.concatenate([[0.0], times[:count]])
    raw = np.concatenate([[azimuth], az[:count]])
    # the bob reaches opposite ends of the swing line in turn: unwrap modulo π
    swing = np.unwrap(2.0 * raw) / 2.0
    swing += azimuth - swing[0]
    tilt = np.concatenate([[amplitude], tilt[:count]])
    jacobi = np.array([_jacobi(y0, p), _jacobi(y_end, p)])
    return FoucaultSwing(t, swing, tilt, jacobi, y_end)
