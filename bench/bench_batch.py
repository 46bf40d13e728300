"""Dense output of ``simulate_batch``: every step stored, against the end state only and the copy bound.

Many free bodies (default 20,000) integrated over 1000 steps; ``simulate_batch`` returns either the
end state only (``t = [0, T]``) or every step (1001 samples, 56 bytes each: ω′ and q), or every 10th
sample (``every=10``: the same steps, a tenth of the memory). The copy bound is the cost of writing
the dense output's bytes: ``np.copyto`` into an output allocated per run, as a dense run's result is.
All runs of one method are timed in alternation in this process, so the ratios compare like with
like on a shared machine; the excess of the dense run over the end-state run is what storing the
samples costs, and the goal is an excess within 2× of the copy bound.

Usage: ``python bench/bench_batch.py [bodies] [repeats]`` (defaults 20000 and 3).
"""

from __future__ import annotations

import sys

import numpy as np
from _common import header, interleaved, load_average, markdown_table, write_results

import kreisel as kr

METHODS = ("splitting", "splitting4", "rk4", "dop853")
STEPS, T_END, EVERY = 1000, 10.0, 10


def bodies_and_rates(count):
    """``count`` physical bodies around I = (1, 2, 2.85) spinning near the intermediate axis."""
    rng = np.random.default_rng(0)
    moments = np.empty((count, 3))
    moments[:, :2] = [1.0, 2.0] * (1.0 + 0.1 * rng.random((count, 2)))
    moments[:, 2] = 0.95 * (moments[:, 0] + moments[:, 1])
    return moments, np.array([0.1, 1.0, 0.1]) + 0.05 * rng.normal(size=(count, 3))


def discard(fn):
    """``fn`` returning nothing: a kept gigabyte result would distort the next runs."""
    def run():
        fn()
    return run


def main(count=20000, repeats=3):
    load_before = load_average()
    moments, omega0 = bodies_and_rates(count)
    t_dense = np.linspace(0.0, T_END, STEPS + 1)
    t_end = np.array([0.0, T_END])
    source, target = np.random.rand(count, STEPS + 1, 7), np.zeros((count, STEPS + 1, 7))

    def copy_fresh():
        np.copyto(np.empty_like(source), source)

    def copy_kept():
        np.copyto(target, source)

    def settle():
        # untimed: maps and releases as many bytes as the dense output, so that the next run that allocates
        # gets pages the kernel has just taken back (this VM returns released pages to its host after about a
        # second; faulting those in again costs 3-4x more, by an amount that depends on the order of runs)
        np.empty_like(source).fill(0.0)

    rows = []
    for method in METHODS:
        kw = {} if method == "dop853" else {"dt": T_END / STEPS}

        def run(t, every=1, kw=kw, method=method):
            return discard(lambda: kr.simulate_batch(moments, t, omega0, method=method, every=every, **kw))

        timings = interleaved(run(t_end), settle, run(t_dense), settle, run(t_dense, EVERY), settle, copy_fresh,
                              copy_kept, repeats=repeats)
        end, dense, sparse, copy, kept = timings[0], timings[2], timings[4], timings[6], timings[7]
        excess = dense.median - end.median
        excess_cpu = dense.cpu_median - end.cpu_median
        samples = count * (STEPS + 1)
        label = f"`{method}`" + (" (rtol 1e-12)" if method == "dop853" else f" (dt = {T_END / STEPS:g})")
        rows.append((label, f"{end.median:.3f}", f"{dense.median:.3f}", f"{sparse.median:.3f}",
                     f"{copy.median:.3f}", f"{dense.median / end.median:.2f}", f"{sparse.median / end.median:.2f}",
                     f"{kept.median:.3f}", f"{excess / copy.median:.2f}", f"{excess_cpu / copy.cpu_median:.2f}",
                     f"{excess / kept.median:.2f}",
                     f"{excess / samples * 1e9:.0f}"))
    lines = header(
        f"simulate_batch dense output: {count} free bodies × {STEPS} steps",
        f"End state (`t = [0, {T_END:g}]`) against every step stored ({STEPS + 1} samples, "
        f"{count * (STEPS + 1) * 56 / 1e9:.2f} GB) and every {EVERY}th (`every={EVERY}`); copy bound: "
        "`np.copyto` of the dense output's bytes into an output allocated per run (copy, kept output: into "
        "one allocated once, whose pages are mapped already: the bandwidth alone). Every run that allocates "
        "follows an untimed allocation and release of the dense output's size, so that all of them get pages "
        "just released (this VM hands released pages back to its host after about a second, and faulting those "
        "in again cost 3-4x more, depending on the order of runs: the copy bound varied 0.17-0.66 s). Medians of "
        f"{repeats} runs in alternation, one process. Excess = dense − end state; goal: excess within "
        "2× of the copy bound. CPU column: the same ratio from process CPU times (all threads), "
        "which other jobs on a shared machine inflate less than wall times.",
        load_before=load_before)
    lines += markdown_table(
        ["method", "end state (s)", "dense (s)", f"every={EVERY} (s)", "copy bound (s)", "dense / end",
         f"every={EVERY} / end", "copy, kept output (s)", "excess / copy bound", "excess / copy bound (CPU)",
         "excess / copy, kept output", "excess ns per sample"],
        rows, "lrrrrrrrrrrr")
    lines += ["", "Splitting methods take the sample's half flow about the first axis from the sine and cosine "
              "of the merged flow that the end-state run takes too (double-angle formulas), so a stored step "
              "adds no flow, only the sample's ω′ = m/I, its unit quaternion and the bytes; DOP853 adds three "
              "stages per step that holds an output and the interpolant per sample."]
    write_results("batch", "\n".join(lines))


if __name__ == "__main__":
    main(*(int(arg) for arg in sys.argv[1:3]))
