"""Scaffolding shared by the ``bench/bench_<topic>.py`` scripts and ``bench/run_all.py``.

The scripts run as ``python bench/bench_<topic>.py``, so this folder is on
``sys.path`` and they ``import _common`` (or ``from _common import ...``).

Stable API (names, signatures and return types are kept; additions only):

``Timing``
    Frozen dataclass of one timed function: ``median`` and ``best`` wall
    seconds, ``cpu_median`` process CPU seconds (all threads), ``times``
    (the wall times, in run order) and ``result`` (what the last timed call
    returned).
``time_runs(fn, repeats=5, *, warmup=True) -> Timing``
    Calls ``fn()`` once untimed when ``warmup`` (numba compilation or cache
    load, first-touch of buffers), then ``repeats`` timed calls.
``median_time(fn, repeats=5, *, warmup=True) -> float``
    ``time_runs(...).median``.
``interleaved(*fns, repeats=5, warmup=True) -> list[Timing]``
    Times several functions in alternation (a, b, c, a, b, c, ...): on a
    shared machine the load drifts within seconds, and alternating gives
    every function the same conditions. ``warmup`` is a bool (all or none)
    or a sequence of bools, one per function.
``streaming_copy(n_in, n_out) -> callable``
    A run that copies ``n_in`` doubles and ``n_out`` doubles between
    preallocated buffers: the least memory traffic of an operation that
    reads ``n_in`` and writes ``n_out`` doubles (the "copy bound").
``load_average() -> str``
    ``"1.2/0.9/0.8"`` (1/5/15 min) or ``"n/a"`` where the OS has none.
``versions() -> str``
    ``"kreisel …, numpy …, scipy …, numba …"``.
``machine() -> str``
    ``"x86_64, 2 cores, Python 3.12.3"``.
``header(title=None, *notes, load_before=None) -> list[str]``
    Markdown lines: ``# title`` (if given), the ``notes`` (one line each),
    then one line naming machine, versions, numba threads and the load
    average before (``load_before``, a ``load_average()`` string taken when
    the measurements started; omitted if None) and now, followed by a blank
    line.
``markdown_table(columns, rows, align=None) -> list[str]``
    Lines of a markdown table. ``rows`` hold already formatted cells (any
    object is passed through ``str``); ``align`` is a string with one of
    ``"l"``, ``"r"``, ``"c"`` or ``"-"`` (unspecified) per column, or None for
    all unspecified.
``table_section(title, notes, columns, rows, align=None, *, load_before=None) -> list[str]``
    ``header(title, *notes, load_before=load_before)`` followed by
    ``markdown_table(columns, rows, align)``: the usual results section.
``write_results(topic, text, *, echo=True) -> pathlib.Path``
    Writes ``text`` (newline-terminated) to ``bench/results/<topic>.md``
    atomically (temporary file in the same folder, then ``os.replace``), so
    that ``run_all.py --assemble`` never reads a half-written table. If the
    file already holds the line ``NOTES_MARKER``, that line and everything
    after it (hand-written notes on earlier runs) are kept after the new
    text. Prints ``text`` first when ``echo``.
``atomic_write(path, text) -> pathlib.Path``
    Writes ``text`` to ``path`` through a temporary file in the same folder
    and ``os.replace`` (readers see the old or the new file, never a part).
``RESULTS``
    ``pathlib.Path`` of ``bench/results``.
"""

from __future__ import annotations

import dataclasses
import os
import pathlib
import platform
import tempfile
import time
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
RESULTS = HERE / "results"
NOTES_MARKER = "<!-- notes below are kept when the benchmark rewrites this file -->"


@dataclasses.dataclass(frozen=True)
class Timing:
    """Wall and CPU times of the timed calls of one function."""

    median: float
    best: float
    cpu_median: float
    times: tuple[float, ...]
    result: Any = dataclasses.field(default=None, repr=False, compare=False)


class _Clock:
    """Accumulates wall and CPU times of one function's calls."""

    def __init__(self, fn: Callable[[], Any]):
        self.fn, self.walls, self.cpus, self.result = fn, [], [], None

    def run(self):
        start, start_cpu = time.perf_counter(), time.process_time()
        self.result = self.fn()
        self.walls.append(time.perf_counter() - start)
        self.cpus.append(time.process_time() - start_cpu)

    def timing(self) -> Timing:
        return Timing(float(np.median(self.walls)), float(min(self.walls)), float(np.median(self.cpus)),
                      tuple(self.walls), self.result)


def interleaved(*fns: Callable[[], Any], repeats: int = 5, warmup: bool | Sequence[bool] = True) -> list[Timing]:
    """Time ``fns`` in alternation, ``repeats`` rounds, after optional untimed warm-up calls."""
    if repeats < 1:
        raise ValueError(f"repeats must be at least 1, got {repeats}")
    warm = [warmup] * len(fns) if isinstance(warmup, bool) else list(warmup)
    if len(warm) != len(fns):
        raise ValueError(f"warmup must be a bool or one bool per function ({len(fns)}), got {len(warm)}")
    for fn, w in zip(fns, warm):
        if w:
            fn()
    clocks = [_Clock(fn) for fn in fns]
    for _ in range(repeats):
        for clock in clocks:
            clock.run()
    return [clock.timing() for clock in clocks]


