"""Tour sections for Theory §2: Euler angles, gimbal lock, quaternion renormalisation."""

from __future__ import annotations

import warnings

import numpy as np
from matplotlib.figure import Figure
from scipy.spatial.transform import Rotation as ScipyRotation

from .. import kinematics, so3
from .report import Check, Section, panel

__all__ = ["euler_angles_and_nodal_line", "gimbal_lock", "quaternion_renormalisation", "SECTIONS", "ALL_SEQUENCES",
           "axis_rotation"]

ALL_SEQUENCES = ("xyz", "xzy", "yxz", "yzx", "zxy", "zyx", "xyx", "xzx", "yxy", "yzy", "zxz", "zyz")


def axis_rotation(axis, angle):
    """The chapter's elementary rotation matrix about axis 0, 1 or 2 (x, y, z), built by hand.

    Examples
    --------
    >>> axis_rotation(2, np.pi / 2).round(12) + 0.0
    array([[ 0., -1.,  0.],
           [ 1.,  0.,  0.],
           [ 0.,  0.,  1.]])
    """
    c, s = np.cos(angle), np.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = np.eye(3)
    m[i, i] = m[j, j] = c
    m[i, j], m[j, i] = -s, s
    return m


def euler_angles_and_nodal_line(quick):
    """Euler angles and the nodal line"""
    phi, theta, psi = np.deg2rad([40.0, 35.0, 25.0])
    R = so3.euler_to_matrix("ZXZ", [phi, theta, psi])
    chapter_R = axis_rotation(2, phi) @ axis_rotation(0, theta) @ axis_rotation(2, psi)
    back = so3.matrix_to_euler("ZXZ", R)
    rng = np.random.default_rng(1)
    angles = rng.uniform(-np.pi, np.pi, (200 if quick else 2000, 3))
    angles[:, 1] = rng.uniform(0.1, np.pi - 0.1, angles.shape[0])
    worst = 0.0
    for seq in ALL_SEQUENCES:
        for s in (seq, seq.upper()):
            ours = so3.euler_to_matrix(s, angles)
            theirs = ScipyRotation.from_euler(s, angles).as_matrix()
            worst = max(worst, float(np.max(np.abs(ours - theirs))))

    fig = Figure(figsize=(5.5, 5), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    for k, name in enumerate("xyz"):
        e = np.eye(3)[k]
        ax.quiver(0, 0, 0, *e, color="0.6", arrow_length_ratio=0.08)
        ax.text(*(1.12 * e), name, color="0.4")
        b = R[:, k]
        ax.quiver(0, 0, 0, *b, color=f"C{k}", arrow_length_ratio=0.08, linewidth=2)
        ax.text(*(1.1 * b), f"{name}′", color=f"C{k}")
    node = axis_rotation(2, phi)[:, 0]
    ax.plot(*np.c_[-node, node], "k--", linewidth=1.2)
    ax.text(*(0.55 * node + [0.0, 0.0, 0.08]), "nodal line N", color="k", ha="center")
    ax.set(xlim=(-1.1, 1.1), ylim=(-1.1, 1.1), zlim=(-1.1, 1.1), xlabel="x (space)", ylabel="y (space)",
           zlabel="z (space)")
    ax.set_box_aspect((1, 1, 1))
    ax.set_title("ZXZ (φ, θ, ψ) = (40°, 35°, 25°)")

    return Section(
        "Euler angles and the nodal line", "§2.3",
        "The mechanics Euler angles (φ, θ, ψ) are the intrinsic sequence ZXZ: R = Rz(φ) Rx(θ) Rz(ψ). "
        "The body x′y′ plane meets the space xy plane along the nodal line N = Rz(φ) e_x. All 24 "
        "sequences (12 axis orders, intrinsic and extrinsic) agree with scipy.",
        [Check.below("|R − Rz(φ)Rx(θ)Rz(ψ)| (chapter's product)", np.max(np.abs(R - chapter_R)), 1e-15),
         Check.below("angles recovered from R (rad)", np.max(np.abs(back - [phi, theta, psi])), 1e-14),
         Check.below("max |R − scipy R| over 24 conventions", worst, 1e-14)],
        [(fig, "Space axes (grey) and body axes (colour) for ZXZ angles; the dashed line is the line of nodes.")],
    )


def gimbal_lock(quick):
    """Gimbal lock"""
    theta = np.logspace(-8, np.log10(np.pi / 2), 60)
    angles = np.stack([np.full_like(theta, 0.3), theta, np.full_like(theta, 0.2)], axis=-1)
    omega = np.array([0.3, -0.5, 0.8])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rates = kinematics.euler_rates("ZXZ", angles, omega, frame="body")
    q = so3.euler_to_quat("ZXZ", angles)
    qdot = kinematics.quat_rate(q, omega, frame="body")
    near = np.array([[0.7, 0.0, -1.1], [0.7, 1e-9, -1.1], [0.7, np.pi, 0.4], [0.7, np.pi - 1e-8, 0.4]])
    R = so3.euler_to_matrix("ZXZ", near)
    recon = so3.euler_to_matrix("ZXZ", so3.matrix_to_euler("ZXZ", R))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        locked = kinematics.euler_rates("ZXZ", [0.7, 0.0, -1.1], omega, frame="body")
    warned = any(issubclass(w.category, kinematics.GimbalLockWarning) for w in caught)

    fig, ax = panel("θ (rad)", "rate", "ZXZ Euler rates blow up like 1/sin θ; quaternion rates do not")
    ax.loglog(theta, np.abs(rates[:, 0]), label="|φ̇|")
    ax.loglog(theta, np.abs(rates[:, 2]), "--", label="|ψ̇|")
    ax.loglog(theta, np.linalg.norm(qdot, axis=-1), label="|q̇| = |ω|/2")
    ax.legend()
    return Section(
        "Gimbal lock", "§2.3, §3.6",
        "At θ = 0 or π the ZXZ angles φ and ψ rotate about the same axis and only φ ± ψ is defined. "
        "Euler rates for a fixed ω diverge like 1/sin θ, and at the singular point kreisel returns NaN "
        "with a GimbalLockWarning rather than a wrong finite number. The quaternion rate q̇ = ½ q ω′ "
        "stays |ω|/2. Converting a matrix to angles at or near the lock still reconstructs the rotation "
        "to round-off.",
        [Check.below("|R(angles(R)) − R| at and near θ = 0, π", np.max(np.abs(recon - R)), 4e-16),
         Check.equal("NaN rates and a GimbalLockWarning at θ = 0", bool(np.isnan(locked[0]) and warned), True),
         Check.close("|q̇| / (|ω|/2) over all θ", float(np.max(np.linalg.norm(qdot, axis=-1)) / (np.linalg.norm(omega) / 2)),
                     1.0, rtol=1e-14)],
        [(fig, "Euler-angle rates against the middle angle θ for one fixed body angular velocity.")],
    )


def quaternion_renormalisation(quick):
    """Quaternion renormalisation against DCM drift"""
    steps = 2000 if quick else 20000
    h = 0.01
    q = np.array([1.0, 0.0, 0.0, 0.0])
    qn = q.copy()
    R = np.eye(3)
    Rn = np.eye(3)
    err = np.empty((steps, 4))

    def omega(t):
        return np.array([np.sin(t), np.cos(2 * t), 0.5])

    def rk4(f, y, t):
        k1 = f(t, y)
        k2 = f(t + h / 2, y + h / 2 * k1)
        k3 = f(t + h / 2, y + h / 2 * k2)
        k4 = f(t + h, y + h * k3)
        return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)

    def fq(t, y):
        return kinematics.quat_rate(y, omega(t), frame="body")

    def fR(t, y):
        return y @ so3.hat(omega(t))

    for n in range(steps):
        t = n * h
        q, qn, R, Rn = rk4(fq, q, t), rk4(fq, qn, t), rk4(fR, R, t), rk4(fR, Rn, t)
        qn = so3.quat_normalize(qn)
        Rn = so3.orthonormalize(Rn)
        err[n] = [abs(np.linalg.norm(q) - 1), abs(np.linalg.norm(qn) - 1),
                  np.linalg.norm(R.T @ R - np.eye(3)), np.linalg.norm(Rn.T @ Rn - np.eye(3))]
    fig, ax = panel("t (s)", "| |q| − 1 |  or  |RᵀR − 1|", "RK4 attitude integration, h = 0.01 s")
    t = h * np.arange(1, steps + 1)
    for k, label in enumerate(["quaternion, raw", "quaternion, renormalised", "DCM, raw", "DCM, SVD-projected"]):
        ax.semilogy(t, np.maximum(err[:, k], 1e-17), label=label, linewidth=1)
    ax.legend()
    return Section(
        "Quaternion renormalisation vs DCM drift", "§2.4(2)",
        "Integrating the attitude numerically lets a quaternion leave the unit sphere and a DCM leave SO(3). "
        "The quaternion is repaired by one division by its norm after each step; the DCM needs the nearest "
        "rotation (polar decomposition / SVD). Both repairs hold the error at round-off.",
        [Check.below("renormalised quaternion: max | |q| − 1 |", np.max(err[:, 1]), 1e-15),
         Check.below("SVD-projected DCM: max |RᵀR − 1| (Frobenius)", np.max(err[:, 3]), 1e-14),
         Check.equal("raw DCM drifts further than projected DCM", bool(err[-1, 2] > 100 * err[-1, 3]), True)],
        [(fig, "Constraint error of quaternion and DCM attitude under RK4, with and without repair.")],
    )


SECTIONS = (euler_angles_and_nodal_line, gimbal_lock, quaternion_renormalisation)
