"""The one compiled adaptive Dormand–Prince 8(5,3) integrator of kreisel.

Stepping, error norm, step-size control and the 7th-order dense output follow
Hairer, Nørsett & Wanner, *Solving ODEs I* (II.10), as scipy's ``DOP853``; the
Butcher tableau is read from ``scipy.integrate._ivp.dop853_coefficients`` so
that no coefficient is re-typed. :mod:`kreisel.dynamics` (Euler's equations)
and :mod:`kreisel.frames`/:mod:`kreisel.earth` (particles in rotating frames)
both integrate with it.

The right-hand side is passed in as a compiled function
``rhs(t, y, args, dy, offset)`` writing dy/dt into ``dy[offset:offset + y.size]``
(the stages live in one flat array, stage r at ``r·ny``, so no array views are
created in the hot loop); ``args`` is whatever the model needs (a tuple, an
array). Routines that take ``rhs`` are compiled without ``cache=True``: numba
cannot cache a function whose argument is another compiled function (each
process would add a new, never reused entry to ``__pycache__``). Callers make
them cacheable by calling them from a cached kernel with a fixed module-level
``rhs`` (the kernel's cache then holds the whole compiled loop); only
user-supplied callables are compiled per call.

Status codes: 0 success, 1 the step fell below round-off, 2 non-finite state,
4 paused: :func:`integrate_steps` took its budget of steps and returns to
Python (so that a long run can be interrupted and report progress); calling it
again with the same state continues bit for bit as if it had not stopped.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from . import cached, generic, vectorised
from .kernels import SIZE_HIGH, SIZE_LOW, quat_unit

OK, STEP_TOO_SMALL, NOT_FINITE = 0, 1, 2
PAUSED = 4
MESSAGES = {
    STEP_TOO_SMALL: "the adaptive step fell below round-off (the solution is probably singular)",
    NOT_FINITE: "the state became non-finite (step too large or model unbounded)",
}

N_STAGES = 12  # stage 12 is the slope at the new point (first-same-as-last)
N_STAGES_EXTENDED = 16  # three more for the 7th-order interpolant
_LATE = 5  # the extra stages and the interpolant weigh stage 0 and stages from 5 on only (Hairer's tableau)
_SAFETY = 0.9
_MIN_FACTOR = 0.2
_MAX_FACTOR = 10.0
_ERROR_EXPONENT = -1.0 / 8.0
_EPS = 2.220446049250313e-16


_TABLES: list[tuple[NDArray[np.float64], ...]] = []


def tableau() -> tuple[NDArray[np.float64], ...]:
    """Hairer's DOP853 coefficients ``(A, B, C, E3, E5, D)`` as contiguous float arrays (scipy's numbers)."""
    if not _TABLES:
        from scipy.integrate._ivp import dop853_coefficients as scipy_tables

        if (scipy_tables.N_STAGES != N_STAGES or scipy_tables.N_STAGES_EXTENDED != N_STAGES_EXTENDED
                or scipy_tables.INTERPOLATOR_POWER != 7):
            raise RuntimeError("scipy's DOP853 coefficient tables changed layout; kreisel needs 12+4 stages")
        tables = (scipy_tables.A, scipy_tables.B, scipy_tables.C, scipy_tables.E3, scipy_tables.E5, scipy_tables.D)
        if np.any(scipy_tables.A[N_STAGES + 1:, 1:_LATE]) or np.any(scipy_tables.D[:, 1:_LATE]):
            raise RuntimeError("scipy's DOP853 coefficients give stages 2-5 a weight in the dense output; "
                               "kreisel leaves them out")
        _TABLES.append(tuple(np.ascontiguousarray(a, dtype=np.float64) for a in tables))
    return _TABLES[0]


def check_status(status, messages=MESSAGES):
    """Raise ``RuntimeError`` for a failed integration (``status != OK``)."""
    if status != OK:
        raise RuntimeError(f"integration failed: {messages[int(status)]}")


@generic
def _scaled_rms(u, v, c, y, rtol, atol):
    """RMS of (u − c v)/(atol + rtol |y|), without overflowing its squares where the RMS is representable."""
    ny = y.size
    total = 0.0
    for i in range(ny):
        total += ((u[i] - c * v[i]) / (atol[i] + abs(y[i]) * rtol)) ** 2
    if math.isfinite(total):
        return math.sqrt(total / ny)
    # a derivative ~1e154 times the scale of a component (a body or particle far out): ratios divided by
    # the largest before squaring
    big = 0.0
    for i in range(ny):
        big = max(big, abs((u[i] - c * v[i]) / (atol[i] + abs(y[i]) * rtol)))
    total = 0.0
    for i in range(ny):
        total += ((u[i] - c * v[i]) / (atol[i] + abs(y[i]) * rtol) / big) ** 2
    return big * math.sqrt(total / ny)


@generic
def initial_step(rhs, args, t, y, f, span, rtol, atol, tmp, probe):
    """Starting step of Hairer's algorithm (scipy's ``select_initial_step``), at most ``span``."""
    ny = y.size
    d0 = 0.0
    for i in range(ny):
        d0 += (y[i] / (atol[i] + abs(y[i]) * rtol)) ** 2
    d0 = math.sqrt(d0 / ny)
    d1 = _scaled_rms(f, f, 0.0, y, rtol, atol)
    h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
    h0 = min(h0, span)
    if not h0 > 0.0:
        # d1 overflowed (a tiny atol against an order-one slope): no step can meet the tolerance;
        # a zero step makes the integration stop with STEP_TOO_SMALL instead of dividing by it
        return 0.0
    for i in range(ny):
        tmp[i] = y[i] + h0 * f[i]
    rhs(t + h0, tmp, args, probe, 0)
    d2 = _scaled_rms(probe, f, 1.0, y, rtol, atol) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100.0 * h0, h1, span)


@generic
def stages(rhs, args, t, y, h, first, last, tables, k, tmp):
    """Stages ``first … last-1``: k_s = f(t + c_s h, y + h Σ_r a_sr k_r)."""
    A, C = tables[0], tables[2]
    ny = y.size
    for s in range(first, last):
        for i in range(ny):
            acc = 0.0
            for r in range(s):
                acc += A[s, r] * k[r * ny + i]
            tmp[i] = y[i] + h * acc
        rhs(t + C[s] * h, tmp, args, k, s * ny)


@generic
def attempt(rhs, args, t, y, h, tables, k, tmp, y_new):
    """One step of size ``h`` from ``(t, y)`` with ``k[:ny] = f(t, y)``: ``y_new`` and its slope (stage 12)."""
    ny = y.size
    B = tables[1]
    stages(rhs, args, t, y, h, 1, N_STAGES, tables, k, tmp)
    for i in range(ny):
        acc = 0.0
        for r in range(N_STAGES):
            acc += B[r] * k[r * ny + i]
        y_new[i] = y[i] + h * acc
    rhs(t + h, y_new, args, k, N_STAGES * ny)


@cached
def combined_error(e5, e3, h, ny):
    """Hairer's error norm ``h e5/√((e5 + 0.01 e3) ny)`` from the sums of squares of the scaled 5th/3rd-order errors."""
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return h * e5 / math.sqrt((e5 + 0.01 * e3) * ny)


