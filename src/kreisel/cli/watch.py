"""How long a run will take, measured while it runs: progress for a long one, a refusal for one far too long.

A long run reports the fraction of its time span done after each compiled
chunk (:mod:`kreisel._compiled.chunks`, about 20 a second). From the second
report on, :class:`RunWatch` knows the speed of this run on this machine —
the steps the integrator took per second of computing times the span each
step covered — without the compile time of the first chunk, and so the time
the rest needs. A run estimated to need more than :data:`SHOW_AFTER` seconds
shows a progress bar on a terminal (one line of estimate elsewhere); one
estimated over :data:`REFUSE_AFTER` seconds is stopped with
:class:`RunTooLong` unless forced.
"""

from __future__ import annotations

import time

from ._output import note, progress

__all__ = ["RunTooLong", "RunWatch", "SHOW_AFTER", "REFUSE_AFTER", "MEASURE", "duration"]

#: A run estimated to need longer than this (seconds) shows its progress.
SHOW_AFTER = 2.0
#: A run estimated to need longer than this (seconds) is refused unless forced.
REFUSE_AFTER = 600.0
#: Computing time (seconds, after the first report) over which the speed is measured before judging the run.
MEASURE = 0.3


class RunTooLong(Exception):
    """A run stopped because the rest would take longer than :data:`REFUSE_AFTER` (``seconds``, estimated).

    It was estimated from ``fraction`` of the run's time span done in ``elapsed`` seconds.
    """

    def __init__(self, seconds, fraction, elapsed):
        self.seconds, self.fraction, self.elapsed = seconds, fraction, elapsed
        super().__init__(f"the run needs about {duration(seconds)} of computing (it covered {fraction:.2g} of "
                         f"its time span in {elapsed:.2g} s), over the {duration(REFUSE_AFTER)} kreisel runs unasked")


def duration(seconds):
    """A rough duration in the largest fitting unit.

    Examples
    --------
    >>> duration(42.0), duration(600.0), duration(3.2e6)
    ('42 s', '10 min', '37 days')
    """
    for unit, size in (("years", 3.15576e7), ("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= size:
            return f"{seconds / size:.2g} {unit}"
    return f"{seconds:.2g} s"


class RunWatch:
    """The ``progress(fraction)`` callback of a run: measures it, shows its progress, refuses it if far too long.

    Use it as a context manager around the run (the progress bar is removed
    at the end). ``force``: never refuse.

    Examples
    --------
    >>> clock = iter([1.0, 2.0])
    >>> watch = RunWatch("simulating", clock=lambda: next(clock))
    >>> with watch:
    ...     watch(1e-6)          # the first report: the compile time is behind
    ...     watch(2e-6)          # a millionth of the span a second
    Traceback (most recent call last):
        ...
    kreisel.cli.watch.RunTooLong: the run needs about 12 days of computing (it covered 1e-06 of its time span in 1 s), over the 10 min kreisel runs unasked
    """

    def __init__(self, description, force=False, clock=time.perf_counter):
        self.description, self.force, self.clock = description, force, clock
        self.first = None
        self.bar = self.task = None
        self.shown = False

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.bar is not None:
            self.bar.stop()

    def __call__(self, fraction):
        now = self.clock()
        if self.first is None:
            self.first = (now, fraction)
            return
        since, done = now - self.first[0], fraction - self.first[1]
        if since < MEASURE or done <= 0.0:
            return
        remaining = (1.0 - fraction) * since / done
        if remaining > REFUSE_AFTER and not self.force:
            raise RunTooLong(remaining, done, since)
        if not self.shown and remaining > SHOW_AFTER:
            self.shown = True
            self.bar = progress()
            if self.bar is None:
                note(f"{self.description}: about {duration(remaining)} to go")
            else:
                self.bar.start()
                self.task = self.bar.add_task(self.description, total=1.0)
        if self.bar is not None:
            self.bar.update(self.task, completed=fraction)
