"""Dask overhead of kreisel.sweep against the same chunks run in process.

Overhead: a free-body sweep of 4 chunks of 10^4 bodies (splitting, 1000 steps each,
reduced to min ω2) on a LocalCluster of 2 worker processes × 1 thread, against the
same chunks run in this process (``scheduler="serial"``, numba using both cores).
Overhead = (Dask wall − in-process wall) / Dask wall; the cluster start-up is
excluded (started once), the submission, transfer and assembly are included.
Writes bench/results/sweep.md.
"""

import os
import pathlib
import statistics
import time

import numpy as np

import kreisel as kr
from kreisel.sweep import sweep

CHUNK = 10_000
STEPS = 200


def free_body_chunk(middle_moment, tilt):
    bodies = np.stack([np.ones_like(middle_moment), middle_moment, np.full_like(middle_moment, 2.0)], axis=-1)
    omega0 = np.stack([np.sin(tilt), np.cos(tilt), np.zeros_like(tilt)], axis=-1)
    t = np.linspace(0.0, STEPS * 0.01, 11)
    low = kr.simulate_batch(bodies, t, omega0, method="splitting", dt=0.01,
                            reduce=lambda tr: tr.omega[..., 1].min(axis=-1), chunk_size=CHUNK)
    return {"min_omega2": low}


GRID = {"middle_moment": np.linspace(1.05, 1.95, 20), "tilt": np.linspace(0.01, 0.5, CHUNK // 10)}


def median_time(fn, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    from distributed import Client, LocalCluster

    free_body_chunk(np.array([1.5]), np.array([0.1]))   # compile
    bodies = GRID["middle_moment"].size * GRID["tilt"].size
    rows = []
    serial = median_time(lambda: sweep(free_body_chunk, GRID, chunk_size=CHUNK, scheduler="serial"), 3)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                      env={"NUMBA_NUM_THREADS": "1"}) as cluster, Client(cluster) as client:
        client.run(free_body_chunk, np.array([1.5]), np.array([0.1]))   # compile (numba cache) on the workers
        reference = sweep(free_body_chunk, GRID, chunk_size=CHUNK, scheduler="serial")
        assert sweep(free_body_chunk, GRID, chunk_size=CHUNK, scheduler=client).identical(reference)
        dask = median_time(lambda: sweep(free_body_chunk, GRID, chunk_size=CHUNK, scheduler=client), 3)
    rows.append(("in process (serial chunks, numba 2 threads)", serial, bodies * STEPS / serial))
    rows.append(("Dask LocalCluster 2 workers × 1 thread", dask, bodies * STEPS / dask))
    overhead = (dask - serial) / dask

    lines = [f"Free-body sweep, {bodies} bodies in chunks of {CHUNK}, splitting, {STEPS} steps each "
             f"(attitude included), medians of 3 runs", "",
             "| run | median wall (s) | body-steps/s |", "|---|---|---|"]
    lines += [f"| {name} | {wall:.3f} | {rate:.3g} |" for name, wall, rate in rows]
    lines += ["", f"Dask overhead: {100 * overhead:.1f} % of the Dask wall time (target < 10 %)",
              "(simulate_batch speed-up from 1 to 2 threads: see bench/results/dynamics.md)"]
    text = "\n".join(lines) + "\n"
    print(text)
    out = pathlib.Path(__file__).parent / "results" / "sweep.md"
    out.parent.mkdir(exist_ok=True)
    out.write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
