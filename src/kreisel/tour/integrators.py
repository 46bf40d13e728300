"""Tour section for Theory §4.5: choosing an integrator for Euler's equations."""

from __future__ import annotations

import time

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import FormatStrFormatter, LogLocator, NullFormatter

from ..dynamics import simulate
from .report import Check, Section

__all__ = ["work_precision", "SECTIONS", "FIXED_STEP_METHODS", "timed_run"]

# Hairer–Lubich–Wanner's free rigid body (Theory §4.5)
_MOMENTS = np.array([2.0, 1.0, 2.0 / 3.0])
_OMEGA0 = np.array([np.cos(1.1), 0.0, np.sin(1.1)]) / _MOMENTS
FIXED_STEP_METHODS = ("splitting", "splitting4", "dmv", "rkmk4", "midpoint", "rk4")


def timed_run(t, **options):
    """Simulate once to compile, then time a second run; return (errors, seconds)."""
    simulate(_MOMENTS, t[:2], _OMEGA0, allow_unphysical=True, **options)
    start = time.perf_counter()
    traj = simulate(_MOMENTS, t, _OMEGA0, allow_unphysical=True, **options)
    seconds = time.perf_counter() - start
    energy = traj.energy
    m = np.linalg.norm(traj.angular_momentum_body, axis=-1)
    return np.abs(energy / energy[0] - 1), float(np.max(np.abs(m / m[0] - 1))), seconds


def work_precision(quick):
    """Integrators: work–precision and conservation"""
    t_end = 200.0 if quick else 2000.0
    t = np.linspace(0.0, t_end, int(t_end) + 1)  # output every 1 s: each step size below divides it
    steps = (0.2, 0.1, 0.05, 0.025) if quick else (0.2, 0.1, 0.05, 0.025, 0.0125)
    fig = Figure(figsize=(11, 4.2), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    norm_errors, drift_ratio = {}, {}
    for k, method in enumerate(FIXED_STEP_METHODS):
        errs, costs = [], []
        for dt in steps:
            energy, norm, seconds = timed_run(t, method=method, dt=dt)
            errs.append(max(float(np.max(energy)), 1e-17))
            costs.append(seconds)
            if dt == 0.1:
                norm_errors[method] = norm
                half = energy.size // 2
                drift_ratio[method] = float(np.max(energy[half:]) / max(np.max(energy[:half]), 1e-300))
                # the running maximum: the error's growth, without the oscillation within each orbit
                ax2.semilogy(t, np.maximum.accumulate(np.maximum(energy, 1e-17)), color=f"C{k}", linewidth=1.4,
                             label=method)
        ax1.loglog(costs, errs, "o-", color=f"C{k}", label=method)
    errs, costs = [], []
    for rtol in (1e-6, 1e-8, 1e-10, 1e-12):
        energy, _, seconds = timed_run(t, method="dop853", rtol=rtol)
        errs.append(max(float(np.max(energy)), 1e-17))
        costs.append(seconds)
    ax1.loglog(costs, errs, "s--", color="k", label="dop853 (adaptive)")
    ax1.set(xlabel="CPU time (s)", ylabel="max relative energy error", title=f"work–precision, T = {t_end:g} s")
    # CPU times span one to a few decades, depending on the machine's load: plain numbers at 1, 2, 5 × 10^k
    # (every decade when the span is wide), no minor-tick labels (in scientific notation they overlapped)
    low, high = ax1.get_xlim()
    ax1.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0) if np.log10(high / low) < 2.5 else (1.0,)))
    ax1.xaxis.set_major_formatter(FormatStrFormatter("%g"))
    ax1.xaxis.set_minor_formatter(NullFormatter())
    ax1.legend(fontsize=7)
    ax2.set(xlabel="t (s)", ylabel="largest relative energy error so far",
            title="energy error along the run, h = 0.1 s")
    ax2.legend(fontsize=7, ncol=2, loc="lower right")
    return Section(
        "Choosing an integrator", "§4.5",
        "Euler's equations of the free body, I = (2, 1, 2/3), m0 = (cos 1.1, 0, sin 1.1) (Hairer, Lubich and "
        "Wanner's test). The Lie–Poisson splitting methods and the discrete Moser–Veselov map keep |m| to "
        "round-off and their energy error bounded without drift; the implicit midpoint rule keeps the "
        "energy exactly (quadratic invariant); classical RK4 drifts. The adaptive DOP853 default reaches "
        "1e-12 accuracy at modest cost.",
        [Check.below("splitting: | |m| − |m0| | relative, h = 0.1", norm_errors["splitting"], 1e-12),
         Check.below("dmv: | |m| − |m0| | relative, h = 0.1", norm_errors["dmv"], 1e-12),
         Check.below("splitting: energy error late / early (no drift)", drift_ratio["splitting"], 2.0),
         Check.below("midpoint: max energy error, h = 0.1", float(timed_run(t, method="midpoint", dt=0.1)[0].max()), 1e-13)],
        [(fig, "Left: accuracy against cost for every method. Right: the energy error along one run.")],
    )


SECTIONS = (work_precision,)
