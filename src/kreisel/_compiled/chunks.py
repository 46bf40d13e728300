"""Long integrations in chunks: interruptible by Ctrl-C, bounded by a step budget, reporting progress.

A compiled loop does not return to Python by itself, so neither Ctrl-C nor a
budget check can reach it. Every integrator of kreisel that may run long
(:mod:`kreisel.dynamics`, :mod:`kreisel.frames`, :mod:`kreisel.earth`) is
therefore written as a resumable ``step(budget)`` that takes at most
``budget`` steps and :func:`run_chunked` calls it until it is done: between
two calls a pending Ctrl-C raises ``KeyboardInterrupt``, the step budget
``max_steps`` is enforced and ``progress`` is told how far the run got. A
chunk lasts about :data:`CHUNK_SECONDS`; its length adapts to the measured
speed, and results never depend on it (a resumed loop continues bit for bit).
"""

from __future__ import annotations

import contextlib
import signal
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np


__all__ = ["MAX_STEPS", "CHUNK_SECONDS", "SAMPLES_PER_CALL", "StepBudgetExceeded", "check_max_steps", "compile_ahead",
           "interrupts_between_chunks", "run_chunked", "run_resumable"]

#: Default step budget of a run: about an hour of the slowest compiled method.
MAX_STEPS = 10**10
#: A chunk returns to Python after about this long (checks for Ctrl-C, reports progress).
CHUNK_SECONDS = 0.05
#: Samples per compiled call of the exact solutions (a few µs each): Ctrl-C takes effect between calls.
SAMPLES_PER_CALL = 2**15


class StepBudgetExceeded(RuntimeError):
    """A run that took its budget of ``max_steps`` steps before reaching its end time ``t_reached``."""

    def __init__(self, max_steps: int, t_reached: float, t_end: float) -> None:
        super().__init__(f"integration stopped after max_steps = {max_steps} steps at t = {t_reached:.6g} of "
                         f"{t_end:.6g} (pass a larger max_steps to go on)")
        self.max_steps, self.t_reached, self.t_end = max_steps, t_reached, t_end


def check_max_steps(max_steps: object) -> int:
    """``max_steps`` as a positive int (``None``: :data:`MAX_STEPS`); TypeError/ValueError naming it."""
    if max_steps is None:
        return MAX_STEPS
    if isinstance(max_steps, bool) or not isinstance(max_steps, (int, np.integer)):
        raise TypeError(f"max_steps must be a positive integer, got {type(max_steps).__name__}")
    if max_steps < 1:
        raise ValueError(f"max_steps must be a positive integer, got {max_steps}")
    return int(max_steps)


def compile_ahead(function: Any, *args: Any) -> None:
    """Compile (or load from the cache) the compiled ``function`` for the types of ``args``, without calling it.

    Called before :func:`run_chunked`: a first call's compile takes up to a minute with an empty
    cache, and inside the loop that holds back Ctrl-C it could not be interrupted.

    Examples
    --------
    >>> from numba import njit
    >>> twice = njit(lambda x: 2.0 * x)
    >>> compile_ahead(twice, 1.5)
    >>> [str(types) for types in twice.signatures]
    ['(float64,)']
    """
    from numba import typeof

    function.compile(tuple(typeof(a) for a in args))


@contextlib.contextmanager
def interrupts_between_chunks() -> Iterator[list[int]]:
    """Hold back Ctrl-C during a chunk; yields a list that records it (raise it between chunks).

    A ``KeyboardInterrupt`` raised while a Python callable runs inside a
    compiled loop would reach numba's object-mode glue and come out as a
    ``SystemError``; deferring it by at most one chunk keeps it clean. Only
    the main thread can install handlers; elsewhere nothing changes.
    """
    seen: list[int] = []
    if threading.current_thread() is not threading.main_thread() or \
            signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        yield seen
        return
    previous = signal.signal(signal.SIGINT, lambda signum, frame: seen.append(signum))
    try:
        yield seen
    finally:
        signal.signal(signal.SIGINT, previous)


def run_chunked(step: Callable[[int], bool], reached: Callable[[], float], t_end: float, max_steps: int,
                first_budget: int, progress: Callable[[float], object] | None = None) -> None:
    """Call ``step(budget) -> finished`` until it returns True, within ``max_steps`` steps in all.

    ``reached()`` is the time the run has got to (for ``progress`` and for
    :class:`StepBudgetExceeded`, raised when the budget is spent before
    ``t_end``); ``first_budget`` is the length of the first chunk, in steps
    (short when a Python callable, slow per step, is in the loop).

    Examples
    --------
    >>> done = []
    >>> def step(budget):
    ...     done.append(budget)
    ...     return sum(done) >= 10
    >>> run_chunked(step, lambda: sum(done), 10.0, 100, first_budget=4)
    >>> sum(done) >= 10
    True
    >>> run_chunked(lambda budget: False, lambda: 0.5, 10.0, 100, first_budget=4)
    Traceback (most recent call last):
    ...
    kreisel._compiled.chunks.StepBudgetExceeded: integration stopped after max_steps = 100 steps at t = 0.5 of 10 (pass a larger max_steps to go on)
    """
    with interrupts_between_chunks() as interrupted:
        budget = first_budget
        taken = 0
        while True:
            # one step over the budget: a run that needs exactly max_steps steps finishes
            budget = min(budget, max_steps - taken + 1)
            start = time.perf_counter()
            finished = step(budget)
            elapsed = time.perf_counter() - start
            if interrupted:
                raise KeyboardInterrupt
            if finished:
                return
            taken += budget
            if taken > max_steps:
                raise StepBudgetExceeded(max_steps, reached(), t_end)
            if progress is not None:
                progress(reached())
            budget = int(min(8 * budget, max(1.0, budget * CHUNK_SECONDS / max(elapsed, 1e-9))))


def run_resumable(advance: Callable[[Any, int], int], runs: Any, t_end: float, max_steps: int,
                  first_budget: int, paused: int, progress: Callable[[float], object] | None = None) -> int:
    """:func:`run_chunked` for a compiled ``advance(runs, budget) -> status`` that resumes from ``runs``.

    ``runs`` is a :class:`kreisel._compiled.dop853.Runs` of one run (or
    anything whose ``t[0]`` is the time reached); ``advance`` returns
    ``paused`` when it took its budget of steps before the end and any other
    status when it is done, successfully or not; that final status is
    returned.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> def advance(runs, budget):  # a clock that ticks to 10
    ...     runs.t[0] = min(10.0, runs.t[0] + budget)
    ...     return 4 if runs.t[0] < 10.0 else 0
    >>> run_resumable(advance, SimpleNamespace(t=[0.0]), 10.0, 100, 3, paused=4)
    0
    """
    status = [paused]

    def step(budget: int) -> bool:
        status[0] = advance(runs, budget)
        return status[0] != paused

    run_chunked(step, lambda: float(runs.t[0]), t_end, max_steps, first_budget, progress)
    return status[0]
