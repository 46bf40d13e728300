"""Figures of a :class:`~kreisel.dynamics.trajectory.Trajectory`.

Every function returns a :class:`matplotlib.figure.Figure` built with the
object-oriented API (no pyplot state), so it works in scripts, notebooks and
the command line alike.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ..so3 import quat_apply


def omega(traj, frame="body"):
    """Components of the angular velocity against time (Theory §3.1).

    Examples
    --------
    >>> import kreisel as kr, numpy as np
    >>> tr = kr.EulerTop(1, 2, 3).solve(np.linspace(0, 20, 200), [0.01, 1, 0.01])
    >>> fig = omega(tr)
    >>> fig.axes[0].get_ylabel()
    'ω (rad/s)'
    """
    values = traj.omega if frame == "body" else traj.omega_space
    prime = "′" if frame == "body" else ""
    fig = Figure(figsize=(7, 3.6), layout="constrained")
    ax = fig.add_subplot()
    for i in range(3):
        ax.plot(traj.t, values[..., i], label=f"ω{prime}{i + 1}")
    ax.set(xlabel="t (s)", ylabel="ω (rad/s)", title=f"angular velocity, {frame} components")
    ax.legend(loc="upper right")
    return fig


def energy(traj, integrals=None):
    """"First integrals" panel: the relative change of each conserved quantity along the run.

    Parameters
    ----------
    traj : Trajectory
    integrals : FirstIntegrals, optional
        The integrals of the model that was simulated (see
        :func:`kreisel.tops.first_integrals`); default: those of a free body
        (T and the space J). Under a torque without integrals the panel shows
        T and |J| themselves, which the torque changes.

    Examples
    --------
    A closed-form free top conserves T and J, so the plotted changes are at
    rounding level:

    >>> import kreisel as kr, numpy as np
    >>> tr = kr.EulerTop(1, 2, 3).solve(np.linspace(0, 20, 200), [0.01, 1, 0.01])
    >>> fig = energy(tr)
    >>> [line.get_label() for line in fig.axes[0].lines]
    ['T: kinetic energy', 'J: angular momentum (space)']
    >>> bool(max(np.abs(line.get_ydata()).max() for line in fig.axes[0].lines) < 1e-12)
    True
    """
    from ..tops import first_integrals

    found = first_integrals(traj) if integrals is None else integrals
    fig = Figure(figsize=(7, 3.6), layout="constrained")
    ax = fig.add_subplot()
    if not len(found):
        J = np.linalg.norm(traj.angular_momentum_body, axis=-1)
        ax.plot(traj.t, traj.energy.T, label="T (J)")
        ax.plot(traj.t, J.T, label="|J| (kg m²/s)")
        ax.set(xlabel="t (s)", ylabel="value (SI units)",
               title="energy and angular momentum (not conserved under this torque)")
        ax.legend(loc="best")
        return fig
    for integral in found:
        if integral.is_vector:
            change = np.linalg.norm(integral.values - integral.values[..., :1, :], axis=-1)
        else:
            change = integral.values - integral.values[..., :1]
        ax.plot(traj.t, (change / integral.scale[..., None]).T, label=f"{integral.symbol}: {integral.name}")
    ax.set(xlabel="t (s)", ylabel="change relative to its size",
           title=f"first integrals of the {found.model}: change since t = {traj.t[0]:g} s")
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 3))
    ax.legend(loc="best", fontsize="small")
    return fig


def euler(traj, seq="ZXZ", degrees=True):
    """Euler angles in sequence ``seq`` against time (Theory §2.3).

    Examples
    --------
    The chapter's mechanics angles (φ, θ, ψ) of a free symmetric top (I1 = I2),
    in degrees unless ``degrees=False``:

    >>> import kreisel as kr, numpy as np
    >>> tr = kr.EulerTop(1, 1, 2).solve(np.linspace(0, 10, 101), [0.3, 0.0, 1.0])
    >>> fig = euler(tr)
    >>> [line.get_label() for line in fig.axes[0].lines], fig.axes[0].get_ylabel()
    (['φ', 'θ', 'ψ'], 'angle (°)')
    """
    angles = traj.euler(seq, degrees=degrees)
    fig = Figure(figsize=(7, 3.6), layout="constrained")
    ax = fig.add_subplot()
    names = ("φ", "θ", "ψ") if seq == "ZXZ" else tuple(f"angle {i + 1}" for i in range(3))
    for i in range(3):
        ax.plot(traj.t, angles[..., i], label=names[i])
    ax.set(xlabel="t (s)", ylabel="angle (°)" if degrees else "angle (rad)", title=f"Euler angles ({seq})")
    ax.legend(loc="best")
    return fig


def polhode(traj):
    """Path of ω′ in the body frame on the energy ellipsoid (Theory §5.6).

    Examples
    --------
    The polhode lies on the energy ellipsoid ω′·I ω′ = 2T:

    >>> import kreisel as kr, numpy as np
    >>> tr = kr.EulerTop(1, 2, 3).solve(np.linspace(0, 20, 200), [0.01, 1, 0.01])
    >>> x, y, z = polhode(tr).axes[0].lines[0].get_data_3d()
    >>> bool(np.allclose(1 * x**2 + 2 * y**2 + 3 * z**2, 2 * tr.energy[0]))
    True
    """
    fig = Figure(figsize=(5.5, 5), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    w = traj.omega.reshape(-1, traj.t.size, 3)
    moments = np.diagonal(traj.inertia.reshape(-1, 3, 3)[0])
    t2 = float(np.einsum("i,i,i->", moments, w[0, 0], w[0, 0]))
    semi = np.sqrt(t2 / moments)
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 40), np.linspace(0, np.pi, 20))
    ax.plot_wireframe(semi[0] * np.cos(u) * np.sin(v), semi[1] * np.sin(u) * np.sin(v), semi[2] * np.cos(v),
                      color="0.8", linewidth=0.4)
    for path in w:
        ax.plot(path[:, 0], path[:, 1], path[:, 2], color="C3", linewidth=1.5)
    ax.set(xlabel="ω′1", ylabel="ω′2")
    ax.set_zlabel("ω′3")
    ax.set_title("polhode on the energy ellipsoid")
    ax.set_box_aspect(semi)
    return fig


def herpolhode(traj):
    """Path of ω (space) projected on the invariable plane ⟂ J (Theory §5.5).

    Examples
    --------
    For a symmetric top the herpolhode is a circle about the invariable line:

    >>> import kreisel as kr, numpy as np
    >>> tr = kr.EulerTop(1, 1, 2).solve(np.linspace(0, 10, 101), [0.3, 0.0, 1.0])
    >>> line = herpolhode(tr).axes[0].lines[0]
    >>> radius = np.hypot(line.get_xdata(), line.get_ydata())
    >>> bool(np.allclose(radius, radius[0]))
    True
    """
    j = traj.angular_momentum_space
    n = j[..., 0, :] / np.linalg.norm(j[..., 0, :], axis=-1, keepdims=True)
    w = traj.omega_space
    e1 = np.cross(n, [1.0, 0.0, 0.0])
    if np.linalg.norm(e1) < 1e-6:
        e1 = np.cross(n, [0.0, 1.0, 0.0])
    e1 = e1 / np.linalg.norm(e1, axis=-1, keepdims=True)
    e2 = np.cross(n, e1)
    fig = Figure(figsize=(5, 5), layout="constrained")
    ax = fig.add_subplot()
    x = np.einsum("...i,...i->...", w, e1[..., None, :])
    y = np.einsum("...i,...i->...", w, e2[..., None, :])
    ax.plot(x.T if x.ndim > 1 else x, y.T if y.ndim > 1 else y, color="C0", linewidth=0.8)
    ax.set_aspect("equal")
    ax.set(xlabel="ω · e1 (rad/s)", ylabel="ω · e2 (rad/s)", title="herpolhode on the invariable plane")
    return fig


def apex(traj, axis=2):
    """Locus of the body's symmetry axis on the unit sphere (Theory §6.5).

    Examples
    --------
    The symmetry axis of a free symmetric top sweeps a cone about J: the
    plotted tip stays on the unit sphere at a fixed angle from J:

    >>> import kreisel as kr, numpy as np
    >>> tr = kr.EulerTop(1, 1, 2).solve(np.linspace(0, 10, 101), [0.3, 0.0, 1.0])
    >>> tip = np.stack(apex(tr).axes[0].lines[0].get_data_3d(), axis=-1)
    >>> j = tr.angular_momentum_space[0] / np.linalg.norm(tr.angular_momentum_space[0])
    >>> bool(np.allclose(np.linalg.norm(tip, axis=-1), 1.0)), bool(np.allclose(tip @ j, tip[0] @ j))
    (True, True)
    """
    e = np.zeros(3)
    e[axis] = 1.0
    tip = quat_apply(traj.q, e)
    fig = Figure(figsize=(5.5, 5), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 36), np.linspace(0, np.pi, 18))
    ax.plot_wireframe(np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v), color="0.85", linewidth=0.4)
    ax.plot(tip[..., 0], tip[..., 1], tip[..., 2], color="C3", linewidth=1.2)
    ax.set_box_aspect((1, 1, 1))
    ax.set_title(f"apex locus of body axis {axis + 1}")
    return fig


KINDS = {"omega": omega, "energy": energy, "euler": euler, "polhode": polhode,
         "herpolhode": herpolhode, "apex": apex}
