"""Figures of gyroscope recordings: the raw rates, and a free-top fit (:func:`kreisel.fit_free_rotation`)."""

from __future__ import annotations

import os

import numpy as np
from matplotlib.figure import Figure

__all__ = ["gyro_fit", "gyro_recording"]

_COLORS = ("tab:blue", "tab:orange", "tab:green")


def gyro_fit(fit, title=None):
    """Measured ω (points) against the fitted free-top ω (curves), residuals underneath.

    Parameters
    ----------
    fit : FreeRotationFit
        Result of :func:`kreisel.fit_free_rotation`.
    title : str, optional
        Figure title; by default the fitted moment ratios and the RMS.

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> t = np.linspace(0.0, 1.0, 300)
    >>> fit = kr.fit_free_rotation(t, kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.5, 12.0, 0.3]))
    >>> fig = gyro_fit(fit)
    >>> [ax.get_ylabel() for ax in fig.axes]
    ['ω (rad/s)', 'residual (rad/s)']
    """
    dense = np.linspace(fit.t[0], fit.t[-1], max(1000, 4 * fit.t.size))
    curve = fit.predict(dense)
    residuals = fit.residuals
    fig = Figure(figsize=(8, 5.6), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True, height_ratios=(3, 1.3))
    marker = 2.0 if fit.t.size > 300 else 4.0
    for k, (name, color) in enumerate(zip("xyz", _COLORS)):
        top.plot(fit.t, fit.omega[:, k], ".", ms=marker, color=color, alpha=0.5, label=f"measured ω{name}")
        top.plot(dense, curve[:, k], "-", lw=1.4, color=color, label=f"fitted ω{name}")
        bottom.plot(fit.t, residuals[:, k], ".", ms=marker, color=color, alpha=0.6)
    bottom.axhline(0.0, color="0.3", lw=0.8)
    bottom.axhspan(-fit.rms, fit.rms, color="0.85", zorder=0, label=f"± RMS = {fit.rms:.3g} rad/s")
    ratios = " : ".join(f"{m:.4f}" for m in fit.moments)
    top.set(ylabel="ω (rad/s)",
            title=title or f"free-top fit: I_x : I_y : I_z = {ratios} (largest = 1)")
    top.legend(loc="best", ncols=3, fontsize="small")
    bottom.set(xlabel="t (s)", ylabel="residual (rad/s)")
    bottom.legend(loc="upper right", fontsize="small")
    return fig


def gyro_recording(recording, window=None, title=None):
    """A recording's measured rates ωx, ωy, ωz and their magnitude against time, with the window a fit uses.

    Parameters
    ----------
    recording : GyroRecording
        As read by :func:`kreisel.io.read_gyro`.
    window : (t_start, t_stop), optional
        The samples :func:`kreisel.fit_free_rotation` would fit (either end
        None: the recording's); by default the whole recording.
    title : str, optional
        Figure title; by default the recording's source.

    Examples
    --------
    >>> import numpy as np
    >>> from kreisel.io.gyro import GyroRecording
    >>> t = np.linspace(0.0, 2.0, 201)
    >>> rec = GyroRecording(t, np.column_stack([np.sin(t), np.cos(t), 0 * t]), source="spin.csv")
    >>> fig = gyro_recording(rec, window=(0.5, None))
    >>> fig.axes[0].get_ylabel(), fig.axes[0].get_title()
    ('ω (rad/s)', 'spin.csv: 201 samples; a fit uses t = 0.5 … 2 s (shaded)')
    """
    t, omega = recording.t, recording.omega
    start, stop = window if window is not None else (None, None)
    start = t[0] if start is None else max(float(start), t[0])
    stop = t[-1] if stop is None else min(float(stop), t[-1])
    if not start < stop:
        raise ValueError(f"window {window!r} holds no sample: the record spans t = {t[0]:g} … {t[-1]:g} s")
    fig = Figure(figsize=(8, 4), layout="constrained")
    ax = fig.add_subplot()
    marker = 2.0 if t.size > 300 else 4.0
    for k, (name, color) in enumerate(zip("xyz", _COLORS)):
        ax.plot(t, omega[:, k], ".-", ms=marker, lw=0.6, color=color, label=f"ω{name}")
    ax.plot(t, np.linalg.norm(omega, axis=-1), "-", lw=1.0, color="0.3", label="|ω|")
    ax.axvspan(start, stop, color="0.9", zorder=0, label="fit window")
    ax.set(xlabel="t (s)", ylabel="ω (rad/s)",
           title=title or f"{os.path.basename(recording.source)}: {t.size} samples; a fit uses t = {start:g} … {stop:g} s (shaded)")
    ax.legend(loc="best", ncols=5, fontsize="small")
    return fig
