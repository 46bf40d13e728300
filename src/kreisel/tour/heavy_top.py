"""Tour sections for Theory §6–§7: Lagrange top, fast and sleeping top, Kovalevskaya top."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .. import so3
from ..tops import KovalevskayaTop, LagrangeTop
from .report import Check, Section, panel

__all__ = ["lagrange_top", "fast_and_sleeping_top", "kovalevskaya_top", "SECTIONS", "TOP", "THETA0", "LOCI"]

TOP = LagrangeTop(1.0, 0.5, 1.0)  # I1 about the pivot, I3, mgl
THETA0 = 0.6
_SPIN = 5.0  # ψ̇ at release: slow enough for the loci to be seen
LOCI = {  # ZXZ rates (φ̇, θ̇, ψ̇) at release, θ = θ0
    "monotone": [0.3, 0.0, _SPIN],
    "cusp": [0.0, 0.0, _SPIN],
    "loop": [-0.3, 0.0, _SPIN],
}


def lagrange_top(quick):
    """Lagrange top: effective potential and the three kinds of apex locus"""
    euler0 = [0.0, THETA0, 0.0]
    t = np.linspace(0.0, 10.0, 1500 if quick else 6000)
    fig = Figure(figsize=(12, 3.6), layout="constrained")
    ax0 = fig.add_subplot(1, 4, 1)
    theta = np.linspace(0.3, 1.1, 400)
    checks, levels = [], []
    for k, (kind, rates) in enumerate(LOCI.items()):
        consts = TOP.constants(euler0, rates)
        ax0.plot(theta, TOP.effective_potential(theta, consts.J3, consts.Jz), color=f"C{k}", label=kind)
        ax0.axhline(consts.E, color=f"C{k}", linestyle=":", linewidth=0.8)
        levels.append(consts.E)
        exact = TOP.solve(t, euler0, rates)
        simulated = TOP.simulate(t, euler0, rates)
        dq = np.minimum(np.linalg.norm(exact.q - simulated.q, axis=-1), np.linalg.norm(exact.q + simulated.q, axis=-1))
        tips = so3.quat_apply(exact.q, [0.0, 0.0, 1.0])
        theta_path = np.arccos(np.clip(tips[:, 2], -1, 1))
        low, high = TOP.turning_points(euler0, rates)
        ax = fig.add_subplot(1, 4, k + 2)
        ax.plot(tips[:, 0], tips[:, 1], linewidth=1)
        ring = np.linspace(0, 2 * np.pi, 200)
        for bound in (low, high):
            ax.plot(np.sin(bound) * np.cos(ring), np.sin(bound) * np.sin(ring), color="0.6", linestyle=":")
        ax.set_aspect("equal")
        ax.set_title(f"apex locus seen from above: {kind}", fontsize=9)
        ax.set(xlabel="x of the axis tip (unit sphere)", ylabel="y of the axis tip")
        checks += [
            Check.equal(f"{kind}: apex_locus_kind", TOP.apex_locus_kind(euler0, rates), kind),
            Check.close(f"{kind}: largest θ on the sampled path (rad)", float(theta_path.max()), float(high),
                        rtol=1e-4, source="turning point"),
            Check.below(f"{kind}: exact (elliptic) vs simulated attitude, max |Δq|", float(dq.max()), 1e-9),
        ]
    span = max(levels) - min(levels)
    ax0.set_ylim(min(levels) - 2 * span, max(levels) + 2 * span)
    ax0.set(xlabel="θ (rad)", ylabel="energy (J)")
    ax0.set_title("V_eff(θ) and energy E (dotted)")
    ax0.legend(fontsize=8)
    return Section(
        "Lagrange top: effective potential and apex loci", "§6.2–5",
        "With J3 = I3 ω3 and Jz conserved, θ moves in the effective potential V_eff(θ) between the two "
        "roots u1, u2 of the cubic f(u) = u̇². φ̇ = (b − a u)/(1 − u²) keeps its sign (monotone precession), "
        "vanishes at a turning point (cusps: released with θ̇ = φ̇ = 0) or changes sign inside the range "
        "(loops). The exact solution u = u1 + (u2 − u1) sn² with φ, ψ from elliptic integrals of the third "
        "kind is compared with kreisel.simulate under a gravity torque.",
        checks,
        [(fig, "Effective potentials, and the path of the symmetry axis seen from above between the circles "
               "of the turning points, for a top released at θ0 = 0.6 rad with three initial precession rates.")],
    )


def fast_and_sleeping_top(quick):
    """Fast top and sleeping top"""
    euler0 = [0.0, THETA0, 0.0]
    spins = np.geomspace(5.0, 200.0, 12 if quick else 30)
    exact_rates, approx_rates = [], []
    for spin in spins:
        fast = TOP.fast_top(THETA0, spin)
        exact_rates.append(fast.exact_precession_rate)
        approx_rates.append(fast.approx_precession_rate)
    exact_rates, approx_rates = np.array(exact_rates), np.array(approx_rates)
    spin = 60.0
    period = 2 * np.pi / (TOP.mgl / (TOP.I3 * spin))
    t = np.linspace(0.0, period, 4000 if quick else 20000)
    traj = TOP.simulate(t, euler0, [0.0, 0.0, spin])
    tips = so3.quat_apply(traj.q, [0.0, 0.0, 1.0])
    measured = np.unwrap(np.arctan2(tips[:, 1], tips[:, 0]))
    measured_rate = (measured[-1] - measured[0]) / (t[-1] - t[0])
    threshold = TOP.sleeping_top_threshold()
    fig, ax = panel("spin ω3 (rad/s)", "mean precession rate (rad/s)", "fast top released from rest at θ0 = 0.6 rad")
    ax.loglog(spins, exact_rates, "o-", label="exact mean φ̇")
    ax.loglog(spins, approx_rates, "--", label="m g l/(I3 ω3)")
    ax.legend()
    return Section(
        "Fast top and sleeping top", "§6.6–7",
        "A top released from rest with a large spin nutates with small amplitude 2 I1 m g l sin²θ0/J3² "
        "at frequency J3/I1 and precesses on average at m g l/(I3 ω3). An upright (sleeping) top is stable "
        "when J3² > 4 I1 m g l.",
        [Check.close("mean precession at ω3 = 60 rad/s, measured from simulation (rad/s)", float(measured_rate),
                     TOP.mgl / (TOP.I3 * spin), rtol=2e-2, source="m g l/(I3 ω3), Theory §6.7"),
         Check.below("exact vs approximate precession at ω3 = 200 rad/s (relative)",
                     abs(exact_rates[-1] / approx_rates[-1] - 1), 1e-3),
         Check.close("sleeping-top threshold ω3 (rad/s)", float(threshold), 2 * np.sqrt(TOP.I1 * TOP.mgl) / TOP.I3,
                     rtol=1e-14, source="J3² = 4 I1 m g l"),
         Check.equal("1 % above / 1 % below the threshold",
                     " / ".join("stable" if TOP.sleeping_top_stable(f * threshold) else "unstable" for f in (1.01, 0.99)),
                     "stable / unstable")],
        [(fig, "Mean precession rate of the fast top: exact against the chapter's approximation.")],
    )


def kovalevskaya_top(quick):
    """Kovalevskaya top"""
    top = KovalevskayaTop(1.0, 1.0)
    t = np.linspace(0.0, 50.0 if quick else 200.0, 2000 if quick else 8000)
    traj = top.simulate(t, [0.3, 0.7, 1.5], so3.euler_to_quat("ZXZ", [0.0, 0.7, 0.35]))
    integrals = top.integrals(traj.omega, traj.gamma)
    K = integrals.kovalevskaya
    fig, ax = panel("t (s)", "ω′ (rad/s)", f"Kovalevskaya top: K = {K[0]:.6f} conserved to {np.ptp(K) / abs(K[0]):.1e}")
    ax.plot(t, traj.omega, linewidth=0.8, label=["ω′1", "ω′2", "ω′3"])
    ax.legend(loc="center left", bbox_to_anchor=(1.0, 0.5), fontsize=8)   # beside the panel: the curves fill it
    return Section(
        "Kovalevskaya top", "§7",
        "With I1 = I2 = 2 I3 and the centre of mass in the equatorial plane the heavy top has a fourth "
        "integral, Kovalevskaya's K = (p² − q² − cγ1)² + (2pq − cγ2)², c = m g l/I3. kreisel integrates the "
        "motion and checks K along with the energy, the vertical angular momentum and |γ| = 1.",
        [Check.below("relative drift of K", float(np.ptp(K) / abs(K[0])), 1e-9),
         Check.below("relative drift of the energy", float(np.ptp(integrals.energy) / abs(integrals.energy[0])), 1e-9)],
        [(fig, "Body angular velocity of a Kovalevskaya top: chaotic-looking, yet integrable.")],
    )


SECTIONS = (lagrange_top, fast_and_sleeping_top, kovalevskaya_top)
