"""Figures of a :class:`~kreisel.dynamics.trajectory.Trajectory`.

Every function returns a :class:`matplotlib.figure.Figure` built with the
object-oriented API (no pyplot state), so it works in scripts, notebooks and
the command line alike.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ..so3 import quat_apply

__all__ = ["omega", "energy", "euler", "polhode", "herpolhode", "apex", "coning", "foucault", "regular_sequence", "KINDS",
           "DATASET_KINDS"]


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


_SEQUENCES = ("ZXZ", "ZYZ", "XYX", "XZX", "YXY", "YZY", "ZYX", "ZXY", "XYZ", "XZY", "YXZ", "YZX")
_NAMES = {"ZXZ": ("φ", "θ", "ψ")}


def regular_sequence(q):
    """The Euler sequence whose middle angle stays farthest from its singularity along attitudes ``q``.

    The chapter's ZXZ is kept whenever θ stays at least 10° away from 0 and
    180°; otherwise the intrinsic sequence with the largest margin is chosen
    (Theory §2.3: every sequence has a gimbal lock, at a different attitude).

    Examples
    --------
    A tennis racket spun about body axis 2 starts with θ = 0 in ZXZ (singular);
    a sequence whose lock lies elsewhere is chosen:

    >>> import kreisel as kr, numpy as np
    >>> tr = kr.EulerTop(1, 2, 3).solve(np.linspace(0, 5, 51), [0.01, 1, 0.01])
    >>> regular_sequence(tr.q) != "ZXZ"
    True
    >>> regular_sequence(kr.euler_to_quat("ZXZ", [[0.1, 0.8, 0.2], [0.3, 1.1, 0.4]]))
    'ZXZ'
    """
    from ..so3 import quat_to_matrix

    R = quat_to_matrix(q).reshape(-1, 3, 3)
    axis = {"X": 0, "Y": 1, "Z": 2}

    def margin(seq):
        # R[i, k] (i, k the outer axes) is ±cos of the middle angle for proper Euler sequences (i = k) and ±sin
        # for Tait–Bryan ones: both lock where it is ±1, and arccos|R[i, k]| is the angle to the lock
        i, k = axis[seq[0]], axis[seq[2]]
        return float(np.min(np.arccos(np.clip(np.abs(R[:, i, k]), 0.0, 1.0))))

    if margin("ZXZ") >= np.radians(10.0):
        return "ZXZ"
    return max(_SEQUENCES, key=margin)


def euler(traj, seq=None, degrees=True):
    """Euler angles against time, unwrapped, in a sequence regular for the motion (Theory §2.3).

    Parameters
    ----------
    traj : Trajectory
    seq : str, optional
        Axis sequence; default: :func:`regular_sequence` of the trajectory
        (the chapter's ZXZ unless the motion passes near its gimbal lock).
    degrees : bool
        Angles in degrees (default) or radians.

    Angles are unwrapped (no jumps of 360°), so a steady spin is a straight line.

    Examples
    --------
    The chapter's mechanics angles (φ, θ, ψ) of a tilted free symmetric top (I1 = I2):

    >>> import kreisel as kr, numpy as np
    >>> q0 = kr.euler_to_quat("ZXZ", [0.0, 0.5, 0.0])
    >>> tr = kr.EulerTop(1, 1, 2).solve(np.linspace(0, 10, 101), [0.3, 0.0, 1.0], q0)
    >>> fig = euler(tr)
    >>> [line.get_label() for line in fig.axes[0].lines], fig.axes[0].get_ylabel()
    (['φ', 'θ', 'ψ'], 'angle (°)')
    >>> bool(np.all(np.abs(np.diff(fig.axes[0].lines[2].get_ydata())) < 180))   # unwrapped
    True
    """
    seq = regular_sequence(traj.q) if seq is None else seq
    angles = np.unwrap(traj.euler(seq), axis=-2)
    angles = np.degrees(angles) if degrees else angles
    fig = Figure(figsize=(7, 3.6), layout="constrained")
    ax = fig.add_subplot()
    names = _NAMES.get(seq, tuple(f"angle {i + 1} (about {a})" for i, a in enumerate(seq.upper())))
    for i in range(3):
        ax.plot(traj.t, angles[..., i].T, label=names[i])
    ax.set(xlabel="t (s)", ylabel="angle (°)" if degrees else "angle (rad)",
           title=f"Euler angles, {'intrinsic' if seq.isupper() else 'extrinsic'} {seq}, unwrapped")
    ax.legend(loc="best")
    return fig


def polhode(traj):
    """Path of ω′ in the body frame on the energy ellipsoid (Theory §5.6).

    Under a torque (a heavy top) the kinetic energy changes and ω′ is on no one
    ellipsoid: the path is then drawn alone, on axes fitted to it.

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
    energy = np.asarray(traj.energy).reshape(-1, traj.t.size)
    for path in w:
        ax.plot(path[:, 0], path[:, 1], path[:, 2], color="C3", linewidth=1.5)
    ax.set(xlabel="ω′1 (rad/s)", ylabel="ω′2 (rad/s)", zlabel="ω′3 (rad/s)")
    if np.all(np.ptp(energy, axis=-1) <= 1e-6 * np.max(np.abs(energy), axis=-1)):
        moments = np.diagonal(traj.inertia.reshape(-1, 3, 3)[0])
        t2 = float(np.einsum("i,i,i->", moments, w[0, 0], w[0, 0]))
        semi = np.sqrt(t2 / moments)
        u, v = np.meshgrid(np.linspace(0, 2 * np.pi, 40), np.linspace(0, np.pi, 20))
        ax.plot_wireframe(semi[0] * np.cos(u) * np.sin(v), semi[1] * np.sin(u) * np.sin(v), semi[2] * np.cos(v),
                          color="0.8", linewidth=0.4)
        ax.set_title("polhode on the energy ellipsoid")
        ax.set_box_aspect(semi / semi.max(), zoom=0.8)   # zoom < 1 leaves room for the axis labels
    else:
        # under a torque T changes and ω′ leaves the ellipsoid; a fast top's ω′ circles its pole so closely
        # that on the ellipsoid's scale the path would not be seen: the axes fit the path instead
        ax.set_title("path of ω′ in the body (T changes under the torque:\nno energy ellipsoid)")
        ax.set_box_aspect(None, zoom=0.8)
    ax.locator_params(nbins=5)
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
    """Path of the tip of a body axis: seen from above, and its tilt against time (Theory §6.5).

    The left panel shows the tip of the unit body axis projected on the
    horizontal plane (zoomed to the path, so a fast top's small nutation
    loops show); the right panel its angle θ from the vertical, in which
    nutation is the oscillation.

    Examples
    --------
    The symmetry axis of a free symmetric top sweeps a cone about J:

    >>> import kreisel as kr, numpy as np
    >>> tr = kr.EulerTop(1, 1, 2).solve(np.linspace(0, 10, 101), [0.3, 0.0, 1.0])
    >>> fig = apex(tr)
    >>> [ax.get_xlabel() for ax in fig.axes]
    ['x (unit length)', 't (s)']
    >>> tip = np.stack(fig.axes[0].lines[0].get_data(), axis=-1)
    >>> bool(np.allclose(tip, kr.quat_apply(tr.q, [0, 0, 1.0])[:, :2]))
    True
    """
    e = np.zeros(3)
    e[axis] = 1.0
    tip = quat_apply(traj.q, e)
    tilt = np.degrees(np.arctan2(np.hypot(tip[..., 0], tip[..., 1]), tip[..., 2]))
    fig = Figure(figsize=(10, 4.2), layout="constrained")
    top, side = fig.subplots(1, 2, width_ratios=(1, 1.4))
    top.plot(tip[..., 0].T, tip[..., 1].T, color="C3", linewidth=0.9)
    top.plot(tip[..., 0, 0], tip[..., 0, 1], "ko", markersize=4, label="start")
    top.set_aspect("equal", adjustable="datalim")
    top.set(xlabel="x (unit length)", ylabel="y (unit length)", title=f"tip of body axis {axis + 1}, seen from above")
    top.legend(loc="best", fontsize=8)
    side.plot(traj.t, tilt.T, color="C0", linewidth=0.9)
    side.set(xlabel="t (s)", ylabel="θ, angle from the vertical (°)", title="tilt: nutation is its oscillation")
    return fig


def foucault(dataset):
    """Swing-plane azimuth and tilt of a Foucault-pendulum run of :mod:`kreisel.io` (Theory §8.3).

    Examples
    --------
    >>> import kreisel as kr
    >>> ds = kr.io.run_scenario(kr.io.load_scenario("foucault"))
    >>> fig = foucault(ds)
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['swing azimuth change (°)', 'swing amplitude (°)']

    The amplitude, nearly constant, is drawn from 0 in plain degrees (no axis offset):

    >>> float(fig.axes[1].get_ylim()[0]), fig.axes[1].yaxis.get_major_formatter().get_useOffset()
    (0.0, False)
    """
    t = dataset["time"].values
    azimuth = np.degrees(np.unwrap(dataset["swing_azimuth"].values))
    fig = Figure(figsize=(8, 5), layout="constrained")
    turn, tilt = fig.subplots(2, 1, sharex=True)
    turn.plot(t / 3600, azimuth - azimuth[0], label="measured at each swing")
    rate = dataset.attrs.get("precession_rate_theory")
    if rate is not None:
        turn.plot(t / 3600, np.degrees(rate * (t - t[0])), "k--", linewidth=0.8, label="−Ω sin λ t")
    turn.set(ylabel="swing azimuth change (°)", title="Foucault pendulum: the swing plane turns")
    turn.legend(loc="best", fontsize=8)
    amplitude = np.degrees(dataset["tilt"].values)
    tilt.plot(t / 3600, amplitude, linewidth=0.8)
    # the amplitude barely changes: from 0 and without an offset ("1e-9 + 2.86478897") its scale reads at a glance
    tilt.ticklabel_format(axis="y", useOffset=False)
    top = 1.2 * float(np.max(amplitude, initial=0.0)) or 1.0
    tilt.set(ylim=(0.0, top), xlabel="t (h)", ylabel="swing amplitude (°)", title="string angle from the vertical at each swing")
    return fig


def coning(dataset):
    """Attitude error of strapdown integration under coning motion, from :mod:`kreisel.io` (Theory §3.5).

    Examples
    --------
    One curve for each body-axis component of the error the run stored:

    >>> from kreisel.io import load_scenario, run_scenario
    >>> ds = run_scenario(load_scenario("coning"))
    >>> ax = coning(ds).axes[0]
    >>> ax.get_ylabel(), [bool((line.get_ydata() == ds["attitude_error"][:, k]).all()) for k, line in enumerate(ax.lines)]
    ('attitude error (rad)', [True, True, True])
    """
    t = dataset["time"].values
    error = dataset["attitude_error"].values
    fig = Figure(figsize=(7, 3.6), layout="constrained")
    ax = fig.add_subplot()
    for k, name in enumerate("xyz"):
        ax.plot(t, error[:, k], label=f"about body {name}")
    ax.set(xlabel="t (s)", ylabel="attitude error (rad)", title="strapdown attitude error under coning")
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 3))
    ax.legend(loc="best", fontsize=8)
    return fig


KINDS = {"omega": omega, "energy": energy, "euler": euler, "polhode": polhode,
         "herpolhode": herpolhode, "apex": apex}
DATASET_KINDS = {"Foucault pendulum": {"azimuth": foucault}, "coning": {"error": coning}}
"""Plots of the result files that hold no trajectory, by their ``kreisel`` attribute: {kind: function}."""
