"""
Gimbal lock (Theory §2.3, §3.6)
========================================

For a fixed body angular velocity the ZXZ Euler rates grow like 1/sin θ as the
middle angle θ approaches 0, while the quaternion rate q̇ = ½ q ω′ keeps the
size ‖ω‖/2. At θ = 0 itself kreisel returns NaN with a ``GimbalLockWarning``
instead of a wrong finite number.
"""

import warnings

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr

theta = np.logspace(-8, np.log10(np.pi / 2), 60)
angles = np.stack([np.full_like(theta, 0.3), theta, np.full_like(theta, 0.2)], axis=-1)
omega = np.array([0.3, -0.5, 0.8])
rates = kr.euler_rates("ZXZ", angles, omega, frame="body")
qdot = kr.quat_rate(kr.euler_to_quat("ZXZ", angles), omega, frame="body")

with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    locked = kr.euler_rates("ZXZ", [0.3, 0.0, 0.2], omega, frame="body")
print("rates at θ = 0:", locked, "-", caught[0].category.__name__)

fig, ax = plt.subplots(figsize=(7, 3.8), layout="constrained")
ax.loglog(theta, np.abs(rates[:, 0]), label="|φ̇|")
ax.loglog(theta, np.abs(rates[:, 2]), label="|ψ̇|")
ax.loglog(theta, np.linalg.norm(qdot, axis=-1), label="|q̇| = |ω|/2")
ax.set_xlabel("θ (rad)")
ax.set_ylabel("rate (1/s)")
ax.legend()
plt.show()
