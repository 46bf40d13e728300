"""kreisel.fit_free_rotation against the usual hand-made fit: scipy least_squares around solve_ivp(DOP853).

A phone recording as the bundled one (146 × 71 × 8 mm slab tossed about its
middle axis, ~400 Hz with jittered stamps, 0.05 rad/s noise) of n samples.
kreisel: the whole ``fit_free_rotation`` call (starting values included).
Peer: ``scipy.optimize.least_squares`` (default trf, 2-point Jacobian) of the
residual of Euler's equations integrated by ``solve_ivp(method="DOP853",
rtol=1e-10, atol=1e-10, t_eval=t)``, parameters (I_x/I_z, I_y/I_z, ω0), started
from kreisel's own starting values so that both do the same fit. Medians of
runs taken in alternation, same process. Writes ``bench/results/fit.md``.
"""

from __future__ import annotations

import numpy as np
from _common import header, interleaved, load_average, markdown_table, write_results
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares

import kreisel as kr
from kreisel.tops import fitting

SIZES = (250, 1000)
REPEATS = 5
PEER_REPEATS = 2


def recording(n, seed=0):
    rng = np.random.default_rng(seed)
    moments = np.diag(kr.inertia.box(0.17, (0.071, 0.146, 0.008)))
    t = np.cumsum(rng.uniform(0.6, 1.4, n) / 400.0)
    omega = kr.EulerTop(*moments).omega(t - t[0], [13.0, 0.45, 0.35]) + rng.normal(0.0, 0.05, (n, 3))
    return t, omega, moments / moments.max()


def peer_fit(t, omega, x0):
    """Least squares around DOP853, the way a fit is written by hand."""
    tau = t - t[0]

    def residual(x):
        moments = np.array([x[0], x[1], 1.0])

        def euler(_, w):
            return np.cross(moments * w, w) / moments

        sol = solve_ivp(euler, (0.0, tau[-1]), x[2:5], method="DOP853", t_eval=tau, rtol=1e-10, atol=1e-10)
        return (sol.y.T - omega).ravel()

    solution = least_squares(residual, x0)
    return solution.x, solution.nfev + solution.njev * len(x0)


def start(t, omega):
    model, x = fitting._start(t, omega, False, False)
    moments = fitting._moments(model.second(x))
    return np.concatenate([moments[:2] / moments[2], x[2:5]])


def main():
    load_before = load_average()
    rows = []
    for n in SIZES:
        t, omega, truth = recording(n)
        x0 = start(t, omega)
        ours, = interleaved(lambda: kr.fit_free_rotation(t, omega), repeats=REPEATS)
        peer, = interleaved(lambda: peer_fit(t, omega, x0), repeats=PEER_REPEATS, warmup=False)
        print(f"n = {n}: kreisel {ours.median:.3f} s, peer {peer.median:.2f} s", flush=True)
        fit = ours.result
        peer_x, peer_evals = peer.result
        peer_moments = np.array([peer_x[0], peer_x[1], 1.0]) / max(peer_x[0], peer_x[1], 1.0)
        rows.append([
            n, f"{1e3 * ours.median:.1f}", f"{1e3 * ours.cpu_median:.1f}", f"{1e3 * peer.median:.0f}",
            f"{1e3 * peer.cpu_median:.0f}", f"{peer.median / ours.median:.0f}×", f"{peer.cpu_median / ours.cpu_median:.0f}×",
            fit.nfev, peer_evals,
            f"{np.max(np.abs(fit.moments - truth)):.1e}", f"{np.max(np.abs(peer_moments - fit.moments)):.1e}",
        ])
    lines = header(
        "kreisel.fit_free_rotation vs least_squares around solve_ivp(DOP853)",
        "Phone recording (slab 146 × 71 × 8 mm tossed about its middle axis, one flip, ~400 Hz jittered, "
        "0.05 rad/s noise) of n samples. kreisel: the whole call, starting values included; peer: "
        "scipy least_squares (2-point Jacobian) of the DOP853 solution (rtol = atol = 1e-10), started from "
        f"kreisel's starting values. Medians of {REPEATS} (peer {PEER_REPEATS}) runs in one process; "
        "CPU: process CPU time of the same runs (less sensitive than wall time to other jobs on the machine).",
        load_before=load_before,
    )
    lines += markdown_table(
        ["samples", "kreisel (ms)", "kreisel CPU (ms)", "scipy DOP853 fit (ms)", "peer CPU (ms)", "speed-up",
         "speed-up, CPU", "kreisel model evals", "peer ODE solves", "kreisel |Δ ratios| vs truth",
         "peer − kreisel ratios"],
        rows, align="rrrrrrrrrrr",
    )
    write_results("fit", "\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
