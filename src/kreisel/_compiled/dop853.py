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
array). Routines that take ``rhs`` (or a hook) are compiled without
``cache=True``: numba cannot cache a function whose argument is another
compiled function (each process would add a new, never reused entry to
``__pycache__``). Callers make them cacheable by calling them from a cached
kernel with a fixed module-level ``rhs`` (the kernel's cache then holds the
whole compiled loop); only user-supplied callables are compiled per call.

All of it is one resumable driver, :func:`advance`: runs (:class:`Runs`,
any number, one per row) continue where they stopped, through the work
arrays of one run (:class:`Work`), with an event hook that finds the steps
across a crossing and locates it in them. Its status codes: 0 success, 1 the
step fell below round-off, 2 non-finite state, 4 paused: :func:`advance` took
its budget of steps and returns to Python (so that a long run can be
interrupted and report progress), or has no room to record a crossing;
calling it again continues bit for bit as if it had not stopped; 5 stopped
before a step that crosses an end (a landing).
"""

from __future__ import annotations

import math
from collections import namedtuple
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from . import cached, generic, inlined, vectorised
from .kernels import SIZE_HIGH, SIZE_LOW, quat_unit

OK, STEP_TOO_SMALL, NOT_FINITE = 0, 1, 2
PAUSED, STOPPED = 4, 5
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


@cached
def combined_error(e5, e3, h, ny):
    """Hairer's error norm ``h e5/√((e5 + 0.01 e3) ny)`` from the sums of squares of the scaled 5th/3rd-order errors."""
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return h * e5 / math.sqrt((e5 + 0.01 * e3) * ny)


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


@cached
def interpolated(x, y, d0, d1, d2, d3, d4, d5, d6):
    """One component at the fraction ``x`` ∈ [0, 1] of the last step: ``y`` at its start, ``d`` its column of ``dense``.

    Takes numbers, not arrays: the sample loop of :func:`advance`
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


class Runs(NamedTuple):
    """The resumable states of DOP853 runs, one per row: :func:`advance` continues run ``b`` from row ``b``.

    Attributes
    ----------
    t : (n,) ndarray
        Time reached.
    h : (n,) ndarray
        Step to try next.
    sample : (n,) ndarray of int64
        Index of the next output time; 0 before the first call.
    found : (n,) ndarray of int64
        Crossings located and recorded so far.
    y : (n, ny) ndarray
        State at ``t``.
    f : (n, ny) ndarray
        Its slope f(t, y).
    """

    t: NDArray[np.float64]
    h: NDArray[np.float64]
    sample: NDArray[np.int64]
    found: NDArray[np.int64]
    y: NDArray[np.float64]
    f: NDArray[np.float64]


@cached
def new_runs(y0: NDArray[np.float64]) -> Runs:
    """Runs that start from the rows of ``y0 (n, ny)``, not yet started (see :class:`Runs`)."""
    n = y0.shape[0]
    return Runs(np.zeros(n), np.zeros(n), np.zeros(n, dtype=np.int64), np.zeros(n, dtype=np.int64), y0.copy(),
                np.zeros_like(y0))


class Work(namedtuple("Work", "k y y_new tmp probe dense block")):
    """The work arrays of one run of :func:`advance` (:func:`new_work`): what a step leaves behind.

    Attributes
    ----------
    k : (16 ny,) ndarray
        The stages, stage ``r`` at ``r·ny``; stage 0 is the slope at the step's start, stage 12 at its end.
    y, y_new : (ny,) ndarray
        The state at the start and at the end of the step.
    tmp, probe : (ny,) ndarray
        Stage points; interpolated states.
    dense : (7, ny) ndarray
        Coefficients of the 7th-order interpolant of the step.
    block : (ny + 2, BLOCK) ndarray
        Samples interpolated together (:func:`interpolate_samples`).
    """

    __slots__ = ()


@cached
def new_work(ny):
    """:class:`Work` for states of ``ny`` components."""
    # views of one allocation: a batch makes one per body and chunk, often for a single step when every step
    # is stored, and an allocation costs more than a view
    work = np.empty((N_STAGES_EXTENDED + 11) * ny + (ny + 2) * BLOCK)
    ends = np.cumsum(np.array([N_STAGES_EXTENDED * ny, ny, ny, ny, ny, 7 * ny]))
    return Work(work[:ends[0]], work[ends[0]:ends[1]], work[ends[1]:ends[2]], work[ends[2]:ends[3]],
                work[ends[3]:ends[4]], work[ends[4]:ends[5]].reshape((7, ny)), work[ends[5]:].reshape((ny + 2, BLOCK)))


#: What a step crosses, as a crossing hook of :func:`advance` tells: nothing; a crossing to locate and record;
#: the end of the run (before the step); a step to retry at half its length.
ONWARD, LOCATE, STOP, RETRY = 0, 1, 2, 3


@inlined
def no_crossing(marks, t, y, t_new, y_new):
    """The crossing hook of a run without events: every step goes on."""
    return ONWARD


@inlined
def no_record(marks, n, t, y):
    """The record hook of a run without events (never called)."""
    return False


# inlined: a cached kernel would be compiled for each type of ``b`` (a literal, a prange index)
@generic
def _keep(runs, b, t, h, j, found, y, f):
    """Store a run's point in row ``b`` of ``runs``: from there :func:`advance` continues."""
    runs.t[b], runs.h[b], runs.sample[b], runs.found[b] = t, h, j, found
    for i in range(y.size):
        runs.y[b, i] = y[i]
        runs.f[b, i] = f[i]


