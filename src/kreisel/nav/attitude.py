"""Attitude and heading from gyro, accelerometer and magnetometer samples (Theory §3.3, §3.5).

Integrating the gyro alone (:mod:`kreisel.nav.strapdown`) drifts: its bias
and noise accumulate into the attitude. The accelerometer measures the
specific force, which on average points up, and so corrects the
inclination; the magnetometer's horizontal part points to magnetic north and
corrects the heading. Both are disturbed — the body's own accelerations,
magnets and iron nearby — so a filter must weigh them against the gyro and
reject them when they cannot be trusted.

kreisel's estimator (``method=None``) is an error-state Kalman filter whose
attitude error δ is taken in the earth frame, q̂ = exp(δ) ⊗ q: there each
sensor measures one component of δ — the accelerometer (low-passed in the
earth frame, where the body's accelerations average out) δx and δy, the
field's horizontal direction δz — and the gyro bias β, coupled by
δ' = δ − R β dt, is learned in motion and, at detected rest, measured
directly. A magnetic field is used only after its norm and dip have stayed
unchanged while the sensor turned (a magnet on the sensor turns with it and
changes both), and only while they stay within tolerance.
``offline=True`` smooths with the whole recording: the filter runs forward
and then backward in time (reversed samples, negated gyro), their fused
tilt shows each sample's field norm and dip, and the samples whose norm and
dip stay near the recording's medians are judged to hold the earth's field.
Both passes run again with that decision, using the field there only (the
gyro bridges the rest from both sides), and are fused by their covariances.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validation import as_float_array, positive_float
from ..so3 import quat_apply, quat_conjugate, quat_multiply
from . import _attitude_kernels
from .attitude_error import attitude_error, quaternion_rows

__all__ = ["AttitudeEstimate", "estimate_attitude", "compare_attitude", "KREISEL_DEFAULTS"]

_METHODS = (None, "kreisel", "madgwick", "mahony", "complementary")
_FRAMES = ("ENU", "NED")

#: The one parameter set of kreisel's estimator, tuned on the seven BROAD trials of the benchmark.
KREISEL_DEFAULTS = {
    "gyro_noise": 4.77e-4,        # rad/s/√Hz: gyro white noise into the attitude
    "bias_walk": 2.44e-5,         # rad/s/√s: random walk of the gyro bias
    "acc_noise": 0.041,           # rad: noise of the tilt read from the low-passed accelerometer
    "acc_disturbance": 0.244,     # rad per relative deviation of |a| from gravity, added to acc_noise
    "mag_noise": 0.16,            # rad: noise of the heading read from the field
    "mag_norm_tol": 0.256,        # relative tolerance of the field norm against the reference
    "mag_dip_tol": 0.109,         # rad: tolerance of the dip against the reference
    "rest_gyro": 0.366,           # rad/s: rest when the gyro stays this close to its 0.5 s mean (and the mean small)
    "rest_acc": 1.28,             # m/s^2: same for the accelerometer
    "rest_time": 1.5,             # s: how long both must hold
    "rest_noise": 0.01,           # rad/s: noise of the bias measured at rest
    "rest_tau": 0.5,              # s: time constant of the rest detector's means
    "bias_std0": 4.91,            # rad/s: initial bias uncertainty (large: the bias is learned quickly)
    "gravity": 9.81,              # m/s^2
    "mag_ref_tau": 10.0,          # s: time constant of the field reference's norm and dip
    "mag_new_time": 1.95,         # s: a candidate field must hold this long ...
    "acc_tau": 1.875,             # s: time constant of the accelerometer's low-pass in the earth frame
    "mag_new_turn": 0.39,         # rad: ... while the sensor turns at least this much
}
_PUBLISHED = {"madgwick": {"beta": 0.12}, "mahony": {"kp": 0.74, "ki": 0.0012}, "complementary": {"gain": 0.0005}}
# ENU ← NWU: a quarter turn about up (north, the NWU x axis, becomes the ENU y axis)
_ENU_FROM_NWU = np.array([np.sqrt(0.5), 0.0, 0.0, np.sqrt(0.5)])
# NED ← ENU: a half turn about the horizontal axis between north and east
_NED_FROM_ENU = np.array([0.0, np.sqrt(0.5), np.sqrt(0.5), 0.0])


@dataclass(frozen=True)
class AttitudeEstimate:
    """Attitude estimated from IMU samples.

    Attributes
    ----------
    q : ndarray, shape (n, 4)
        Scalar-first unit quaternions frame ← sensor (ENU or NED as asked).
    bias : ndarray, shape (n, 3) or None
        Estimated gyro bias in rad/s, sensor axes (None for filters that do not estimate it).
    covariance : ndarray, shape (n, 3, 3) or None
        Covariance (rad²) of the attitude error δ, q = exp(δ) ⊗ q_true, δ in
        the earth frame of ``q`` (kreisel's estimator only); its square-rooted
        diagonal bounds the tilt about east and north (in NED: north and east)
        and the heading error.
    method : str
        The filter that produced it.
    """

    q: np.ndarray
    bias: np.ndarray | None
    covariance: np.ndarray | None
    method: str


def _samples(x, name, n=None):
    x = as_float_array(x, name, finite=False)
    if x.ndim != 2 or x.shape[1] != 3:
        raise ValueError(f"{name} must have shape (n, 3), got {x.shape}")
    if n is not None and x.shape[0] != n:
        raise ValueError(f"{name} must have as many samples as gyro ({n}), got {x.shape[0]}")
    if not np.isfinite(x).all():
        row = int(np.flatnonzero(~np.isfinite(x).all(axis=1))[0])
        raise ValueError(f"{name} must be finite: sample {row} is {x[row].tolist()} "
                         "(remove or interpolate missing samples first)")
    if x.size and not np.abs(x).max() <= LARGEST_COMPONENT:
        # the filters square the samples: beyond this their squares are not representable
        raise ValueError(f"{name} holds a component of size {np.abs(x).max():.3g}, beyond any sensor's reading "
                         f"(at most {LARGEST_COMPONENT:g} in any unit)")
    return np.ascontiguousarray(x)


#: Largest sample component the filters take: its square and sums of squares stay far from overflow.
LARGEST_COMPONENT = 1e150
#: Smallest length of the first accelerometer sample that gives the up direction, m/s².
SMALLEST_FIRST_ACCEL = 1e-6
#: Band, relative to the recording's median |a|, for the length of the first accelerometer sample (the start tilt).
FIRST_ACCEL_BAND = (0.5, 2.0)
#: Band, in units of the ``gravity`` parameter, that the 90th percentile of |a| must lie in for kreisel's estimator
#: (the band :func:`kreisel.io.read_imu` judges a unitless accelerometer by: held still 1, beyond 40 g no phone).
ACCEL_BAND = (4.0 / 9.81, 400.0 / 9.81)


def _parameters(method, params, offline=False):
    defaults = KREISEL_DEFAULTS if method == "kreisel" else _PUBLISHED[method]
    unknown = set(params) - set(defaults)
    if unknown:
        raise ValueError(f"unknown parameter(s) {sorted(unknown)} for method {method!r}; "
                         f"expected some of {sorted(defaults)}")
    merged = {**defaults, **params}
    # the filter divides by these; offline, the fusion of the two passes divides by the sum of their tilt and
    # heading variances, which these noises keep from being zero in both
    positive = {"gravity", "rest_tau", "mag_ref_tau"} | ({"acc_noise", "mag_noise"} if offline else set())
    for key, value in merged.items():
        if key in positive and not (np.isfinite(value) and value > 0):
            raise ValueError(f"parameter {key} must be a finite number > 0, got {value!r}")
        if not (np.isfinite(value) and value >= 0):
            raise ValueError(f"parameter {key} must be a finite number >= 0, got {value!r}")
    return merged


def _kreisel_run(gyr, acc, mag, dt, p, mag_clean=None, start=None):
    n = gyr.shape[0]
    q = np.empty((n, 4))
    bias = np.empty((n, 3))
    cov = np.empty((n, 3, 3))
    bias_var = np.empty((n, 3))
    end = np.empty(43)
    clean = np.zeros(0, dtype=np.bool_) if mag_clean is None else np.ascontiguousarray(mag_clean)
    # without a field the accelerometer stands in for the unread magnetometer argument
    _attitude_kernels.kreisel_filter(gyr, acc, acc if mag is None else mag, mag is not None, clean, dt, p,
                                     np.full(43, np.nan) if start is None else start, q, bias, cov, bias_var,
                                     end)
    return q, bias, cov, bias_var, end


def _kreisel_backward(gyr, acc, mag, dt, p, end, mag_clean=None):
    """The filter run backward in time from the forward pass's end state ``end``.

    The samples are reversed, the rates negated (and with them the bias and
    its correlations) and shifted by one, since the step into sample i uses
    the rate of sample i forward and so that of sample i + 1 backward.
    Starting from the forward end state keeps the backward pass on track
    where the recording ends in motion (a start from the last samples alone,
    with the bias unknown, can diverge there).
    """
    start = end.copy()
    start[4:7] *= -1.0
    P = start[7:].reshape(6, 6)
    P[:3, 3:] *= -1.0
    P[3:, :3] *= -1.0
    rev = slice(None, None, -1)
    q, bias, cov, bias_var, _ = _kreisel_run(-np.concatenate([gyr[:1], gyr[:0:-1]]), np.ascontiguousarray(acc[rev]),
                                             None if mag is None else np.ascontiguousarray(mag[rev]), dt, p,
                                             None if mag_clean is None else mag_clean[rev], start)
    return q[rev], -bias[rev], cov[rev], bias_var[rev]


def _kreisel(gyr, acc, mag, dt, params, offline):
    p = np.array([params[name] for name in _attitude_kernels.KREISEL_PARAMETERS])
    *forward, end = _kreisel_run(gyr, acc, mag, dt, p)
    if not offline:
        return forward[:3]
    backward = _kreisel_backward(gyr, acc, mag, dt, p, end)
    if mag is None:
        return _smoothed(forward, backward, heading=False)
    # each pass alone judges the field by what it has seen and may lock onto a magnet for a while; the
    # whole recording judges it better: both passes again, told which samples hold the earth's field
    clean = _clean_field(_smoothed(forward, backward, heading=False)[0], mag, dt, params)
    smoothed = _smoothed_with(gyr, acc, mag, dt, p, clean)
    # a field of the right norm and dip can still point the wrong way: then it disagrees for a while with
    # the heading that the gyro carries from the clean field on both sides
    clean &= _agrees_with_heading(smoothed[0], mag, dt, params)
    return _smoothed_with(gyr, acc, mag, dt, p, clean)


def _smoothed_with(gyr, acc, mag, dt, p, clean):
    """Forward and backward pass using the field at the ``clean`` samples only, fused."""
    *forward, end = _kreisel_run(gyr, acc, mag, dt, p, clean)
    return _smoothed(forward, _kreisel_backward(gyr, acc, mag, dt, p, end, clean), heading=True)


def _clean_field(q, mag, dt, params):
    """Samples whose field is the earth's, judged with the whole recording's hindsight.

    With the smoothed tilt, each sample's field gives a norm and a dip; the
    earth's are their medians over the recording (right as long as the field
    is undisturbed for more than half of it), and a sample is clean while
    both stay within the causal filter's tolerances for at least
    ``mag_new_time`` (shorter runs are a disturbed field passing by chance).
    """
    f = quat_apply(q, mag)
    horizontal = np.hypot(f[:, 0], f[:, 1])
    norm = np.hypot(horizontal, f[:, 2])
    dip = np.arctan2(-f[:, 2], horizontal)
    ref_norm, ref_dip = np.median(norm), np.median(dip)
    clean = ((np.abs(norm - ref_norm) < params["mag_norm_tol"] * ref_norm)
             & (np.abs(dip - ref_dip) < params["mag_dip_tol"]))
    bounds = np.concatenate([[0], np.flatnonzero(np.diff(clean.astype(np.int8))) + 1, [clean.size]])
    lengths = np.diff(bounds)
    return np.repeat(clean[bounds[:-1]] & (lengths * dt >= params["mag_new_time"]), lengths)


def _agrees_with_heading(q, mag, dt, params):
    """Samples whose field's horizontal direction agrees with the heading of ``q`` around them.

    The sine of the turn of the measured north from the estimated north,
    averaged over a centred window of ``mag_new_time``, must stay below that
    of ``mag_dip_tol``: the angular tolerance of the dip test, applied to the
    direction that the dip test cannot see.
    """
    f = quat_apply(q, mag)
    horizontal = np.hypot(f[:, 0], f[:, 1])
    turn = np.divide(-f[:, 0], horizontal, out=np.zeros(len(f)), where=horizontal > 0.0)
    # capped at the recording's length: a longer window holds the same samples (and int() of a huge one overflows)
    half = int(min(0.5 * params["mag_new_time"] / dt, len(f)))
    sums = np.concatenate([[0.0], np.cumsum(turn)])
    index = np.arange(len(f))
    lo, hi = np.maximum(index - half, 0), np.minimum(index + half + 1, len(f))
    return np.abs((sums[hi] - sums[lo]) / (hi - lo)) < np.sin(params["mag_dip_tol"])


def _smoothed(forward, backward, heading):
    """The two passes (attitude, bias, covariance, bias variance) fused by their covariances.

    The attitude is exp(W δ) ⊗ q_f with W = P_f (P_f + P_b)⁻¹ and δ the
    error q_b ⊗ q_f⁻¹ in the earth frame, split as BROAD's metric splits it
    into a tilt (δx, δy) and a turn about the vertical δz
    (``_attitude_kernels.smoother_fusion``). Without
    ``heading`` (no magnetometer: each pass's heading starts at the
    sensor's own, so they differ by an arbitrary turn) only the tilt is
    fused and the heading, its variance and correlations stay forward's.
    """
    qf, bf, pf, vf = forward
    qb, bb, pb, vb = backward
    q = np.empty_like(qf)
    cov = np.empty_like(pf)
    _attitude_kernels.smoother_fusion(qf, pf, qb, pb, 3 if heading else 2, q, cov)
    # the bias by its variances too, axis by axis (its correlations are not kept per sample)
    total = vf + vb
    # both variances zero only with bias_std0 = bias_walk = 0: both passes then keep the bias at zero
    bias = np.where(total > 0.0, (bf * vb + bb * vf) / np.where(total > 0.0, total, 1.0), 0.5 * (bf + bb))
    return q, bias, cov


def _published(method, gyr, acc, mag, dt, params):
    n = gyr.shape[0]
    use_mag = mag is not None
    mag_arg = mag if use_mag else acc
    start = np.array(_attitude_kernels.triad_start(acc[0], mag_arg[0], use_mag))
    q = np.empty((n, 4))
    bias = None
    if method == "madgwick":
        start_nwu = quat_multiply(quat_conjugate(_ENU_FROM_NWU), start)
        _attitude_kernels.madgwick_filter(gyr, acc, mag_arg, use_mag, dt, params["beta"], start_nwu, q)
        q = quat_multiply(_ENU_FROM_NWU, q)
    elif method == "mahony":
        bias = np.empty((n, 3))
        _attitude_kernels.mahony_filter(gyr, acc, mag_arg, use_mag, dt, params["kp"], params["ki"], start, q,
                                        bias)
    else:
        _attitude_kernels.complementary_filter(gyr, acc, mag_arg, use_mag, dt, params["gain"], start, q)
    return q, bias, None


def estimate_attitude(gyro, accel, mag=None, *, rate, offline=False, frame="ENU", method=None, params=None):
    """Attitude frame ← sensor from gyro, accelerometer and (optionally) magnetometer samples.

    Parameters
    ----------
    gyro : array_like, shape (n, 3)
        Angular velocity in rad/s, sensor axes, sampled at ``rate``.
    accel : array_like, shape (n, 3)
        Specific force in m/s² (at rest it points up: +9.81 along the sensor's up axis).
    mag : array_like, shape (n, 3), optional
        Magnetic field in any consistent unit (e.g. µT). Without it the
        heading comes from the gyro alone and starts at the sensor's own.
    rate : float
        Sampling rate in Hz.
    offline : bool
        kreisel's estimator only: smooth with a forward and a backward pass
        (for recorded data; each sample then uses the whole recording, and
        the magnetic field is judged with hindsight: module notes).
    frame : {"ENU", "NED"}
        Earth frame of the result (north is magnetic north).
    method : None or {"madgwick", "mahony", "complementary"}
        None (or "kreisel") for kreisel's estimator (module notes);
        "madgwick": Madgwick's gradient-descent filter (parameter ``beta``,
        default 0.12); "mahony": Mahony's explicit complementary filter
        (``kp`` 0.74, ``ki`` 0.0012); "complementary": nlerp of the gyro
        attitude towards the TRIAD attitude of each sample (``gain`` 0.0005).
    params : dict, optional
        Parameters overriding the method's defaults (see
        :data:`KREISEL_DEFAULTS` for kreisel's estimator): finite and
        >= 0, and > 0 for ``gravity``, ``rest_tau``, ``mag_ref_tau`` (and,
        offline, ``acc_noise``, ``mag_noise``).

    Returns
    -------
    AttitudeEstimate

    Notes
    -----
    The samples are taken as uniformly spaced at ``rate``: no timestamps are
    read, so a log with gaps, jitter or time running backwards must be
    resampled first (the IMU readers check the time column). The first
    sample fixes the start (TRIAD of accelerometer and field, or the
    accelerometer's tilt with the sensor's own heading), so the recording
    should start at rest or slowly moving. Measured on BROAD's seven trials
    (``bench/bench_attitude.py``): mean total error 1.49° causal, 1.17°
    offline, inclination 0.60° without magnetometer. The offline judgement of
    the field takes its medians over the recording as the earth's, so it needs
    the field undisturbed for more than half of the recording.

    Raises
    ------
    ValueError
        For shapes that disagree, non-finite samples (remove or interpolate
        them first: a filter cannot step over a hole without making up the
        motion in it), a non-positive or non-finite ``rate``, an
        accelerometer sample of zero length at the start or one outside
        0.5 … 2 times the recording's median length (``FIRST_ACCEL_BAND``:
        free fall or a jolt, not gravity, would give the start tilt), a magnetometer
        whose first sample has no horizontal part (along the measured up):
        the heading would be undefined. Later zero-length accelerometer or
        magnetometer samples are skipped (the gyro carries the attitude
        through them); later fields without a horizontal part are rejected
        by kreisel's estimator's disturbance test. For kreisel's estimator,
        an accelerometer not in m/s²: the 90th percentile of |a| outside
        0.41 … 41 g (``ACCEL_BAND``, as :func:`kreisel.io.read_imu` judges
        a unitless one), which g or mg give.

    Examples
    --------
    A sensor at rest, tilted 10° about east, in a field pointing north and down:

    >>> import numpy as np
    >>> from kreisel import quat_apply
    >>> tilt = np.radians(10.0)
    >>> q_true = np.array([np.cos(tilt / 2), np.sin(tilt / 2), 0.0, 0.0])
    >>> n = 500
    >>> acc = np.tile(quat_apply(q_true, [0.0, 0.0, 9.81], inverse=True), (n, 1))
    >>> mag = np.tile(quat_apply(q_true, [0.0, 20.0, -40.0], inverse=True), (n, 1))
    >>> est = estimate_attitude(np.zeros((n, 3)), acc, mag, rate=100.0)
    >>> bool(np.allclose(est.q[-1], q_true, atol=1e-9))
    True
    """
    if method not in _METHODS:
        raise ValueError(f"method must be None or one of {', '.join(map(repr, _METHODS[1:]))}, got {method!r}")
    method = "kreisel" if method is None else method
    if frame not in _FRAMES:
        raise ValueError(f"frame must be 'ENU' or 'NED', got {frame!r}")
    if not isinstance(offline, (bool, np.bool_)):
        # any other object is truthy or falsy by accident ("no" would smooth)
        raise TypeError(f"offline must be True or False, got {offline!r}")
    if offline and method != "kreisel":
        raise ValueError(f"offline=True is available for kreisel's estimator only, not method {method!r}")
    rate = positive_float(rate, "rate")
    gyr = _samples(gyro, "gyro")
    n = gyr.shape[0]
    if n == 0:
        raise ValueError("gyro must hold at least one sample")
    acc = _samples(accel, "accel", n)
    mag = None if mag is None else _samples(mag, "mag", n)
    turn = float(np.sqrt(np.max(np.sum(gyr * gyr, axis=1)))) / rate
    if not turn < np.pi:
        # beyond half a turn between samples a rate no longer tells which way the body turned (aliasing)
        raise ValueError(f"rate = {rate:g} Hz is too low for gyro: the body turns up to {turn:.3g} rad between "
                         "samples, and a sampled rate resolves less than π")
    lengths = np.linalg.norm(acc, axis=1)
    first = lengths[0]
    if not first >= SMALLEST_FIRST_ACCEL:
        raise ValueError(f"accel's first sample has length {first:.3g} m/s², below "
                         f"{SMALLEST_FIRST_ACCEL:g}: the initial inclination needs the up direction, which gravity "
                         "gives (start the recording at rest)")
    typical = float(np.median(lengths))
    if not FIRST_ACCEL_BAND[0] * typical <= first <= FIRST_ACCEL_BAND[1] * typical:
        # a first sample that is not mostly gravity (free fall, a jolt) gives a wrong start tilt, which the
        # filters then take many seconds to forget
        raise ValueError(f"accel's first sample has length {first:.3g}, outside {FIRST_ACCEL_BAND[0]:g} … "
                         f"{FIRST_ACCEL_BAND[1]:g} times the recording's median length {typical:.3g}: the start tilt "
                         "needs a sample that is mostly gravity (start the recording at rest, or drop the first "
                         "samples)")
    if mag is not None:
        up = acc[0] / first
        horizontal = np.linalg.norm(mag[0] - (mag[0] @ up) * up)
        if not horizontal > 1e-6 * np.linalg.norm(mag[0]):
            raise ValueError("mag has no horizontal part in its first sample (zero, or parallel to the measured up): "
                             "the heading is undefined; pass mag=None for a gyro-only heading")
    params = _parameters(method, dict(params or {}), offline)
    if method == "kreisel":
        # kreisel's estimator weighs the accelerometer by |a| against gravity (the published filters use only
        # its direction): in g or mg it would reject or trust every sample and return a wrong attitude
        typical = float(np.percentile(lengths, 90))
        low, high = (bound * params["gravity"] for bound in ACCEL_BAND)
        if not low <= typical <= high:
            raise ValueError(f"accel's samples are {typical:.3g} long (90th percentile), outside {low:.3g} … "
                             f"{high:.3g}: kreisel's estimator needs them in m/s² (gravity {params['gravity']:g}); "
                             "convert g by × 9.80665, mg by × 0.00980665")
    dt = 1.0 / rate
    if method == "kreisel":
        q, bias, cov = _kreisel(gyr, acc, mag, dt, params, offline)
    else:
        q, bias, cov = _published(method, gyr, acc, mag, dt, params)
    if frame == "NED":
        q = quat_multiply(_NED_FROM_ENU, q)
        if cov is not None:
            # NED components of an ENU vector: (y, x, −z)
            turn = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
            cov = turn @ cov @ turn.T
    return AttitudeEstimate(q=q, bias=bias, covariance=cov, method=method)


def compare_attitude(gyro, accel, mag=None, *, rate, reference, mask=None,
                     methods=("kreisel", "kreisel offline", "madgwick", "mahony", "complementary")):
    """Errors of several estimators on one recording against a reference attitude, in one call.

    Parameters
    ----------
    gyro, accel, mag, rate
        As for :func:`estimate_attitude`.
    reference : array_like, shape (n, 4)
        Reference attitude ENU ← sensor (e.g. motion capture); NaN rows are left out.
    mask : array_like of bool, shape (n,), optional
        Samples to evaluate (e.g. the motion phases).
    methods : sequence of str
        "kreisel", "kreisel offline", "madgwick", "mahony", "complementary".

    Returns
    -------
    dict
        Method name → (total, heading, inclination) RMSE in degrees
        (:func:`kreisel.nav.attitude_error`).

    Examples
    --------
    >>> import numpy as np
    >>> n = 300
    >>> acc = np.tile([0.0, 0.0, 9.81], (n, 1))
    >>> mag = np.tile([0.0, 20.0, -40.0], (n, 1))
    >>> ref = np.tile([1.0, 0.0, 0.0, 0.0], (n, 1))
    >>> errors = compare_attitude(np.zeros((n, 3)), acc, mag, rate=100.0, reference=ref, methods=("kreisel", "mahony"))
    >>> {name: round(e[0], 9) for name, e in errors.items()}
    {'kreisel': 0.0, 'mahony': 0.0}
    """
    known = ("kreisel", "kreisel offline", "madgwick", "mahony", "complementary")
    if isinstance(methods, str):
        # a str is a sequence too: of letters, none of them a method
        raise TypeError(f"methods must be a sequence of method names, not one str ({methods!r}); "
                        f"e.g. ({methods!r},)")
    methods = tuple(methods)
    if not methods:
        raise ValueError(f"methods must name at least one method among {', '.join(map(repr, known))}")
    unknown = [m for m in methods if m not in known]
    if unknown:
        raise ValueError(f"methods must be among {', '.join(map(repr, known))}, got {unknown}")
    # reference and mask checked against the samples here, not by the first error computation after its estimate
    reference = quaternion_rows(reference, "reference")
    n = np.shape(gyro)[0] if np.ndim(gyro) else 0
    if reference.shape[0] != n:
        raise ValueError(f"reference must have as many rows as gyro ({n}), got {reference.shape[0]}")
    if mask is not None and (np.asarray(mask).dtype != bool or np.shape(mask) != (n,)):
        raise ValueError(f"mask must be a boolean array of shape ({n},), got {np.asarray(mask).dtype} "
                         f"{np.shape(mask)}")
    results = {}
    for name in methods:
        offline = name == "kreisel offline"
        method = None if name.startswith("kreisel") else name
        est = estimate_attitude(gyro, accel, mag, rate=rate, offline=offline, method=method)
        results[name] = attitude_error(est.q, reference, mask)
    return results
