"""Tour sections for Theory §4.1–3 and §5: inertia ellipsoid, tennis racket, Poinsot, symmetric top."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .. import inertia, plot, so3
from ..tops import EulerTop
from ..tops.symmetric import SymmetricTop
from .report import Check, Section

__all__ = ["inertia_ellipsoid", "tennis_racket", "poinsot_construction", "symmetric_top_cones", "cone_sense"]


def inertia_ellipsoid(quick):
    """Inertia tensor, principal axes and the inertia ellipsoid"""
    mass, size = 2.0, np.array([0.3, 0.2, 0.1])
    I_box = inertia.box(mass, size)
    a, b, c = size
    textbook = mass / 12 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
    turn = so3.euler_to_matrix("ZXZ", [0.4, 0.9, -0.3])
    turned = turn @ I_box @ turn.T
    moments, axes = inertia.principal_axes(turned)
    # ascending moments belong to the edges a > b > c in order: |axesᵀ turn| = 1 up to signs
    alignment = np.max(np.abs(np.abs(axes.T @ turn) - np.eye(3)))
    corner = np.array([a, b, c]) / 2
    about_corner = inertia.parallel_axis(I_box, mass, corner)
    corner_closed_form = mass * (np.diag([b * b + c * c, a * a + c * c, a * a + b * b]) / 3
                                 - (np.outer(size, size) - np.diag(size * size)) / 4)
    fig = plot.inertia_ellipsoid(turned, title="inertia ellipsoid xᵀ I x = 1 of a turned box")
    return Section(
        "Inertia tensor and the inertia ellipsoid", "§4.1–3",
        "The inertia tensor of a box with edges (a, b, c) is diagonal in the edge axes with "
        "I = m(b² + c²)/12 and cyclic. Turned into other axes it is full; its eigenvectors, the principal "
        "axes, recover the edges, and the inertia ellipsoid xᵀ I x = 1 has semi-axes 1/√I_k along them "
        "(the longest along the smallest moment). The parallel-axis theorem I = I_C + M(r²1 − r rᵀ) moves "
        "the tensor to a corner.",
        [Check.below("box moments vs m(b² + c²)/12 (relative)", np.max(np.abs(np.diag(I_box) / textbook - 1)), 1e-15),
         Check.below("principal moments of the turned tensor (relative)",
                     np.max(np.abs(moments / np.sort(textbook) - 1)), 1e-13),
         Check.below("principal axes vs the box's edges", alignment, 1e-12),
         Check.below("parallel axis to a corner vs the corner's closed form (relative)",
                     np.max(np.abs(about_corner - corner_closed_form)) / np.max(corner_closed_form), 1e-15)],
        [(fig, "The inertia ellipsoid with its three principal axes.")],
    )


def tennis_racket(quick):
    """Tennis-racket theorem: flips about the middle axis"""
    top = EulerTop(1.0, 2.0, 3.0)
    t = np.linspace(0.0, 60.0, 1500 if quick else 6000)
    starts = {"near axis 1 (smallest)": [1.0, 0.01, 0.01], "near axis 2 (middle)": [0.01, 1.0, 0.01],
              "near axis 3 (largest)": [0.01, 0.01, 1.0]}
    fig = Figure(figsize=(9, 6), layout="constrained")
    axes = fig.subplots(3, 1, sharex=True)
    for ax, (label, w0) in zip(axes, starts.items()):
        tr = top.solve(t, w0)
        for k in range(3):
            ax.plot(t, tr.omega[:, k], label=f"ω′{k + 1}")
        ax.set_ylabel("rad/s")
        ax.set_title(f"spun {label}", fontsize=10)
    axes[0].legend(loc="center right", ncol=3)   # between ω′1 ≈ 1 and the small components
    axes[-1].set_xlabel("t (s)")   # shared by the panels above
    middle = top.solve(t, starts["near axis 2 (middle)"])
    crossings = t[:-1][np.diff(np.sign(middle.omega[:, 1])) != 0]
    measured = float(np.mean(np.diff(crossings)))
    predicted = top.dzhanibekov_flip_time(starts["near axis 2 (middle)"])
    kinds = [s.kind for s in top.steady_rotations()]
    late = top.solve([0.0, 1e5], [0.01, 1.0, 0.01])
    energy_error = abs(late.energy[1] / late.energy[0] - 1)
    j_error = np.max(np.abs(late.angular_momentum_space[1] - late.angular_momentum_space[0])) / np.linalg.norm(
        late.angular_momentum_space[0])
    return Section(
        "Tennis-racket theorem and the Dzhanibekov flip", "§5.4",
        "Steady rotation about the axes of largest and smallest moment is stable; about the middle axis a "
        "small perturbation grows exponentially and the body flips over again and again (Dzhanibekov "
        "effect). kreisel's Euler top is the exact elliptic-function solution, so the flip time "
        "2K(m)/λ and the first integrals hold at any time without time stepping.",
        [Check.equal("stability of axes 1, 2, 3", ", ".join(kinds), "stable, unstable, stable"),
         Check.close("flip time from the zero crossings of ω′2 (s)", measured, predicted, rtol=3e-3,
                     source="2K(m)/λ"),
         Check.below("energy error at t = 1e5 s (relative)", energy_error, 1e-12),
         Check.below("space angular momentum error at t = 1e5 s (relative)", j_error, 1e-12)],
        [(fig, "Body angular velocity of the free top I = (1, 2, 3) kg m² started near each principal axis.")],
    )


def poinsot_construction(quick):
    """Poinsot construction: polhodes and herpolhode"""
    moments = np.array([1.0, 2.0, 3.0])
    top = EulerTop(*moments)
    fig = Figure(figsize=(10, 4.8), layout="constrained")
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 40), np.linspace(0, np.pi, 20))
    semi = 1 / np.sqrt(moments)
    ax.plot_surface(semi[0] * np.cos(u) * np.sin(v), semi[1] * np.sin(u) * np.sin(v), semi[2] * np.cos(v),
                    color="0.85", alpha=0.3, linewidth=0)
    t = np.linspace(0.0, 40.0, 800 if quick else 3000)
    spread = []
    for angle in np.linspace(0.15, 1.45, 6):
        for sign in (1, -1):
            for w0 in ([np.cos(angle), 0.0, sign * np.sin(angle)], [sign * np.sin(angle), np.cos(angle) * 0.3, 0.0]):
                tr = top.solve(t, w0)
                rho = tr.omega / np.sqrt(2 * tr.energy[:, None])  # on the inertia ellipsoid ρᵀ I ρ = 1
                ax.plot(rho[:, 0], rho[:, 1], rho[:, 2], color="C3", linewidth=0.8)
                j_hat = tr.angular_momentum_space / np.linalg.norm(tr.angular_momentum_space, axis=-1, keepdims=True)
                distance = np.einsum("ij,ij->i", so3.quat_apply(tr.q, rho), j_hat)
                spread.append(np.max(np.abs(distance / (np.sqrt(2 * tr.energy) / np.linalg.norm(
                    tr.angular_momentum_space, axis=-1)) - 1)))
    ax.set_box_aspect(semi)
    unit = "(1/√(kg m²))"
    ax.set(xlabel=f"ρ′1 {unit}", ylabel=f"ρ′2 {unit}", zlabel=f"ρ′3 {unit}")
    ax.set_title("polhodes on the inertia ellipsoid")
    tr = top.solve(np.linspace(0, 200, 4000 if quick else 20000), [0.4, 0.2, 1.0])
    j_hat = tr.angular_momentum_space[0] / np.linalg.norm(tr.angular_momentum_space[0])
    e1 = np.cross(j_hat, [1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(j_hat, e1)
    rho_space = so3.quat_apply(tr.q, tr.omega) / np.sqrt(2 * tr.energy[:, None])
    ax2 = fig.add_subplot(1, 2, 2)
    ax2.plot(rho_space @ e1, rho_space @ e2, linewidth=0.6)
    ax2.set_aspect("equal")
    ax2.set(xlabel="ρ · e1 (1/√(kg m²))", ylabel="ρ · e2 (1/√(kg m²))")
    ax2.set_title("herpolhode on the invariable plane")
    return Section(
        "Poinsot construction", "§5.5–6",
        "The point ρ = ω/√(2T) lies on the inertia ellipsoid ρᵀ I ρ = 1, whose tangent plane there is "
        "normal to J and at the fixed distance √(2T)/|J| from the fixed point: the ellipsoid rolls without "
        "slipping on this invariable plane. ρ traces the polhode on the ellipsoid (closed curves around "
        "the largest and smallest axes, separated by the separatrix through the middle axis) and the "
        "herpolhode on the plane.",
        [Check.below("invariable-plane distance vs √(2T)/|J| over all orbits (relative)", max(spread), 1e-12)],
        [(fig, "Left: polhodes of the free top I = (1, 2, 3). Right: one herpolhode.")],
    )


def symmetric_top_cones(quick):
    """Symmetric free top: regular precession and the body and space cones"""
    I1, I3, J, theta0 = 1.0, 2.0, 1.5, 0.5
    sym = SymmetricTop(I1, I3)
    t = np.linspace(0.0, 30.0, 300 if quick else 1500)
    closed = sym.solve(t, J, theta0)
    exact = EulerTop(I1, I1, I3).solve(t, closed.omega[0], closed.q[0])
    dq = np.min(np.stack([np.linalg.norm(closed.q - exact.q, axis=-1), np.linalg.norm(closed.q + exact.q, axis=-1)]), 0)
    angles = so3.quat_to_euler("ZXZ", closed.q)
    psi_rate = np.polyfit(t, np.unwrap(angles[:, 2]), 1)[0]
    chapter_psi_rate = -(I3 - I1) * J * np.cos(theta0) / (I1 * I3)
    oblate, prolate = sym.cones(J, theta0), SymmetricTop(2.0, 1.0).cones(J, theta0)

    fig = Figure(figsize=(5.5, 5), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    w_space = closed.omega_space
    e3 = so3.quat_apply(closed.q, [0.0, 0.0, 1.0])
    ax.plot(*w_space.T / np.linalg.norm(w_space[0]), color="C3", label="ω (space cone)")
    ax.plot(*e3.T, color="C0", label="symmetry axis e3")
    ax.quiver(0, 0, 0, 0, 0, 1, color="k", arrow_length_ratio=0.08)
    ax.text(0, 0, 1.08, "J")
    for k in range(0, t.size, max(1, t.size // 12)):
        ax.plot(*np.c_[np.zeros(3), w_space[k] / np.linalg.norm(w_space[k])], color="C3", alpha=0.3, linewidth=0.6)
    ax.legend(loc="upper left", fontsize=8)
    ax.set(xlabel="x (space, unit vectors)", ylabel="y (space)", zlabel="z (space, along J)")
    ax.set_title("regular precession of an oblate top (I3 = 2 I1)")
    return Section(
        "Symmetric top: regular precession, body and space cones", "§5.7",
        "For I1 = I2 the chapter's closed form is φ = J t/I1 + φ0, θ = θ0, ψ = −(I3 − I1) J cos θ0 t/(I1 I3) + ψ0. "
        "ω lies in the plane of J and e3 and sweeps the space cone about J while it sweeps the body cone "
        "about e3. For an oblate top (I3 > I1) the body cone rolls with its inside on the space cone, in "
        "the same sense; for a prolate top the cones touch outside and turn in opposite senses.",
        [Check.below("closed form vs general elliptic solution, max |Δq|", float(np.max(dq)), 1e-12),
         Check.close("ψ̇ measured (rad/s)", float(psi_rate), chapter_psi_rate, rtol=1e-10, source="Theory §5.7"),
         Check.equal("oblate: cones", f"{oblate.relation}, {cone_sense(oblate)}",
                     "space cone inside body cone, turning in the same sense"),
         Check.equal("prolate: cones", f"{prolate.relation}, {cone_sense(prolate)}",
                     "body cone outside space cone, turning in opposite senses")],
        [(fig, "ω and the symmetry axis during regular precession; J is fixed along z.")],
    )


def cone_sense(cones):
    """How ω goes round the two cones of :meth:`kreisel.tops.SymmetricTop.cones`, in words.

    Examples
    --------
    >>> from kreisel.tops import SymmetricTop
    >>> cone_sense(SymmetricTop(1.0, 2.0).cones(1.0, 0.3))
    'turning in the same sense'
    """
    return "turning in the same sense" if cones.same_sense else "turning in opposite senses"
