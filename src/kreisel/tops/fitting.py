"""The free top fitted to a measured angular velocity: a phone's gyroscope as a laboratory.

A body in free flight obeys Euler's equations with no torque, so the
angular velocity a gyroscope measures in its own axes is the exact elliptic
solution of Theory §5.3, fixed by two moment ratios and the initial ω′.
Fitting that solution to a recording measures the ratios of the principal
moments. Only ratios are observable (scaling all moments leaves ω′(t)
unchanged); kreisel reports them with the largest moment set to 1.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np

from .._html import html_table, number
from .._validation import as_float, as_float_array, refuse_long_turn
from ..so3 import rotvec_to_matrix
from .euler_top import EulerTop

__all__ = ["FreeRotationFit", "NotFreeRotationWarning", "fit_free_rotation"]

AXES = "xyz"
# residuals above this fraction of the signal's RMS: the data are not a free rotation
NOT_FREE_FRACTION = 0.1
# relative standard error of a moment ratio above which the ratios count as undetermined
UNDETERMINED = 0.5
# samples required beyond the number of fitted parameters
MARGIN = 10
# the ratios show only through the change of ω′ over the record; the fit's difference quotients (steps
# of 1.5e-8 of the parameters) resolve changes down to ~1e-14 of the signal, so a change below this
# fraction of the largest |ω′| leaves them to rounding
MIN_CHANGE = 1e-6
# a linear trend of T or |J| (relative, per second) counts against free rotation when it exceeds both this
# size and TREND_SIGMAS of its standard error: the size keeps slowly correlated sensor noise and an unfitted
# bias (about 1 %/s on the bundled toss) from condemning a good fit, the significance keeps noise from it
TREND_LIMIT = 0.05
TREND_SIGMAS = 3.0


class NotFreeRotationWarning(UserWarning):
    """The fit does not explain the recording: hand contact, a catch, torque or a wrong window."""


def _moments(second):
    """Principal moments from the second moments Σm x², Σm y², Σm z² along the same axes.

    I_x = B + C, I_y = A + C, I_z = A + B: every non-negative (A, B, C) gives a
    physical body (triangle inequalities), and a thin slab is C → 0, an
    interior point of the parameter range rather than a boundary of it.
    """
    a, b, c = second
    return np.array([b + c, a + c, a + b])


def _second_moments(moments):
    i_x, i_y, i_z = moments
    return 0.5 * np.array([i_y + i_z - i_x, i_x + i_z - i_y, i_x + i_y - i_z])


def _integral_moments(omega):
    """Candidate moments (up to scale) from the first integrals along the data.

    Both integrals are linear in the squares: Σ I_i ω_i² = 2T and Σ I_i² ω_i² = J²,
    so the rows [ω_x², ω_y², ω_z², −1] have a two-dimensional null space spanned
    by (I, 2T) and (I², J²) (zero-mean sensor noise adds the same constant to
    every row, which the last column absorbs). Writing I = u + s v in the span
    of the two smallest right singular vectors, the condition that I∘I lies in
    the same span is a quadratic in s; its real roots are the candidates.
    """
    rows = np.column_stack([omega**2, -np.ones(len(omega))])
    scale = np.linalg.norm(rows, axis=0)
    # columns scaled to unit norm so that small components count as much as the spin
    null = np.linalg.svd(rows / scale, full_matrices=False)[2][-2:] / scale
    u, v = null[0, :3], null[1, :3]
    coefficients = [np.linalg.det(np.array([u, v, w])) for w in (v * v, 2.0 * u * v, u * u)]
    candidates = [v] if abs(coefficients[0]) < 1e-12 * np.max(np.abs(coefficients)) else []
    for root in np.roots(coefficients):
        if abs(root.imag) <= 1e-9 * max(1.0, abs(root.real)):
            candidates.append(u + root.real * v)
    return [c if c.sum() > 0.0 else -c for c in candidates]


@dataclass
class FreeRotationFit:
    """Result of :func:`fit_free_rotation`.

    Attributes
    ----------
    moments : (3,) ndarray
        Principal moments about the sensor's x, y, z axes (about the fitted
        principal axes ``axes`` when ``align=True``), relative: the largest is 1.
    moments_stderr : (3,) ndarray
        Their standard errors (0 for the largest, fixed by the normalisation;
        inf for a value the data leave free, which also makes ``free_rotation``
        False).
    omega0, omega0_stderr : (3,) ndarray
        Angular velocity at ``t0`` in the sensor axes (without the bias), rad/s.
    bias, bias_stderr : (3,) ndarray
        Constant gyroscope offset, rad/s (zeros unless ``bias=True``). Standard
        errors are inf where the data leave the value free, as for the moments.
    axes : (3, 3) ndarray
        Columns: the principal axes in sensor components (identity unless ``align=True``).
    misalignment : float
        Angle between the sensor axes and the principal axes, radians.
    rms : float
        √(mean of all squared residual components), rad/s.
    signal_rms : float
        √(mean of all squared measured components), rad/s.
    t0 : float
        Time of the first sample in the window, s; ``omega0`` belongs to it.
    t, omega : ndarray
        The measured samples the fit used (inside the window).
    top : EulerTop
        The fitted body in its principal axes.
    regime : str
        ``"about_largest_axis"`` (J² > 2T I_mid), ``"about_smallest_axis"``
        (J² < 2T I_mid), ``"separatrix"``, ``"symmetric"`` or ``"steady"``.
    intermediate_axis : int
        Index (0, 1, 2 for x, y, z) of the axis of intermediate moment.
    separatrix_distance : float
        (J² − 2T I_mid)/(2T I_mid): positive above the separatrix (ω circulates
        about the largest axis), negative below it.
    free_rotation : bool
        False when the residuals are large compared with the signal, when T
        or |J| with the fitted moments trend along the data (see
        :meth:`integrals_drift`), or when the ratios are not determined by the
        data; ``message`` says why.
    message : str
        One line on the quality of the fit.
    nfev : int
        Number of model evaluations.

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> t = np.linspace(0.0, 1.0, 300)
    >>> omega = kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.5, 12.0, 0.3])
    >>> fit = kr.fit_free_rotation(t, omega)
    >>> np.round(fit.moments, 6).tolist(), AXES[fit.intermediate_axis]
    ([0.2, 0.8, 1.0], 'y')
    """

    moments: np.ndarray
    moments_stderr: np.ndarray
    omega0: np.ndarray
    omega0_stderr: np.ndarray
    bias: np.ndarray
    bias_stderr: np.ndarray
    axes: np.ndarray
    misalignment: float
    rms: float
    signal_rms: float
    t0: float
    t: np.ndarray
    omega: np.ndarray
    top: EulerTop
    regime: str
    intermediate_axis: int
    separatrix_distance: float
    free_rotation: bool
    message: str
    nfev: int
    _omega0_principal: np.ndarray = field(repr=False)

    def predict(self, t):
        """Fitted gyroscope reading at times ``t`` (s, as in the file), bias included, rad/s.

        Examples
        --------
        >>> import numpy as np, kreisel as kr
        >>> t = np.linspace(2.0, 3.0, 200)
        >>> omega = kr.EulerTop(1.0, 2.0, 3.0).omega(t - 2.0, [0.2, 4.0, 0.2]) + 0.01
        >>> fit = kr.fit_free_rotation(t, omega, bias=True)
        >>> bool(np.allclose(fit.predict(t), omega, atol=1e-8))
        True
        """
        t = as_float_array(t, "t")
        if t.ndim != 1:
            raise ValueError(f"t must be one-dimensional, got shape {t.shape}")
        return self.top.omega(t - self.t0, self._omega0_principal) @ self.axes.T + self.bias

    @property
    def residuals(self):
        """Measured minus fitted ω at the fitted samples, (n, 3) rad/s.

        Examples
        --------
        >>> import numpy as np, kreisel as kr
        >>> t = np.linspace(0.0, 1.0, 300)
        >>> fit = kr.fit_free_rotation(t, kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.5, 12.0, 0.3]))
        >>> fit.residuals.shape, bool(np.abs(fit.residuals).max() < 1e-6)
        ((300, 3), True)
        """
        return self.omega - self.predict(self.t)

    def __repr__(self):
        return (f"FreeRotationFit(moments={number(self.moments)}, regime={self.regime!r}, "
                f"rms={self.rms:.3g} rad/s, n={self.t.size})")

    def _repr_html_(self):
        drift = self.integrals_drift()
        rows = [
            ("samples", f"{self.t.size}, t = {self.t[0]:g} … {self.t[-1]:g} s"),
            ("moments (largest = 1)", number(self.moments)),
            ("± standard error", number(self.moments_stderr, 2)),
            ("ω0 at t0", number(self.omega0) + " rad/s"),
            ("bias", number(self.bias) + " rad/s"),
            ("misalignment", number(np.degrees(self.misalignment), 3) + "°"),
            ("regime", self.regime),
            ("intermediate axis", AXES[self.intermediate_axis]),
            ("separatrix distance", number(self.separatrix_distance, 3)),
            ("spread of T, |J|", f"{number(drift['energy']['spread'], 3)}, {number(drift['momentum']['spread'], 3)}"),
            ("rms residual / signal", f"{self.rms:.3g} / {self.signal_rms:.3g} rad/s"),
            ("free rotation", self.free_rotation),
        ]
        return html_table("Free-rotation fit", rows, note=self.message)

    def first_integrals(self):
        """Energy T and |J| of the measured ω (bias removed) with the fitted moments.

        In free rotation both are constant; their spread along the data shows how
        well Euler's equations explain the measurement. Units: the moments are
        relative (largest 1), so T is in (rad/s)² and |J| in rad/s times that unit.

        Returns
        -------
        energy, momentum : (n,) ndarray

        Examples
        --------
        >>> import numpy as np, kreisel as kr
        >>> t = np.linspace(0.0, 1.0, 300)
        >>> fit = kr.fit_free_rotation(t, kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.5, 12.0, 0.3]))
        >>> energy, momentum = fit.first_integrals()
        >>> bool(np.ptp(energy) < 1e-6 * energy.mean())
        True
        """
        body = (self.omega - self.bias) @ self.axes
        return self.top.energy(body), self.top.angular_momentum(body)


    def integrals_drift(self):
        """Spread (std/mean) and linear trend (relative, per second) of T and |J| along the data.

        The trend is the least-squares slope divided by the mean, with its standard
        error (``trend_stderr_per_s``, from the scatter about the line). Free
        rotation keeps both constant: a trend beyond 5 %/s and 3 standard errors
        makes the fit's verdict ``free_rotation`` False.

        Examples
        --------
        >>> import numpy as np, kreisel as kr
        >>> t = np.linspace(0.0, 1.0, 300)
        >>> fit = kr.fit_free_rotation(t, kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.5, 12.0, 0.3]))
        >>> drift = fit.integrals_drift()
        >>> sorted(drift), sorted(drift["energy"]), bool(drift["energy"]["spread"] < 1e-6)
        (['energy', 'momentum'], ['spread', 'trend_per_s', 'trend_stderr_per_s'], True)
        """
        return _drift(self.t - self.t0, self.first_integrals())

    def to_dict(self):
        """The results as plain JSON-ready numbers (what ``kreisel fit --json`` writes).

        A standard error the data leave unbounded (inf) is written as ``None``
        (JSON null): strict JSON has no infinity.

        Examples
        --------
        >>> import json, numpy as np, kreisel as kr
        >>> t = np.linspace(0.0, 1.0, 300)
        >>> fit = kr.fit_free_rotation(t, kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.5, 12.0, 0.3]))
        >>> record = json.loads(json.dumps(fit.to_dict()))
        >>> [round(m, 6) for m in record["moments"]], record["intermediate_axis"]
        ([0.2, 0.8, 1.0], 'y')
        """
        return {
            "moments": self.moments.tolist(),
            "moments_stderr": _json_errors(self.moments_stderr),
            "normalisation": "largest moment = 1",
            "omega0": self.omega0.tolist(),
            "omega0_stderr": _json_errors(self.omega0_stderr),
            "t0": self.t0,
            "bias": self.bias.tolist(),
            "bias_stderr": _json_errors(self.bias_stderr),
            "principal_axes": self.axes.tolist(),
            "misalignment_deg": float(np.degrees(self.misalignment)),
            "rms": self.rms,
            "signal_rms": self.signal_rms,
            "n_samples": int(self.t.size),
            "t_first": float(self.t[0]),
            "t_last": float(self.t[-1]),
            "regime": self.regime,
            "intermediate_axis": AXES[self.intermediate_axis],
            "separatrix_distance": self.separatrix_distance,
            "first_integrals": self.integrals_drift(),
            "free_rotation": self.free_rotation,
            "message": self.message,
        }


def _drift(tau, integrals):
    """Spread and least-squares trend, with its standard error, of each series, relative to its mean."""
    centred = tau - np.mean(tau)
    result = {}
    for name, series in zip(("energy", "momentum"), integrals):
        mean = float(np.mean(series))
        slope = float(centred @ (series - mean) / (centred @ centred))
        scatter = series - mean - slope * centred
        stderr = float(np.sqrt(scatter @ scatter / (tau.size - 2) / (centred @ centred)))
        result[name] = {"spread": float(np.std(series)) / mean, "trend_per_s": slope / mean,
                        "trend_stderr_per_s": stderr / mean}
    return result


def _trend_verdict(drift):
    """The message on a significant trend of T or |J| (see TREND_LIMIT), or None when there is none."""
    significant = [name for name, d in drift.items()
                   if abs(d["trend_per_s"]) > max(TREND_LIMIT, TREND_SIGMAS * d["trend_stderr_per_s"])]
    if not significant:
        return None

    def told(name, label):
        d = drift[name]
        sense = "falls" if d["trend_per_s"] < 0.0 else "rises"
        return f"{label} {sense} {100 * abs(d['trend_per_s']):.3g} ± {100 * d['trend_stderr_per_s']:.2g} %/s"

    # a torque changes T at the rate ω·τ and |J| at the rate J·τ/|J|: both in the sense of the torque
    # along the rotation, which drag opposes and the throw drives
    cause = ("a torque slows the rotation: air drag (a light, flat body tumbling fast) or the hand still "
             "touching it at the ends of the window (cut the free flight with a window)"
             if drift[significant[0]]["trend_per_s"] < 0.0 else
             "a torque drives the rotation: the throw is still acting (start the window after the release)")
    return (f"free rotation does not explain the data: with the fitted moments {told('energy', 'the energy T')} "
            f"and {told('momentum', '|J|')} along the data, where free rotation keeps both constant; {cause}")


def _json_errors(stderr):
    return [float(e) if np.isfinite(e) else None for e in stderr]


def _check(t, omega, window):
    t = as_float_array(t, "t")
    omega = as_float_array(omega, "omega")
    if t.ndim != 1:
        raise ValueError(f"t must be one-dimensional (n,), got shape {t.shape}")
    if omega.shape != (t.size, 3):
        raise ValueError(f"omega must have shape (n, 3) = ({t.size}, 3) to match t, got {omega.shape}")
    if np.any(np.diff(t) <= 0.0):
        k = int(np.flatnonzero(np.diff(t) <= 0.0)[0]) + 1
        raise ValueError(f"t must be strictly increasing (t[{k}] = {t[k]!r} after t[{k - 1}] = {t[k - 1]!r})")
    if window is not None:
        try:
            start, stop = window
        except (TypeError, ValueError):
            raise ValueError(f"window must be (t_start, t_stop), got {window!r}") from None
        start = -np.inf if start is None else as_float(start, "window start")
        stop = np.inf if stop is None else as_float(stop, "window stop", finite=False)
        if not start < stop:
            raise ValueError(f"window must have t_start < t_stop, got {window!r}")
        keep = (t >= start) & (t <= stop)
        if t.size and not keep.any():
            # the usual slip: a window from 0 for a phone's clock, which starts anywhere
            raise ValueError(f"window ({start:g}, {stop:g}) holds no sample: the record spans t = {t[0]:g} … "
                             f"{t[-1]:g} s")
        t, omega = t[keep], omega[keep]
    return t, omega


class _Model:
    """ω_sensor(t) = R(θ) ω_top(t − t0) + b with the parameters packed in one vector.

    x = [two free second moments (the reference one is 1), ω0 in principal axes,
    bias (if fitted), rotation vector θ (if fitted)].
    """

    def __init__(self, tau, reference, bias, align):
        self.tau = tau
        self.reference = reference
        self.free = [k for k in range(3) if k != reference]
        self.bias = bias
        self.align = align
        self.size = 5 + 3 * bias + 3 * align
        self._cache = (None, None)

    def second(self, x):
        second = np.ones(3)
        second[self.free] = x[:2]
        return second

    def split(self, x):
        moments = _moments(self.second(x))
        w0 = x[2:5]
        k = 5
        b = x[k:k + 3] if self.bias else np.zeros(3)
        k += 3 * self.bias
        rotation = rotvec_to_matrix(x[k:k + 3]) if self.align else np.eye(3)
        return moments, w0, b, rotation

    def top_omega(self, x):
        key = x[:5].tobytes()
        if self._cache[0] != key:
            moments, w0, _, _ = self.split(x)
            self._cache = (key, EulerTop(*moments).omega(self.tau, w0))
        return self._cache[1]

    def __call__(self, x):
        _, _, b, rotation = self.split(x)
        return self.top_omega(x) @ rotation.T + b

    def jacobian(self, x):
        """Forward differences for the top's parameters, exact columns for the bias."""
        _, _, b, rotation = self.split(x)
        base = self.top_omega(x)
        columns = []
        for j in range(5):
            step = 1.5e-8 * max(1.0, abs(x[j]))
            shifted = x.copy()
            shifted[j] += step
            moments, w0, _, _ = self.split(shifted)
            columns.append(((EulerTop(*moments).omega(self.tau, w0) - base) @ rotation.T / step).ravel())
        if self.bias:
            for c in range(3):
                column = np.zeros((self.tau.size, 3))
                column[:, c] = 1.0
                columns.append(column.ravel())
        if self.align:
            k = 5 + 3 * self.bias
            for j in range(3):
                shifted = x.copy()
                shifted[k + j] += 1.5e-8
                columns.append((base @ (rotvec_to_matrix(shifted[k:k + 3]) - rotation).T / 1.5e-8).ravel())
        return np.column_stack(columns)


