"""Torque-driven rigid body: :func:`simulate`, :func:`simulate_batch`, :func:`simulate_6dof`.

Euler's dynamic equations in the body frame (Theory §4.5),
dJ′/dt + ω′ × J′ = M′, with the attitude carried by a unit quaternion,
q̇ = ½ q ⊗ (0, ω′) (Theory §3.3).

Methods (``method=``):

========== ===== ================================================================
name       order properties
========== ===== ================================================================
dop853     8     default; adaptive Dormand–Prince 8(5,3), error control on every
                 component (``rtol``, ``atol``), 7th-order dense output at ``t``;
                 compiled. No structure preserved, but errors ~ ``rtol``.
splitting  2     Lie–Poisson splitting of the free body into exact rotations
                 about the principal axes (McLachlan 1993, Touma–Wisdom 1994,
                 Reich 1994), Strang-composed; torques by kick–drift–kick.
                 Keeps |J| and the space J to round-off, energy error bounded.
splitting4 4     Yoshida triple-jump composition of ``splitting``.
dmv        2     discrete Moser–Veselov (equivalently RATTLE on SO(3)), solved by
                 fixed-point iteration; keeps |J| and space J, symplectic.
rkmk4      4     Runge–Kutta–Munthe-Kaas on SO(3) × R³ (classical RK4 tableau):
                 q stays unit by construction, no conservation of J or T.
midpoint   2     implicit midpoint on (ω′, q), iterated to round-off: keeps T and
                 |J| (quadratic invariants) to round-off for the free body.
rk4        4     classical RK4 on (ω′, q), q renormalised every step (baseline).
scipy      8     ``scipy.integrate.DOP853`` stepped from Python: independent
                 reference, slow (Python right-hand side).
========== ===== ================================================================

Fixed-step methods need ``dt``: each interval between requested times is cut
into ``ceil(Δt/dt)`` equal steps, so the step never exceeds ``dt`` and the
requested times are hit exactly (no interpolation).

Every run is bounded and interruptible: a fixed-step run whose step count
exceeds ``max_steps`` (by default the steps of about ten minutes of computing,
``DEFAULT_SECONDS``, at most ``MAX_STEPS`` = 10¹⁰) is refused before it starts,
with its estimated time, and so is a torque-free adaptive run that needs more
(a free body turns at ``|ω| >= 2T/|J|`` all along, and a DOP853 step turns it
by a bounded angle: see ``_check_adaptive_span``); any other adaptive run stops
with ``RuntimeError`` once it has taken ``max_steps`` steps (a torque may speed
the body up or bring it to rest, so no count is known before); outputs that
would not fit in memory are refused
with their size. Every method (``scipy`` too) runs in chunks of ~50 ms
(:mod:`kreisel._compiled.chunks`), so Ctrl-C stops any run with a
``KeyboardInterrupt`` and ``progress`` is told how far the run got.

A body given by a non-diagonal tensor is integrated in its principal frame
(Euler's equations take their principal-axis form there, and ``splitting``
needs it) and the result is transformed back: ``q = q_principal ⊗ q_axes*``,
``ω′ = axes ω_principal``.
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._compiled import dop853 as _dop853
from .._compiled.chunks import MAX_STEPS, check_max_steps, compile_ahead, run_chunked
from .._validation import (as_float_array, check_allocation, check_inertia_tensor, check_principal_moments,
                          checked_callable, float_in_range, positive_float)
from ..so3 import matrix_to_quat, quat_conjugate, quat_multiply
from ..so3._coercion import as_quaternion
from . import _integrators
from . import _model_tables
from . import forces as _forces
from . import torques as _torques
from .trajectory import Trajectory

if TYPE_CHECKING:
    from ..inertia.body import RigidBody

_Array = NDArray[np.float64]
#: What ``torque`` may be: a built-in model, a callable torque(t, q, omega_body), or None
_TorqueArg = _torques.TorqueModel | Callable[..., ArrayLike] | None
#: What ``force`` may be: a built-in model, a callable force(t, q, omega_body, position, velocity), or None
_ForceArg = _forces.ForceModel | Callable[..., ArrayLike] | None

__all__ = ["simulate", "simulate_batch", "simulate_6dof", "METHODS", "MAX_STEPS"]

METHODS = {
    "dop853": _integrators.DOP853,
    "splitting": _integrators.SPLITTING,
    "splitting4": _integrators.SPLITTING4,
    "dmv": _integrators.DMV,
    "rkmk4": _integrators.RKMK4,
    "midpoint": _integrators.MIDPOINT,
    "rk4": _integrators.RK4,
    "scipy": None,
}
# the compiled methods' ids (every method but "scipy")
_CODES = {name: code for name, code in METHODS.items() if code is not None}
ADAPTIVE = ("dop853", "scipy")
DEFAULT_RTOL = 1e-12


# rough single-core cost of one step of each compiled method (free body; a torque adds to it), for the
# time estimate in the message that refuses a run over its step budget
_SECONDS_PER_STEP = {"dop853": 1.5e-6, "scipy": 3e-5, "splitting": 3e-7, "splitting4": 1e-6, "dmv": 1e-6, "rkmk4": 6e-7,
                     "midpoint": 5e-7, "rk4": 3.5e-7}
#: Without an explicit ``max_steps`` a run gets the steps of about this many seconds of computing
#: (by _SECONDS_PER_STEP), so that a run estimated far beyond reason is refused rather than left running
DEFAULT_SECONDS = 600.0
# steps of the first call (shared by the bodies of a batch); later calls adapt to the measured speed
_FIRST_CHUNK_STEPS = 2**16

_STATUS = {
    **_dop853.MESSAGES,
    _integrators.NO_CONVERGENCE: "the implicit iteration did not converge (reduce dt)",
}


# ---------------------------------------------------------------------------- input checks


def resolve_body(body: RigidBody | ArrayLike,
                 allow_unphysical: bool = False) -> tuple[_Array, _Array, _Array | None, float]:
    """Return (tensor (3, 3), principal moments (3,), axes or None, mass) for one body.

    ``axes`` has the principal axes as columns in body coordinates; it is None
    when the body axes already are principal.
    """
    mass = 1.0
    if hasattr(body, "inertia") and hasattr(body, "mass"):
        mass = float(body.mass)
        body = body.inertia
    a = as_float_array(body, "body")
    if a.shape == (3,):
        moments = check_principal_moments(a, "body", allow_unphysical=allow_unphysical)
        return np.diag(moments), moments, None, mass
    if a.shape != (3, 3):
        raise ValueError(f"body must be a RigidBody, 3 principal moments or a (3, 3) tensor, got shape {a.shape}")
    a = check_inertia_tensor(a, "body")
    if not np.any(a - np.diag(np.diag(a))):
        return a, check_principal_moments(np.diag(a), "body", allow_unphysical=allow_unphysical), None, mass
    moments, axes = np.linalg.eigh(a)
    if np.linalg.det(axes) < 0.0:
        axes[:, 2] = -axes[:, 2]
    return a, check_principal_moments(moments, "body", allow_unphysical=allow_unphysical), axes, mass


def _check_every(every: object, n_times: int) -> int:
    """``every`` as a positive int dividing ``n_times - 1``; TypeError/ValueError naming it."""
    if isinstance(every, bool) or not isinstance(every, (int, np.integer)):
        raise TypeError(f"every must be a positive integer, got {type(every).__name__}")
    if every < 1 or (n_times - 1) % every:
        raise ValueError(f"every must be a positive integer dividing len(t) - 1 = {n_times - 1} (so that the "
                         f"last time is kept), got {every}")
    return int(every)


def _check_times(t: ArrayLike) -> _Array:
    t = as_float_array(t, "t")
    if t.ndim != 1 or t.size < 1:
        raise ValueError(f"t must be a one-dimensional array of sample times, got shape {t.shape}")
    if t.size > 1 and not np.all(np.diff(t) > 0.0):
        raise ValueError("t must be strictly increasing")
    return t


def _check_method(method: str | None, dt: float | None, t: _Array) -> tuple[str, float]:
    if method is None:
        method = "dop853"
    if not isinstance(method, str):
        raise TypeError(f"method must be a string, got {type(method).__name__}")
    if method not in METHODS:
        raise ValueError(f"unknown method {method!r}; choose one of {', '.join(METHODS)}")
    if method in ADAPTIVE:
        if dt is not None:
            raise ValueError(f"dt is for fixed-step methods; {method!r} chooses its own steps (use rtol)")
        return method, 0.0
    if dt is None:
        raise ValueError(f"method {method!r} is fixed-step: pass dt (the largest step, seconds)")
    return method, positive_float(dt, "dt")


def _check_omega_range(w: _Array, moments: _Array) -> None:
    """Refuse ω0 for which Euler's equations overflow: they multiply two components, scaled by I_max/I_min."""
    size = np.abs(w).max(axis=-1) if w.size else np.zeros(0)
    spread = moments.max(axis=-1) / moments.min(axis=-1)
    with np.errstate(over="ignore"):
        worst = size * size * spread
    if np.any(worst > 1e300):
        raise ValueError(f"omega0 = {np.asarray(w).reshape(-1, 3)[np.argmax(np.ravel(worst > 1e300))]} is out of "
                         "range: Euler's equations multiply its components (times I_max/I_min), which overflows "
                         "double precision above about 1e150 rad/s")