@cached
def error_norm(y, y_new, h, k, E3, E5, rtol, atol):
    """Hairer's combined 5th/3rd-order error estimate, scaled RMS; ``inf`` when not finite."""
    ny = y.size
    # first with big = 1; if the squares overflow (derivatives ~1e154 times the scale of a component),
    # again with every ratio divided by the largest: the same norm, big e5/√(e5 + 0.01 e3) of the ratios
    big = 1.0
    for attempt in range(2):
        e5 = 0.0
        e3 = 0.0
        largest = 0.0
        for i in range(ny):
            scale = (atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol) * big
            a5 = 0.0
            a3 = 0.0
            for r in range(N_STAGES + 1):
                a5 += E5[r] * k[r * ny + i]
                a3 += E3[r] * k[r * ny + i]
            e5 += (a5 / scale) ** 2
            e3 += (a3 / scale) ** 2
            largest = max(largest, abs(a5 / scale), abs(a3 / scale))
        err = combined_error(e5, e3, abs(h) * big, ny)
        if math.isfinite(err) or not 0.0 < largest < np.inf:
            break
        big = largest
    return err if math.isfinite(err) else np.inf


@generic
def too_small(h, t):
    """Whether ``h`` fell below round-off at ``t`` (the integration then stops with ``STEP_TOO_SMALL``)."""
    return h < 10.0 * _EPS * max(abs(t), 1e-300)


