"""kreisel's multi-core loops on a busy machine: its thread choice against numba's count, one thread and scipy.

Every multi-core loop of kreisel runs on numba's thread count, or on fewer
threads while the machine has more runnable tasks than cores
(``kreisel._compiled.threads``). This script times, in one process and in
alternation (in a shuffled order each round), kreisel as it is, kreisel always on numba's count (the choice
switched off, as before it existed), kreisel on one thread
(``numba.set_num_threads(1)``) and scipy, for 10^6-rotation operations and
one batch simulation: first on the machine as it is, then with ``2 × cores``
busy processes started by this script (each ends itself after
``BUSY_SECONDS``, and all are killed when the timing is done). The ratios
are the other runs' times over kreisel's: above 1 means kreisel is faster.
Writes ``bench/results/threads.md`` (notes after the ``_common.NOTES_MARKER``
line are kept).

Usage: ``python bench/bench_threads.py [repeats]`` (default 9).
"""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import time

import numba
import numpy as np
from _common import interleaved, load_average, table_section, write_results
from scipy.spatial.transform import Rotation as S

import kreisel as kr
from kreisel._compiled import threads

N = 1_000_000
BODIES = 2000
#: Timed runs of the batch simulation (each about 0.05 s on a quiet machine, several times that on a busy one).
BATCH_REPEATS = 3
#: Longest life of a busy process, should this script die before it kills them.
BUSY_SECONDS = 40


def _cases(rng):
    """name, kreisel run, scipy run or None."""
    q = rng.normal(size=(N, 4))
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    raw = 2.0 * rng.normal(size=(N, 4))
    last = lambda x: np.ascontiguousarray(x[:, [1, 2, 3, 0]])  # noqa: E731
    sq, raw_last = S.from_quat(last(q)), last(raw)
    moments = np.empty((BODIES, 3))
    moments[:, :2] = [1.0, 2.0] * (1.0 + 0.1 * rng.random((BODIES, 2)))
    moments[:, 2] = 0.95 * (moments[:, 0] + moments[:, 1])
    omega0 = np.array([0.1, 1.0, 0.1]) + 0.05 * rng.normal(size=(BODIES, 3))
    return [
        ("inverse", lambda: kr.quat_inverse(q), lambda: sq.inv()),
        ("normalisation", lambda: kr.quat_normalize(raw), lambda: S.from_quat(raw_last)),
        (f"simulate_batch, {BODIES} bodies, rk4, 1000 steps, end state",
         lambda: kr.simulate_batch(moments, [0.0, 10.0], omega0, method="rk4", dt=0.01), None),
    ]


def _numba_count(run):
    """``run`` with kreisel's thread choice switched off: every loop on numba's count."""
    def fixed():
        threads.ADAPTIVE = False
        try:
            return run()
        finally:
            threads.ADAPTIVE = True
    return fixed


def _one_thread(run):
    def one():
        configured = numba.get_num_threads()
        numba.set_num_threads(1)
        try:
            return run()
        finally:
            numba.set_num_threads(configured)
    return one


@contextlib.contextmanager
def _busy(count):
    """``count`` processes spinning on a core each, killed on exit (and ending themselves after BUSY_SECONDS)."""
    spin = f"import time\nend = time.monotonic() + {BUSY_SECONDS}\nwhile time.monotonic() < end:\n    pass\n"
    processes = [subprocess.Popen([sys.executable, "-c", spin]) for _ in range(count)]
    try:
        time.sleep(0.5)
        yield
    finally:
        for process in processes:
            process.kill()
        for process in processes:
            process.wait()


def _rounds(runs, repeats):
    """(median wall, median CPU) of each run over ``repeats`` rounds, each round in a shuffled order.

    On a busy machine a run that follows one which slept (a two-thread loop
    waiting at its end for a descheduled thread) starts with the scheduler's
    credit for that sleep and is rarely preempted, while one that follows a
    busy run is: a fixed or rotated order would favour whatever run follows
    the sleeper.
    """
    walls, cpus = [[] for _ in runs], [[] for _ in runs]
    shuffle = np.random.default_rng(0)
    for r in range(repeats):
        order = shuffle.permutation(len(runs))
        for i, timing in zip(order, interleaved(*(runs[i] for i in order), repeats=1, warmup=r == 0)):
            walls[i].append(timing.median)
            cpus[i].append(timing.cpu_median)
    return [(float(np.median(w)), float(np.median(c))) for w, c in zip(walls, cpus)]


def _ms(t):
    return f"{t * 1e3:.2f}"


def _rows(cases, label, repeats):
    rows = []
    for name, ours, scipy_run in cases:
        runs = [ours, _numba_count(ours), _one_thread(ours)] + ([scipy_run] if scipy_run else [])
        (ours_wall, ours_cpu), (fixed_wall, fixed_cpu), (one_wall, _), *peer = _rounds(
            runs, repeats if scipy_run else BATCH_REPEATS)
        scipy_cells = [_ms(peer[0][0]), f"{peer[0][0] / ours_wall:.1f}×"] if peer else ["", ""]
        rows.append([
            name, label, _ms(ours_wall), *scipy_cells, _ms(fixed_wall), f"{fixed_wall / ours_wall:.2f}", _ms(one_wall),
            f"{one_wall / ours_wall:.2f}", f"{ours_cpu / ours_wall:.1f}", f"{fixed_cpu / fixed_wall:.1f}",
        ])
        print(" | ".join(rows[-1]), flush=True)
    return rows


def main(repeats=9):
    cases = _cases(np.random.default_rng(0))
    load_before = load_average()
    busy = 2 * (os.cpu_count() or 1)
    rows = _rows(cases, "as it is", repeats)
    with _busy(busy):
        rows += _rows(cases, f"+{busy} busy processes", repeats)
    lines = table_section(
        "kreisel's multi-core loops on a busy machine",
        [f"Medians of {repeats} rounds ({BATCH_REPEATS} for the batch simulation) of runs taken in alternation in one "
         "process, in a shuffled order each round, in ms: kreisel "
         "as it is (numba's thread count, fewer while more tasks are runnable than there are cores), kreisel always on "
         "numba's count (`KREISEL_ADAPTIVE_THREADS=0`), kreisel on one thread (`numba.set_num_threads(1)`) and scipy "
         "(one thread), on 10^6 rotations; first on the machine as it is, then with busy processes (one spinning "
         "Python each) started by the benchmark. Ratios are the other run's time over kreisel's (above 1: kreisel is "
         "faster)."],
        ["operation", "machine", "kreisel", "scipy", "vs scipy", "numba's count", "numba's count / kreisel",
         "one thread", "one thread / kreisel", "kreisel CPU / wall", "numba's count CPU / wall"],
        rows, "ll" + "r" * 9, load_before=load_before,
    )
    write_results("threads", "\n".join(lines))


if __name__ == "__main__":
    main(*map(int, sys.argv[1:2]))