def time_runs(fn: Callable[[], Any], repeats: int = 5, *, warmup: bool = True) -> Timing:
    """Median and best of ``repeats`` timed calls of ``fn()``, after an untimed one if ``warmup``."""
    return interleaved(fn, repeats=repeats, warmup=warmup)[0]


def median_time(fn: Callable[[], Any], repeats: int = 5, *, warmup: bool = True) -> float:
    """Median wall time of ``repeats`` calls of ``fn()``, after an untimed one if ``warmup``."""
    return time_runs(fn, repeats, warmup=warmup).median


def streaming_copy(n_in: int, n_out: int) -> Callable[[], None]:
    """A run that streams ``n_in`` doubles in and ``n_out`` doubles out (two copies)."""
    src_in, dst_in = np.random.rand(n_in), np.empty(n_in)
    src_out, dst_out = np.random.rand(n_out), np.empty(n_out)

    def run():
        np.copyto(dst_in, src_in)
        np.copyto(dst_out, src_out)

    return run


def load_average() -> str:
    """The 1/5/15-minute load averages as ``"a/b/c"``, or ``"n/a"``."""
    if not hasattr(os, "getloadavg"):
        return "n/a"
    return "/".join(f"{x:.1f}" for x in os.getloadavg())


def versions() -> str:
    """Versions of kreisel and of the libraries the benchmarks compare or compile with."""
    import numba
    import scipy

    import kreisel

    kreisel_version = getattr(kreisel, "__version__", None)
    if kreisel_version is None:
        from importlib.metadata import version

        kreisel_version = version("kreisel")
    return f"kreisel {kreisel_version}, numpy {np.__version__}, scipy {scipy.__version__}, numba {numba.__version__}"


def machine() -> str:
    """Architecture, core count and Python version."""
    return f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}"


def header(title: str | None = None, *notes: str, load_before: str | None = None) -> list[str]:
    """Title, notes and the machine / versions / load line of a results file."""
    import numba

    load = f"before: {load_before}, after: {load_average()}" if load_before is not None else f"now: {load_average()}"
    lines = [f"# {title}", ""] if title else []
    lines += list(notes)
    one_minute = [float(x.split("/")[0]) for x in (load_before, load_average()) if x and x != "n/a"]
    busy = bool(one_minute) and max(one_minute) > os.cpu_count()
    note = "above the core count: other jobs shared the CPUs" if busy else "below the core count: a quiet machine"
    lines.append(f"{machine()}; {versions()}; numba threads {numba.get_num_threads()}. "
                 f"Load average (1/5/15 min) {load} ({note}).")
    return lines + [""]


def markdown_table(columns: Sequence[str], rows: Sequence[Sequence[Any]], align: str | None = None) -> list[str]:
    """Lines of a markdown table with ``columns`` as header and preformatted ``rows``."""
    align = align or "-" * len(columns)
    rules = {"-": "---", "l": ":---", "r": "---:", "c": ":---:"}
    if len(align) != len(columns) or set(align) - set(rules):
        raise ValueError(f"align must have one of {''.join(rules)} per column ({len(columns)}), got {align!r}")
    for row in rows:
        if len(row) != len(columns):
            raise ValueError(f"every row must have {len(columns)} cells, got {len(row)}: {row!r}")
    lines = ["| " + " | ".join(columns) + " |", "|" + "|".join(rules[a] for a in align) + "|"]
    return lines + ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]


def table_section(title: str | None, notes: Sequence[str], columns: Sequence[str], rows: Sequence[Sequence[Any]],
                  align: str | None = None, *, load_before: str | None = None) -> list[str]:
    """``header`` (title, notes, machine and load) followed by the markdown table of ``rows``."""
    return header(title, *notes, load_before=load_before) + markdown_table(columns, rows, align)


def write_results(topic: str, text: str, *, echo: bool = True) -> pathlib.Path:
    """Write ``text`` to ``bench/results/<topic>.md`` atomically, keeping notes after ``NOTES_MARKER``."""
    if echo:
        print(text)
    RESULTS.mkdir(parents=True, exist_ok=True)
    path = RESULTS / f"{topic}.md"
    text = text.rstrip("\n") + "\n"
    if path.is_file():
        old = path.read_text(encoding="utf-8")
        at = old.find(NOTES_MARKER)
        if at >= 0:
            text += "\n" + old[at:].rstrip("\n") + "\n"
    return atomic_write(path, text)


def atomic_write(path: pathlib.Path, text: str) -> pathlib.Path:
    """Replace ``path`` by a file holding ``text`` in one step (temporary file, then ``os.replace``)."""
    path = pathlib.Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".tmp", dir=path.parent)
    try:
        os.fchmod(fd, 0o644)  # mkstemp's 0600 would make the file private
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise
    return path