def _initial_quaternion(q0: ArrayLike | None, batch_shape: tuple[int, ...] = ()) -> _Array:
    if q0 is None:
        q = np.zeros(batch_shape + (4,))
        q[..., 0] = 1.0
        return q
    q = as_quaternion(q0, "q0")
    return np.broadcast_to(q, batch_shape + (4,)).copy() if batch_shape else q


def _model_rows(model: _TorqueArg | _ForceArg, name: str, axes: _Array | None, t0: float,
                state: tuple[_Array, ...]) -> _Array | None:
    """Model table of the ``torque`` or ``force`` argument in the integration frame; a callable is registered
    (release the table after use).

    ``state`` is the initial ``(q, omega_body)`` in the user's body frame, for a force followed by the position
    and velocity. A callable is tried there once, then called with the principal-frame state turned to the
    user's body frame; a torque, returned in that frame, is turned back (a force is given in space).
    """
    if model is None:
        return None
    models, model_type = (_forces, _forces.ForceModel) if name == "force" else (_torques, _torques.TorqueModel)
    if isinstance(model, model_type):
        return _table(models.to_principal(model.rows(), axes))
    if not callable(model):
        arguments = "t, q, omega_body, position, velocity" if name == "force" else "t, q, omega_body"
        raise TypeError(f"{name} must be None, a {name} model or a callable {name}({arguments}), "
                        f"got {type(model).__name__}")
    checked = checked_callable(model, name)
    checked(t0, *(x.copy() for x in state))
    if axes is None:
        fn = checked
    else:
        q_axes = matrix_to_quat(axes)

        def fn(t: float, q: _Array, w: _Array, *translation: _Array) -> _Array:
            value = checked(t, quat_multiply(q, quat_conjugate(q_axes)), axes @ w, *translation)
            return axes.T @ value if name == "torque" else value

    return _model_tables.register_callback(fn, translation=name == "force")


