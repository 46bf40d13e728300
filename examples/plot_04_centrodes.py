"""
Instantaneous centre and centrodes (Theory §3.8)
=========================================================

A wheel of radius a rolling without slipping: its instantaneous centre is the
contact point, so the space centrode is the ground line and the body centrode
is the rim. A ladder sliding between wall and floor: circles of radius L and
L/2.
"""

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr
from _quick import size

radius, speed, length = 0.5, 1.0, 2.0
t = np.linspace(0.0, 3 * np.pi * radius / speed, size(240, 40))
wheel = kr.centrodes(t, lambda s: -speed * s / radius,
                     lambda s: np.stack([speed * s, np.full_like(s, radius)], -1))
s = np.linspace(0.15, 1.4, size(240, 40))
ladder = kr.centrodes(s, lambda u: -u, lambda u: 0.5 * length * np.stack([np.cos(u), np.sin(u)], -1))
print("wheel: max height of the instantaneous centre =", np.abs(wheel.space[:, 1]).max())
print("ladder: centrode radii =", np.linalg.norm(ladder.space, axis=-1).mean(), np.linalg.norm(ladder.body, axis=-1).mean())

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.8), layout="constrained")
ax1.plot(*wheel.space.T, "C3", linewidth=3, label="space centrode")
ax1.plot(*wheel.body.T, "C0", label="body centrode (body frame)")
ax1.set_aspect("equal")
ax1.legend(fontsize=8)
ax2.plot(*ladder.space.T, "C3", label="space centrode")
ax2.plot(*ladder.body.T, "C0", label="body centrode (body frame)")
ax2.set_aspect("equal")
ax2.legend(fontsize=8)
plt.show()