def _local_mean(omega, index, half=2):
    return omega[max(0, index - half):index + half + 1].mean(axis=0)


def _start(t, omega, bias, align):
    """Starting parameters: moments from the first integrals, ω0 from the best of several anchors."""
    tau = t - t[0]
    tail = np.zeros(3 * bias + 3 * align)
    best, best_cost = None, np.inf
    # a sphere as the last resort: the tumbling then starts the fit from ω0 alone
    for moments in _integral_moments(omega) or [np.ones(3)]:
        second = _second_moments(moments)
        if not np.all(np.isfinite(second)) or second.max() <= 0.0:
            continue
        second = np.maximum(second / second.max(), 1e-3)
        reference = int(np.argmax(second))
        model = _Model(tau, reference, bias, align)
        top = EulerTop(*_moments(second))
        # the state at a few anchors, carried back to t0 along the trial body's motion: near the
        # separatrix the flip time depends on ω0 too sharply for the first sample alone
        for index in np.unique(np.linspace(0, t.size - 1, 9).astype(int)):
            w0 = top.omega(np.array([-tau[index]]), _local_mean(omega, index))[0]
            x = np.concatenate([second[model.free], w0, tail])
            cost = np.sum((model(x) - omega) ** 2)
            if cost < best_cost:
                best, best_cost, best_model = x, cost, model
    return best_model, best


