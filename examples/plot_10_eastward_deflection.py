"""
Eastward deflection of a falling body (Theory §8.3)
============================================================

The chapter's example: a 100 m drop at Hefei (λ = 31.8584°, g = 9.7947 m/s²,
ω = 7.27221e-5 rad/s) lands (2/3) ω cos λ √(2h³/g) ≈ 0.0186 m east of the
vertical. The analytic formula against a simulation of the full rotating-frame
equations.
"""

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr
from _quick import size

latitude, g, omega = 31.8584, 9.7947, 7.27221e-5
print("analytic :", kr.earth.eastward_deflection(100.0, latitude, g=g, omega=omega), "m")
print("simulated:", kr.earth.simulate_drop(100.0, latitude, g=g, omega=omega)[0], "m")
heights = np.geomspace(1.0, 1000.0, size(12, 4))
simulated = [kr.earth.simulate_drop(h, latitude, g=g, omega=omega)[0] for h in heights]
fig, ax = plt.subplots(figsize=(6, 3.8), layout="constrained")
ax.loglog(heights, simulated, "o", label="simulation")
ax.loglog(heights, kr.earth.eastward_deflection(heights, latitude, g=g, omega=omega), label="(2/3) ω cos λ √(2h³/g)")
ax.set(xlabel="drop height (m)", ylabel="eastward deflection (m)")
ax.legend()
plt.show()