@generic
def shrunk(h, err):
    """The step to retry after a rejected step ``h`` with error norm ``err`` ≥ 1."""
    return h * max(_MIN_FACTOR, _SAFETY * err**_ERROR_EXPONENT)


@generic
def next_step(h, err, rejected, clipped, h_natural):
    """The step to try after accepting ``h`` (error norm ``err`` < 1).

    After a rejection in the same step it may not grow; a step shortened
    (``clipped``) only to land on a target time says nothing about the
    natural step ``h_natural`` it was shortened from.
    """
    factor = _MAX_FACTOR if err == 0.0 else min(_MAX_FACTOR, _SAFETY * err**_ERROR_EXPONENT)
    if rejected:
        return h * min(1.0, factor)
    return max(h * factor, h_natural) if clipped else h * factor


@generic
def advance(rhs, args, t, y, h, t_end, max_step, rtol, atol, tables, k, tmp, y_new):
    """One accepted step from ``t`` towards ``t_end`` (never past it), trying ``h`` first.

    Returns ``(status, t_new, h_taken, h_next)``; the new state is in
    ``y_new`` and its slope in stage 12 of ``k``.
    """
    rejected = False
    h = min(h, max_step)
    h_natural = h
    while True:
        if too_small(h, t):
            return STEP_TOO_SMALL, t, 0.0, h
        clipped = t + h >= t_end
        t_new = t_end if clipped else t + h
        h = t_new - t
        attempt(rhs, args, t, y, h, tables, k, tmp, y_new)
        err = error_norm(y, y_new, h, k, tables[3], tables[4], rtol, atol)
        if err < 1.0:
            return OK, t_new, h, next_step(h, err, rejected, clipped, h_natural)
        h = shrunk(h, err)
        rejected = True


@generic
def dense_coefficients(rhs, args, t, y, y_new, h, tables, k, tmp, dense):
    """Three extra stages and the (7, ny) coefficients of the 7th-order interpolant of the last step."""
    ny = y.size
    D = tables[5]
    stages(rhs, args, t, y, h, N_STAGES + 1, N_STAGES_EXTENDED, tables, k, tmp)
    for i in range(ny):
        dy = y_new[i] - y[i]
        dense[0, i] = dy
        dense[1, i] = h * k[i] - dy
        dense[2, i] = 2.0 * dy - h * (k[N_STAGES * ny + i] + k[i])
        for p in range(4):
            acc = 0.0
            for r in range(N_STAGES_EXTENDED):
                acc += D[p, r] * k[r * ny + i]
            dense[3 + p, i] = h * acc


@cached
def interpolated(x, y, d0, d1, d2, d3, d4, d5, d6):
    """One component at the fraction ``x`` ∈ [0, 1] of the last step: ``y`` at its start, ``d`` its column of ``dense``.

    Takes numbers, not arrays: the sample loop of :func:`integrate_steps`
    then hands no array over per sample (a reference count update each).
    """
    u = 1.0 - x
    return ((((((d6 * x + d5) * u + d4) * x + d3) * u + d2) * x + d1) * u + d0) * x + y


@cached
def interpolate(dense, y, x, out):
    """``out`` = the state at the fraction ``x`` ∈ [0, 1] of the step that starts at ``y``."""
    for i in range(y.size):
        out[i] = interpolated(x, y[i], dense[0, i], dense[1, i], dense[2, i], dense[3, i], dense[4, i], dense[5, i],
                              dense[6, i])


# A squared norm inside (_SQUARED_LOW, _SQUARED_HIGH) puts the largest component of a quaternion inside
# (SIZE_LOW, SIZE_HIGH), with a margin for the rounding of the sum, so quat_unit would not rescale it
_SQUARED_LOW = 8.0 * SIZE_LOW**2
_SQUARED_HIGH = 0.5 * SIZE_HIGH**2
#: Samples interpolated together (:func:`interpolate_samples`): its work arrays are (ny + 2, BLOCK).
BLOCK = 64
#: Doubles in one SIMD register (AVX-512); a multiple of it divides :data:`BLOCK`.
LANES = 8


