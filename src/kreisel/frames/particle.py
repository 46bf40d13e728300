"""Simulation of a particle in a moving, rotating frame (Theory §8.1, Lagrange equations).

m r̈ = F - m a0 - 2m ω×ṙ - m ω×(ω×r) - m ω̇×r, integrated by the compiled
adaptive DOP853 of :mod:`kreisel._compiled.dop853`.
"""

from __future__ import annotations

import itertools

import numpy as np
from numba import njit, objmode

from .._compiled import cached, dop853 as _dop853
from .._compiled.chunks import check_max_steps, run_resumable
from .._norms import norm
from .._validation import as_float, as_float_array, checked_callable, positive_float, refuse_long_turn
from .relative import canonical_momentum, hamiltonian

__all__ = ["ParticleTrajectory", "simulate_particle"]

# parameter layout of the built-in model (constant or linearly growing ω)
_W, _WDOT, _A0, _FIELD, _SPRING, _T0, _NPAR = 0, 3, 6, 9, 12, 13, 14


@cached
def _cross_into(a, b, out):
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]


@cached
def relative_acceleration(r, v, w, wdot, a0, specific_force, out, offset):
    """``out[offset:offset + 3] = f - a0 - 2 ω×v - ω×(ω×r) - ω̇×r`` for a specific force ``f`` (force per mass)."""
    c = np.empty(3)
    wr = np.empty(3)
    wwr = np.empty(3)
    er = np.empty(3)
    _cross_into(w, v, c)
    _cross_into(w, r, wr)
    _cross_into(w, wr, wwr)
    _cross_into(wdot, r, er)
    for i in range(3):
        out[offset + i] = specific_force[i] - a0[i] - 2.0 * c[i] - wwr[i] - er[i]


@cached
def builtin_rhs(t, y, p, out, offset):
    """Particle with ω(t) = ω0 + ω̇ (t - t0), constant a0, uniform field and isotropic spring.

    The right-hand side of :mod:`kreisel._compiled.dop853`: dy/dt into ``out[offset:offset + 6]``.
    """
    w = np.empty(3)
    f = np.empty(3)
    dt = t - p[_T0]
    for i in range(3):
        w[i] = p[_W + i] + p[_WDOT + i] * dt
        f[i] = p[_FIELD + i] - p[_SPRING] * y[i]
        out[offset + i] = y[3 + i]
    relative_acceleration(y[:3], y[3:], w, p[_WDOT:_WDOT + 3], p[_A0:_A0 + 3], f, out, offset + 3)


def builtin_parameters(omega, omega_dot=(0.0, 0.0, 0.0), a0=(0.0, 0.0, 0.0), field=(0.0, 0.0, 0.0), spring=0.0,
                       t0=0.0):
    """The parameter vector ``p`` of :func:`builtin_rhs` (its layout stays private to this module).

    Parameters
    ----------
    omega, omega_dot : (3,) array_like
        ω(t0), rad/s, and the constant ω̇, rad/s².
    a0 : (3,) array_like
        Acceleration of the frame's origin, m/s².
    field : (3,) array_like
        Uniform specific force (gravity), m/s².
    spring : float
        Isotropic spring constant over mass, 1/s².
    t0 : float
        Time at which ω = ``omega``, s.

    Returns
    -------
    p : (14,) ndarray

    Examples
    --------
    >>> p = builtin_parameters([0.0, 0.0, 1.0], field=[0.0, 0.0, -9.8])
    >>> p.shape, float(p[2])
    ((14,), 1.0)
    """
    p = np.zeros(_NPAR)
    p[_W:_W + 3], p[_WDOT:_WDOT + 3], p[_A0:_A0 + 3], p[_FIELD:_FIELD + 3] = omega, omega_dot, a0, field
    p[_SPRING], p[_T0] = spring, t0
    return p


