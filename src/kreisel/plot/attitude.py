"""Figures of an estimated attitude: its yaw, pitch and roll, and its errors against a reference attitude."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ..nav.attitude_error import attitude_error_angles
from ..so3 import quat_to_euler

__all__ = ["attitude_estimate"]

_COLORS = ("tab:blue", "tab:orange", "tab:green")


def _yaw_pitch_roll(q):
    """Intrinsic Z-Y-X angles in degrees of the finite rows of ``q`` (NaN elsewhere)."""
    angles = np.full((q.shape[0], 3), np.nan)
    tracked = np.isfinite(q).all(axis=1)
    if tracked.any():
        angles[tracked] = quat_to_euler("ZYX", q[tracked], degrees=True)
    # a jump across ±180° is a wrap, not a motion: leave a gap instead of a vertical line
    wraps = np.abs(np.diff(angles, axis=0)) > 180.0
    angles[1:][wraps] = np.nan
    return angles


def attitude_estimate(t, q, reference=None, mask=None, title=None):
    """Yaw, pitch and roll of an estimated attitude against time; with a reference, theirs and the errors.

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times, s.
    q : array_like, shape (n, 4)
        Estimated attitude, scalar-first, frame ← sensor.
    reference : array_like, shape (n, 4), optional
        Reference attitude in the same frame (NaN rows where it was lost): drawn dashed, and the
        total, heading and inclination errors (:func:`kreisel.nav.attitude_error_angles`) underneath.
    mask : array_like of bool, shape (n,), optional
        Samples the error statistics use (shaded where false).
    title : str, optional

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 1.0, 50)
    >>> q = np.column_stack([np.cos(t / 2), 0 * t, 0 * t, np.sin(t / 2)])
    >>> fig = attitude_estimate(t, q, reference=q)
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['angle (°)', 'error (°)']
    """
    t = np.asarray(t, dtype=float)
    q = np.asarray(q, dtype=float)
    fig = Figure(figsize=(8, 5.6 if reference is not None else 3.6), layout="constrained")
    axes = fig.subplots(2 if reference is not None else 1, 1, sharex=True, squeeze=False)[:, 0]
    top = axes[0]
    angles = _yaw_pitch_roll(q)
    for k, (name, color) in enumerate(zip(("yaw", "pitch", "roll"), _COLORS)):
        top.plot(t, angles[:, k], "-", lw=1.1, color=color, label=f"{name} (estimate)")
    if reference is not None:
        reference = np.asarray(reference, dtype=float)
        ref_angles = _yaw_pitch_roll(reference)
        for k, (name, color) in enumerate(zip(("yaw", "pitch", "roll"), _COLORS)):
            top.plot(t, ref_angles[:, k], "--", lw=1.1, color=color, alpha=0.7, label=f"{name} (reference)")
        total, heading, inclination = np.degrees(attitude_error_angles(q, reference))
        bottom = axes[1]
        for values, name, color in ((total, "total", "0.2"), (heading, "heading", "tab:purple"),
                                    (inclination, "inclination", "tab:red")):
            bottom.plot(t, values, "-", lw=1.0, color=color, label=name)
        if mask is not None:
            bottom.fill_between(t, 0.0, 1.0, where=~np.asarray(mask, dtype=bool), color="0.9", step="mid",
                                transform=bottom.get_xaxis_transform(), zorder=0, label="not evaluated")
        bottom.set(ylabel="error (°)")
        bottom.legend(loc="upper right", ncols=4, fontsize="small")
    top.set(ylabel="angle (°)", title=title or "attitude: intrinsic Z-Y-X angles of frame ← sensor")
    top.legend(loc="best", ncols=3 if reference is None else 2, fontsize="small")
    axes[-1].set(xlabel="t (s)")
    return fig
