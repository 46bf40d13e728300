"""Foucault pendulum: kreisel's compiled DOP853 loop against scipy's solve_ivp (DOP853) on the same equations.

Run: python bench/bench_earth.py  (writes bench/results/earth.md)
"""

import pathlib
import time

import numpy as np
from scipy.integrate import solve_ivp

import kreisel as kr
from kreisel.earth.foucault import pendulum_rhs

LENGTH, LAT, DURATION, AMP, OMEGA = 1.0, 45.0, 100.0, 0.05, 0.02


def run_kreisel():
    return kr.earth.foucault_pendulum(LENGTH, LAT, DURATION, AMP, omega=OMEGA).precession_rate


def run_scipy():
    p = np.concatenate([kr.earth.angular_velocity_enu(LAT, OMEGA), [9.80665, LENGTH]])

    def rhs(t, y):
        out = np.empty(6)
        pendulum_rhs.py_func(t, y, p, out, 0)
        return out

    y0 = np.array([np.sin(AMP), 0, -np.cos(AMP), 0, 0, 0])
    return solve_ivp(rhs, (0, DURATION), y0, method="DOP853", rtol=1e-10, atol=1e-12).y[:, -1]


def median_time(fn, repeats=5):
    fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


if __name__ == "__main__":
    tk = median_time(run_kreisel)
    ts = median_time(run_scipy, repeats=3)
    table = "\n".join([
        f"Foucault pendulum, {DURATION:g} s of a {LENGTH:g} m pendulum (50 swings), rtol 1e-10",
        "",
        "| implementation | median time (s) | ratio to kreisel |",
        "|---|---|---|",
        f"| kreisel.earth.foucault_pendulum (compiled DOP853 + event search) | {tk:.4f} | 1.0 |",
        f"| scipy solve_ivp DOP853, same right-hand side in Python (no events) | {ts:.4f} | {ts / tk:.1f} |",
    ])
    print(table)
    out = pathlib.Path(__file__).parent / "results"
    out.mkdir(exist_ok=True)
    (out / "earth.md").write_text(table + "\n")