@cached
def _integrate_builtin(p, t, runs, rtol, atol, max_step, tables, out, budget):
    # a fixed right-hand side makes the whole compiled loop cacheable (see kreisel._compiled.dop853)
    return _dop853.advance(builtin_rhs, p, _dop853.no_crossing, _dop853.no_record, None, t, runs, 0,
                           _dop853.new_work(runs.y.shape[1]), rtol, atol, max_step, tables, out, True, budget, -1, True)


def _vector(value, name):
    v = as_float_array(value, name, tail=(3,))
    if v.shape != (3,):
        raise ValueError(f"{name} must be a single vector of shape (3,), got {v.shape}")
    return v


# the Python callables of the runs in progress, by key: object mode takes numbers, not Python objects
_MODELS = {}
_KEYS = itertools.count(1)


def _evaluate(key, t, y):
    return _MODELS[int(key)](t, y)


# object mode holds the GIL, so not the nogil flavour
@njit(cache=True)
def callback_rhs(t, y, p, out, offset):
    """Particle whose force, ω, ω̇ and a0 come from the Python model registered under the key ``p[0]``.

    The model returns (f/m, ω, ω̇, a0), twelve numbers. One compiled loop serves
    every callable (cached on disk): nothing is compiled per call, and a Ctrl-C
    is held back for one chunk at most.
    """
    with objmode(v="float64[:]"):
        v = _evaluate(p[0], t, y)
    for i in range(3):
        out[offset + i] = y[3 + i]
    relative_acceleration(y[:3], y[3:], v[3:6], v[6:9], v[9:12], v[0:3], out, offset + 3)


@cached
def _integrate_callbacks(p, t, runs, rtol, atol, max_step, tables, out, budget):
    return _dop853.advance(callback_rhs, p, _dop853.no_crossing, _dop853.no_record, None, t, runs, 0,
                           _dop853.new_work(runs.y.shape[1]), rtol, atol, max_step, tables, out, True, budget, -1, True)


def _model(omega, omega_dot, a0, force, mass, field, spring):
    """The Python model of :func:`callback_rhs`, each callable's output checked at every call."""
    def of_time(value, name):
        if callable(value):
            return checked_callable(value, name)
        const = _vector(value, name).copy()
        return lambda t: const

    w, wdot, acc = of_time(omega, "omega"), of_time(omega_dot, "omega_dot"), of_time(a0, "a0")
    user = checked_callable(force, "force") if force is not None else None

    def evaluate(t, y):
        r, v = y[:3].copy(), y[3:].copy()
        specific = field - spring * r
        if user is not None:
            specific = specific + user(t, r, v) / mass
        return np.concatenate([specific, w(t), wdot(t), acc(t)])

    return evaluate


class ParticleTrajectory:
    """Particle motion in a moving frame, sampled at times ``t``.

    Attributes
    ----------
    t : (n,) ndarray
    r, v : (n, 3) ndarray
        Position and relative velocity ṙ in moving-frame components.
    omega, a0 : (n, 3) ndarray
        Frame angular velocity and origin acceleration at each time.
    potential : (n,) ndarray or None
        Potential energy of the built-in fields (``gravity``, ``spring``);
        None when a callable ``force`` (whose potential is unknown) was given.
    mass : float

    Examples
    --------
    A mass on an isotropic spring (k/m = 4 s⁻²) observed from a frame turning at
    0.5 rad/s: the Coriolis force curls the orbit, and the Jacobi integral
    (:attr:`hamiltonian`) stays constant:

    >>> import numpy as np
    >>> tr = simulate_particle(np.linspace(0.0, 10.0, 201), [1, 0, 0], [0, 0.5, 0], [0, 0, 0.5], spring=4.0)
    >>> tr, tr.r.shape
    (ParticleTrajectory(n=201, t=[0, 10]), (201, 3))
    >>> H = tr.hamiltonian
    >>> float(H[0]), bool(np.ptp(H) < 1e-9)
    (2.0, True)
    """

    def __init__(self, t, r, v, omega, a0, potential, mass):
        self.t, self.r, self.v, self.omega, self.a0 = t, r, v, omega, a0
        self.potential = potential
        self.mass = mass

    def __len__(self):
        return self.t.size

    def __repr__(self):
        return f"ParticleTrajectory(n={self.t.size}, t=[{self.t[0]:g}, {self.t[-1]:g}])"

    @property
    def momentum(self):
        """Canonical momentum p = m (ṙ + ω×r) (Theory §8.1)."""
        return canonical_momentum(self.r, self.v, self.omega, self.mass)

    @property
    def hamiltonian(self):
        """H(r, p) of Theory §8.1 along the motion (the Jacobi integral for constant ω, a0)."""
        if self.potential is None:
            raise ValueError("the Hamiltonian needs the potential, unknown for a callable force")
        return hamiltonian(self.r, self.momentum, self.omega, self.a0, self.potential, self.mass)


