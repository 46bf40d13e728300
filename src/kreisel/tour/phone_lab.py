"""Tour section: a phone's gyroscope recording fitted with the exact free top (Theory §5.3–§5.4)."""

from __future__ import annotations

import warnings

import numpy as np

from ..inertia import box
from ..io.gyro import read_gyro, recording_path
from ..plot.fit import gyro_fit
from ..tops.fitting import fit_free_rotation
from .report import Check, Section

__all__ = ["phone_laboratory", "PHONE_SIZE", "NOISE", "SECTIONS"]

# the bundled recording is a 146 × 71 × 8 mm slab with 0.05 rad/s of gyroscope noise
PHONE_SIZE = (0.071, 0.146, 0.008)
NOISE = 0.05


def phone_laboratory(quick):
    """Your phone as a free-rotation laboratory: the Euler top fitted to a gyroscope"""
    recording = read_gyro(recording_path("phone_toss"))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a not-free-rotation warning fails the section
        fit = fit_free_rotation(recording.t, recording.omega, bias=True)
    slab = np.diag(box(1.0, PHONE_SIZE))
    slab = slab / slab.max()
    pull = np.max(np.abs(fit.moments[:2] - slab[:2]) / fit.moments_stderr[:2])
    energy, momentum = fit.first_integrals()
    figure = gyro_fit(fit, title="phone tossed end over end: measured ω and the fitted free top")
    ratios = " : ".join(f"{m:.4f} ± {e:.4f}" if e else f"{m:g}" for m, e in zip(fit.moments, fit.moments_stderr))
    return Section(
        "Your phone as a free-rotation laboratory", "§5.3–§5.4",
        "A phone tossed spinning about its middle axis (x, across the screen) flips over in flight, and its "
        "gyroscope records the body angular velocity ω′ in the phone's own axes: exactly the quantity "
        "Euler's equations describe. kreisel fits the exact elliptic solution to the samples "
        "(kreisel fit RECORDING) and reads off the moment ratios, ω′ at release and the gyroscope bias. "
        f"Here the bundled recording (phyphox CSV, about 400 Hz with jittered time stamps, "
        f"{NOISE} rad/s noise, a bias on each axis) of a 146 × 71 × 8 mm slab gives "
        f"I_x : I_y : I_z = {ratios}; a homogeneous slab has {slab[0]:.4f} : {slab[1]:.4f} : 1.",
        [Check.below("largest deviation from the slab's ratios (standard errors)", pull, 4.0),
         Check.close("residual RMS (rad/s)", fit.rms, NOISE, rtol=0.1, source="sensor noise"),
         Check.equal("intermediate axis", "xyz"[fit.intermediate_axis], "x"),
         Check.below("spread of |J| with the fitted moments (relative)", np.std(momentum) / np.mean(momentum),
                     3 * NOISE / fit.signal_rms),
         Check.below("spread of T with the fitted moments (relative)", np.std(energy) / np.mean(energy),
                     6 * NOISE / fit.signal_rms)],
        [(figure, "Bundled phone recording (points) against the fitted free top (curves); residuals below.")],
    )


SECTIONS = (phone_laboratory,)