@generic
def advance(rhs, args, crossing, record, marks, t_out, runs, b, work, rtol, atol, max_step, tables, out,
            land_on_outputs, budget, unit, adaptive):
    """Continue run ``b`` of ``runs`` for at most ``budget`` accepted steps: the one DOP853 driver.

    Writes the state at every sorted time ``t_out`` (``t_out[0]`` the initial
    time) reached into ``out``. Steps are chosen by the error control; output
    times inside a step are filled by the dense output, or, with
    ``land_on_outputs``, every step is shortened to end on the next output
    time (more steps on a fine output grid, no interpolation error). With
    ``unit >= 0``, the four components from ``unit`` of every sample are a
    quaternion, stored normalised (:func:`kreisel._compiled.kernels.quat_unit`;
    the state itself is left as it is): the samples of a step are
    interpolated and normalised together in a small work array
    (:func:`interpolate_samples`, SIMD over the samples) and then written,
    not fixed by a second pass over the output.

    Events: every step that passes the error control is shown to
    ``crossing(marks, t, y, t_new, y_new)``, which returns what it crosses:
    :data:`ONWARD`, nothing; :data:`LOCATE`, a crossing, located by bisection
    on the dense output with the same hook (crossed by the point ``(t_m,
    y_m)`` inside the step unless it returns :data:`ONWARD` for ``(t, y, t_m,
    y_m)``) and stored by ``record(marks, n, t_c, y_c)`` as crossing number
    ``n``, which returns False when it has no room (the run then pauses
    before the step); :data:`STOP`, the run ends before the step (status
    :data:`STOPPED`; its end stays in ``work``); :data:`RETRY`, the step is
    taken again at half its length.

    Returns a status code: :data:`PAUSED` when the budget ran out before
    ``t_out[-1]``. ``runs`` then holds where to continue, and calling again
    continues bit for bit as if the run had not stopped; at the end, it holds
    the last point. With ``adaptive`` False, one step of exactly
    ``runs.h[b]`` (of either sign) is taken from the run's point without
    error control, the run left where it is and the step's end in ``work``
    (Newton's method on the length of a step, :func:`step_exactly`).

    Everything a step does is written out in this one loop, over the work
    arrays taken out of ``work`` once: every array handed to a helper (even
    an inlined one) costs reference counting per step, atomic updates that
    every thread of a batch makes on the one count of a shared array (the
    tables, ``atol``).
    """
    A, B, C, E3, E5, D = tables[0], tables[1], tables[2], tables[3], tables[4], tables[5]
    k, y, y_new, tmp, probe, dense, block = work.k, work.y, work.y_new, work.tmp, work.probe, work.dense, work.block
    ny = y.size
    n_out = t_out.size
    for i in range(ny):
        y[i] = runs.y[b, i]
    t_end = t_out[n_out - 1]
    j = runs.sample[b]
    found = runs.found[b]
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
        t = runs.t[b]
        h = runs.h[b]
        for i in range(ny):
            k[i] = runs.f[b, i]
    taken = 0
    while j < n_out:
        if taken >= budget:
            _keep(runs, b, t, h, j, found, y, k)
            return PAUSED
        taken += 1
        target = t_out[j] if land_on_outputs else t_end
        h_start = h
        rejected = False
        h = min(h, max_step)
        h_natural = h
        while True:
            if adaptive:
                if too_small(h, t):
                    return STEP_TOO_SMALL
                clipped = t + h >= target
                t_new = target if clipped else t + h
                h = t_new - t
            else:
                t_new = t + h
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
            if not adaptive:
                return OK
            # Hairer's combined 5th/3rd-order error estimate, scaled RMS; first with big = 1, and if the squares
            # overflow (derivatives ~1e154 times the scale of a component) again with every ratio divided by the
            # largest: the same norm, big e5/√(e5 + 0.01 e3) of the ratios
            big = 1.0
            for _ in range(2):
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
            if not math.isfinite(err):
                err = np.inf
            if err < 1.0:
                event = crossing(marks, t, y, t_new, y_new)
                if event != RETRY:
                    break
                h = 0.5 * h
                rejected = False
                h_natural = h
            else:
                h = shrunk(h, err)
                rejected = True
        if event == STOP:
            _keep(runs, b, t, h_start, j, found, y, k)
            return STOPPED
        h_taken = h
        h = next_step(h, err, rejected, clipped, h_natural)
        # a sample at the step's end is y_new itself (the last sample of an end-state run, every sample of a
        # run that lands on its outputs), which interpolate_samples puts there whatever ``dense`` holds
        if event == LOCATE or t_out[j] < t_new:
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
            # here, or it would come out as a non-finite sample (or crossing) of a run that succeeded
            if bad:
                return NOT_FINITE
        if event == LOCATE:
            lo, hi = 0.0, 1.0
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                interpolate(dense, y, mid, probe)
                if crossing(marks, t, y, t + mid * h_taken, probe) == ONWARD:
                    lo = mid
                else:
                    hi = mid
            interpolate(dense, y, 0.5 * (lo + hi), probe)
            if not record(marks, found, t + 0.5 * (lo + hi) * h_taken, probe):
                _keep(runs, b, t, h_start, j, found, y, k)
                return PAUSED
            found += 1
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
    _keep(runs, b, t, h, j, found, y, k)
    return OK


@generic
def step_exactly(rhs, args, t_out, runs, b, work, tables):
    """One DOP853 step of exactly ``runs.h[b]`` (of either sign) from the point of run ``b``, without error control.

    Its end is left in ``work`` (``y_new``, its slope in stage 12 of ``k``),
    the run where it is: Newton's method on the length of the step across an
    event. ``t_out`` is the run's (only its length is read).
    """
    return advance(rhs, args, no_crossing, no_record, None, t_out, runs, b, work, 0.0, work.y, np.inf, tables,
                   work.dense, False, 1, -1, False)


@generic
def integrate(rhs, args, t_out, y0, rtol, atol, max_step, tables, out, land_on_outputs):
    """Write the state at every sorted time ``t_out`` (``t_out[0]`` the initial time) into ``out``.

    :func:`advance` of one run from ``y0`` in one call, without a step budget
    or events. Returns a status code.
    """
    return advance(rhs, args, no_crossing, no_record, None, t_out, new_runs(y0.reshape((1, y0.size))), 0,
                   new_work(y0.size), rtol, atol, max_step, tables, out, land_on_outputs, 2**62, -1, True)