def _table(rows: _Array) -> _Array | None:
    """A model table for the kernels; None when empty (the kernels then skip the evaluation)."""
    return np.ascontiguousarray(rows) if rows.shape[0] else None


def _run(code: int, t: _Array, dt: float, y0: _Array, moments: _Array, mass: _Array, rows: _Array | None,
         frows: _Array | None, rtol: float, atol: _Array, max_steps: int,
         progress: Callable[[float], object] | None = None, every: int = 1) -> tuple[_Array, NDArray[np.int64]]:
    """Integrate bodies ``y0 (count, ny)`` in compiled chunks (:func:`kreisel._compiled.chunks.run_chunked`).

    Returns ``(out, status)``, ``out`` the samples at ``t[::every]``;
    ``progress(t_reached)`` is told the earliest time over the bodies.
    """
    count, ny = y0.shape
    if code == _integrators.DOP853:  # its steps do not depend on the output times in between: same bits
        t, every = np.ascontiguousarray(t[::every]), 1
    out = np.empty((count, (t.size - 1) // every + 1, ny))
    status = np.full(count, _dop853.PAUSED, dtype=np.int64)
    # one state for the batch: a state per body would leave an array per body for the garbage collector to scan
    if code == _integrators.DOP853:
        runs = _dop853.new_runs(np.ascontiguousarray(y0, dtype=np.float64))
        tables = _dop853.tableau()
        if count == 1:
            compile_ahead(_integrators.run_dop853, t, runs, 0, moments[0], mass[0], rows, frows, rtol, atol[0], tables,
                          out[0], 1)
        else:
            compile_ahead(_integrators.run_dop853_batch, t, runs, moments, mass, rows, frows, rtol, atol, tables, out,
                          status, 1)

        def step(budget: int) -> bool:
            if count == 1:
                status[0] = _integrators.run_dop853(t, runs, 0, moments[0], mass[0], rows, frows, rtol, atol[0],
                                                    tables, out[0], budget)
            else:
                _integrators.run_dop853_batch(t, runs, moments, mass, rows, frows, rtol, atol, tables, out, status,
                                              budget)
            return not np.any(status == _dop853.PAUSED)

        def reached() -> float:
            return float(runs.t[status == _dop853.PAUSED].min())
    else:
        grid = _integrators.step_grid(t, dt)
        state = _integrators.new_state(y0)
        runners = _integrators.runners(code, free=ny == 7 and rows is None)
        if count == 1:
            compile_ahead(runners.one, t, grid, state, 0, moments[0], mass[0], rows, frows, out[0], 1, every)
        else:
            compile_ahead(runners.many, t, grid, state, moments, mass, rows, frows, out, status, 1, every)

        def step(budget: int) -> bool:
            if count == 1:
                status[0] = runners.one(t, grid, state, 0, moments[0], mass[0], rows, frows, out[0], budget, every)
            else:
                runners.many(t, grid, state, moments, mass, rows, frows, out, status, budget, every)
            return not np.any(status == _dop853.PAUSED)

        def reached() -> float:
            return _integrators.reached(t, dt, state, status == _dop853.PAUSED)

    callbacks = any(r is not None and np.any(r[:, 0] == _model_tables.CALLBACK) for r in (rows, frows))
    run_chunked(step, reached, t[-1], max_steps, 64 if callbacks else max(1, _FIRST_CHUNK_STEPS // count), progress)
    return out, status


def _check_workload(method: str, t: _Array, dt: float, count: int, ny: int, max_steps: int | None,
                    every: int = 1) -> int:
    """Refuse, before any work, outputs that do not fit in memory and fixed-step runs over the step budget.

    Returns the step budget: ``max_steps`` as given, or by default the steps of about
    :data:`DEFAULT_SECONDS` of computing for ``count`` bodies (at most ``MAX_STEPS``).
    """
    default = max_steps is None
    max_steps = check_max_steps(max_steps)
    if default:
        max_steps = min(max_steps, max(1, int(DEFAULT_SECONDS / (_SECONDS_PER_STEP[method] * count))))
    samples = (t.size - 1) // every + 1
    check_allocation(count * samples * ny * 8.0, f"the output ({count} × {samples} samples × {ny} states)",
                     "ask for fewer times in t, or keep every N-th sample with every=N")
    if method in ADAPTIVE:
        return max_steps
    steps = _integrators.substeps(np.diff(t), dt)
    total = float(np.sum(steps))
    if not (total <= max_steps):
        seconds = total * count * _SECONDS_PER_STEP[method]
        per_body = f" per body ({count} bodies)" if count > 1 else ""
        raise ValueError(f"method {method!r} with dt = {dt:g} over t = {t[0]:g} … {t[-1]:g} needs "
                         f"{total:.3g} steps{per_body}, about {_duration(seconds)} of computing; over the "
                         f"budget max_steps = {max_steps:.3g}{_BUDGET_NOTE}: raise dt, or pass a larger max_steps to run it anyway")
    if steps.size and not steps.max() < 2.0**62:
        raise ValueError(f"method {method!r} with dt = {dt:g} needs {steps.max():.3g} steps for one output "
                         f"interval: more than can be counted (2^62); raise dt")
    return max_steps


def _check_adaptive_span(method: str, t: _Array, moments: _Array, omega: _Array, rtol: float, atol: _Array,
                         max_steps: int, spin: tuple[float, str] | None = None) -> None:
    """Refuse, before any work, torque-free adaptive runs (one body or a batch) that cannot end within ``max_steps``.

    A free body turns at ``|ω| >= 2T/|J|`` all along (``ω·J = 2T``, with T and
    ``|J|`` conserved), and one DOP853 step turns it by at most
    ``40 tol^(1/9)`` rad, ``tol`` being ``rtol`` plus the attitude's ``atol``:
    twice the largest step angle of uniform spin (the easiest motion, with
    the longest steps) over ``rtol`` 1e-15 … 0.999 and ``atol`` up to 1e3.
    So the run needs at least ``(t[-1] - t[0]) 2T/|J|`` over that many steps;
    a body at rest or a short run passes whatever the span. ``spin`` = (rate, why) gives another
    lower bound on |ω| instead (a heavy symmetric top keeps ω3 = J3/I3).
    """
    if method not in ADAPTIVE:
        return
    scaled = moments / moments.max(axis=-1, keepdims=True)  # 2T/|J| does not depend on the moments' scale
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        two_t = np.sum(scaled * omega * omega, axis=-1)
        rate = np.where(two_t > 0.0, two_t / np.linalg.norm(scaled * omega, axis=-1), 0.0)
        if spin is not None:
            rate = np.asarray(spin[0])
        per_step = 40.0 * (rtol + atol[..., 3:7].max(axis=-1)) ** (1.0 / 9.0)
        steps = np.broadcast_to((t[-1] - t[0]) * rate / per_step, rate.shape)
    worst = int(np.argmax(steps))
    if not steps.flat[worst] <= max_steps:
        body = f" (body {worst} of {steps.size})" if steps.ndim else ""
        rate, per_step = rate.flat[worst], np.broadcast_to(per_step, rate.shape).flat[worst]
        seconds = steps.flat[worst] * _SECONDS_PER_STEP[method]
        raise ValueError(f"t = {t[0]:g} … {t[-1]:g} is out of reach of the adaptive method {method!r}: the "
                         f"{'body' if spin else 'free body'}{body} turns at |ω| >= {rate:.3g} rad/s "
                         f"({spin[1] if spin else '2T/|J| from omega0 and the moments'}), "
                         f"through {rate * (t[-1] - t[0]):.3g} rad, and one step at rtol = {rtol:g} turns it by at "
                         f"most {per_step:.2g} rad, so the run needs at least {steps.flat[worst]:.3g} steps, about "
                         f"{_duration(seconds)} of computing; over the budget max_steps = {max_steps:.3g}{_BUDGET_NOTE}: "
                         "shorten t, or pass a larger max_steps to run it anyway")


_BUDGET_NOTE = f" (by default about {DEFAULT_SECONDS / 60:g} minutes of computing, at most 1e+10)"


def _conserved_spin(moments: _Array, lever: _Array, omega: _Array) -> float | None:
    """|ω_k| if the lever lies on principal axis k and the other two moments are equal (a heavy symmetric
    top: gravity's torque has no component along k and Euler's k-th equation has none either)."""
    for k in range(3):
        i, j = (k + 1) % 3, (k + 2) % 3
        if lever[i] == 0.0 and lever[j] == 0.0 and moments[i] == moments[j]:
            return float(abs(omega[k]))
    return None


def _duration(seconds: float) -> str:
    """A rough duration in the largest fitting unit, for messages."""
    for unit, size in (("years", 3.15e7), ("days", 86400.0), ("hours", 3600.0), ("minutes", 60.0)):
        if seconds >= size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"


def _raise_status(status: ArrayLike) -> None:
    status = np.asarray(status)
    if np.any(status != 0):
        code = int(status[status != 0].flat[0])
        where = "" if status.ndim == 0 else f" for {int(np.count_nonzero(status))} bodies"
        raise RuntimeError(f"integration failed{where}: {_STATUS[code]}")


def _atol(atol: float | None, omega_scale: _Array, ny: int, rtol: float) -> _Array:
    """Absolute tolerance per component: scaled by |ω0| so rtol is meaningful in any units."""
    if atol is not None:
        a = positive_float(atol, "atol")
        if a < 1e-150:
            raise ValueError(f"atol = {a:g} is below 1e-150: the error estimate is squared after dividing by "
                             "atol, which overflows for order-one states; use a larger atol")
        return np.full(omega_scale.shape + (ny,), a)
    out = np.empty(omega_scale.shape + (ny,))
    out[...] = rtol
    out[..., :3] = rtol * np.where(omega_scale > 0.0, omega_scale, 1.0)[..., None]
    return out


def _check_rtol(rtol: float) -> float:
    return float_in_range(rtol, "rtol", 1e-15, 1.0)


# ---------------------------------------------------------------------------- drivers


def _integrate(method: str, t: _Array, dt: float, y0: _Array, moments: _Array, mass: float, rows: _Array | None,
               frows: _Array | None, rtol: float, atol: _Array, max_steps: int,
               progress: Callable[[float], object] | None, every: int = 1) -> _Array:
    # a fresh writable C array: numba compiles one specialisation per array layout
    moments = np.array(moments, dtype=np.float64, order="C")
    if method == "scipy":  # its steps do not depend on the output times: the kept samples are those of t
        y = _scipy(np.ascontiguousarray(t[::every]), y0, moments, mass, rows, frows, rtol, atol, max_steps, progress)
        y[:, 3:7] = _normalized(y[:, 3:7])  # as the compiled drivers write their samples
        return y
    out, status = _run(_CODES[method], t, dt, y0[None, :], moments[None, :], np.array([mass]), rows, frows,
                       rtol, atol[None, :], max_steps, progress, every)
    _raise_status(status[0])
    samples: _Array = out[0]
    return samples


def _scipy(t: _Array, y0: _Array, moments: _Array, mass: float, rows: _Array | None, frows: _Array | None, rtol: float,
           atol: _Array, max_steps: int, progress: Callable[[float], object] | None) -> _Array:
    """scipy's DOP853 stepped in chunks like the compiled methods, the states at ``t`` from its dense output."""
    from scipy.integrate import DOP853

    scratch = np.empty(13)

    def fun(tt: float, y: _Array) -> _Array:
        dy = np.empty_like(y)
        _integrators.rhs(tt, y, y.size, moments, mass, rows, frows, dy, 0, scratch)
        return dy

    out = np.empty((t.size, y0.size))
    out[0] = y0
    if t.size == 1:
        return out
    solver = DOP853(fun, t[0], y0, t[-1], rtol=rtol, atol=atol)
    filled = [1]

    def step(budget: int) -> bool:
        for _ in range(budget):
            message = solver.step()
            if solver.status == "failed":
                raise RuntimeError(f"integration failed: {message}")
            reached = int(np.searchsorted(t, solver.t, side="right"))
            if reached > filled[0]:
                out[filled[0]:reached] = solver.dense_output()(t[filled[0]:reached]).T
                filled[0] = reached
            if solver.status == "finished":
                return True
        return False

    # each step calls the Python right-hand side 12 times: start with short chunks
    run_chunked(step, lambda: float(solver.t), t[-1], max_steps, 16, progress)
    return out


def _to_body_frame(omega: _Array, q: _Array, axes: _Array | None) -> tuple[_Array, _Array]:
    if axes is None:
        return omega, q
    return omega @ axes.T, quat_multiply(q, quat_conjugate(matrix_to_quat(axes)))


def _normalized(q: _Array) -> _Array:
    unit: _Array = q / np.linalg.norm(q, axis=-1, keepdims=True)
    return unit


def _single(body: RigidBody | ArrayLike, t: ArrayLike, omega0: ArrayLike, q0: ArrayLike | None, torque: _TorqueArg,
            method: str | None, dt: float | None, rtol: float, atol: float | None, allow_unphysical: bool,
            max_steps: int | None, progress: Callable[[float], object] | None,
            translation: tuple[_Array, _Array] | None = None, force: _ForceArg = None,
            every: int = 1) -> tuple[_Array, float, _Array, _Array, _Array, _Array, dict[str, Any]]:
    """Shared validation and integration of :func:`simulate` and :func:`simulate_6dof`; the samples at ``t[::every]``."""
    tensor, moments, axes, mass = resolve_body(body, allow_unphysical)
    t = _check_times(t)
    every = _check_every(every, t.size)
    method, dt = _check_method(method, dt, t)
    rtol = _check_rtol(rtol)
    max_steps = _check_workload(method, t, dt, 1, 7 if translation is None else 13, max_steps, every)
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be callable, got {type(progress).__name__}")
    w_body = as_float_array(omega0, "omega0", tail=(3,))
    if w_body.ndim != 1:
        raise ValueError(f"omega0 must have shape (3,), got {w_body.shape}")
    _check_omega_range(w_body, moments)
    q_body = _initial_quaternion(q0)
    if q_body.ndim != 1:
        raise ValueError(f"q0 must have shape (4,), got {q_body.shape}")
    w_pr = w_body if axes is None else axes.T @ w_body
    q_pr = q_body if axes is None else quat_multiply(q_body, matrix_to_quat(axes))
    parts = [w_pr, q_pr]
    if translation is not None:
        parts.extend(translation)
    y0 = np.ascontiguousarray(np.concatenate(parts))
    atol_v = _atol(atol, np.asarray(np.linalg.norm(w_body)), y0.size, rtol)
    if torque is None:  # forces move the centre of mass only: the attitude is still a free body's
        _check_adaptive_span(method, t, moments, w_pr, rtol, atol_v, max_steps)
    elif isinstance(torque, _torques.GravityTorque):
        spin = _conserved_spin(moments, torque.lever if axes is None else axes.T @ torque.lever, w_pr)
        if spin is not None:
            _check_adaptive_span(method, t, moments, w_pr, rtol, atol_v, max_steps,
                                 (spin, "the spin about the symmetry axis, conserved under gravity"))
    rows = frows = None
    try:
        rows = _model_rows(torque, "torque", axes, t[0], (q_body, w_body))
        frows = None if translation is None else _model_rows(force, "force", axes, t[0], (q_body, w_body, *translation))
        y = _integrate(method, t, dt, y0, moments, mass, rows, frows, rtol, atol_v, max_steps, progress, every)
    finally:
        _model_tables.release_callback(rows)
        _model_tables.release_callback(frows)
    omega, q = _to_body_frame(y[:, 0:3], y[:, 3:7], axes)
    meta = {"method": method, "dt": dt, "rtol": rtol if method in ADAPTIVE else 0.0,
            "torque": repr(torque) if torque is not None else "none"}
    return tensor, mass, t[::every], omega, q, y, meta


def simulate(body: RigidBody | ArrayLike, t: ArrayLike, omega0: ArrayLike, q0: ArrayLike | None = None,
             torque: _TorqueArg = None, method: str | None = None, dt: float | None = None, rtol: float = DEFAULT_RTOL,
             atol: float | None = None, allow_unphysical: bool = False, max_steps: int | None = None,
             progress: Callable[[float], object] | None = None, every: int = 1) -> Trajectory:
    """Integrate Euler's dynamic equations with quaternion attitude (Theory §4.4–5).

    Parameters
    ----------
    body : RigidBody, (3,) or (3, 3) array_like
        A :class:`kreisel.RigidBody`, three principal moments (body axes are
        principal), or a body-frame inertia tensor (integrated in its
        principal frame, results returned in the body frame), kg m².
    t : (n,) array_like
        Strictly increasing output times; the initial state is at ``t[0]``.
    omega0 : (3,) array_like
        Initial body angular velocity ω′, rad/s.
    q0 : (4,) or (3, 3) array_like or Rotation, optional
        Initial attitude, body -> space (default identity): a quaternion
        (scalar first, any nonzero norm), a rotation matrix or a rotation
        object.
    torque : TorqueModel or callable, optional
        A built-in model (:class:`GravityTorque`, :class:`ConstantTorque`,
        :class:`MagneticTorque`, :class:`LinearDamping`, sums of them: run
        compiled) or ``torque(t, q, omega_body) -> body torque (3,)`` in N m
        (called back from the compiled loop, far slower than a built-in
        model). A callable is called once with the initial state to check its
        output before integrating.
    method : str, optional
        One of ``"dop853"`` (default), ``"splitting"``, ``"splitting4"``,
        ``"dmv"``, ``"rkmk4"``, ``"midpoint"``, ``"rk4"``, ``"scipy"`` (see the
        module documentation for orders and conserved quantities).
    dt : float, optional
        Largest step of a fixed-step method (required for them).
    rtol, atol : float
        Tolerances of the adaptive methods. ``atol=None`` uses ``rtol·|ω0|``
        for ω′ (``rtol`` rad/s when ω0 = 0) and ``rtol`` for q, so accuracy
        does not depend on units.
    allow_unphysical : bool
        Accept positive moments that violate the triangle inequality
        I_i <= I_j + I_k (textbook test problems); refused by default. The
        rule and its tolerance are those of every entry point: user guide,
        "Which inertia input is accepted".
    max_steps : int, optional
        Step budget (default: the steps of about ten minutes of computing,
        at most 10¹⁰; pass it to run longer): a fixed-step run needing
        more steps is refused before it starts, as is a torque-free adaptive
        run that needs more (at least its turn ``(t[-1] - t[0]) 2T/|J|`` over
        a bound on the angle of one step); another adaptive run is stopped
        when it has taken that many.
    progress : callable, optional
        ``progress(t_reached)``, called about every 50 ms of a long run
        with the time the integration has reached.
    every : int
        Keep every ``every``-th sample, as in :func:`simulate_batch`: the
        trajectory holds the samples at ``t[::every]`` (``every`` divides
        ``len(t) - 1``) of the run over all of ``t``, bit for bit.

    Returns
    -------
    Trajectory
        Samples at ``t[::every]``; ``meta`` records the method and its settings.

    Raises
    ------
    ValueError, TypeError
        For non-physical bodies, non-finite initial states, non-increasing
        ``t``, unknown methods, a missing ``dt``, a step count over the
        budget, an output too large for memory, or a torque callable with
        the wrong output (checked at every call); raised before
        integrating, or for the callable as soon as it returns a bad value.
    RuntimeError
        If the integration itself fails (step size collapse, divergence,
        step budget exhausted).
    KeyboardInterrupt
        On Ctrl-C, within a fraction of a second.

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> tr = kr.simulate([1.0, 2.0, 3.0], np.linspace(0, 10, 5), [0.1, 1.0, 0.1])
    >>> bool(abs(tr.energy[-1] - tr.energy[0]) < 1e-12)
    True
    >>> tr.q.shape, tr.omega.shape
    ((5, 4), (5, 3))
    >>> kr.simulate([1.0, 2.0, 3.0], np.linspace(0, 10, 1001), [0.1, 1.0, 0.1], every=250).t
    array([ 0. ,  2.5,  5. ,  7.5, 10. ])
    """
    tensor, _, t, omega, q, _, meta = _single(body, t, omega0, q0, torque, method, dt, rtol, atol,
                                            allow_unphysical, max_steps, progress, every=every)
    return Trajectory(t, q, omega, tensor, meta=meta)


def simulate_6dof(body: RigidBody | ArrayLike, t: ArrayLike, omega0: ArrayLike, q0: ArrayLike | None = None,
                  position0: ArrayLike = (0.0, 0.0, 0.0), velocity0: ArrayLike = (0.0, 0.0, 0.0),
                  force: _ForceArg = None, torque: _TorqueArg = None, method: str | None = None, dt: float | None = None,
                  rtol: float = DEFAULT_RTOL, atol: float | None = None, allow_unphysical: bool = False,
                  max_steps: int | None = None, progress: Callable[[float], object] | None = None,
                  every: int = 1) -> Trajectory:
    """A free rigid body in six degrees of freedom: centre of mass and attitude (Theory §4.4, §4.7).

    The centre of mass obeys m r̈ = F (space frame, Theory §4.7 with r_C the
    reference point); the rotation obeys Euler's equations about the centre of
    mass under ``torque``. Adaptive methods integrate all 13 states together;
    fixed-step methods advance the translation by velocity Verlet (second
    order) around their rotation step.

    Parameters
    ----------
    body : RigidBody or (3,) / (3, 3) array_like
        Inertia about the centre of mass; a plain array means mass 1 kg.
    t, omega0, q0, torque, method, dt, rtol, atol, allow_unphysical, max_steps, progress, every
        As in :func:`simulate`.
    position0, velocity0 : (3,) array_like
        Centre-of-mass position (m) and velocity (m/s) in space.
    force : ForceModel or callable, optional
        :class:`ConstantForce`, :class:`LinearDrag`, sums of them, or
        ``force(t, q, omega_body, position, velocity) -> space force (3,)`` N.

    Returns
    -------
    Trajectory
        With extra arrays ``position`` and ``velocity`` (n, 3) in space.

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> from kreisel.dynamics import ConstantForce
    >>> body = kr.RigidBody([1.0, 2.0, 3.0], mass=2.0)
    >>> tr = kr.simulate_6dof(body, [0.0, 1.0], [0, 0, 1.0], velocity0=[1.0, 0, 0],
    ...                       force=ConstantForce([0, 0, -19.6]))
    >>> np.round(tr.position[-1], 10)
    array([ 1. ,  0. , -4.9])
    """
    r0 = as_float_array(position0, "position0", tail=(3,))
    v0 = as_float_array(velocity0, "velocity0", tail=(3,))
    if r0.ndim != 1 or v0.ndim != 1:
        raise ValueError("position0 and velocity0 must have shape (3,)")
    tensor, mass, t, omega, q, y, meta = _single(body, t, omega0, q0, torque, method, dt, rtol, atol,
                                                 allow_unphysical, max_steps, progress, translation=(r0, v0),
                                                 force=force, every=every)
    meta["mass"] = mass
    meta["force"] = repr(force) if force is not None else "none"
    return Trajectory(t, q, omega, tensor, meta=meta, position=y[:, 7:10], velocity=y[:, 10:13])


def simulate_batch(bodies: ArrayLike, t: ArrayLike, omega0: ArrayLike, q0: ArrayLike | None = None,
                   torque: _TorqueArg = None, method: str | None = None, dt: float | None = None,
                   reduce: Callable[[Trajectory], ArrayLike] | None = None, rtol: float = DEFAULT_RTOL,
                   atol: float | None = None, chunk_size: int | None = None, allow_unphysical: bool = False,
                   max_steps: int | None = None, every: int = 1) -> Trajectory | NDArray[Any]:
    """Many rigid bodies in one compiled, parallel call (numba ``prange``).

    Parameters
    ----------
    bodies : (..., 3) array_like
        Principal moments of each body (body axes are principal).
    t : (n,) array_like
        Output times shared by all bodies.
    omega0 : (..., 3) array_like
        Initial body angular velocities, broadcast against ``bodies``.
    q0 : (..., 4) array_like, optional
        Initial attitudes (default identity), broadcast likewise.
    torque : TorqueModel, optional
        One built-in model shared by every body (Python callables are not
        accepted here: they would serialise the parallel loop).
    method, dt, rtol, atol, allow_unphysical, max_steps
        As in :func:`simulate` (``max_steps`` per body); results agree with :func:`simulate` body by body
        to round-off (the same compiled code runs for each body).
    reduce : callable, optional
        ``reduce(trajectory) -> array (k, ...)`` applied to each chunk of ``k``
        bodies (a batched :class:`Trajectory` with batch shape ``(k,)``);
        only the reduced arrays are kept, so memory stays bounded by
        ``chunk_size`` bodies × ``len(t)``. The results are concatenated and
        reshaped to the batch shape.
    chunk_size : int, optional
        Bodies per chunk when ``reduce`` is given (default 4096).
    every : int
        Keep every ``every``-th sample: the trajectory is sampled at
        ``t[::every]`` (``every`` must divide ``len(t) - 1``, so that the
        last time is kept), integrated over all of ``t`` as without it. The
        kept samples are bit for bit those of the full run (fixed-step
        methods step each interval of ``t``; DOP853's steps do not depend on
        the times in between), at a fraction of the memory.

    Returns
    -------
    Trajectory or ndarray
        A batched trajectory with arrays ``(batch..., n, 3 or 4)``, or the
        reduced array ``(batch..., ...)``.

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> bodies = np.array([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]])
    >>> tr = kr.simulate_batch(bodies, np.linspace(0, 1, 3), [0.1, 1.0, 0.1])
    >>> tr.omega.shape
    (2, 3, 3)
    >>> flip = kr.simulate_batch(bodies, np.linspace(0, 1, 3), [0.1, 1.0, 0.1],
    ...                          reduce=lambda tr: tr.omega[:, :, 1].min(axis=1))
    >>> flip.shape
    (2,)
    >>> kr.simulate_batch(bodies, np.linspace(0, 1, 101), [0.1, 1.0, 0.1], every=25).t
    array([0.  , 0.25, 0.5 , 0.75, 1.  ])
    """
    moments = check_principal_moments(bodies, "bodies", allow_unphysical=allow_unphysical)
    t = _check_times(t)
    every = _check_every(every, t.size)
    method, dt = _check_method(method, dt, t)
    if method == "scipy":
        raise ValueError("simulate_batch runs compiled methods only; 'scipy' is available in simulate")
    rtol = _check_rtol(rtol)
    w = as_float_array(omega0, "omega0", tail=(3,))
    q_in = None if q0 is None else _initial_quaternion(q0)
    shapes = [moments.shape[:-1], w.shape[:-1]] + ([] if q_in is None else [q_in.shape[:-1]])
    try:
        batch = np.broadcast_shapes(*shapes)
    except ValueError as exc:
        raise ValueError(f"bodies, omega0 and q0 batch shapes do not broadcast: {shapes}") from exc
    if 0 in batch:
        raise ValueError(f"bodies, omega0 and q0 (batch shapes {shapes}) broadcast to an empty batch {batch}; give "
                         "at least one body")
    _check_omega_range(np.broadcast_to(w, batch + (3,)), np.broadcast_to(moments, batch + (3,)))
    if torque is not None and not isinstance(torque, _torques.TorqueModel):
        raise TypeError("simulate_batch takes a built-in torque model (GravityTorque, ConstantTorque, "
                        f"MagneticTorque, LinearDamping or a sum); got {type(torque).__name__}")
    rows = None if torque is None else _table(torque.rows())
    if reduce is not None and not callable(reduce):
        raise TypeError(f"reduce must be callable, got {type(reduce).__name__}")
    count = int(np.prod(batch))
    chunk = 4096 if chunk_size is None else operator.index(chunk_size)
    if chunk < 1:
        raise ValueError(f"chunk_size must be a positive integer, got {chunk}")
    max_steps = _check_workload(method, t, dt, count if reduce is None else min(count, chunk), 7, max_steps,
                                every)
    # writable C copies: the batch kernel then reuses the single-body specialisation of the integrators
    moments = np.array(np.broadcast_to(moments, batch + (3,)).reshape(count, 3), order="C")
    y0 = np.empty((count, 7))
    y0[:, 0:3] = np.broadcast_to(w, batch + (3,)).reshape(count, 3)
    y0[:, 3:7] = _initial_quaternion(q_in, batch).reshape(count, 4) if q_in is not None else [1.0, 0, 0, 0]
    atol_v = _atol(atol, np.linalg.norm(y0[:, 0:3], axis=-1), 7, rtol)
    if torque is None:
        _check_adaptive_span(method, t, moments, y0[:, 0:3], rtol, atol_v, max_steps)
    mass = np.ones(count)
    code = _CODES[method]
    meta = {"method": method, "dt": dt, "rtol": rtol if method in ADAPTIVE else 0.0,
            "torque": repr(torque) if torque is not None else "none"}

    def integrate(lo: int, hi: int) -> _Array:
        out, status = _run(code, t, dt, y0[lo:hi], moments[lo:hi], mass[lo:hi], rows, None, rtol, atol_v[lo:hi],
                           max_steps, every=every)
        _raise_status(status)
        return out

    kept = t[::every]
    if reduce is None:
        y = integrate(0, count)
        # views of the drivers' output (unit attitudes already): dense output costs no pass after the run
        omega = y[..., 0:3].reshape(batch + (kept.size, 3))
        q = y[..., 3:7].reshape(batch + (kept.size, 4))
        return Trajectory(kept, q, omega, moments.reshape(batch + (3,))[..., None] * np.eye(3), meta=meta)
    pieces = []
    for lo in range(0, count, chunk):
        hi = min(count, lo + chunk)
        y = integrate(lo, hi)
        tr = Trajectory(kept, y[..., 3:7], y[..., 0:3], moments[lo:hi, :, None] * np.eye(3), meta=meta)
        piece = np.asarray(reduce(tr))
        if piece.ndim < 1 or piece.shape[0] != hi - lo:
            raise ValueError(f"reduce must return an array whose first axis is the {hi - lo} bodies "
                             f"of the chunk, got shape {piece.shape}")
        pieces.append(piece)
    result = np.concatenate(pieces, axis=0)
    return result.reshape(batch + result.shape[1:])
