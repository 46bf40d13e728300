"""
The Bortz coefficient (Theory §3.5)
=============================================

The body-frame rate of the rotation vector is the Bortz equation
ψ̇ = ω′ + ½ ψ × ω′ + c(ψ) ψ × (ψ × ω′) with
c(ψ) = (2 sin ψ − ψ(1 + cos ψ)) / (2ψ² sin ψ) = 1/12 + ψ²/720 + …
The closed form loses all its digits to cancellation for small ψ;
:func:`kreisel.kinematics.bortz_coefficient` does not.
"""

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr

psi = np.logspace(-8, np.log10(6.0), 300)
c = kr.bortz_coefficient(psi)
with np.errstate(invalid="ignore", divide="ignore"):
    closed = (2 * np.sin(psi) - psi * (1 + np.cos(psi))) / (2 * psi**2 * np.sin(psi))
series = 1 / 12 + psi**2 / 720 + psi**4 / 30240

fig, ax = plt.subplots(figsize=(7, 3.8), layout="constrained")
ax.loglog(psi, np.abs(closed / c - 1) + 1e-17, label="closed form")
ax.loglog(psi, np.abs(series / c - 1) + 1e-17, label="three-term series")
ax.set_xlabel("ψ (rad)")
ax.set_ylabel("relative difference to kreisel")
ax.legend()
print("c(0) =", kr.bortz_coefficient(0.0), " 1/12 =", 1 / 12)
plt.show()
