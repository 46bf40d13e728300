"""``kreisel fit``: the lines it prints for a free-top fit (the JSON is ``FreeRotationFit.to_dict``)."""

from __future__ import annotations

import numpy as np

__all__ = ["integrals_drift", "summary", "as_dict", "REGIMES"]

REGIMES = {
    "about_largest_axis": "above the separatrix (J² > 2T·I_mid): ω circulates about the largest axis",
    "about_smallest_axis": "below the separatrix (J² < 2T·I_mid): ω circulates about the smallest axis",
    "separatrix": "on the separatrix (J² = 2T·I_mid)",
    "symmetric": "symmetric body: regular precession",
    "steady": "steady rotation",
}


def summary(fit):
    """Lines of text describing ``fit`` (ratios with uncertainties, ω0, bias, RMS, regime, integrals).

    Examples
    --------
    >>> import numpy as np, kreisel as kr
    >>> t = np.linspace(0.0, 1.0, 300)
    >>> fit = kr.fit_free_rotation(t, kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.5, 12.0, 0.3]))
    >>> print(summary(fit)[1])
      I_x = 0.20000 ± 0.00000   I_y = 0.80000 ± 0.00000   I_z = 1 (reference)
    """
    names = "xyz"
    axis = lambda k: f"I_{names[k]}"  # noqa: E731
    moments = "   ".join(
        f"{axis(k)} = 1 (reference)" if fit.moments_stderr[k] == 0.0 and fit.moments[k] == 1.0
        else f"{axis(k)} = {fit.moments[k]:.5f} ± {fit.moments_stderr[k]:.5f}"
        for k in range(3)
    )
    vector = lambda v, e: ", ".join(f"{a:+.4f} ± {b:.4f}" for a, b in zip(v, e))  # noqa: E731
    lines = [
        f"free-top fit to {fit.t.size} samples, t = {fit.t[0]:.4f} … {fit.t[-1]:.4f} s",
        "  " + moments,
        f"  ω0 at t = {fit.t0:.4f} s (rad/s): {vector(fit.omega0, fit.omega0_stderr)}",
    ]
    if np.any(fit.bias != 0.0):
        lines.append(f"  gyro bias (rad/s): {vector(fit.bias, fit.bias_stderr)}")
    if fit.misalignment > 0.0:
        lines.append(f"  principal axes turned {np.degrees(fit.misalignment):.2f}° from the sensor axes")
    lines += [
        f"  residual RMS {fit.rms:.4f} rad/s ({100 * fit.rms / fit.signal_rms:.2f} % of the signal's "
        f"{fit.signal_rms:.3f} rad/s)",
        f"  intermediate axis {names[fit.intermediate_axis]}; {REGIMES.get(fit.regime, fit.regime)}, "
        f"(J² − 2T·I_mid)/(2T·I_mid) = {fit.separatrix_distance:+.3g}",
    ]
    drift = fit.integrals_drift()
    for name, label in (("energy", "energy T"), ("momentum", "|J|")):
        lines.append(f"  {label} with the fitted moments: spread {100 * drift[name]['spread']:.2f} %, "
                     f"trend {100 * drift[name]['trend_per_s']:+.2f} %/s along the data")
    lines.append(("  " if fit.free_rotation else "  warning: ") + fit.message)
    return lines