def _determinable(t, omega, bias):
    """Refuse, before the fit, a record whose ω′ changes too little or faster than free rotation can.

    ``t`` and ``omega`` are the scaled ones (time from the first sample, |ω| of order 1). By Euler's
    equations and the triangle inequalities |I_j − I_k| <= I_i, |dω′/dt| <= |ω|²/√3, so over the
    record ω′ can move by at most ∫|ω|² dt/√3 from its first value (with a bias the true |ω| is not
    known and this bound is not used).
    """
    speed = np.linalg.norm(omega, axis=1)
    change = float(np.max(np.linalg.norm(omega - omega[0], axis=1)))
    size = float(np.max(speed))
    if size == 0.0:
        raise ValueError("t and omega cannot determine the moment ratios: omega is zero at every sample (the "
                         "sensor did not turn: a phone lying still, or a recording of another sensor)")
    if change < MIN_CHANGE * size:
        raise ValueError(
            f"t and omega cannot determine the moment ratios: omega changes over the record by only "
            f"{change / size:.3g} of its largest size, less than {MIN_CHANGE:g}; the ratios show only through "
            "that change (a steady spin about a principal axis fits every body)"
        )
    dt = np.diff(t)
    turn = float(0.5 * np.sum((speed[1:] + speed[:-1]) * dt))
    reach = float(0.5 * np.sum((speed[1:] ** 2 + speed[:-1] ** 2) * dt)) / np.sqrt(3.0)
    if not bias and change > 2.0 * reach:
        raise ValueError(
            f"t and omega are not a free rotation: over the record the body turns through {turn:.3g} rad, "
            f"so Euler's equations let omega change by at most {reach / size:.3g} of its largest size "
            f"(|dω/dt| <= |ω|²/√3), but it changes by {change / size:.3g} (a wrong time unit, a torque, or "
            "noise larger than the motion)"
        )