@vectorised
def interpolate_samples(dense, y, y_new, t, t_new, h, count, unit, block):
    """``block[:ny, :count]`` = the states at the times ``block[ny, :count]`` in the last step, ``(t, t_new]`` of size ``h``.

    Sample ``s`` is column ``s``. A sample at the step's end is ``y_new``
    itself. With ``unit >= 0``, the four components from ``unit`` are a
    quaternion, normalised as by :func:`kreisel._compiled.kernels.quat_unit`
    (same bits). ``block`` is a work array of shape ``(ny + 2, BLOCK)``,
    ``count`` at most ``BLOCK``; the caller puts the times in its row ``ny``
    (so that this kernel keeps one signature whatever array of times the
    caller has) and copies the samples out (handed the output, this kernel
    would update its reference count at every step, a count that all the
    threads of a batch share).

    One component at a time over the samples, not one sample at a time: the
    interpolant's and the norm's loops then run over contiguous rows of
    ``block`` and vectorise (SIMD) over the samples. From :data:`LANES`
    samples on they run over a whole number of SIMD registers, the last
    columns padded with the step's end (computed, never copied out): LLVM
    runs the remainder of a vectorised loop one sample at a time, which cost
    a step of about 20 samples 1.6x as much.
    """
    ny = y.size
    # rows of ``block`` indexed in place: a row view per component would cost reference counting per step
    times, x = ny, ny + 1
    padded = count if count < LANES else (count + LANES - 1) // LANES * LANES
    for s in range(count, padded):
        block[times, s] = t_new
    for s in range(padded):
        block[x, s] = (block[times, s] - t) / h
    for i in range(ny):
        y_i, d0, d1, d2, d3, d4, d5, d6 = y[i], dense[0, i], dense[1, i], dense[2, i], dense[3, i], dense[4, i], \
            dense[5, i], dense[6, i]
        for s in range(padded):
            block[i, s] = interpolated(block[x, s], y_i, d0, d1, d2, d3, d4, d5, d6)
    for s in range(count):
        if block[times, s] == t_new:
            for i in range(ny):
                block[i, s] = y_new[i]
    if unit >= 0:
        _normalise(block, unit, x, padded)


@vectorised
def _normalise(block, unit, norm, count):
    """Quaternions in rows ``unit … unit + 3`` of ``block``, columns ``< count``, divided by their norms, as ``quat_unit``.

    Row ``norm`` is work space.
    """
    q0, q1, q2, q3 = unit, unit + 1, unit + 2, unit + 3
    for s in range(count):
        block[norm, s] = block[q0, s] * block[q0, s] + block[q1, s] * block[q1, s] + block[q2, s] * block[q2, s] \
            + block[q3, s] * block[q3, s]
    # every sample in practice; any other goes through quat_unit itself, which rescales it
    outside = 0
    for s in range(count):
        outside += not (_SQUARED_LOW < block[norm, s] < _SQUARED_HIGH)
    if outside:
        for s in range(count):
            block[q0, s], block[q1, s], block[q2, s], block[q3, s] = quat_unit(block[q0, s], block[q1, s],
                                                                               block[q2, s], block[q3, s])
        return
    for s in range(count):
        n = math.sqrt(block[norm, s])
        block[q0, s] /= n
        block[q1, s] /= n
        block[q2, s] /= n
        block[q3, s] /= n


def new_state(y0):
    """The resumable states of :func:`integrate_steps` for initial states ``y0 (..., ny)``.

    Layout ``[t, h, j, y (ny), f(t, y) (ny)]`` along the last axis: ``j`` is
    the next output index, 0 before the first call.
    """
    y0 = np.asarray(y0, dtype=np.float64)
    ny = y0.shape[-1]
    state = np.zeros((*y0.shape[:-1], 3 + 2 * ny))
    state[..., 3:3 + ny] = y0
    return state


@generic
def integrate(rhs, args, t_out, y0, rtol, atol, max_step, tables, out, land_on_outputs):
    """Write the state at every sorted time ``t_out`` (``t_out[0]`` the initial time) into ``out``.

    :func:`integrate_steps` in one call, without a step budget. Returns a status code.
    """
    ny = y0.size
    state = np.zeros(3 + 2 * ny)
    for i in range(ny):
        state[3 + i] = y0[i]
    return integrate_steps(rhs, args, t_out, state, rtol, atol, max_step, tables, out, land_on_outputs,
                           2**62)


