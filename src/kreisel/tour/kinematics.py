"""Tour sections for Theory §3: instantaneous centre and centrodes, the Bortz coefficient."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .. import kinematics
from .report import Check, Section, panel

__all__ = ["rolling_wheel_centrodes", "bortz_series_and_closed_form", "SECTIONS"]


def rolling_wheel_centrodes(quick):
    """Rolling wheel and sliding ladder: instantaneous centre and centrodes"""
    radius, speed = 0.5, 1.0
    t = np.linspace(0.0, 2 * np.pi * radius / speed * 1.5, 60 if quick else 240)
    # wheel rolling to the right: centre (v t, a), angle −v t / a (clockwise)
    wheel = kinematics.centrodes(t, lambda s: -speed * s / radius,
                                 lambda s: np.stack([speed * s, np.full_like(s, radius)], -1))
    ladder_length = 2.0
    s = np.linspace(0.15, 1.4, 60 if quick else 240)
    # ladder from the wall (0, L sin θ) to the floor (L cos θ, 0); reference point its midpoint
    ladder = kinematics.centrodes(s, lambda u: -u, lambda u: 0.5 * ladder_length * np.stack([np.cos(u), np.sin(u)], -1))

    fig = Figure(figsize=(10, 4.4), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2, width_ratios=(1.3, 1))
    ax1.plot(wheel.space[:, 0], wheel.space[:, 1], "C3", linewidth=3, label="space centrode (ground line)")
    phi = np.linspace(0, 2 * np.pi, 100)
    for k in range(0, t.size, t.size // 4):
        cx = speed * t[k]
        ax1.plot(cx + radius * np.cos(phi), radius + radius * np.sin(phi), color="0.6", linewidth=0.8)
        ax1.plot(wheel.space[k, 0], wheel.space[k, 1], "ko")
    ax1.set_aspect("equal")
    ax1.set(xlabel="x (m)", ylabel="y (m)")
    ax1.set_title("rolling wheel: the contact point\nis the instantaneous centre", fontsize=10)
    ax1.legend(loc="upper right", fontsize=8)
    ax2.plot(ladder.space[:, 0], ladder.space[:, 1], "C3", label="space centrode: |r_I| = L")
    for k in range(0, s.size, s.size // 5):
        a, b = np.array([0, ladder_length * np.sin(s[k])]), np.array([ladder_length * np.cos(s[k]), 0])
        ax2.plot(*np.c_[a, b], color="0.5")
        centre = 0.5 * (a + b)
        angle = -s[k]
        c, d = np.cos(angle), np.sin(angle)
        body_now = centre + ladder.body @ np.array([[c, d], [-d, c]])
        ax2.plot(body_now[:, 0], body_now[:, 1], "C0", linewidth=0.6)
    ax2.set_aspect("equal")
    ax2.set(xlabel="x (m)", ylabel="y (m)")
    ax2.set_title("sliding ladder: body centrode (blue)\nrolls in the space centrode", fontsize=10)
    ax2.legend(loc="upper right", fontsize=8)

    contact_error = np.max(np.abs(wheel.space[:, 1]))
    travel_error = np.max(np.abs(wheel.space[:, 0] - speed * t))
    body_radius = np.linalg.norm(wheel.body, axis=-1)
    return Section(
        "Instantaneous centre and centrodes", "§3.8",
        "In plane motion the point of zero velocity r_I = r_C + ẑ × v_C/ω is the instantaneous centre. "
        "For a wheel rolling without slipping it is the contact point: the space centrode is the ground "
        "line and the body centrode the rim. For a ladder sliding between wall and floor the space "
        "centrode is the circle of radius L about the corner and the body centrode the circle of "
        "radius L/2 about the ladder's midpoint, rolling inside it.",
        [Check.below("wheel: height of the instantaneous centre (m)", contact_error, 1e-9),
         Check.below("wheel: centre below the hub, |x_I − v t| (m)", travel_error, 1e-9),
         Check.below("wheel: max | |body centrode| − a | (m)", float(np.max(np.abs(body_radius - radius))), 1e-9),
         Check.close("ladder: space centrode radius (m)", float(np.mean(np.linalg.norm(ladder.space, axis=-1))),
                     ladder_length, rtol=1e-9),
         Check.close("ladder: body centrode radius (m)", float(np.mean(np.linalg.norm(ladder.body, axis=-1))),
                     ladder_length / 2, rtol=1e-9)],
        [(fig, "Instantaneous centres of a rolling wheel and of a sliding ladder.")],
    )


def bortz_series_and_closed_form(quick):
    """The Bortz coefficient"""
    psi = np.concatenate([[0.0], np.logspace(-8, np.log10(6.0), 200)])
    coefficient = kinematics.bortz_coefficient(psi)
    series = 1 / 12 + psi**2 / 720 + psi**4 / 30240
    closed = np.full_like(psi, np.nan)
    big = psi > 0.5
    closed[big] = (2 * np.sin(psi[big]) - psi[big] * (1 + np.cos(psi[big]))) / (2 * psi[big] ** 2 * np.sin(psi[big]))
    small = psi < 1e-3
    fig, ax = panel("ψ (rad)", "coefficient", "Bortz equation: ψ̇ = ω′ + ½ ψ × ω′ + c(ψ) ψ × (ψ × ω′)", figsize=(7, 3.6))
    ax.semilogy(psi, coefficient, label="kreisel")
    ax.semilogy(psi[big], closed[big], "--", label="closed form (2 sin ψ − ψ(1 + cos ψ))/(2ψ² sin ψ)")
    ax.axvline(2 * np.pi, color="0.6", linestyle=":")
    ax.legend(fontsize=8)
    return Section(
        "The Bortz coefficient", "§3.5",
        "The body-frame rotation-vector rate (the Bortz equation) has the coefficient "
        "c(ψ) = (2 sin ψ − ψ(1 + cos ψ))/(2ψ² sin ψ) = 1/12 + ψ²/720 + …, singular at ψ = 2π. "
        "The closed form loses every digit to cancellation as ψ → 0; kreisel switches to the series.",
        [Check.close("c(0)", float(coefficient[0]), 1 / 12, rtol=1e-15, source="Theory §3.5 series"),
         Check.below("max relative error vs series for ψ < 1e-3",
                     float(np.max(np.abs(coefficient[small] / series[small] - 1))), 1e-15),
         Check.below("max relative error vs closed form for ψ > 0.5",
                     float(np.max(np.abs(coefficient[big] / closed[big] - 1))), 1e-12)],
        [(fig, "The Bortz coefficient from ψ = 0 to near its pole at 2π.")],
    )


SECTIONS = (rolling_wheel_centrodes, bortz_series_and_closed_form)