def simulate_particle(
    t,
    r0,
    v0,
    omega,
    *,
    omega_dot=None,
    a0=(0.0, 0.0, 0.0),
    gravity=(0.0, 0.0, 0.0),
    spring=0.0,
    force=None,
    mass=1.0,
    rtol=1e-10,
    atol=1e-12,
    max_step=np.inf,
    max_steps=None,
):
    """Integrate a particle's motion observed in a moving, rotating frame (Theory §8.1).

    Solves m r̈ = F - m a0 - 2m ω×ṙ - m ω×(ω×r) - m ω̇×r (the Lagrange
    equations of :func:`kreisel.frames.lagrangian`) in the frame's components.

    Parameters
    ----------
    t : (n,) array_like
        Strictly increasing output times, s; ``t[0]`` is the initial time.
    r0, v0 : (3,) array_like
        Initial position and relative velocity ṙ in the frame, m and m/s.
    omega : (3,) array_like or callable
        Frame angular velocity in its own components, rad/s: a constant, or
        ``omega(t) -> (3,)``.
    omega_dot : (3,) array_like or callable, optional
        dω/dt. With a constant ``omega`` it defaults to zero and a constant value
        makes ω grow linearly, ω(t) = omega + omega_dot (t - t[0]). With a
        callable ``omega`` it is required (a callable or constant consistent
        with ``omega``).
    a0 : (3,) array_like or callable
        Acceleration of the frame origin, moving-frame components, m/s².
    gravity : (3,) array_like
        Uniform field (force per mass) in the frame, m/s²; potential -m g·r.
    spring : float
        Isotropic spring constant per mass k/m about the origin, 1/s²;
        potential ½ m k |r|².
    force : callable, optional
        Extra force ``force(t, r, v) -> (3,)`` in newtons, any Python
        callable. Callables (here and for ``omega``, ``omega_dot``, ``a0``)
        are called from the compiled integrator at each stage, a few µs a
        call, and their output is checked every time (real, finite, (3,)).
    mass : float
        kg.
    rtol, atol : float
        Tolerances of the adaptive Dormand–Prince 8(5,3) integrator.
    max_step : float
        Largest step, s.
    max_steps : int, optional
        Step budget (default ``10**10``): the run stops with ``RuntimeError``
        after that many steps. The integrator returns to Python every ~50 ms,
        so Ctrl-C stops any run with a ``KeyboardInterrupt``.

    Returns
    -------
    ParticleTrajectory

    Examples
    --------
    A particle at rest in the inertial frame seen from a frame turning at
    1 rad/s about z moves on a circle, clockwise:

    >>> import numpy as np
    >>> tr = simulate_particle([0.0, np.pi / 2], [1, 0, 0], [0, -1, 0], [0, 0, 1])
    >>> np.round(tr.r[-1], 9).tolist()
    [0.0, -1.0, 0.0]
    """
    t = as_float_array(t, "t")
    if t.ndim != 1 or t.size < 1:
        raise ValueError(f"t must be a non-empty one-dimensional array, got shape {t.shape}")
    if t.size > 1 and not np.all(np.diff(t) > 0):
        raise ValueError("t must be strictly increasing")
    r0 = as_float_array(r0, "r0", tail=(3,))
    v0 = as_float_array(v0, "v0", tail=(3,))
    if r0.shape != (3,) or v0.shape != (3,):
        raise ValueError("r0 and v0 must be single vectors of shape (3,)")
    mass = positive_float(mass, "mass")
    gravity = _vector(gravity, "gravity")
    spring = as_float(spring, "spring")
    rtol, atol = positive_float(rtol, "rtol"), positive_float(atol, "atol")
    max_step = positive_float(max_step, "max_step", allow_inf=True)
    if callable(omega) and omega_dot is None:
        raise ValueError("omega_dot is required when omega is a callable")
    if force is not None and not callable(force):
        raise TypeError("force must be a callable force(t, r, v) -> (3,) or None")
    if omega_dot is None:
        omega_dot = (0.0, 0.0, 0.0)
    max_steps = check_max_steps(max_steps)
    if not (callable(omega) or callable(omega_dot)):
        _check_turn(_vector(omega, "omega"), _vector(omega_dot, "omega_dot"), t)

    y0 = np.concatenate([r0, v0])
    tables = _dop853.tableau()
    atol = np.full(y0.size, atol)
    y = np.empty((t.size, y0.size))
    builtin = not (callable(omega) or callable(omega_dot) or callable(a0) or force is not None)
    if builtin:
        w = _vector(omega, "omega")
        wdot = _vector(omega_dot, "omega_dot")
        acc0 = _vector(a0, "a0")
        p = builtin_parameters(w, omega_dot=wdot, a0=acc0, field=gravity, spring=spring, t0=t[0])
        status = run_resumable(
            lambda runs, budget: _integrate_builtin(p, t, runs, rtol, atol, max_step, tables, y, budget),
            _dop853.new_runs(y0[None]), t[-1], max_steps, 2**14, _dop853.PAUSED)
        omega_t = w + wdot * (t - t[0])[:, None]
        a0_t = np.broadcast_to(acc0, (t.size, 3)).copy()
    else:
        if not callable(omega):
            w0 = _vector(omega, "omega").copy()
            wd = _vector(omega_dot, "omega_dot").copy()
            t_start = float(t[0])

            def omega(tt):
                return w0 + wd * (tt - t_start)

        key = next(_KEYS)
        _MODELS[key] = _model(omega, omega_dot, a0, force, mass, gravity.copy(), spring)
        try:
            status = run_resumable(
                lambda runs, budget: _integrate_callbacks(np.array([float(key)]), t, runs, rtol, atol, max_step,
                                                          tables, y, budget),
                _dop853.new_runs(y0[None]), t[-1], max_steps, 64, _dop853.PAUSED)
        finally:
            del _MODELS[key]
        omega_t = _sample(omega, "omega", t)
        a0_t = _sample(a0, "a0", t)
    _dop853.check_status(status)
    r, v = y[:, :3], y[:, 3:]
    if force is None:
        # without a spring no r² term: r² overflows from 1e154 m, and 0 times it is NaN
        potential = mass * (-(r @ gravity) + (0.5 * spring * np.sum(r * r, axis=-1) if spring else 0.0))
    else:
        potential = None
    return ParticleTrajectory(t, r, v, omega_t, a0_t, potential, mass)


def _check_turn(omega, omega_dot, t):
    """Refuse a frame that turns too far for double precision to resolve over ``t``.

    Beyond ~1e15 rad the rounding of the turned angle (1e-16 of it) exceeds 0.1 rad
    and the integrator's steps fall below the rounding of ``t`` itself.
    """
    span = float(t[-1] - t[0])
    with np.errstate(over="ignore", invalid="ignore"):
        # |ω(t)| is largest at an end of t, since ω changes linearly
        turn = max(float(norm(omega)), float(norm(omega + omega_dot * span))) * span
    refuse_long_turn(turn, "omega and t", "the frame turns through about", "resolves its motion")


def _sample(value, name, t):
    if callable(value):
        return np.array([np.asarray(value(ti), dtype=np.float64).reshape(3) for ti in t])
    return np.broadcast_to(_vector(value, name), (t.size, 3)).copy()
