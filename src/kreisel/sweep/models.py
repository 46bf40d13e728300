"""The bundled sweeps: chunk functions, their checks and their plots.

Each chunk function takes the grid parameters of a chunk as 1-D arrays plus
keyword constants and returns ``{variable: array}`` (see :func:`kreisel.sweep.sweep`).
Each plot function takes the resulting dataset and returns a
:class:`matplotlib.figure.Figure` (object-oriented API, no pyplot state).
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np

from .._optional import require

__all__ = [
    "tennis_racket_flip",
    "plot_tennis_racket",
    "lagrange_apex_locus",
    "plot_lagrange_apex_locus",
    "imu_attitude_error",
    "plot_imu_attitude_error",
    "SweepModel",
    "APEX_LOCUS_KINDS",
    "MODELS",
]

APEX_LOCUS_KINDS = ("monotone", "cusp", "loop")


def _matplotlib(module):
    """``matplotlib.<module>``, or one line naming the ``plot`` extra if matplotlib is missing."""
    return require(f"matplotlib.{module}", extra="plot", feature="sweep plots")


def _figure():
    """``(figure, axes)``: the one-axes figure every sweep plot draws on."""
    fig = _matplotlib("figure").Figure(figsize=(6.4, 4.8), layout="constrained")
    return fig, fig.add_subplot()


# ---- tennis-racket stability map (Theory §5.4) ----------------------------------------------------
def _first_middle_axis_zero(trajectory):
    """Time of the first sign change of ω2 on each body, by cubic Hermite interpolation.

    Between samples ω2 and its derivative ω̇2 = (I3 − I1) ω3 ω1 / I2 (Euler's
    equations) fix a cubic whose root is found by bisection: the error is
    O(h⁴) in the sample spacing h instead of the O(h²) of a linear
    interpolation. Bodies whose ω2 keeps its sign give NaN.
    """
    t = trajectory.t
    w = trajectory.omega
    moments = np.diagonal(trajectory.inertia, axis1=-2, axis2=-1)
    w2 = w[..., 1]
    rate = ((moments[:, 2] - moments[:, 0]) / moments[:, 1])[:, None] * w[..., 2] * w[..., 0]
    crossed = np.signbit(w2[:, 1:]) != np.signbit(w2[:, :1])
    has = crossed.any(axis=1)
    j = np.argmax(crossed, axis=1)
    rows = np.arange(w2.shape[0])
    h = t[j + 1] - t[j]
    f0, f1 = w2[rows, j], w2[rows, j + 1]
    d0, d1 = rate[rows, j] * h, rate[rows, j + 1] * h

    def hermite(s):
        return ((2 * s**3 - 3 * s**2 + 1) * f0 + (s**3 - 2 * s**2 + s) * d0
                + (-2 * s**3 + 3 * s**2) * f1 + (s**3 - s**2) * d1)

    lo, hi = np.zeros_like(f0), np.ones_like(f0)
    sign0 = np.signbit(f0)
    for _ in range(60):  # 2^-60 of the interval: below round-off
        mid = 0.5 * (lo + hi)
        same = np.signbit(hermite(mid)) == sign0
        lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
    return np.where(has, t[j] + 0.5 * (lo + hi) * h, np.nan)


def _check_omega_samples(store_omega, every, n_samples):
    """``every`` decimates the stored ω′ and must keep the last sample (as in :func:`kreisel.simulate_batch`)."""
    if isinstance(every, bool) or not isinstance(every, (int, np.integer)) or every < 1:
        raise ValueError(f"every must be a positive integer, got {every!r}")
    if not store_omega and every != 1:
        raise ValueError("every decimates the stored angular velocity: set store_omega = true, or leave every at 1")
    if (n_samples - 1) % every:
        raise ValueError(f"every must divide n_samples - 1 = {n_samples - 1} (so that the last sample is kept), "
                         f"got {every}")


def tennis_racket_flip(middle_moment, tilt_deg, *, I1=1.0, I3=2.0, spin=1.0, t_end=60.0, n_samples=1201,
                       method="dop853", dt=None, exact=True, store_omega=False, every=1):
    """Flip time of a body spun near its middle axis (Dzhanibekov effect, Theory §5.4).

    The body (I1, I2 = ``middle_moment``, I3) starts with ω′ = spin (sin τ, cos τ, 0),
    τ = ``tilt_deg``: ω3 = 0 puts ω2 at an extremum, so the first zero of ω2
    comes after a quarter period of ω2 and the flip time (between successive
    reversals, :meth:`kreisel.EulerTop.dzhanibekov_flip_time`) is twice it.
    All bodies of the chunk are integrated by one :func:`kreisel.simulate_batch`
    call whose ``reduce`` hook keeps only that zero. ``flip_time`` is NaN when
    no flip happens before ``t_end``; ``flip_time_exact`` (when ``exact``) is
    the closed form from Jacobi elliptic functions.

    With ``store_omega`` the body angular velocity ω′ of every body is also
    returned, as ``omega`` of shape ``(points, samples, 3)`` at the times
    ``linspace(0, t_end, n_samples)[::every]``: ``every`` (dividing
    ``n_samples - 1``) decimates the stored samples, while the flip time is
    still found from all of them. Run such a sweep with ``stream=True`` (a
    sweep file's ``stream = true``) when the histories outgrow memory.

    Examples
    --------
    The simulated flip time agrees with the closed form from Jacobi elliptic
    functions, and grows as the initial tilt from the middle axis shrinks:

    >>> out = tennis_racket_flip(np.array([1.5, 1.5]), np.array([1.0, 0.1]), t_end=80.0)
    >>> bool(np.allclose(out["flip_time"], out["flip_time_exact"], rtol=1e-6))
    True
    >>> bool(out["flip_time"][1] > out["flip_time"][0])
    True
    >>> tennis_racket_flip(np.array([1.5]), np.array([1.0]), n_samples=1201, store_omega=True, every=100)["omega"].shape
    (1, 13, 3)
    """
    from ..dynamics import simulate_batch
    from ..tops import EulerTop

    _check_omega_samples(store_omega, every, n_samples)
    middle = np.asarray(middle_moment, dtype=float)
    tilt = np.radians(np.asarray(tilt_deg, dtype=float))
    bodies = np.stack([np.full_like(middle, I1), middle, np.full_like(middle, I3)], axis=-1)
    omega0 = spin * np.stack([np.sin(tilt), np.cos(tilt), np.zeros_like(tilt)], axis=-1)
    t = np.linspace(0.0, t_end, n_samples)
    if store_omega:
        # one row per body: the zero of ω2 (from every sample), then the kept samples of ω′
        rows = simulate_batch(bodies, t, omega0, method=method, dt=dt, reduce=lambda tr: np.concatenate(
            [_first_middle_axis_zero(tr)[:, None], tr.omega[:, ::every].reshape(len(tr.omega), -1)], axis=1))
        first = rows[:, 0]
    else:
        first = simulate_batch(bodies, t, omega0, method=method, dt=dt, reduce=_first_middle_axis_zero)
    out = {"flip_time": 2.0 * first}
    if exact:
        out["flip_time_exact"] = np.array([EulerTop(*b).dzhanibekov_flip_time(w) for b, w in zip(bodies, omega0)])
    if store_omega:
        out["omega"] = rows[:, 1:].reshape(len(rows), -1, 3)
    return out


def _check_tennis_racket(grid, constants):
    _check_omega_samples(constants.get("store_omega", False), constants.get("every", 1), constants.get("n_samples", 1201))
    I1, I3 = constants.get("I1", 1.0), constants.get("I3", 2.0)
    middle = np.asarray(grid["middle_moment"])
    if not (np.all(middle > I1) and np.all(middle < I3)):
        raise ValueError(f"grid.middle_moment must lie strictly between I1 = {I1} and I3 = {I3}")
    if np.any(I3 > I1 + middle):
        raise ValueError(f"grid.middle_moment must be at least I3 - I1 = {I3 - I1} (triangle inequality)")
    tilt = np.asarray(grid["tilt_deg"])
    if not (np.all(tilt > 0) and np.all(tilt < 90)):
        raise ValueError("grid.tilt_deg must lie strictly between 0 and 90 degrees (no flips otherwise)")


def plot_tennis_racket(dataset):
    """Flip time over middle moment and tilt (log colour scale), the closed form as contours.

    Examples
    --------
    >>> from kreisel.sweep import sweep
    >>> ds = sweep(tennis_racket_flip, {"middle_moment": [1.3, 1.7], "tilt_deg": [0.5, 5.0]},
    ...            constants={"t_end": 60.0}, scheduler="serial")
    >>> type(plot_tennis_racket(ds)).__name__
    'Figure'
    """
    LogNorm = _matplotlib("colors").LogNorm
    fig, ax = _figure()
    x, y = dataset["middle_moment"].values, dataset["tilt_deg"].values
    flip = dataset["flip_time"].transpose("tilt_deg", "middle_moment").values
    mesh = ax.pcolormesh(x, y, flip, shading="nearest", norm=LogNorm(), cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="flip time (s)")
    if "flip_time_exact" in dataset and min(x.size, y.size) > 1:
        exact = dataset["flip_time_exact"].transpose("tilt_deg", "middle_moment").values
        lines = ax.contour(x, y, exact, colors="white", linewidths=0.8)
        ax.clabel(lines, fontsize=7)
    ax.set_xlabel("middle moment I2 (kg m²)")
    if y.size > 1 and y.max() / y.min() > 10:  # small tilts carry the logarithmic growth of the flip time
        ax.set_yscale("log")
    ax.set_ylabel("initial tilt from the middle axis (deg)")
    ax.set_title("Tennis-racket flips: simulated (colour) and exact (contours)")
    return fig


# ---- Lagrange-top apex locus (Theory §6.5) -----------------------------------------------------------
def lagrange_apex_locus(phi_dot, psi_dot, *, I1=1.0, I3=0.5, mgl=1.0, theta0_deg=60.0):
    """Shape of the apex locus of a heavy symmetric top released at θ0 with θ̇ = 0 (Theory §6.5).

    ``kind`` codes :data:`APEX_LOCUS_KINDS` (0 monotone, 1 cusp, 2 loop) from
    :meth:`kreisel.LagrangeTop.apex_locus_kind`; ``theta_min_deg`` and
    ``theta_max_deg`` give the nutation range.

    Examples
    --------
    Released without precession (φ̇ = 0) the heavy top falls from θ0 and the
    apex traces cusps (kind 1) with θ0 the top of the nutation range; a fast
    enough forward precession gives loops (kind 2):

    >>> out = lagrange_apex_locus(np.array([0.0, 2.0]), np.array([10.0, 10.0]))
    >>> [APEX_LOCUS_KINDS[k] for k in out["kind"]]
    ['cusp', 'loop']
    >>> round(float(out["theta_min_deg"][0]), 9), bool(out["theta_max_deg"][0] > 60.0)
    (60.0, True)
    """
    from ..tops import LagrangeTop

    top = LagrangeTop(I1, I3, mgl)
    theta0 = np.radians(theta0_deg)
    count = len(phi_dot)
    kind = np.empty(count, dtype=np.int8)
    theta_range = np.empty((count, 2))
    for i, (p, s) in enumerate(zip(phi_dot, psi_dot)):
        state = ([0.0, theta0, 0.0], [p, 0.0, s])
        kind[i] = APEX_LOCUS_KINDS.index(top.apex_locus_kind(*state))
        theta_range[i] = top.turning_points(*state)
    theta_range = np.degrees(theta_range)
    return {"kind": kind, "theta_min_deg": theta_range[:, 0], "theta_max_deg": theta_range[:, 1]}


def _check_lagrange(grid, constants):
    theta0 = constants.get("theta0_deg", 60.0)
    if not 0.0 < theta0 < 180.0:
        raise ValueError(f"theta0_deg must lie strictly between 0 and 180, got {theta0}")


def plot_lagrange_apex_locus(dataset):
    """Map of monotone / cusp / loop apex loci over the initial φ̇ and ψ̇.

    Examples
    --------
    >>> from kreisel.sweep import sweep
    >>> ds = sweep(lagrange_apex_locus, {"phi_dot": [-1.0, 0.0, 2.0], "psi_dot": [4.0, 10.0]}, scheduler="serial")
    >>> type(plot_lagrange_apex_locus(ds)).__name__
    'Figure'
    """
    colors = _matplotlib("colors")
    fig, ax = _figure()
    x, y = dataset["phi_dot"].values, dataset["psi_dot"].values
    kind = dataset["kind"].transpose("psi_dot", "phi_dot").values
    cmap = colors.ListedColormap(["#4c72b0", "#dd8452", "#55a868"])
    mesh = ax.pcolormesh(x, y, kind, shading="nearest", cmap=cmap, norm=colors.BoundaryNorm([-0.5, 0.5, 1.5, 2.5], 3))
    bar = fig.colorbar(mesh, ax=ax, ticks=[0, 1, 2])
    bar.ax.set_yticklabels(APEX_LOCUS_KINDS)
    ax.set_xlabel("initial precession rate φ̇ (rad/s)")
    ax.set_ylabel("initial spin rate ψ̇ (rad/s)")
    ax.set_title("Lagrange top: shape of the apex locus")
    return fig


# ---- attitude error under IMU noise (Theory §3.5, Theory §3.5) ---------------------------------------------
def imu_attitude_error(angle_random_walk, trial, *, bias_instability=0.0, correlation_time=100.0,
                       half_angle_deg=1.0, coning_rate_hz=1.0, sample_time=0.01, duration=60.0,
                       samples_per_update=2, seed=0):
    """Final attitude error of strapdown integration of noisy coning increments.

    The exact coning motion (:func:`kreisel.nav.coning_motion`) is sampled as
    gyro increments, corrupted by :class:`kreisel.nav.GyroErrorModel` (angle
    random walk ``angle_random_walk`` in deg/√h, Gauss–Markov bias
    ``bias_instability`` in deg/h) and integrated by
    :func:`kreisel.nav.attitude_from_increments`. ``attitude_error_deg`` is
    the rotation angle between the computed and the true final attitude. The
    noise of each point is drawn from a seed derived from (``seed``,
    ``trial``, the ARW value), so results do not depend on the chunking.
    With white noise alone the error grows like √3 N √T (RMS over trials).

    Examples
    --------
    Noise-free increments leave only the small coning-algorithm error; an
    angle random walk of 1 deg/√h dominates it after 10 s:

    >>> arw = np.array([0.0, 1.0])
    >>> err = imu_attitude_error(arw, np.array([0, 0]), duration=10.0)["attitude_error_deg"]
    >>> bool(err[0] < 1e-4 < err[1])
    True
    """
    from ..nav import GyroErrorModel, attitude_from_increments, coning_motion

    n = int(round(duration / sample_time))
    n -= n % samples_per_update
    motion = coning_motion(np.radians(half_angle_deg), 2 * np.pi * coning_rate_hz, sample_time, n)
    dtheta = np.empty((len(trial), n, 3))
    for i, (arw, k) in enumerate(zip(angle_random_walk, trial)):
        model = GyroErrorModel.from_datasheet(angle_random_walk=arw, bias_instability=bias_instability,
                                              correlation_time=correlation_time if bias_instability > 0 else None)
        entropy = [int(seed), int(k), int(np.float64(arw).view(np.uint64))]
        dtheta[i] = model.corrupt_increments(motion.dtheta, sample_time, seed=np.random.SeedSequence(entropy))
    q = attitude_from_increments(motion.q[0], dtheta, samples_per_update)[:, -1]
    true = motion.q[-1]
    # angle of q_true* ⊗ q: 2 atan2(|vector part|, |scalar part|), accurate at small angles
    scalar = q @ true
    vector = np.linalg.norm(q - scalar[:, None] * true, axis=-1)
    return {"attitude_error_deg": np.degrees(2.0 * np.arctan2(vector, np.abs(scalar)))}


def _check_imu(grid, constants):
    if np.any(np.asarray(grid["angle_random_walk"]) < 0):
        raise ValueError("grid.angle_random_walk must be non-negative (deg/√h)")
    trial = np.asarray(grid["trial"])
    if trial.dtype.kind not in "iu" or np.any(trial < 0):
        raise ValueError("grid.trial must be non-negative integers (give it as {count = N})")
    if constants.get("samples_per_update", 2) not in (1, 2, 3, 4):
        raise ValueError("samples_per_update must be 1, 2, 3 or 4")


def plot_imu_attitude_error(dataset):
    """Attitude error of every trial against the ARW, the RMS over trials and √3 N √T.

    Examples
    --------
    >>> from kreisel.sweep import sweep
    >>> ds = sweep(imu_attitude_error, {"angle_random_walk": [0.1, 1.0], "trial": [0, 1]},
    ...            constants={"duration": 5.0}, scheduler="serial")
    >>> type(plot_imu_attitude_error(ds)).__name__
    'Figure'
    """
    fig, ax = _figure()
    arw = dataset["angle_random_walk"].values
    error = dataset["attitude_error_deg"].transpose("angle_random_walk", "trial").values
    ax.plot(np.repeat(arw, error.shape[1]), error.ravel(), ".", alpha=0.3, label="trials")
    ax.plot(arw, np.sqrt(np.mean(error**2, axis=1)), "o-", label="RMS over trials")
    duration_hours = json.loads(dataset.attrs.get("sweep_constants", "{}")).get("duration", 60.0) / 3600.0
    ax.plot(arw, np.sqrt(3.0 * duration_hours) * arw, "k--", label="white noise: √3 N √T")
    ax.set_xlabel("angle random walk N (deg/√h)")
    ax.set_ylabel("final attitude error (deg)")
    ax.set_title("Strapdown attitude error under gyro noise")
    ax.legend()
    return fig


# ---- registry ------------------------------------------------------------------------------------------
@dataclasses.dataclass(frozen=True)
class SweepModel:
    """A bundled sweep: chunk function, grid parameters, typed constants, check, plot, units, constants' meaning."""

    function: object
    grid: tuple
    constants: dict  # name -> (kind, default) with kind "number", "int", "str", "bool"
    check: object
    plot: object
    units: dict
    notes: dict = dataclasses.field(default_factory=dict)  # constant -> meaning, for the file reference


MODELS = {
    "tennis_racket": SweepModel(
        tennis_racket_flip, ("middle_moment", "tilt_deg"),
        {"I1": ("number", 1.0), "I3": ("number", 2.0), "spin": ("number", 1.0), "t_end": ("number", 60.0),
         "n_samples": ("int", 1201), "method": ("str", "dop853"), "dt": ("number", None), "exact": ("bool", True),
         "store_omega": ("bool", False), "every": ("int", 1)},
        _check_tennis_racket, plot_tennis_racket,
        {"flip_time": {"units": "s", "long_name": "flip time (simulated)"},
         "flip_time_exact": {"units": "s", "long_name": "flip time (Jacobi elliptic closed form)"},
         "omega": {"units": "rad/s", "long_name": "body angular velocity at linspace(0, t_end, n_samples)[::every]"}},
        {"store_omega": "also store the body angular velocity of every point as `omega` (points × samples × 3, rad/s)",
         "every": "keep every k-th sample of the stored `omega` (k divides `n_samples` − 1); the flip time "
                  "uses all samples"}),
    "lagrange_apex": SweepModel(
        lagrange_apex_locus, ("phi_dot", "psi_dot"),
        {"I1": ("number", 1.0), "I3": ("number", 0.5), "mgl": ("number", 1.0), "theta0_deg": ("number", 60.0)},
        _check_lagrange, plot_lagrange_apex_locus,
        {"kind": {"long_name": "apex locus kind", "flag_values": [0, 1, 2],
                  "flag_meanings": " ".join(APEX_LOCUS_KINDS)},
         "theta_min_deg": {"units": "degree"}, "theta_max_deg": {"units": "degree"}}),
    "imu_monte_carlo": SweepModel(
        imu_attitude_error, ("angle_random_walk", "trial"),
        {"bias_instability": ("number", 0.0), "correlation_time": ("number", 100.0),
         "half_angle_deg": ("number", 1.0), "coning_rate_hz": ("number", 1.0), "sample_time": ("number", 0.01),
         "duration": ("number", 60.0), "samples_per_update": ("int", 2), "seed": ("int", 0)},
        _check_imu, plot_imu_attitude_error,
        {"attitude_error_deg": {"units": "degree", "long_name": "final attitude error"}}),
}
