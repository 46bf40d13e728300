"""Tour sections for Theory §8: the eastward deflection and the Foucault pendulum."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .. import earth
from .report import Check, Section, panel

__all__ = ["eastward_deflection", "foucault_pendulum", "SECTIONS", "LATITUDE", "GRAVITY", "EARTH_RATE"]

# the chapter's figures for Hefei
LATITUDE, GRAVITY, EARTH_RATE = 31.8584, 9.7947, 7.27221e-5


def eastward_deflection(quick):
    """Eastward deflection of a falling body"""
    analytic = float(earth.eastward_deflection(100.0, LATITUDE, g=GRAVITY, omega=EARTH_RATE))
    east, north = earth.simulate_drop(100.0, LATITUDE, g=GRAVITY, omega=EARTH_RATE)
    heights = np.geomspace(1.0, 1000.0, 8 if quick else 20)
    sim = np.array([earth.simulate_drop(h, LATITUDE, g=GRAVITY, omega=EARTH_RATE)[0] for h in heights])
    slope = np.polyfit(np.log(heights), np.log(sim), 1)[0]
    latitudes = np.linspace(-89.0, 89.0, 60)
    fig = Figure(figsize=(10, 3.8), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    ax1.loglog(heights, sim, "o", label="simulation (full rotating-frame equations)")
    ax1.loglog(heights, earth.eastward_deflection(heights, LATITUDE, g=GRAVITY, omega=EARTH_RATE), label="(2/3) ω cos λ √(2h³/g)")
    ax1.set(xlabel="drop height h (m)", ylabel="eastward deflection (m)", title="Hefei, λ = 31.8584°")
    ax1.legend(fontsize=8)
    ax2.plot(latitudes, 1e3 * earth.eastward_deflection(100.0, latitudes, g=GRAVITY, omega=EARTH_RATE))
    ax2.set(xlabel="latitude (°)", ylabel="deflection of a 100 m drop (mm)", title="largest at the equator, zero at the poles")
    return Section(
        "Eastward deflection of a falling body", "§8.3",
        "A body dropped from rest at height h in the rotating Earth frame lands east of the foot of the "
        "vertical by (2/3) ω cos λ √(2h³/g) (Coriolis force, first order in ω). The chapter's example: 100 m "
        "at Hefei (λ = 31.8584°, g = 9.7947 m/s², ω = 7.27221e-5 rad/s) gives 0.0186 m.",
        [Check.close("analytic deflection of the 100 m drop (m)", analytic, 0.0186, atol=5e-5, source="chapter"),
         Check.close("simulated deflection (m)", float(east), analytic, rtol=1e-2, source="analytic"),
         Check.close("scaling exponent of the deflection with h", float(slope), 1.5, atol=1e-3, source="h^(3/2)"),
         Check.below("deflection at the pole (m)", abs(float(earth.eastward_deflection(100.0, 90.0))), 1e-18)],
        [(fig, "Eastward deflection against drop height and against latitude.")],
    )


def foucault_pendulum(quick):
    """Foucault pendulum"""
    period = float(earth.foucault_period(LATITUDE, omega=EARTH_RATE))
    hours, minutes = int(period // 3600), int(round(period % 3600 / 60))
    duration = 1800.0 if quick else 7200.0
    north = earth.foucault_pendulum(10.0, LATITUDE, duration, 0.02, g=GRAVITY, omega=EARTH_RATE)
    south = earth.foucault_pendulum(10.0, -LATITUDE, duration, 0.02, g=GRAVITY, omega=EARTH_RATE)
    theory = float(earth.foucault_precession_rate(LATITUDE, omega=EARTH_RATE))
    fig, ax = panel("t (min)", "swing-plane azimuth change (°)", "10 m pendulum, measured at each maximal excursion")
    for run, label in ((north, "Hefei (north)"), (south, "31.86° S")):
        ax.plot(run.t / 60, np.degrees(run.swing_azimuth - run.swing_azimuth[0]), label=label)
    ax.plot(north.t / 60, np.degrees(theory * north.t), "k--", linewidth=0.8, label="∓ ω sin λ t")
    ax.plot(north.t / 60, -np.degrees(theory * north.t), "k--", linewidth=0.8)
    ax.legend(fontsize=8)
    return Section(
        "Foucault pendulum", "§8.3",
        "In the Earth frame the swing plane of a pendulum turns clockwise (seen from above) at ω sin λ in "
        "the northern hemisphere and counter-clockwise in the southern. kreisel integrates the spherical "
        "pendulum in the rotating frame and measures the azimuth of the swing at each maximal excursion; "
        "at Hefei the plane turns once in 45 h 28 min.",
        [Check.equal("period of the swing plane at Hefei", f"{hours} h {minutes} min", "45 h 28 min"),
         Check.close("measured rate, north (rad/s)", north.precession_rate, theory, rtol=2e-2, source="−ω sin λ"),
         Check.close("measured rate, south (rad/s)", south.precession_rate, -theory, rtol=2e-2, source="+ω sin λ")],
        [(fig, "Swing-plane azimuth (counter-clockwise from east) of Foucault pendulums in both hemispheres.")],
    )


SECTIONS = (eastward_deflection, foucault_pendulum)
