"""Gyroscope recordings in the viewer: the free top fitted to the data, replayed against it.

The fitted body moves exactly (:meth:`kreisel.tops.EulerTop.solve`) through the
recording's own sample times, so the viewer plays the body with its inertia
ellipsoid and polhode while the ω′ plot shows the measurement (bias removed,
in the fitted principal axes) on top of the fitted curves. The fit runs in the
viewer's worker processes like any run (job ``"fit"`` of :mod:`kreisel.web.session`).
"""

from __future__ import annotations

import warnings

from ..io import ScenarioError
from ..io.gyro import GyroFileError, parse_gyro
from ..tops.fitting import NotFreeRotationWarning, fit_free_rotation
from . import session

MAX_RECORDING_SAMPLES = 50_000


def fit_payload(recording, name="upload", start=None, stop=None, bias=True):
    """The viewer's JSON of a fitted recording: a rigid-body run plus ``omega_measured`` and ``fit``.

    Parameters
    ----------
    recording : str or GyroRecording
        The text of a recording (any layout :func:`kreisel.io.read_gyro` reads) or a read recording.
    name : str
        The recording's name in messages (for text).
    start, stop : float, optional
        Window of the free flight, s (as in the file).
    bias : bool
        Also fit a constant gyroscope offset.

    Raises
    ------
    ScenarioError
        The text is not a recording, or the samples cannot be fitted (the viewer answers 400).
    RunRefused
        More than :data:`MAX_RECORDING_SAMPLES` samples (the viewer answers 422).

    Examples
    --------
    >>> import kreisel as kr
    >>> data = fit_payload(kr.io.read_gyro(kr.io.recording_path("phone_toss")))
    >>> data["kind"], len(data["t"]) == len(data["omega_measured"]), data["fit"]["intermediate_axis"]
    ('rigid_body', True, 'x')
    """
    if isinstance(recording, str):
        try:
            recording = parse_gyro(recording, name)
        except GyroFileError as exc:
            raise ScenarioError(str(exc)) from None
    if len(recording.t) > MAX_RECORDING_SAMPLES:
        raise session.RunRefused(f"the recording has {len(recording.t)} samples; the viewer fits at most "
                                 f"{MAX_RECORDING_SAMPLES}")
    window = None if start is None and stop is None else (start, stop)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NotFreeRotationWarning)  # reported in fit.message
        try:
            fit = fit_free_rotation(recording.t, recording.omega, bias=bias, window=window)
        except ValueError as exc:
            raise ScenarioError(f"{recording.source}: {exc}") from None
    traj = fit.top.solve(fit.t - fit.t0, fit.axes.T @ fit.omega0)
    arrays = session.samples(traj, None)
    arrays["t"] = fit.t
    integrals = session.FirstIntegrals("free", traj.inertia, None)
    integrals.add(arrays)
    return {
        "kind": "rigid_body", "title": f"free-top fit of {recording.source}", "method": "exact",
        "inertia": traj.inertia.tolist(), "gravity": None, "analysis": session.analysis(traj, None),
        **{key: value.tolist() for key, value in arrays.items()},
        "omega_measured": ((fit.omega - fit.bias) @ fit.axes).tolist(),
        "integrals": integrals.summary(), "fit": fit.to_dict(),
    }
