"""What one viewer server allows: run slots, time and step budgets, request size.

Its own module because both sides use it: :mod:`kreisel.web.runner` enforces the limits from the
parent process, :mod:`kreisel.web.session` bounds the integration steps inside a worker.
"""

from __future__ import annotations

import dataclasses

__all__ = ["Limits"]


@dataclasses.dataclass(frozen=True)
class Limits:
    """What one viewer server allows.

    Attributes
    ----------
    slots : int
        Runs computed at once; further requests wait up to ``queue_seconds`` for a free slot.
    wall_seconds : float
        Wall-clock time of one run, from its start to its last message.
    max_steps : int
        Integration steps one run may take, all its chunks together (about 10 s of the compiled
        integrators; see :class:`kreisel.web.session.Solver`).
    queue_seconds : float
        How long a request waits for a free slot before it is refused (503).
    grace_seconds : float
        How long a worker may take to stop between two chunks before its process is ended.
    max_body : int
        Largest request body (HTTP) or request message (WebSocket), bytes.

    Examples
    --------
    >>> Limits(slots=1).wall_seconds
    120.0
    """

    slots: int = 2
    wall_seconds: float = 120.0
    max_steps: int = 5_000_000
    queue_seconds: float = 10.0
    grace_seconds: float = 1.0
    max_body: int = 1_000_000

    def __post_init__(self):
        if not isinstance(self.slots, int) or self.slots < 1:
            raise ValueError(f"limits.slots must be an integer >= 1, got {self.slots!r}")
        for name in ("wall_seconds", "queue_seconds", "grace_seconds"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or not 0 < value < float("inf"):
                raise ValueError(f"limits.{name} must be a positive number of seconds, got {value!r}")
        if not isinstance(self.max_steps, int) or isinstance(self.max_steps, bool) or self.max_steps < 1:
            raise ValueError(f"limits.max_steps must be an integer >= 1, got {self.max_steps!r}")
        if not isinstance(self.max_body, int) or self.max_body < 1024:
            raise ValueError(f"limits.max_body must be an integer >= 1024 bytes, got {self.max_body!r}")
