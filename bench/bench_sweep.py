"""Dask overhead of kreisel.sweep against the same chunks run in process.

Overhead: a free-body sweep of 4 chunks of 10^4 bodies (splitting, 1000 steps each,
reduced to min ω2) on a LocalCluster of 2 worker processes × 1 thread, against the
same chunks run in this process (``scheduler="serial"``, numba using both cores).
Overhead = (Dask wall − in-process wall) / Dask wall; the cluster start-up is
excluded (started once), the submission, transfer and assembly are included.
Writes bench/results/sweep.md.
"""

import numpy as np
from _common import header, load_average, markdown_table, median_time, write_results

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


def main():
    from distributed import Client, LocalCluster

    free_body_chunk(np.array([1.5]), np.array([0.1]))   # compile
    bodies = GRID["middle_moment"].size * GRID["tilt"].size
    load_before = load_average()
    rows = []
    serial = median_time(lambda: sweep(free_body_chunk, GRID, chunk_size=CHUNK, scheduler="serial"), 3, warmup=False)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                      env={"NUMBA_NUM_THREADS": "1"}) as cluster, Client(cluster) as client:
        client.run(free_body_chunk, np.array([1.5]), np.array([0.1]))   # compile (numba cache) on the workers
        reference = sweep(free_body_chunk, GRID, chunk_size=CHUNK, scheduler="serial")
        assert sweep(free_body_chunk, GRID, chunk_size=CHUNK, scheduler=client).identical(reference)
        dask = median_time(lambda: sweep(free_body_chunk, GRID, chunk_size=CHUNK, scheduler=client), 3, warmup=False)
    rows.append(("in process (serial chunks, numba 2 threads)", serial, bodies * STEPS / serial))
    rows.append(("Dask LocalCluster 2 workers × 1 thread", dask, bodies * STEPS / dask))
    overhead = (dask - serial) / dask

    lines = header(None, f"Free-body sweep, {bodies} bodies in chunks of {CHUNK}, splitting, {STEPS} steps each "
                   "(attitude included), medians of 3 runs", load_before=load_before)
    lines += markdown_table(["run", "median wall (s)", "body-steps/s"],
                            [(name, f"{wall:.3f}", f"{rate:.3g}") for name, wall, rate in rows])
    lines += ["", f"Dask overhead: {100 * overhead:.1f} % of the Dask wall time (target < 10 %)",
              "(simulate_batch speed-up from 1 to 2 threads: see bench/results/dynamics.md)"]
    write_results("sweep", "\n".join(lines))


if __name__ == "__main__":
    main()
