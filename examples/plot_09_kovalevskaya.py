"""
Kovalevskaya top (Theory §7)
=====================================

With I1 = I2 = 2 I3 and the centre of mass in the equatorial plane the heavy
top has a fourth integral K = (p² − q² − cγ1)² + (2pq − cγ2)², c = m g l / I3.
The simulation keeps it along with the energy.
"""

import matplotlib.pyplot as plt
import numpy as np

import kreisel as kr
from _quick import size

top = kr.KovalevskayaTop(1.0, 1.0)
t = np.linspace(0.0, size(100.0, 20.0), size(4000, 800))
traj = top.simulate(t, [0.3, 0.7, 1.5], kr.euler_to_quat("ZXZ", [0.0, 0.7, 0.35]))
K = top.integrals(traj.omega, traj.gamma).kovalevskaya
print("relative drift of K:", np.ptp(K) / abs(K[0]))
fig, ax = plt.subplots(figsize=(7, 3.8), layout="constrained")
ax.plot(t, traj.omega, linewidth=0.8)
ax.set(xlabel="t (s)", ylabel="ω′ (rad/s)")
plt.show()
