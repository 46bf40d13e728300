"""kreisel.se3.RigidTransform against scipy.spatial.transform.RigidTransform on 10^6 poses.

For each batch operation of the object layer: median wall time of kreisel
and scipy (same process, same poses), the speed-up, and the ratio to a
"streaming copy" bound — ``np.copyto`` of buffers as large as kreisel's
input plus output (7 doubles per pose: quaternion and translation), the
least memory traffic any implementation with that storage needs. Writes
``bench/results/se3.md``.
"""

from __future__ import annotations

import numpy as np
from _common import header, interleaved, load_average, markdown_table, median_time, streaming_copy, write_results
from scipy.spatial.transform import RigidTransform as ScipyRigidTransform

import kreisel as kr

N = 1_000_000
REPEATS = 4


def main():
    a = kr.RigidTransform.random(N, rng=1, translation_scale=2.0)
    b = kr.RigidTransform.random(N, rng=2, translation_scale=2.0)
    one = a[0]
    sa, sb, sone = a.to_scipy(), b.to_scipy(), one.to_scipy()
    points = np.random.default_rng(3).normal(size=(N, 3))
    matrices = a.as_matrix()
    twists = a.as_exp_coords()

    # name, kreisel, scipy, doubles in, doubles out per pose (kreisel's storage)
    cases = [
        ("composition a * b", lambda: a * b, lambda: sa * sb, 14, 7),
        ("apply to points", lambda: a.apply(points), lambda: sa.apply(points), 10, 3),
        ("one pose, 10^6 points", lambda: one.apply(points), lambda: sone.apply(points), 3, 3),
        ("inverse", lambda: a.inv(), lambda: sa.inv(), 7, 7),
        ("from 4x4 matrix", lambda: kr.RigidTransform.from_matrix(matrices), lambda: ScipyRigidTransform.from_matrix(matrices), 16, 7),
        ("as 4x4 matrix", lambda: a.as_matrix(), lambda: sa.as_matrix(), 7, 16),
        ("exp (from twist)", lambda: kr.RigidTransform.from_exp_coords(twists), lambda: ScipyRigidTransform.from_exp_coords(twists), 6, 7),
        ("log (as twist)", lambda: a.as_exp_coords(), lambda: sa.as_exp_coords(), 7, 6),
    ]
    load_before = load_average()
    rows = []
    for name, ours, theirs, n_in, n_out in cases:
        timings = interleaved(ours, theirs, repeats=REPEATS, warmup=(True, False))
        t_ours, t_scipy = (t.median for t in timings)
        t_copy = median_time(streaming_copy(n_in * N, n_out * N), REPEATS)
        rows.append((name, t_ours, t_scipy, t_copy, timings[0].cpu_median / t_ours))
        print(f"{name:24s} kreisel {t_ours * 1e3:8.2f} ms  scipy {t_scipy * 1e3:8.1f} ms  copy {t_copy * 1e3:6.2f} ms", flush=True)

    lines = header(
        "kreisel.se3 vs scipy RigidTransform (10^6 poses)",
        f"Medians of {REPEATS} interleaved runs, same process; kreisel runs every batch below on all cores "
        "(numba prange; CPU / wall about 2 when both cores work), scipy on one; shared noisy machine.",
        "'copy bound' = np.copyto of kreisel's input + output bytes (7 doubles per pose).",
        load_before=load_before,
    )
    lines += markdown_table(
        ["operation", "kreisel (ms)", "scipy (ms)", "speed-up", "kreisel / copy bound", "kreisel CPU / wall"],
        [(name, f"{t_ours * 1e3:.2f}", f"{t_scipy * 1e3:.1f}", f"{t_scipy / t_ours:.1f}x", f"{t_ours / t_copy:.1f}", f"{cpu:.1f}")
         for name, t_ours, t_scipy, t_copy, cpu in rows],
        align="-rrrrr",
    )
    write_results("se3", "\n".join(lines))


if __name__ == "__main__":
    main()
