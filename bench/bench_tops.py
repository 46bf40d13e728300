"""The exact free top against numerical integration producing the same samples.

10^4 free bodies (random physical moments, random ω0 and q0) sampled at 100
times on [0, 20] s, three ways, in one process:

- :func:`kreisel.tops.solve_free_batch`: the exact solution (one compiled,
  parallel call, no time stepping);
- :func:`kreisel.simulate_batch` with DOP853 at rtol 1e-12 (one compiled,
  parallel call integrating every body);
- :func:`kreisel.simulate` with DOP853 at rtol 1e-12, one call per body
  (timed on ``PEER_BODIES`` bodies and scaled).

Also one body at 10^4 times through :meth:`kreisel.EulerTop.solve` and
``simulate``. Reported as samples (body × time) per second and the largest
Δω between the methods. Writes ``bench/results/tops.md``.
"""

from __future__ import annotations

import numpy as np
from _common import header, interleaved, load_average, markdown_table, median_time, write_results

import kreisel as kr

BODIES = 10_000
TIMES = 100
PEER_BODIES = 200
RTOL = 1e-12
REPEATS = 3


def population(n, seed=18):
    rng = np.random.default_rng(seed)
    moments = rng.uniform(1.0, 1.9, size=(n, 3))  # within a factor 2: every triangle inequality holds
    omega0 = rng.normal(size=(n, 3))
    q0 = kr.quat_normalize(rng.normal(size=(n, 4)))
    return moments, omega0, q0


def simulate_each(moments, t, omega0, q0):
    return np.stack([kr.simulate(m, t, w, q, method="dop853", rtol=RTOL).omega
                     for m, w, q in zip(moments, omega0, q0)])


def main():
    moments, omega0, q0 = population(BODIES)
    t = np.linspace(0.0, 20.0, TIMES)
    load_before = load_average()
    exact, batch = interleaved(
        lambda: kr.tops.solve_free_batch(moments, t, omega0, q0),
        lambda: kr.simulate_batch(moments, t, omega0, q0, method="dop853", rtol=RTOL),
        repeats=REPEATS,
    )
    few = slice(0, PEER_BODIES)
    each = median_time(lambda: simulate_each(moments[few], t, omega0[few], q0[few]), repeats=REPEATS)
    each_omega = simulate_each(moments[few], t, omega0[few], q0[few])
    samples = BODIES * TIMES
    rows = [
        ("`solve_free_batch` (exact)", f"{exact.median:.3f}", f"{samples / exact.median:.3g}", "1×", "—"),
        ("`simulate_batch` DOP853 rtol 1e-12", f"{batch.median:.3f}", f"{samples / batch.median:.3g}",
         f"{batch.median / exact.median:.1f}×", f"{np.abs(batch.result.omega - exact.result.omega).max():.1e}"),
        (f"`simulate` DOP853 rtol 1e-12, per body (scaled from {PEER_BODIES})", f"{each * BODIES / PEER_BODIES:.2f}",
         f"{PEER_BODIES * TIMES / each:.3g}", f"{each * BODIES / PEER_BODIES / exact.median:.0f}×",
         f"{np.abs(each_omega - exact.result.omega[few]).max():.1e}"),
    ]

    top = kr.EulerTop(*moments[0])
    long_t = np.linspace(0.0, 200.0, 10_000)
    single, stepped = interleaved(
        lambda: top.solve(long_t, omega0[0], q0[0]),
        lambda: kr.simulate(moments[0], long_t, omega0[0], q0[0], method="dop853", rtol=RTOL),
        repeats=REPEATS,
    )
    omega_only = median_time(lambda: top.omega(long_t, omega0[0]), REPEATS)
    single_rows = [
        ("`EulerTop.solve`", f"{single.median * 1e3:.2f}", f"{long_t.size / single.median:.3g}", "1×", "—"),
        ("`EulerTop.omega` (no attitude)", f"{omega_only * 1e3:.2f}", f"{long_t.size / omega_only:.3g}",
         f"{omega_only / single.median:.2f}×", "—"),
        ("`simulate` DOP853 rtol 1e-12", f"{stepped.median * 1e3:.2f}", f"{long_t.size / stepped.median:.3g}",
         f"{stepped.median / single.median:.1f}×",
         f"{np.abs(stepped.result.omega - single.result.omega).max():.1e}"),
    ]

    lines = header("kreisel.tops: the exact free top vs integration",
                   f"Medians of {REPEATS} runs, exact and batch integration timed in alternation; "
                   "samples = bodies × output times; time ratio relative to the exact solution; "
                   "Δω = largest difference from the exact ω (rad/s; ω0 of norm ~1.6).",
                   load_before=load_before)
    lines += ["", f"## {BODIES} free bodies × {TIMES} times on [0, 20] s", ""]
    lines += markdown_table(["method", "time (s)", "samples/s", "time / exact", "max abs Δω"], rows, align="-rrrr")
    lines += ["", f"## One body, {long_t.size} times on [0, 200] s", ""]
    lines += markdown_table(["method", "time (ms)", "samples/s", "time / solve", "max abs Δω"], single_rows,
                            align="-rrrr")
    write_results("tops", "\n".join(lines))


if __name__ == "__main__":
    main()
