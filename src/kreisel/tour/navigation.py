"""Tour section for Theory §3.3, §3.5: strapdown attitude under coning."""

from __future__ import annotations

import numpy as np

from .. import nav, so3
from .report import Check, Section, panel

__all__ = ["measured_drift", "coning_drift", "SECTIONS", "SAMPLES_PER_CONE"]

# per cone period, divisible by N so that updates end on whole cones
SAMPLES_PER_CONE = {1: (16, 24, 32, 48, 64), 2: (16, 24, 32, 48), 3: (12, 18, 24, 30)}


def measured_drift(alpha, rate, samples_per_cone, cones, n):
    """Drift rate (rad/s) of the N-sample algorithm, fitted over whole cone periods."""
    ts = 2 * np.pi / rate / samples_per_cone
    motion = nav.coning_motion(alpha, rate, ts, samples_per_cone * cones)
    estimate = nav.attitude_from_increments(motion.q[0], motion.dtheta, n)
    truth = motion.q[::n]
    error = so3.quat_to_rotvec(so3.quat_multiply(so3.quat_conjugate(truth), estimate))  # body components
    per_cone = samples_per_cone // n
    times = motion.t[::n][::per_cone]
    drift = np.polyfit(times, error[::per_cone], 1)[0]
    return drift, ts


def coning_drift(quick):
    """Coning drift of strapdown attitude algorithms"""
    alpha, rate = np.radians(1.0), 2 * np.pi
    cones = 10 if quick else 40
    fig, ax = panel("λ = Ω T_s", "drift rate (rad/s)", "coning α = 1°, Ω = 2π rad/s: N-sample updates", figsize=(7, 4.2))
    checks = []
    for n, grid in SAMPLES_PER_CONE.items():
        drifts, steps = zip(*(measured_drift(alpha, rate, per_cone, cones, n) for per_cone in grid))
        lam = rate * np.array(steps)
        measured = -np.array(drifts)[:, 0]
        theory = nav.coning_drift(alpha, rate, np.array(steps), n)
        along_minus_x = measured[-1] / np.linalg.norm(drifts[-1])
        ax.loglog(lam, measured, "o", color=f"C{n - 1}", label=f"N = {n}, measured")
        ax.loglog(lam, theory, "-", color=f"C{n - 1}", linewidth=0.8, label=f"N = {n}, α²Ωλ^{2 * n}·c_N")
        slope = np.polyfit(np.log(lam[-3:]), np.log(measured[-3:]), 1)[0]
        checks += [Check.close(f"N = {n}: log–log slope at small λ", float(slope), 2 * n, rtol=0.05, source="2N"),
                   Check.close(f"N = {n}: drift at λ = {lam[-1]:.3f} (rad/s)", float(measured[-1]), float(theory[-1]),
                               rtol=0.03, source="classical coefficient"),
                   Check.close(f"N = {n}: angle between the drift and body −x (rad)",
                               float(np.arccos(min(1.0, along_minus_x))), alpha, rtol=1e-3,
                               source="α: the drift is about the cone axis")]
    ax.legend(fontsize=7, ncol=2)
    return Section(
        "Strapdown attitude and coning drift", "§3.3, §3.5",
        "A strapdown system turns gyro angle increments into attitude: q ← q ⊗ exp(φ/2) with the update "
        "rotation vector φ = ΣΔθ + δφ. Under coning motion the body rate is not along a fixed axis, and "
        "the optimal N-sample coning correction (from the Bortz equation) leaves a drift "
        "α²Ωλ^(2N) N!/(2^(N+1)(2N+1)!!), λ = Ω T_s, about the cone axis: −x of the body tilted by α.",
        checks,
        [(fig, "Measured drift of the N = 1, 2, 3 algorithms against the sample interval, with the classical formula.")],
    )


SECTIONS = (coning_drift,)
