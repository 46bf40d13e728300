"""
Foucault pendulum (Theory §8.3)
========================================

The swing plane turns clockwise (seen from above) at ω sin λ in the northern
hemisphere; at Hefei once in 45 h 28 min.
"""

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr
from _quick import size

latitude = 31.8584
period = kr.earth.foucault_period(latitude, omega=7.27221e-5)
print(f"swing plane period at Hefei: {period // 3600:.0f} h {period % 3600 / 60:.0f} min")
run = kr.earth.foucault_pendulum(10.0, latitude, size(3600.0, 600.0), 0.02)
rate = kr.earth.foucault_precession_rate(latitude)
fig, ax = plt.subplots(figsize=(7, 3.8), layout="constrained")
ax.plot(run.t / 60, np.degrees(run.swing_azimuth - run.swing_azimuth[0]), label="simulated")
ax.plot(run.t / 60, -np.degrees(rate * run.t), "k--", label="−ω sin λ t")
ax.set(xlabel="t (min)", ylabel="swing-plane azimuth change (°)")
ax.legend()
plt.show()