def _covariance(jacobian, residual, dof):
    """s² (JᵀJ)⁺ by the SVD, and the parameter directions the data do not determine (rows)."""
    _, singular, vt = np.linalg.svd(jacobian, full_matrices=False)
    s2 = residual @ residual / dof
    determined = singular > 1e-10 * singular[0]
    return s2 * (vt[determined].T / singular[determined] ** 2) @ vt[determined], vt[~determined]


def fit_free_rotation(t, omega, *, bias=False, window=None, align=False):
    """Fit the exact free-top motion to measured body angular velocity (a gyroscope recording).

    Least squares of Euler's torque-free solution (Theory §5.3, by elliptic
    functions, no time stepping) to ω′ sampled at arbitrary, irregular times.
    The unknowns are two moment ratios, ω′ at the first sample, optionally a
    constant gyroscope bias and a small rotation from the sensor axes to the
    principal axes. Starting values come from the data's own first integral
    (the energy Σ I_i ω_i² is constant: a linear equation for the ratios) and
    the best of several anchors carried back to the first sample, so no guess
    is needed from the user.

    Parameters
    ----------
    t : (n,) array_like
        Sample times, s, strictly increasing (irregular spacing is fine).
    omega : (n, 3) array_like
        Measured angular velocity in the sensor's axes, rad/s.
    bias : bool
        Also fit a constant offset of each gyroscope axis. Off by default here, so
        that the model is the free top alone; ``kreisel fit`` and the viewer fit it
        by default (``--no-bias`` turns it off), since a real gyroscope has one.
    window : (t_start, t_stop), optional
        Use only the samples with t_start <= t <= t_stop (the free flight; the
        throw and the catch are not free rotation). Either end may be None.
    align : bool
        Also fit the rotation between the sensor axes and the principal axes
        (a phone's principal axes need not be its sensor axes). This needs a
        recording that explores the polhode: during a single flip next to the
        separatrix, ω′ stays close to one plane and a turn about the middle
        axis trades off against the ratios; the fit then warns that the ratios
        are not determined.

    Returns
    -------
    FreeRotationFit
        Moments normalised to a largest moment of 1, with standard errors from
        the Jacobian at the solution; ``omega0`` at the window's first sample.

    Raises
    ------
    ValueError
        Wrong shapes, NaN or inf, time not strictly increasing, a bad window,
        fewer samples than the fitted parameters plus 10, or a record that
        cannot determine the ratios: ω′ changes by less than 1e-6 of its size
        (they show only through that change), or, without ``bias``, by more
        than Euler's equations allow while the body turns through
        θ = ∫|ω| dt (|dω′/dt| <= |ω|²/√3, so at most ∫|ω|² dt/√3; twice that
        is refused).

    Warns
    -----
    NotFreeRotationWarning
        The residuals are more than 10 % of the signal, the energy T or |J|
        with the fitted moments trends along the data by more than 5 %/s and
        3 standard errors (a torque: air drag, the hand, the throw), or the
        data do not determine the ratios (no tumbling): the result is not to
        be trusted.

    Examples
    --------
    A synthetic recording of a (0.2, 0.8, 1) body spun near its middle axis, with
    0.05 rad/s noise at irregular times:

    >>> import numpy as np, kreisel as kr
    >>> rng = np.random.default_rng(1)
    >>> t = np.sort(rng.uniform(0.0, 1.5, 600))
    >>> omega = kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.4, 12.0, 0.3]) + rng.normal(0, 0.05, (600, 3))
    >>> fit = kr.fit_free_rotation(t, omega)
    >>> bool(np.all(np.abs(fit.moments - [0.2, 0.8, 1.0]) < 4 * fit.moments_stderr + 1e-12))
    True
    >>> round(fit.rms, 2), fit.regime
    (0.05, 'about_smallest_axis')
    """
    t, omega = _check(t, omega, window)
    n_params = 5 + 3 * bool(bias) + 3 * bool(align)
    if t.size < n_params + MARGIN:
        raise ValueError(
            f"too few samples: {t.size} (in the window); fitting {n_params} parameters needs at least "
            f"{n_params + MARGIN}"
        )
    from scipy.optimize import least_squares  # slow to import: only when fitting

    # free rotation is homogeneous: data ω(t) and c ω(c t) have the same moments. The fit runs with time
    # from the first sample and rates divided by c, a power of two (exact) near the largest |ω|, so that
    # no sum of squares overflows or underflows; rates come back multiplied by c
    t_data, omega_data = t, omega
    k = int(np.frexp(np.max(np.abs(omega), initial=0.0))[1])
    with np.errstate(over="ignore"):
        t = np.ldexp(t - t[0], k)
    refuse_long_turn(float(t[-1]), "t and omega", "the body turns through up to")
    omega = np.ldexp(omega, -k)
    scale = np.ldexp(1.0, k)
    _determinable(t, omega, bool(bias))

    model, x0 = _start(t, omega, bool(bias), bool(align))
    lower = np.full(model.size, -np.inf)
    lower[:2] = 1e-9
    x0[:2] = np.maximum(x0[:2], 1e-6)
    solution = least_squares(
        lambda x: (model(x) - omega).ravel(), x0, jac=model.jacobian, bounds=(lower, np.inf),
        method="trf", x_scale="jac",
    )
    x = solution.x
    residual = solution.fun
    jacobian = model.jacobian(x)
    covariance, null = _covariance(jacobian, residual, residual.size - model.size)

    def reported(x):
        moments, w0, b, rotation = model.split(x)
        return np.concatenate([moments / moments.max(), rotation @ w0, b])

    values = reported(x)
    gradient = np.empty((9, model.size))
    for j in range(model.size):
        step = 1e-7 * max(1.0, abs(x[j]))
        shifted = x.copy()
        shifted[j] += step
        gradient[:, j] = (reported(shifted) - values) / step
    stderr = np.sqrt(np.abs(np.diag(gradient @ covariance @ gradient.T)))
    # a reported number that moves along a direction the data do not fix has no finite standard error
    loose = np.abs(gradient @ null.T).max(axis=1, initial=0.0) > 1e-8 * np.abs(gradient).max(axis=1, initial=0.0)
    stderr[loose] = np.inf

    moments, w0, b, rotation = model.split(x)
    moments = moments / moments.max()
    top = EulerTop(*moments)
    rms = float(np.sqrt(np.mean(residual**2)) * scale)
    signal = float(np.sqrt(np.mean(omega**2)) * scale)
    values[3:], stderr[3:], b = values[3:] * scale, stderr[3:] * scale, b * scale
    middle = int(np.argsort(moments)[1])
    energy, momentum = float(top.energy(w0)), float(top.angular_momentum(w0))
    distance = (momentum**2 - 2.0 * energy * moments[middle]) / (2.0 * energy * moments[middle])
    relative = stderr[:3] / moments
    # T and |J| along the data from the scaled rates and times (no overflow); relative trends per second
    # come back multiplied by the time scale
    body = (omega - b / scale) @ rotation
    drift = _drift(t, (top.energy(body), top.angular_momentum(body)))
    for d in drift.values():
        d["trend_per_s"] *= scale
        d["trend_stderr_per_s"] *= scale
    trending = _trend_verdict(drift)
    if rms > NOT_FREE_FRACTION * signal:
        free, message = False, (
            f"residual RMS {rms:.3g} rad/s is {100 * rms / signal:.0f} % of the signal's {signal:.3g} rad/s: "
            "this is not a free rotation (hand contact, a catch or a torque?); cut the free flight with a window"
        )
    elif not np.max(relative) <= UNDETERMINED:
        free, message = False, (
            "the moment ratios are not determined by the data ("
            + (f"standard error up to {100 * np.max(relative):.3g} %): " if np.all(np.isfinite(relative))
               else "the fit's derivatives leave a combination of them free): ")
            + ("the fitted axis rotation trades off against them (a single flip near the separatrix "
               "cannot tell them apart; fit without align)" if align else
               "the body hardly tumbles (toss it spinning about its middle axis)")
        )
    elif not np.linalg.norm(b) < signal:
        # a gyroscope's offset is a small fraction of the rates of a toss; one as large as the signal is
        # the fit's escape into a nearly spherical body spinning fast with an offset that cancels the spin
        free, message = False, (
            f"the fitted bias {np.linalg.norm(b):.3g} rad/s is as large as the measured rates (RMS {signal:.3g} "
            "rad/s): no gyroscope is that far off; the fit traded a fast spin of a nearly round body for it "
            "(fit without the bias, or cut the free flight with a window)"
        )
    elif trending is not None:
        free, message = False, trending
    else:
        free, message = True, (
            f"free rotation explains the data: residual RMS {rms:.3g} rad/s, "
            f"{100 * rms / signal:.2g} % of the signal's {signal:.3g} rad/s"
        )
    if not free:
        warnings.warn(message, NotFreeRotationWarning, stacklevel=2)
    cos_angle = np.clip(0.5 * (np.trace(rotation) - 1.0), -1.0, 1.0)
    return FreeRotationFit(
        moments=moments,
        moments_stderr=stderr[:3],
        omega0=values[3:6],
        omega0_stderr=stderr[3:6],
        bias=b.copy(),
        bias_stderr=stderr[6:9] if bias else np.zeros(3),
        axes=rotation,
        misalignment=float(np.arccos(cos_angle)),
        rms=rms,
        signal_rms=signal,
        t0=float(t_data[0]),
        t=t_data,
        omega=omega_data,
        top=top,
        regime=top.regime(w0),
        intermediate_axis=middle,
        separatrix_distance=float(distance),
        free_rotation=free,
        message=message,
        nfev=int(solution.nfev),
        _omega0_principal=w0 * scale,
    )