@generic
def integrate_steps(rhs, args, t_out, state, rtol, atol, max_step, tables, out, land_on_outputs, budget,
                    unit=-1):
    """Integrate from ``state`` (see :func:`new_state`) for at most ``budget`` accepted steps.

    Writes the state at every sorted time ``t_out`` (``t_out[0]`` the initial
    time) reached into ``out``. Steps are chosen by the error control; output
    times inside a step are filled by the dense output, or, with
    ``land_on_outputs``, every step is shortened to end on the next output
    time (more steps on a fine output grid, no interpolation error). Returns a
    status code: :data:`PAUSED` when the budget ran out before ``t_out[-1]``
    (``state`` then holds where to continue). With ``unit >= 0``, the four
    components from ``unit`` of every sample are a quaternion, stored
    normalised (:func:`kreisel._compiled.kernels.quat_unit`; the state itself
    is left as it is): the samples of a step are interpolated and normalised
    together in a small work array (:func:`interpolate_samples`, SIMD over
    the samples) and then written, not fixed by a second pass over the output.

    The step (:func:`attempt`, as :func:`advance` takes it), the dense
    output (:func:`dense_coefficients`) and the error norm's sums
    (:func:`error_norm`, called only when they overflow) are written out in
    this one loop, a deliberate copy over the work arrays allocated here:
    every array handed to an inlined helper costs reference counting in the
    stage loop, which made it ~1.5x slower (same steps, same bits), and a
    plain call takes a reference to each array argument and gives it back,
    atomic updates that every thread of a batch makes on the one count of a
    shared array (the tables, ``atol``): per step, the error norm's cost
    ~1.3x the dense output's. The interpolation takes work arrays of this
    body only.
    """
    A, B, C, E3, E5, D = tables[0], tables[1], tables[2], tables[3], tables[4], tables[5]
    ny = (state.size - 3) // 2
    n_out = t_out.size
    # the work arrays as views of one allocation: a batch calls this once per body and chunk, often for a
    # single step when every step is stored, and an allocation costs more than a view
    work = np.empty((N_STAGES_EXTENDED + 11) * ny + (ny + 2) * BLOCK)
    k = work[:N_STAGES_EXTENDED * ny]
    y = work[N_STAGES_EXTENDED * ny:(N_STAGES_EXTENDED + 1) * ny]
    y_new = work[(N_STAGES_EXTENDED + 1) * ny:(N_STAGES_EXTENDED + 2) * ny]
    tmp = work[(N_STAGES_EXTENDED + 2) * ny:(N_STAGES_EXTENDED + 3) * ny]
    probe = work[(N_STAGES_EXTENDED + 3) * ny:(N_STAGES_EXTENDED + 4) * ny]
    dense = work[(N_STAGES_EXTENDED + 4) * ny:(N_STAGES_EXTENDED + 11) * ny].reshape((7, ny))
    block = work[(N_STAGES_EXTENDED + 11) * ny:].reshape((ny + 2, BLOCK))
    for i in range(ny):
        y[i] = state[3 + i]
    t_end = t_out[n_out - 1]
    j = int(state[2])
    if j == 0:
        for i in range(ny):
            out[0, i] = y[i]
        if unit >= 0:
            q = quat_unit(out[0, unit], out[0, unit + 1], out[0, unit + 2], out[0, unit + 3])
            for c in range(4):
                out[0, unit + c] = q[c]
        if n_out == 1:
            return OK
        t = t_out[0]
        rhs(t, y, args, k, 0)
        h = initial_step(rhs, args, t, y, k, min(t_end - t, max_step), rtol, atol, tmp, probe)
        j = 1
    else:
        t = state[0]
        h = state[1]
        for i in range(ny):
            k[i] = state[3 + ny + i]
    taken = 0
    while j < n_out:
        if taken >= budget:
            state[0] = t
            state[1] = h
            state[2] = j
            for i in range(ny):
                state[3 + i] = y[i]
                state[3 + ny + i] = k[i]
            return PAUSED
        taken += 1
        target = t_out[j] if land_on_outputs else t_end
        rejected = False
        h = min(h, max_step)
        h_natural = h
        while True:
            if too_small(h, t):
                return STEP_TOO_SMALL
            clipped = t + h >= target
            t_new = target if clipped else t + h
            h = t_new - t
            # attempt() written out (the documented stage copy, see the docstring)
            for s in range(1, N_STAGES):
                for i in range(ny):
                    acc = 0.0
                    for r in range(s):
                        acc += A[s, r] * k[r * ny + i]
                    tmp[i] = y[i] + h * acc
                rhs(t + C[s] * h, tmp, args, k, s * ny)
            for i in range(ny):
                acc = 0.0
                for r in range(N_STAGES):
                    acc += B[r] * k[r * ny + i]
                y_new[i] = y[i] + h * acc
            rhs(t + h, y_new, args, k, N_STAGES * ny)
            # error_norm() written out for the common case, its sums not overflowing (see the docstring)
            e5 = 0.0
            e3 = 0.0
            for i in range(ny):
                scale = atol[i] + max(abs(y[i]), abs(y_new[i])) * rtol
                a5 = 0.0
                a3 = 0.0
                for r in range(N_STAGES + 1):
                    a5 += E5[r] * k[r * ny + i]
                    a3 += E3[r] * k[r * ny + i]
                e5 += (a5 / scale) ** 2
                e3 += (a3 / scale) ** 2
            err = combined_error(e5, e3, abs(h), ny)
            if not math.isfinite(err):
                err = error_norm(y, y_new, h, k, E3, E5, rtol, atol)
            if err < 1.0:
                break
            h = shrunk(h, err)
            rejected = True
        h_taken = h
        h = next_step(h, err, rejected, clipped, h_natural)
        if t_out[j] <= t_new:
            # a sample inside the step needs the interpolant; one at its end is y_new itself (the last sample of
            # an end-state run, every sample of a run that lands on its outputs), which interpolate_samples puts
            # there whatever ``dense`` holds
            if t_out[j] < t_new:
                # dense_coefficients() written out (the documented stage copy, see the docstring)
                # the stages of index 1 … _LATE - 1 have no weight here: left out of the sums (the same bits: each
                # left-out term is ±0, and a sum started from +0.0 is never −0.0)
                for s in range(N_STAGES + 1, N_STAGES_EXTENDED):
                    for i in range(ny):
                        acc = 0.0 + A[s, 0] * k[i]
                        for r in range(_LATE, s):
                            acc += A[s, r] * k[r * ny + i]
                        tmp[i] = y[i] + h_taken * acc
                    rhs(t + C[s] * h_taken, tmp, args, k, s * ny)
                bad = 0
                for i in range(ny):
                    dy = y_new[i] - y[i]
                    dense[0, i] = dy
                    dense[1, i] = h_taken * k[i] - dy
                    dense[2, i] = 2.0 * dy - h_taken * (k[N_STAGES * ny + i] + k[i])
                    # the four sums side by side: each stage value is loaded once, four independent additions
                    a3 = 0.0 + D[0, 0] * k[i]
                    a4 = 0.0 + D[1, 0] * k[i]
                    a5 = 0.0 + D[2, 0] * k[i]
                    a6 = 0.0 + D[3, 0] * k[i]
                    for r in range(_LATE, N_STAGES_EXTENDED):
                        k_r = k[r * ny + i]
                        a3 += D[0, r] * k_r
                        a4 += D[1, r] * k_r
                        a5 += D[2, r] * k_r
                        a6 += D[3, r] * k_r
                    dense[3, i] = h_taken * a3
                    dense[4, i] = h_taken * a4
                    dense[5, i] = h_taken * a5
                    dense[6, i] = h_taken * a6
                    bad += not (math.isfinite(a3) and math.isfinite(a4) and math.isfinite(a5) and math.isfinite(a6))
                # a non-finite extra stage (13-15) shapes the interpolant only, not the accepted step: refused
                # here, or it would come out as a non-finite sample of a run that succeeded
                if bad:
                    return NOT_FINITE
            while j < n_out and t_out[j] <= t_new:
                count = 1
                while count < BLOCK and j + count < n_out and t_out[j + count] <= t_new:
                    count += 1
                for s in range(count):
                    block[ny, s] = t_out[j + s]
                # np.int64: a literal ``unit`` would compile the shared kernel once per value
                interpolate_samples(dense, y, y_new, t, t_new, h_taken, count, np.int64(unit), block)
                for s in range(count):
                    for i in range(ny):
                        out[j + s, i] = block[i, s]
                j += count
        for i in range(ny):
            y[i] = y_new[i]
            k[i] = k[N_STAGES * ny + i]
            if not math.isfinite(y[i]):
                return NOT_FINITE
        t = t_new
    return OK
