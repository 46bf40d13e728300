"""Foucault pendulum: kreisel's compiled DOP853 loop against scipy's solve_ivp (DOP853) on the same equations.

Run: python bench/bench_earth.py  (writes bench/results/earth.md)
"""

import numpy as np
from _common import header, load_average, markdown_table, median_time, write_results
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


if __name__ == "__main__":
    load_before = load_average()
    tk = median_time(run_kreisel, 5)
    ts = median_time(run_scipy, 3)
    lines = header(None, f"Foucault pendulum, {DURATION:g} s of a {LENGTH:g} m pendulum (50 swings), rtol 1e-10",
                   load_before=load_before)
    lines += markdown_table(
        ["implementation", "median time (s)", "ratio to kreisel"],
        [("kreisel.earth.foucault_pendulum (compiled DOP853 + event search)", f"{tk:.4f}", "1.0"),
         ("scipy solve_ivp DOP853, same right-hand side in Python (no events)", f"{ts:.4f}", f"{ts / tk:.1f}")],
    )
    write_results("earth", "\n".join(lines))
