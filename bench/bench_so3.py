"""kreisel.so3 against scipy.spatial.transform on 10^6 rotations.

For each batch operation: median wall time of kreisel and scipy (same
process, same inputs), the speed-up, and the ratio to a "streaming copy"
bound — ``np.copyto`` of buffers as large as the operation's input plus
output, the least memory traffic any implementation needs. Plus the time of
one single-rotation ``quat_multiply``. Writes ``bench/results/so3.md``.

kreisel runs batches of at least ``PARALLEL_THRESHOLD`` rotations on all
cores (numba ``prange``); scipy is single-threaded. The load average is
recorded with the table because the machine may be shared.
"""

from __future__ import annotations

import os
import pathlib
import time

import numpy as np
from scipy.spatial.transform import Rotation as S

import kreisel as kr

N = 1_000_000
REPEATS = 5


def median_time(fn, repeats=REPEATS):
    fn()  # compile / warm caches
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return float(np.median(times))


def copy_buffers(n_in, n_out):
    """A run that streams ``n_in`` doubles in and ``n_out`` doubles out (two copies)."""
    src_in, dst_in = np.random.rand(n_in), np.empty(n_in)
    src_out, dst_out = np.random.rand(n_out), np.empty(n_out)

    def run():
        np.copyto(dst_in, src_in)
        np.copyto(dst_out, src_out)

    return run


def interleaved_times(ours, theirs, copy, rounds=REPEATS):
    """Median and best times of the three runs, taken in alternation.

    On a shared machine the load drifts within seconds; alternating the
    runs gives kreisel, scipy and the copy bound the same conditions, and
    the best times are the least disturbed by other jobs.
    """
    runs = (ours, theirs, copy)
    for fn in runs:
        fn()  # compile / warm caches
    times = [[], [], []]
    for _ in range(rounds):
        for fn, bucket in zip(runs, times):
            t = time.perf_counter()
            fn()
            bucket.append(time.perf_counter() - t)
    return [float(np.median(b)) for b in times], [min(b) for b in times]


def main():
    rng = np.random.default_rng(0)
    q = rng.normal(size=(N, 4))
    q /= np.linalg.norm(q, axis=-1, keepdims=True)
    p = rng.normal(size=(N, 4))
    p /= np.linalg.norm(p, axis=-1, keepdims=True)
    R = kr.quat_to_matrix(q)
    psi = kr.quat_to_rotvec(q)
    euler = kr.quat_to_euler("ZXZ", q)
    v = rng.normal(size=(N, 3))
    sq, sp = S.from_quat(q[:, [1, 2, 3, 0]]), S.from_quat(p[:, [1, 2, 3, 0]])

    # name, kreisel, scipy, doubles in, doubles out per rotation
    cases = [
        ("quat -> matrix", lambda: kr.quat_to_matrix(q), lambda: S.from_quat(q[:, [1, 2, 3, 0]]).as_matrix(), 4, 9),
        ("matrix -> quat", lambda: kr.matrix_to_quat(R), lambda: S.from_matrix(R).as_quat(), 9, 4),
        ("rotvec -> matrix", lambda: kr.rotvec_to_matrix(psi), lambda: S.from_rotvec(psi).as_matrix(), 3, 9),
        ("rotvec -> quat", lambda: kr.rotvec_to_quat(psi), lambda: S.from_rotvec(psi).as_quat(), 3, 4),
        ("matrix -> rotvec", lambda: kr.matrix_to_rotvec(R), lambda: S.from_matrix(R).as_rotvec(), 9, 3),
        ("Euler ZXZ -> matrix", lambda: kr.euler_to_matrix("ZXZ", euler), lambda: S.from_euler("ZXZ", euler).as_matrix(), 3, 9),
        ("matrix -> Euler ZXZ", lambda: kr.matrix_to_euler("ZXZ", R), lambda: S.from_matrix(R).as_euler("ZXZ"), 9, 3),
        ("composition p q", lambda: kr.quat_multiply(p, q), lambda: sp * sq, 8, 4),
        ("apply R(q) v", lambda: kr.quat_apply(q, v), lambda: sq.apply(v), 7, 3),
    ]
    load_before = os.getloadavg()
    rows = []
    for name, ours, theirs, n_in, n_out in cases:
        (t_ours, t_scipy, t_copy), best = interleaved_times(ours, theirs, copy_buffers(n_in * N, n_out * N))
        rows.append((name, t_ours, t_scipy, t_copy, best))
        print(f"{name:22s} kreisel {t_ours * 1e3:8.2f} ms  scipy {t_scipy * 1e3:8.1f} ms  copy {t_copy * 1e3:6.2f} ms", flush=True)

    a, b = np.array([0.9, 0.1, 0.3, 0.2]), np.array([0.5, -0.5, 0.5, 0.5])
    sa, sb = S.from_quat(a[[1, 2, 3, 0]]), S.from_quat(b[[1, 2, 3, 0]])
    single = median_time(lambda: [kr.quat_multiply(a, b) for _ in range(1000)]) / 1000
    single_scipy = median_time(lambda: [(sa * sb).as_quat() for _ in range(1000)]) / 1000
    load_after = os.getloadavg()
    load = lambda la: "/".join(f"{x:.1f}" for x in la)  # noqa: E731

    lines = [
        "# kreisel.so3 vs scipy.spatial.transform",
        "",
        f"10^6 rotations, medians of {REPEATS} runs taken in alternation (kreisel, scipy, copy), one process, float64. "
        f"scipy {__import__('scipy').__version__}, numpy {np.__version__}, numba {__import__('numba').__version__}. "
        "Copy bound: `np.copyto` of input- and output-sized (preallocated) buffers; kreisel also allocates its output. "
        f"{os.cpu_count()} cores, kreisel uses {__import__('numba').get_num_threads()} threads for batches. "
        f"Load average (1/5/15 min) before: {load(load_before)}, after: {load(load_after)} "
        "(a load above the core count means other jobs shared the CPUs and the times are inflated; "
        "the best-of-runs columns are the least disturbed).",
        "",
        "| operation | kreisel (ms) | scipy (ms) | speed-up vs scipy | copy bound (ms) | kreisel / copy "
        "| best kreisel (ms) | best speed-up | best kreisel / best copy |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for name, t_ours, t_scipy, t_copy, (b_ours, b_scipy, b_copy) in rows:
        lines.append(
            f"| {name} | {t_ours * 1e3:.2f} | {t_scipy * 1e3:.1f} | {t_scipy / t_ours:.1f}× | {t_copy * 1e3:.2f} | {t_ours / t_copy:.2f} "
            f"| {b_ours * 1e3:.2f} | {b_scipy / b_ours:.1f}× | {b_ours / b_copy:.2f} |"
        )
    lines += [
        "",
        f"Single call `quat_multiply` of two 4-vectors: kreisel {single * 1e6:.2f} µs, "
        f"scipy (`Rotation * Rotation`, then `as_quat`) {single_scipy * 1e6:.2f} µs.",
        "",
    ]
    text = "\n".join(lines)
    print(text)
    out = pathlib.Path(__file__).parent / "results" / "so3.md"
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text)


if __name__ == "__main__":
    main()
